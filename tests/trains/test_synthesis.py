"""Tests of gearlever.trains.synthesis: the old module path re-exports the split modules."""

import importlib

import pytest

from gearlever.trains import continued, design, rules, search, synthesis


@pytest.mark.parametrize("name", synthesis.__all__)
def test_every_public_name_is_the_split_modules_object(name):
    homes = [m for m in (rules, continued, design, search) if hasattr(m, name)]
    assert homes, name
    assert getattr(synthesis, name) is getattr(homes[0], name)


def test_old_alias_and_package_exports():
    alias = importlib.import_module("gearlever.synthesis")
    assert alias.search_best is search.search_best and alias.parse_ratio is continued.parse_ratio
    import gearlever.trains as trains

    for name in ("HookeJoint", "TrainRatio", "design_train", "search_best", "train_ratio", "parse_ratio"):
        assert hasattr(trains, name)
    res = synthesis.search_best("1/6.931", 2, 12, 60)  # Sandgren's problem through the old path
    assert [(s.drivers, s.followers) for s in res.solutions] == [((16, 19), (43, 49))]
