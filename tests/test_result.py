"""One result convention (gearlever.Result): every result class of the package found by walking its modules.

Checked: ``gearlever.Result`` is the base of ``gearlever._result``; every
subclass is a frozen dataclass; the results named in the issue (the chariot's
run, the trains' solutions and designs) derive from it, and so does every
dataclass whose name says it is a result (``*Result``, ``*Solution``,
``*Design``, ``*Run``, ``*State``, ``*Report``) except the listed ones of the
synthesis driver files; on small instances ``as_dict`` is a dict of the
fields, ``to_frame`` a DataFrame and ``summary`` strict JSON (NaN as null),
rounded by the digits rule.
"""

from __future__ import annotations

import dataclasses
import importlib
import json
import pkgutil
import re
from fractions import Fraction

import numpy as np
import pandas as pd
import pytest

import gearlever
from gearlever import Result
from gearlever._format import DIGITS_DESIGN, quantize
from gearlever._result import SUMMARY_MAX_ITEMS

#: Result-like dataclasses in files another change owns (the synthesis driver: curves/search.py).
NOT_YET = {"gearlever.synthesis.curve.search.CurveSynthesis"}
RESULT_NAME = re.compile(r".*(Result|Solution|Design|Run|State|Report)$")


def _modules():
    names = [m.name for m in pkgutil.walk_packages(gearlever.__path__, "gearlever.")]
    return [importlib.import_module(n) for n in sorted(names) if not n.endswith("__main__") and ".cli" not in n]


def _classes():
    out = {}
    for mod in _modules():
        for name, obj in vars(mod).items():
            if isinstance(obj, type) and obj.__module__ == mod.__name__:
                out[f"{mod.__name__}.{name}"] = obj
    return out


CLASSES = _classes()
RESULTS = {k: c for k, c in CLASSES.items() if issubclass(c, Result) and c is not Result}


def test_result_is_exported_at_top_level():
    assert gearlever.Result is Result and "Result" in gearlever.__all__


def test_walk_finds_the_results_of_every_family():
    families = {k.split(".")[1] for k in RESULTS}
    assert {"mechanism", "gears", "trains", "cams", "laws", "loops", "synthesis", "flywheels"} <= families
    assert len(RESULTS) >= 25


@pytest.mark.parametrize("name", sorted(RESULTS))
def test_every_result_subclass_is_a_frozen_dataclass(name):
    cls = RESULTS[name]
    assert dataclasses.is_dataclass(cls), name
    assert cls.__dataclass_params__.frozen, name


@pytest.mark.parametrize(
    "name",
    [
        "gearlever.gears.chariot.ChariotRun",
        "gearlever.trains.search.TrainSolution",
        "gearlever.trains.design.TrainDesign",
    ],
)
def test_the_issues_results_derive_from_result(name):
    assert issubclass(CLASSES[name], Result)


def test_every_dataclass_named_as_a_result_derives_from_result():
    named = {
        k
        for k, c in CLASSES.items()
        if dataclasses.is_dataclass(c) and RESULT_NAME.match(k.rsplit(".", 1)[1]) and not k.rsplit(".", 1)[1][0] == "_"
    }
    assert named - set(RESULTS) <= NOT_YET, sorted(named - set(RESULTS) - NOT_YET)


def test_no_result_spells_its_summary_report_or_to_dict():
    for name, cls in RESULTS.items():
        for spelling in ("report", "to_dict"):
            assert not callable(getattr(cls, spelling, None)), f"{name}.{spelling}: call it summary()"


# --------------------------------------------------------------------------- small instances
def _instances():
    from gearlever.cams.design import design_cam
    from gearlever.gears.car import car_differential
    from gearlever.gears.chariot import NuttallTeeth, design_nuttall, simulate
    from gearlever.laws import law_from_segments
    from gearlever.mechanism import Mechanism
    from gearlever.trains import design_train, search_best, train_ratio

    mech = Mechanism.from_dict(
        {
            "points": {"O2": [0, 0], "O4": [4, 0], "A": [1, 0], "B": [4.5, 2.8]},
            "links": {"ground": ["O2", "O4"], "crank": ["O2", "A"], "coupler": ["A", "B"], "rocker": ["O4", "B"]},
            "inputs": [{"link": "crank"}],
        }
    )
    law = law_from_segments(
        "displacement",
        "mm",
        [
            {"to": 120, "motion": "dwell"},
            {"to": 240, "motion": "cycloidal", "rise": 10},
            {"to": 360, "motion": "cycloidal", "rise": -10},
        ],
    )
    design = design_train("1/6.931", min_teeth=12, max_teeth=60)
    search = search_best("1000/6931", pairs=2, min_teeth=12, max_teeth=60)
    nuttall = design_nuttall(NuttallTeeth.uniform(30), track=1.0)
    yield "MechanismResult", mech.solve(np.linspace(0.0, 1.0, 4))
    yield "MechanismStructure", mech.structure()
    yield "ChariotRun", simulate(nuttall, np.full(5, 0.1), np.full(5, 0.12))
    yield "NuttallDesign", nuttall
    yield "CarState", car_differential(11, 41, 300.0, 100.0)
    yield "TrainRatio", train_ratio([20, 30], [60, 45])
    yield "DesignResult", design
    yield "TrainDesign", design.designs[0]
    yield "SearchResult", search
    yield "TrainSolution", search.solutions[0]
    yield "CamDesign", design_cam(law, "translating-roller", base_radius=30.0, roller_radius=5.0, points=72)


INSTANCES = list(_instances())


@pytest.mark.parametrize("name,res", INSTANCES, ids=[n for n, _ in INSTANCES])
def test_as_dict_to_frame_and_summary_return_their_types(name, res):
    assert isinstance(res, Result)
    d = res.as_dict()
    assert list(d) == [f.name for f in dataclasses.fields(res)]
    assert isinstance(res.to_frame(), pd.DataFrame)
    s = res.summary()
    assert isinstance(s, dict) and s
    json.dumps(s, allow_nan=False)  # strict JSON


def test_default_summary_keeps_scalars_and_short_arrays_rounded_and_strict():
    @dataclasses.dataclass(frozen=True)
    class R(Result):
        short: np.ndarray
        long: np.ndarray
        ratio: Fraction
        peak: float
        bad: float
        label: str

    r = R(np.array([1 / 3, 2.0]), np.zeros(SUMMARY_MAX_ITEMS + 1), Fraction(2, 9), 2 / 3, float("nan"), "x")
    s = r.summary()
    assert s == {
        "short": [quantize(1 / 3, 0.0, DIGITS_DESIGN), 2.0],
        "ratio": "2/9",
        "peak": quantize(2 / 3, 0.0, DIGITS_DESIGN),
        "bad": None,
        "label": "x",
    }
    assert s["peak"] == 0.6666666667
    assert json.loads(json.dumps(s, allow_nan=False)) == s


def test_trains_summaries_keep_the_command_lines_keys():
    from gearlever.trains import design_train, search_best

    d = design_train("1/6.931", min_teeth=12, max_teeth=60)
    assert list(d.designs[0].summary())[:3] == ["drivers", "followers", "ratio"]
    assert d.summary()["designs"][0] == d.designs[0].summary()
    s = search_best("1000/6931", pairs=2, min_teeth=12, max_teeth=60)
    assert s.summary()["solutions"][0]["pairs"] == [list(p) for p in s.solutions[0].pairing]
    assert d.designs[0].to_frame().shape[0] == 1
