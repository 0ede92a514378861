"""The contract of every registered synthesis kind (``gearlever.synthesis.kinds()``), run over the registry.

Each kind, on its tiny problem (:attr:`Kind.example`): returns a result of the common convention
(a frozen dataclass deriving ``gearlever._result.Result``), the same result for the same input and seed,
and, for the searched kinds (a seeded multistart with a budget): ``evaluations <= budget`` (the law
kinds count their polishes inside it, :attr:`Kind.polish_counted`), and a bad budget (below the
least, above the cap, a fraction, a bool) refused with the one message of
:func:`gearlever.synthesis.driver.check_budget`.
"""

from __future__ import annotations

import dataclasses
import functools

import numpy as np
import pytest

import gearlever.synthesis
from gearlever._result import Result
from gearlever.errors import GearleverError
from gearlever.synthesis import driver, registry

KINDS = gearlever.synthesis.kinds()
SEARCHED = [k for k in KINDS if k.searched]
#: The budget of a searched kind's tiny run: a little above the least the kind takes.
BUDGET = {"path": 2000, "law": 600, "curve": 1000}


def _id(kind) -> str:
    return f"{kind.family}-{kind.name}"


@functools.cache
def _run(family: str, name: str, seed: int = 0):
    kind = registry.get(family, name)
    args, kwargs = kind.example()
    if kind.searched:
        kwargs = {**kwargs, "seed": seed, "budget": BUDGET[family], "workers": 1}
    return kind(*args, **kwargs)


def _same(a, b, where: str = "result") -> None:
    """Equal value by value (arrays exactly, dataclasses and containers recursively), wall times aside."""
    if dataclasses.is_dataclass(a) and not isinstance(a, type):
        assert type(a) is type(b), where
        for f in dataclasses.fields(a):
            if f.name != "seconds":
                _same(getattr(a, f.name), getattr(b, f.name), f"{where}.{f.name}")
    elif isinstance(a, np.ndarray):
        assert a.dtype == b.dtype and np.array_equal(a, b, equal_nan=a.dtype.kind in "fc"), where
    elif isinstance(a, dict):
        assert list(a) == list(b), where
        for k in a:
            _same(a[k], b[k], f"{where}[{k!r}]")
    elif isinstance(a, (list, tuple)):
        assert len(a) == len(b), where
        for i, (x, y) in enumerate(zip(a, b)):
            _same(x, y, f"{where}[{i}]")
    elif hasattr(a, "as_dict"):
        _same(a.as_dict(), b.as_dict(), where)
    else:
        assert repr(a) == repr(b), where


def test_every_family_is_registered_with_its_kinds():
    listing = {(k.family, k.name) for k in KINDS}
    assert listing == {
        ("function", "fourbar"),
        ("function", "slider-crank"),
        ("motion", "3-poses"),
        ("motion", "4-poses"),
        ("motion", "5-poses"),
        ("path", "fourbar"),
        ("path", "geared-fivebar"),
        ("path", "sixbar"),
        ("law", "fourbar"),
        ("law", "slider-crank"),
        ("law", "geared-fourbar"),
        ("law", "sixbar-dwell"),
        ("law", "gear-lever"),
        ("law", "slotted-lever"),
        ("law", "sixbar-slider"),
        ("curve", "topology"),
    }
    for k in KINDS:
        assert type(k).__qualname__ == "Kind" and k.description and callable(k.synthesize) and callable(k.example)


def test_the_cli_type_choices_are_the_registered_kinds():
    from gearlever.cli import main  # noqa: F401 (the parsers are built from the registry)
    from gearlever.synthesis.law import KINDS as LAW
    from gearlever.synthesis.path import KINDS as PATH

    assert PATH == (*registry.names("path"), "auto")
    assert tuple(LAW) == registry.names("law")


