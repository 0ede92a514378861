"""``gearlever synthesize law``: the quick-return law met by ``--type auto`` (a miss over 2 % of the range warned on
stderr with the time ratio achieved against the one wanted), ``--dwell-tolerance`` (the bound reported and held;
bad values refused naming the flag, one line, exit 2, nothing written), the budget a cap in the report.

Run through :func:`gearlever.cli.main` (its error handling included).
"""

from __future__ import annotations

import json

import numpy as np
import pytest

import gearlever.cli as cli
from gearlever.data import example_path
from gearlever.mechanism import Mechanism
from gearlever.synthesis.law.measure import mechanism_law

DWELL = example_path("law_dwell_rocker.toml")
QUICK = example_path("law_quick_return.toml")


@pytest.fixture
def run(capsys):
    def go(*argv):
        code = cli.main([*map(str, argv)])
        out, err = capsys.readouterr()
        return code, out, err

    return go


@pytest.fixture(scope="module")
def quick(tmp_path_factory):
    folder = tmp_path_factory.mktemp("quick")
    out, rep = folder / "qr.toml", folder / "r.json"
    argv = ["synthesize", "law", QUICK, "--type", "auto", "--out", out, "--report", rep, "--budget", 20000]
    import contextlib
    import io

    so, se = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(so), contextlib.redirect_stderr(se):
        code = cli.main([*map(str, argv + ["--workers", 1])])
    return code, so.getvalue(), se.getvalue(), out, json.loads(rep.read_text())


def test_auto_gives_the_quick_return_law_a_slotted_lever_kind_and_says_why_the_others_were_not_tried(quick):
    code, text, _, out, rep = quick
    assert code == 0 and rep["kind"] in ("slotted-lever", "sixbar-slider")
    assert rep["time_ratio"]["wanted"] == pytest.approx(2.0, rel=1e-12)
    assert 1.6 < rep["time_ratio"]["achieved"] < 2.6
    lines = text.splitlines()
    assert any(ln.startswith("time ratio       ") and "(wanted 2)" in ln for ln in lines)
    not_tried = [ln for ln in lines if ln.startswith("not tried")]
    assert len(not_tried) == 4 and all("gives an output angle, the law is displacement" in ln for ln in not_tried)
    # the written model, turned by the engine, moves its ram as reported
    ml = mechanism_law(Mechanism.load(out), "output", 3600)
    assert ml.closed.all()
    assert np.ptp(ml.s) == pytest.approx(rep["range"] + 0.0, rel=0.1)


def test_a_miss_over_two_percent_of_the_range_is_warned_on_stderr_with_the_time_ratio(quick):
    code, _, err, _, rep = quick
    frac = rep["error_fraction_of_range"]
    assert rep["misses_law"] == (frac > 0.02) and rep["miss_fraction_limit"] == 0.02
    if rep["misses_law"]:
        warn = [ln for ln in err.splitlines() if "warning" in ln]
        assert len(warn) == 1 and "misses the law by" in warn[0] and "(more than 2 %)" in warn[0]
        assert f"time ratio {rep['time_ratio']['achieved']:.3g} achieved, 2 wanted" in warn[0]
    else:
        assert "warning" not in err


def test_the_report_counts_every_evaluation_within_the_budget_per_type(quick):
    _, text, _, _, rep = quick
    assert rep["budget_per_type"] == 20000
    assert all(0 < n <= 20000 for n in rep["evaluations_per_type"].values())
    assert rep["evaluations"] == sum(rep["evaluations_per_type"].values())
    assert "budget 20000 per type" in text


def test_a_design_within_two_percent_is_not_warned(tmp_path, run):
    # a law a four-bar gives exactly (its own output): no miss, no warning
    law = tmp_path / "law.toml"
    law.write_text('[law]\noutput = "angle"\nunits = "deg"\nsamples = "s.csv"\n')
    from gearlever.synthesis.law import kind_class, law_target

    th = np.linspace(0, 2 * np.pi, 360, endpoint=False)
    G, _ = kind_class("fourbar")(law_target(th, np.sin(th))).generate(np.array([[2.0, 1.6, 0.4, 0.7, 1.0]]), th)
    rows = "\n".join(f"{np.degrees(t):.12g},{np.degrees(g - G[0, 0]):.12g}" for t, g in zip(th, G[0]))
    (tmp_path / "s.csv").write_text("input_deg,output\n" + rows + "\n")
    out, rep = tmp_path / "m.toml", tmp_path / "r.json"
    code, _, err = run("synthesize", "law", law, "--type", "fourbar", "--out", out, "--report", rep, "--budget", 4000)
    assert code == 0, err
    r = json.loads(rep.read_text())
    assert not r["misses_law"] and r["error_fraction_of_range"] < 0.02 and "warning" not in err


def test_dwell_tolerance_is_held_and_reported(tmp_path, run):
    out, rep = tmp_path / "m.toml", tmp_path / "r.json"
    argv = ["synthesize", "law", DWELL, "--type", "fourbar", "--out", out, "--report", rep, "--budget", 4000]
    code, text, err = run(*argv, "--dwell-tolerance", 1.0)
    assert code == 0, err
    r = json.loads(rep.read_text())
    assert r["dwell_tolerance_deg"] == 1.0 and r["dwell_excursion_deg"] <= 1.0
    assert "dwell excursion  " in text and "(at most 1 deg)" in text


@pytest.mark.parametrize(
    ("law", "value", "words"),
    [
        (DWELL, "0", "--dwell-tolerance must be greater than 0"),
        (DWELL, "-2", "--dwell-tolerance must be greater than 0"),
        (QUICK, "0.5", "--dwell-tolerance bounds the output's excursion over a dwell: the law has no dwell"),
    ],
)
def test_a_bad_dwell_tolerance_is_refused_naming_the_flag(tmp_path, run, law, value, words):
    out = tmp_path / "m.toml"
    code, _, err = run(
        "synthesize", "law", law, "--type", "auto", "--out", out, "--budget", 600, "--dwell-tolerance", value
    )
    assert code == 2 and words in err and len(err.strip().splitlines()) == 1 and not out.exists()


def test_auto_says_which_types_were_searched_without_a_design_and_why(tmp_path, run):
    # at a transmission angle of 89 deg only the slotted lever (its block drives the lever square to the slot)
    # is buildable: the other angle types are searched and give no design, the displacement types are not tried
    out, rep = tmp_path / "m.toml", tmp_path / "r.json"
    argv = ["synthesize", "law", DWELL, "--type", "auto", "--out", out, "--report", rep, "--budget", 600]
    code, text, err = run(*argv, "--min-transmission", 89)
    assert code == 0, err
    r = json.loads(rep.read_text())
    assert r["kind"] == "slotted-lever"
    assert set(r["types_not_tried"]) == {"slider-crank", "sixbar-slider"}
    assert set(r["types_without_design"]) == {"fourbar", "geared-fourbar", "gear-lever", "sixbar-dwell"}
    for k, why in r["types_without_design"].items():
        assert why == "no design within the constraints (transmission angle at least 89 deg)"
        assert f"no design        {k}: {why}" in text
