"""CLI tests: gearlever train ratio|design|search and gearlever hooke."""

import json

import pytest

from gearlever.cli import main


def _json(capsys, argv):
    assert main(argv) == 0
    return json.loads(capsys.readouterr().out)


def test_train_ratio_json(capsys):
    rec = _json(capsys, ["train", "ratio", "--drivers", "20", "30", "--followers", "60", "45", "--format", "json"])
    assert rec["ratio"] == "2/9" and rec["sense"] == "same"
    rec = _json(
        capsys,
        [
            "train",
            "ratio",
            "--drivers",
            "20",
            "30",
            "--followers",
            "60",
            "45",
            "--internal",
            "2",
            "--format",
            "json",
        ],
    )
    assert rec["sense"] == "reversed" and rec["signed_ratio_float"] == pytest.approx(-2 / 9)


def test_train_ratio_table(capsys):
    assert main(["train", "ratio", "--drivers", "20", "--followers", "60", "--idlers", "37"]) == 0
    out = capsys.readouterr().out
    assert "1/3" in out and "same" in out


def test_train_design_json(capsys):
    rec = _json(
        capsys,
        [
            "train",
            "design",
            "--ratio",
            "1/6.931",
            "--min-teeth",
            "12",
            "--max-teeth",
            "60",
            "--format",
            "json",
        ],
    )
    assert rec["method"] == "continued fraction" and rec["approximation"] == "304/2107"
    d = rec["designs"][0]
    assert d["drivers"] == [16, 19] and d["followers"] == [43, 49] and d["gcd"] == [1, 1]
    assert d["error"] == pytest.approx(1.6434e-6, rel=1e-4)


def test_train_design_table(capsys):
    assert main(["train", "design", "--ratio", "100", "--prefer", "wear", "--keep", "2"]) == 0
    out = capsys.readouterr().out
    assert "exact" in out and "sharing a divisor: none" in out


def test_train_search_json(capsys):
    rec = _json(
        capsys,
        [
            "train",
            "search",
            "--ratio",
            "1/6.931",
            "--pairs",
            "2",
            "--min-teeth",
            "12",
            "--max-teeth",
            "60",
            "--format",
            "json",
        ],
    )
    assert set(rec) >= {"best_error", "best_ratio", "solutions"}
    assert rec["best_error"] ** 2 == pytest.approx(2.700857e-12, rel=1e-6)
    assert rec["solutions"] == [
        {
            "drivers": [16, 19],
            "followers": [43, 49],
            "ratio": "304/2107",
            "pairs": [[16, 43], [19, 49]],
            "gcd": [1, 1],
        }
    ]


def test_train_search_all_flag_and_out_file(capsys, tmp_path):
    argv = [
        "train",
        "search",
        "--ratio",
        "2",
        "--pairs",
        "2",
        "--min-teeth",
        "12",
        "--max-teeth",
        "30",
        "--format",
        "json",
    ]
    short = _json(capsys, argv)
    full = _json(capsys, argv + ["--all"])
    assert len(short["solutions"]) == 10 < len(full["solutions"]) == full["n_solutions"]
    out = tmp_path / "s.json"
    assert main(argv + ["--out", str(out)]) == 0
    assert json.loads(out.read_text())["n_solutions"] == full["n_solutions"]
    assert main(argv[:-2]) == 0
    assert "more (use --all)" in capsys.readouterr().out


def test_hooke_json_single_and_double(capsys):
    recs = _json(capsys, ["hooke", "--shaft-angle", "60", "--input-angle", "0", "90", "--format", "json"])
    assert [r["input_deg"] for r in recs] == [0.0, 90.0]
    assert recs[0]["ratio"] == pytest.approx(2.0) and recs[1]["ratio"] == pytest.approx(0.5)
    recs = _json(capsys, ["hooke", "--shaft-angle", "30", "--second-angle", "30", "--format", "json"])
    assert len(recs) == 25 and all(r["ratio"] == pytest.approx(1.0) for r in recs)
    assert all(r["output_deg"] == pytest.approx(r["input_deg"], abs=1e-9) for r in recs)


def test_hooke_table(capsys):
    assert main(["hooke", "--shaft-angle", "30", "--second-angle", "20", "--phase", "90", "--input-angle", "0"]) == 0
    assert "double coupling" in capsys.readouterr().out


@pytest.mark.parametrize(
    "argv, word",
    [
        (
            ["train", "search", "--ratio", "0", "--pairs", "2", "--min-teeth", "12", "--max-teeth", "60"],
            "ratio",
        ),
        (
            ["train", "search", "--ratio", "-3", "--pairs", "2", "--min-teeth", "12", "--max-teeth", "60"],
            "ratio",
        ),
        (
            ["train", "search", "--ratio", "nan", "--pairs", "2", "--min-teeth", "12", "--max-teeth", "60"],
            "ratio",
        ),
        (
            ["train", "search", "--ratio", "2", "--pairs", "2", "--min-teeth", "61", "--max-teeth", "60"],
            "min_teeth",
        ),
        (
            ["train", "search", "--ratio", "2", "--pairs", "0", "--min-teeth", "12", "--max-teeth", "60"],
            "--pairs",
        ),
        (
            ["train", "search", "--ratio", "2", "--pairs", "6", "--min-teeth", "12", "--max-teeth", "60"],
            "search space too large: 25,827,165",
        ),
        (["train", "design", "--ratio", "0"], "ratio"),
        (["train", "design", "--ratio", "2", "--min-teeth", "30", "--max-teeth", "20"], "min_teeth"),
        (["train", "design", "--ratio", "2", "--pairs", "0"], "--pairs"),
        (["train", "ratio", "--drivers", "20", "--followers", "60", "45"], "followers"),
        (["hooke", "--shaft-angle", "90"], "shaft_angle"),
        (["hooke", "--shaft-angle", "30", "--second-angle", "120"], "second_angle"),
        (["hooke", "--shaft-angle", "nan"], "--shaft-angle"),
        (["hooke", "--shaft-angle", "30", "--phase", "10"], "phase"),
    ],
)
def test_bad_input_exits_2_with_one_line(capsys, argv, word):
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and word in err
