"""CLI: gearlever mobility and gearlever zrdpm, good and bad input."""

import json

import pytest

from gearlever.cli import main


@pytest.mark.parametrize(
    "argv, out",
    [
        (["mobility", "--n", "5", "--p5", "8", "--p4", "0", "--w", "1"], "q = 2"),
        (["mobility", "--n", "7", "--p5", "8", "--p4", "3", "--q", "0"], "W = 2"),
        (["mobility", "--n", "9", "--p5", "12", "--p4", "3", "--q", "2"], "W = 2"),
    ],
)
def test_mobility_prints_the_papers_cases(capsys, argv, out):
    assert main(argv) == 0
    assert capsys.readouterr().out.strip() == out


def test_zrdpm_json_records(capsys):
    assert main(["zrdpm", "--contour", "1", "--phi", "0", "90", "--ratio", "0.5", "--format", "json"]) == 0
    recs = json.loads(capsys.readouterr().out)
    keys = ["phi_deg", "u_carrier", "u_gear", "e_carrier", "e_gear", "a_B_cm", "a_A_cm"]
    assert [list(r) for r in recs] == [keys] * 2
    assert recs[0]["u_carrier"] == pytest.approx(1.0) and recs[0]["u_gear"] == pytest.approx(1.0)
    assert recs[1]["e_gear"] == pytest.approx(-1.5)


def test_zrdpm_range_table_and_csv(capsys):
    assert main(["zrdpm", "--contour", "2", "--start", "0", "--stop", "360", "--step", "90"]) == 0
    lines = capsys.readouterr().out.strip().splitlines()
    assert lines[0].split() == ["phi_deg", "u_2", "u_7", "e_2", "e_7", "a_D_cm", "a_E_cm"] and len(lines) == 6
    assert main(["zrdpm", "--contour", "2", "--phi", "45", "--format", "csv"]) == 0
    out = capsys.readouterr().out.strip().splitlines()
    assert out[0] == "phi_deg,u_carrier,u_gear,e_carrier,e_gear,a_D_cm,a_E_cm"
    assert float(out[1].split(",")[1]) == pytest.approx(2**0.5)


def test_zrdpm_teeth_give_the_same_table_as_the_ratio(capsys):
    assert main(["zrdpm", "--contour", "1", "--phi", "10", "200", "--teeth", "20", "40", "--format", "csv"]) == 0
    by_teeth = capsys.readouterr().out
    assert main(["zrdpm", "--contour", "1", "--phi", "10", "200", "--ratio", "0.5", "--format", "csv"]) == 0
    assert capsys.readouterr().out == by_teeth


def test_zrdpm_internal_mesh_changes_the_gear_only(capsys):
    assert main(["zrdpm", "--contour", "1", "--phi", "30", "--mesh", "internal", "--format", "json"]) == 0
    rec = json.loads(capsys.readouterr().out)[0]
    # internal mesh: u_gear = (1 - k) u_carrier + k with k = 0.5
    assert rec["u_gear"] == pytest.approx(0.5 * rec["u_carrier"] + 0.5)


def test_zrdpm_writes_file_atomically(tmp_path, capsys):
    target = tmp_path / "out.json"
    assert main(["zrdpm", "--contour", "1", "--phi", "30", "--format", "json", "--out", str(target)]) == 0
    assert json.loads(target.read_text())[0]["phi_deg"] == 30.0
    assert [p.name for p in tmp_path.iterdir()] == ["out.json"]


