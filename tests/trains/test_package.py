"""Tests of gearlever.trains: the package is the one public face of the split modules of tooth-number design."""

import importlib

import pytest

import gearlever.trains as trains
from gearlever.trains import continued, design, hooke, ratio, rules, search


@pytest.mark.parametrize("name", trains.__all__)
def test_every_public_name_is_the_split_modules_object(name):
    homes = [m for m in (rules, continued, design, search, hooke, ratio) if hasattr(m, name)]
    assert homes, name
    assert getattr(trains, name) is getattr(homes[0], name)


def test_every_public_name_of_the_design_modules_is_exported_by_the_package():
    for module in (rules, continued, design, search):
        # the function rules.rules is left in its module: the package's name `rules` is the module
        missing = sorted(set(module.__all__) - set(trains.__all__) - {"rules"})
        assert missing == [], f"{module.__name__}: {missing}"


def test_a_submodule_is_not_shadowed_by_an_exported_name():
    assert rules.__name__ == "gearlever.trains.rules" and trains.rules is rules


def test_package_exports_and_linkage_synthesis_is_its_own_package():
    assert importlib.import_module("gearlever.synthesis").__name__ == "gearlever.synthesis"
    for name in ("HookeJoint", "TrainRatio", "design_train", "search_best", "train_ratio", "parse_ratio"):
        assert hasattr(trains, name)
    res = trains.search_best("1/6.931", 2, 12, 60)  # Sandgren's problem
    assert [(s.drivers, s.followers) for s in res.solutions] == [((16, 19), (43, 49))]