def test_a_kind_registered_again_replaces_the_old_and_a_bad_record_is_refused(monkeypatch):
    monkeypatch.setattr(registry, "_KINDS", {**registry._KINDS})
    old = registry.get("function", "fourbar")
    registry.register(dataclasses.replace(old, description="probe"))
    assert registry.get("function", "fourbar").description == "probe"
    assert registry.names("function") == ("fourbar", "slider-crank")
    with pytest.raises(GearleverError, match="family must be one of"):
        registry.register(dataclasses.replace(old, family="nonsense"))
    with pytest.raises(GearleverError, match="kind must be one of fourbar, slider-crank, got 'nonsense'"):
        registry.get("function", "nonsense")


@pytest.mark.parametrize("kind", KINDS, ids=_id)
def test_each_kind_returns_a_result_of_the_common_convention(kind):
    res = _run(kind.family, kind.name)
    assert isinstance(res, Result) and dataclasses.is_dataclass(res)
    with pytest.raises(dataclasses.FrozenInstanceError):
        res.seed = 99  # frozen
    assert list(res.as_dict()) == [f.name for f in dataclasses.fields(res)]
    if kind.searched:
        assert res.seed == 0 and res.evaluations > 0 and res.starts >= 1


@pytest.mark.parametrize("kind", KINDS, ids=_id)
def test_each_kind_gives_the_same_result_for_the_same_input_and_seed(kind):
    a = _run(kind.family, kind.name)
    args, kwargs = kind.example()
    if kind.searched:
        kwargs = {**kwargs, "seed": 0, "budget": BUDGET[kind.family], "workers": 2}  # other workers: the same
    _same(a, kind(*args, **kwargs))


@pytest.mark.parametrize("kind", SEARCHED, ids=_id)
def test_each_searched_kind_respects_its_budget(kind):
    res = _run(kind.family, kind.name)
    assert 0 < res.evaluations <= BUDGET[kind.family]  # the law's polishes included (polish_counted)


@pytest.mark.parametrize("bad", [1, 10**8, 1500.5, True, "600"])
@pytest.mark.parametrize("kind", SEARCHED, ids=_id)
def test_each_searched_kind_refuses_a_bad_budget_with_the_one_message(kind, bad):
    args, kwargs = kind.example()
    with pytest.raises(GearleverError, match=r"^budget must be a whole number from \d+ to 10000000\b.* got "):
        kind(*args, **kwargs, budget=bad, workers=1)


@pytest.mark.parametrize("kind", SEARCHED, ids=_id)
def test_a_whole_float_budget_is_that_integer(kind):
    if kind.family == "curve":
        pytest.skip("the curve's tiny run is the slowest: check_budget is the same function (its doctest)")
    args, kwargs = kind.example()
    a = _run(kind.family, kind.name)
    b = kind(*args, **kwargs, seed=0, budget=float(BUDGET[kind.family]), workers=1)
    _same(a, b)


def test_the_budget_rule():
    assert driver.check_budget("budget", 1e5, 100, 10**7) == 100_000
    assert driver.check_budget("budget", np.int64(500), 100, 10**7) == 500
    for bad in (99, 10**7 + 1, 500.5, float("nan"), float("inf"), True, "500", None):
        with pytest.raises(GearleverError, match=r"^budget must be a whole number from 100 to 10000000"):
            driver.check_budget("budget", bad, 100, 10**7)


def test_workers_an_int_or_a_map_like_give_the_same_starts():
    from concurrent.futures import ThreadPoolExecutor

    from gearlever.synthesis.path import search_problem

    make = search_problem({"targets": [[1.0, 2.0], [1.5, 2.4], [1.8, 3.0], [1.2, 3.5]], "coord_range": (-5, 5)})
    one = driver.multistart(make, 4, 7, budget=2000, workers=1)
    with ThreadPoolExecutor(2) as pool:
        mapped = driver.multistart(make, 4, 7, budget=2000, workers=pool)
    _same(one, mapped)
    assert [s.index for s in one] != [] and all(s.evaluations <= 500 for s in one)
    with pytest.raises(GearleverError, match="workers must be a number of threads, a map-like"):
        driver.multistart(make, 4, 7, budget=2000, workers=2.5)
