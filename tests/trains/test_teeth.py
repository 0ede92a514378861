"""Tests of gearlever.trains.teeth: one name re-exports the split modules of tooth-number design."""

import importlib

import pytest

from gearlever.trains import continued, design, rules, search, teeth


@pytest.mark.parametrize("name", teeth.__all__)
def test_every_public_name_is_the_split_modules_object(name):
    homes = [m for m in (rules, continued, design, search) if hasattr(m, name)]
    assert homes, name
    assert getattr(teeth, name) is getattr(homes[0], name)


def test_package_exports_and_linkage_synthesis_is_its_own_package():
    assert importlib.import_module("gearlever.synthesis").__name__ == "gearlever.synthesis"
    import gearlever.trains as trains

    for name in ("HookeJoint", "TrainRatio", "design_train", "search_best", "train_ratio", "parse_ratio"):
        assert hasattr(trains, name)
    res = teeth.search_best("1/6.931", 2, 12, 60)  # Sandgren's problem
    assert [(s.drivers, s.followers) for s in res.solutions] == [((16, 19), (43, 49))]