@pytest.mark.parametrize(
    "argv, word",
    [
        (["mobility", "--n", "-1", "--p5", "8", "--p4", "0", "--w", "1"], "--n"),
        (["mobility", "--n", "5", "--p5", "8", "--p4", "0"], "--q"),
        (["mobility", "--n", "9", "--p5", "0", "--p4", "0", "--w", "1"], "w must"),
        (["mobility", "--n", "5", "--p5", "x", "--p4", "0", "--q", "1"], "--p5"),
        (["zrdpm", "--contour", "1", "--phi", "abc"], "--phi"),
        (["zrdpm", "--contour", "3"], "--contour"),
        (["zrdpm", "--contour", "1", "--l", "-2"], "--l"),
        (["zrdpm", "--contour", "1", "--r-a", "0"], "--r-a"),
        (["zrdpm", "--contour", "1", "--ratio", "0"], "--ratio"),
        (["zrdpm", "--contour", "1", "--start", "10", "--stop", "0"], "--stop"),
        (["zrdpm", "--contour", "1", "--step", "-5"], "--step"),
        (["zrdpm", "--contour", "1", "--phi", "1", "--start", "0"], "--phi"),
        (["zrdpm", "--contour", "1", "--teeth", "-20", "40"], "--teeth"),
        (["zrdpm", "--contour", "1", "--teeth", "0", "40"], "--teeth"),
        (["zrdpm", "--contour", "1", "--teeth", "20", "40", "--ratio", "2"], "--ratio"),
    ],
)
def test_bad_input_exits_2_with_one_line(capsys, argv, word, tmp_path):
    target = tmp_path / "never.csv"
    assert main([*argv, "--out", str(target)] if argv[0] == "zrdpm" else argv) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and word in err and "Traceback" not in err
    assert not target.exists() and list(tmp_path.iterdir()) == []


@pytest.mark.parametrize(
    "argv, needles",
    [
        (["--ratio", "1e308"], ["--ratio", "1e12"]),
        (["--start=-1e308", "--stop=1e308"], ["--start", "--stop", "overflows"]),
        (["--step", "1e-300"], ["--step", "cap 1,000,000"]),
        (["--step", "0.0001", "--stop", "999", "--format", "json"], ["--step", "cap 100,000 with --format json"]),
        (["--stop", "360", "--step", "0.0036", "--format", "json"], ["100001 angles", "cap 100,000"]),
    ],
)
def test_zrdpm_refuses_sizes_and_overflows_naming_the_users_flags(capsys, argv, needles, tmp_path):
    # known bugs: --ratio 1e308 spoke of the internal "r_lead"; the JSON output had no cap of its own
    target = tmp_path / "never.json"
    assert main(["zrdpm", "--contour", "1", *argv, "--out", str(target)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "Traceback" not in err and "r_lead" not in err
    for needle in needles:
        assert needle in err
    assert not target.exists()


def test_zrdpm_json_at_its_cap_is_written(capsys, tmp_path):
    target = tmp_path / "a.json"
    assert (
        main(
            [
                "zrdpm",
                "--contour",
                "1",
                "--stop",
                "359.9964",
                "--step",
                "0.0036",
                "--format",
                "json",
                "--out",
                str(target),
            ]
        )
        == 0
    )
    recs = json.loads(target.read_text())
    assert len(recs) == 100_000 and recs[-1]["phi_deg"] == pytest.approx(359.9964)


def test_zrdpm_point_accelerations_are_the_apis_a_B_a_A():
    """The CLI's a_B_cm, a_A_cm columns are the API's ``analogues(...).named(1)`` values (paper Table I names)."""
    import io
    from contextlib import redirect_stdout

    import numpy as np

    from gearlever import zrdpm

    buf = io.StringIO()
    with redirect_stdout(buf):
        assert main(["zrdpm", "--contour", "1", "--phi", "0", "30", "77", "--format", "json"]) == 0
    recs = json.loads(buf.getvalue())
    p = zrdpm.ZrdpmContour(contour=1).with_ratio(0.5)
    api = zrdpm.analogues(p, np.deg2rad([0.0, 30.0, 77.0])).named(1)
    assert [r["a_B_cm"] for r in recs] == pytest.approx(api["a_B"].tolist(), rel=1e-12)
    assert [r["a_A_cm"] for r in recs] == pytest.approx(api["a_A"].tolist(), rel=1e-12)
