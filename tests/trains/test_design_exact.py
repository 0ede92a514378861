"""The classical train design shown with the exhaustive-search optimum beside it (191/23, teeth 24..144)."""

import json
from fractions import Fraction

import pytest

from gearlever.cli import main
from gearlever.trains.design import design_train, exact_optimum


def test_classical_design_191_23_misses_the_search_optimum():
    r = design_train("191/23", min_teeth=24, max_teeth=144)
    assert r.method == "continued fraction"
    assert r.approximation == Fraction(8512, 1025)
    assert r.designs[0].error == pytest.approx(4.2418e-5, rel=1e-4)
    best = exact_optimum(r)
    assert best.pairs == 2 and best.min_teeth == 24 and best.max_teeth == 144
    assert best.best_ratios == (Fraction(13287, 1600),)
    assert float(best.best_error) == pytest.approx(2.7174e-5, rel=1e-4)
    assert float(best.best_error) < abs(r.designs[0].error)


def test_classical_design_1_6931_is_already_optimal():
    r = design_train("1/6.931", min_teeth=12, max_teeth=60)
    best = exact_optimum(r)
    assert best.best_ratios[0] == r.approximation


def test_cli_train_design_reports_exact_optimum_beside_classical(capsys):
    argv = ["train", "design", "--ratio", "191/23", "--min-teeth", "24", "--max-teeth", "144"]
    assert main(argv) == 0
    out = capsys.readouterr().out
    assert "continued fraction (classical rules), using 8512/1025" in out
    assert "error +4.242e-05" in out
    assert "exact optimum    13287/1600 = 8.304375  error +2.717e-05" in out
    assert "closer than the classical design" in out
    assert main(argv + ["--format", "json"]) == 0
    rec = json.loads(capsys.readouterr().out)
    assert rec["approximation"] == "8512/1025"
    assert rec["exact_optimum"]["ratio"] == "13287/1600"
    assert rec["exact_optimum"]["error"] == pytest.approx(2.7174e-5, rel=1e-4)
    assert {"drivers": [103, 129], "followers": [25, 64]} in rec["exact_optimum"]["solutions"]


def test_cli_train_design_exact_ratio_needs_no_search(capsys):
    assert main(["train", "design", "--ratio", "6"]) == 0
    assert "the classical design is exact (error 0)" in capsys.readouterr().out
