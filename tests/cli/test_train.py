"""CLI tests: gearlever train ratio|design|search."""

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
    assert len(short["solutions"]) == 20 < len(full["solutions"]) == full["n_solutions"] == full["count"]
    out = tmp_path / "s.json"
    assert main(argv + ["--out", str(out)]) == 0
    assert json.loads(out.read_text())["n_solutions"] == full["n_solutions"]
    assert main(argv[:-2]) == 0
    assert "more, counted but not listed" in capsys.readouterr().out


S = ["train", "search", "--pairs", "2", "--min-teeth", "12", "--max-teeth", "60", "--ratio"]


@pytest.mark.parametrize(
    "argv, word",
    [
        (S + ["0"], "--ratio"),
        (S + ["-3"], "--ratio"),
        (S + ["nan"], "--ratio"),
        (S + ["1/3/4"], "--ratio"),
        (S + ["1e99999"], "--ratio"),
        (S + ["1" * 65], "--ratio must be at most 64 characters"),
        (["train", "search", "--ratio", "2", "--pairs", "2", "--min-teeth", "61", "--max-teeth", "60"], "--min-teeth"),
        (["train", "search", "--ratio", "2", "--pairs", "0"], "--pairs"),
        (["train", "search", "--ratio", "2", "--pairs", "13"], "--pairs: must be at most 12"),
        (
            ["train", "search", "--ratio", "2", "--pairs", "2", "--max-teeth", "10001"],
            "--max-teeth: must be at most 10^4",
        ),
        (["train", "search", "--ratio", "2", "--pairs", "2", "--limit", "1001"], "--limit: must be at most 10^3"),
        (
            ["train", "search", "--ratio", "2", "--pairs", "2", "--max-space", "20000001"],
            "--max-space: must be at most",
        ),
        (["train", "search", "--ratio", "2", "--pairs", "6"], "--max-space: search space too large: 25,827,165"),
        (["train", "search", "--ratio", "2", "--pairs", "12", "--min-teeth", "30", "--max-teeth", "30"], "--max-teeth"),
        (["train", "design", "--ratio", "0"], "--ratio"),
        (["train", "design", "--ratio", "1/3/4"], "--ratio"),
        (["train", "design", "--ratio", "2", "--min-teeth", "30", "--max-teeth", "20"], "--min-teeth"),
        (["train", "design", "--ratio", "2", "--pairs", "0"], "--pairs"),
        (["train", "design", "--ratio", "2", "--keep", "1001"], "--keep: must be at most 10^3"),
        (["train", "design", "--ratio", "1e-20"], "--ratio"),
        (["train", "ratio", "--drivers", "20", "--followers", "60", "45"], "--followers"),
    ],
)
def test_bad_input_exits_2_with_one_line_naming_the_flag(capsys, argv, word):
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and word in err and "Traceback" not in err
    assert "max_teeth" not in err and "min_teeth" not in err and "max_space" not in err


def test_search_counts_without_listing_and_defaults(capsys):
    # --min-teeth 12 and --max-teeth 60 by default; 78 million sets counted, 20 listed
    rec = _json(capsys, ["train", "search", "--ratio", "3", "--pairs", "5", "--format", "json"])
    assert (rec["min_teeth"], rec["max_teeth"], rec["listed"], rec["limit"]) == (12, 60, 20, 20)
    assert rec["count"] == 78477517 and rec["n_ordered"] == 845740940215
    rec = _json(capsys, ["train", "search", "--ratio", "3", "--pairs", "2", "--limit", "3", "--format", "json"])
    assert len(rec["solutions"]) == 3 and rec["count"] > 3


def test_search_design_ratio_forms_agree(capsys):
    # "1/6.931", "1000/6931" and "0.144279324773..." name different targets only in the last
    a = _json(
        capsys, ["train", "design", "--ratio", "1/6.931", "--min-teeth", "12", "--max-teeth", "60", "--format", "json"]
    )
    b = _json(
        capsys,
        ["train", "design", "--ratio", "1000/6931", "--min-teeth", "12", "--max-teeth", "60", "--format", "json"],
    )
    assert a["target"] == b["target"] == "1000/6931" and a["designs"] == b["designs"]
