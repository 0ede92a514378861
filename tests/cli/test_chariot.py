"""CLI runs: gearlever chariot nuttall|simulate and gearlever differential car."""

import json

import pytest

from gearlever.cli import main

TEETH = ["--n2", "30", "--n5", "24", "--n6", "18", "--n7", "36", "--n8", "20", "--n9", "25", "--n11", "40"]
UP2 = ["--n2", "20", "--n5", "20", "--n6", "20", "--n7", "40", "--n8", "20", "--n9", "20", "--n11", "20"]


def run(capsys, *argv):
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


def test_nuttall_json_keys_and_exact_fractions(capsys):
    code, out, err = run(capsys, "chariot", "nuttall", *UP2, "--track", "3", "--format", "json")
    assert code == 0 and err == ""
    data = json.loads(out)
    assert {"d1", "d12", "d1_fraction", "d12_fraction", "dof", "redundant"} <= set(data)
    assert (data["d1"], data["d12"], data["d1_fraction"], data["d12_fraction"]) == (1.5, 1.5, "1/2", "1/2")
    assert data["dof"] == 2 and data["redundant"] == ["e"]


def test_nuttall_table(capsys):
    code, out, _ = run(capsys, "chariot", "nuttall", *TEETH)
    assert code == 0
    assert "26/37 t" in out and "144/185 t" in out and "degrees of freedom 2" in out
    assert "(e) = -(c) + (d)" in out


def test_simulate_exact_wheels_json(capsys):
    code, out, _ = run(
        capsys,
        "chariot",
        "simulate",
        "--design",
        "nuttall",
        *TEETH,
        "--path",
        "random",
        "--turns",
        "5",
        "--seed",
        "2",
        "--format",
        "json",
    )
    assert code == 0
    data = json.loads(out)
    assert {"max_drift_rad", "final_drift_rad", "distance", "turns"} <= set(data)
    assert data["turns"] == pytest.approx(5, rel=1e-9)
    assert data["max_drift_rad"] < 1e-9 * data["turns"]


def test_simulate_one_percent_wrong_d1_reports_the_drift(capsys):
    code, out, _ = run(capsys, "chariot", "simulate", *TEETH, "--d1", str(26 / 37 * 1.01), "--turns", "5")
    assert code == 0
    assert "pointer drift: max" in out
    code, out, _ = run(
        capsys, "chariot", "simulate", *TEETH, "--d1", str(26 / 37 * 1.01), "--turns", "5", "--format", "json"
    )
    assert json.loads(out)["max_drift_rad"] > 0.01


@pytest.mark.parametrize("text", ["x,y\n0,0\n4,0\n4,3\n", "0 0\n4 0   # corner\n\n4 3\n"])
def test_simulate_waypoints_csv_and_whitespace(capsys, tmp_path, text):
    f = tmp_path / "pts.txt"
    f.write_text(text)
    code, out, _ = run(capsys, "chariot", "simulate", *TEETH, "--waypoints", str(f), "--format", "json")
    assert code == 0
    data = json.loads(out)
    assert data["distance"] == pytest.approx(7.0, rel=1e-12)
    assert data["turns"] == pytest.approx(0.25, rel=1e-12)
    assert data["max_drift_rad"] < 1e-12


@pytest.mark.parametrize(
    "argv",
    [
        ["chariot"],
        ["differential"],
        ["chariot", "nuttall", *TEETH[:-1], "0"],
        ["chariot", "nuttall", "--n2", "20"],
        ["chariot", "nuttall", *TEETH, "--track", "-1"],
        ["chariot", "simulate", *TEETH, "--turns", "0"],
        ["chariot", "simulate", *TEETH, "--waypoints", "/nonexistent/file.csv"],
        ["chariot", "simulate", *TEETH, "--d1", "nan"],
        [
            "differential",
            "car",
            "--pinion-teeth",
            "0",
            "--ring-teeth",
            "41",
            "--pinion-speed",
            "1",
            "--pinion-torque",
            "1",
        ],
        [
            "differential",
            "car",
            "--pinion-teeth",
            "11",
            "--ring-teeth",
            "41",
            "--pinion-speed",
            "1",
            "--pinion-torque",
            "1",
            "--turn-radius",
            "5",
        ],
        [
            "differential",
            "car",
            "--pinion-teeth",
            "11",
            "--ring-teeth",
            "41",
            "--pinion-speed",
            "1",
            "--pinion-torque",
            "1",
            "--turn-radius",
            "0",
            "--track",
            "1",
        ],
    ],
)
def test_bad_input_exit_2_one_line(capsys, argv):
    code, out, err = run(capsys, *argv)
    assert code == 2 and out == ""
    assert len(err.strip().splitlines()) == 1 and "Traceback" not in err


def test_bad_waypoints_file_content_exit_2(capsys, tmp_path):
    f = tmp_path / "bad.csv"
    f.write_text("0 0\n1 two\n")
    code, _, err = run(capsys, "chariot", "simulate", *TEETH, "--waypoints", str(f))
    assert code == 2 and "waypoints line 2" in err and len(err.strip().splitlines()) == 1


CAR = [
    "differential",
    "car",
    "--pinion-teeth",
    "11",
    "--ring-teeth",
    "41",
    "--pinion-speed",
    "300",
    "--pinion-torque",
    "100",
]
KEYS = {
    "carrier_speed",
    "left_speed",
    "right_speed",
    "ring_torque",
    "left_torque",
    "right_torque",
    "power_in",
    "power_out",
}


def test_car_straight_turn_and_held_wheel(capsys):
    code, out, _ = run(capsys, *CAR, "--format", "json")
    straight = json.loads(out)
    assert code == 0 and set(straight) == KEYS
    assert straight["left_speed"] == straight["right_speed"] == straight["carrier_speed"]
    code, out, _ = run(capsys, *CAR, "--turn-radius", "5", "--track", "1.5", "--format", "json")
    turn = json.loads(out)
    assert turn["left_speed"] == pytest.approx(straight["carrier_speed"] * (1 - 0.15), rel=1e-12)
    code, out, _ = run(capsys, *CAR, "--left-speed", "0", "--format", "json")
    held = json.loads(out)
    assert held["right_speed"] == pytest.approx(2 * held["carrier_speed"], rel=1e-15)
    assert held["power_in"] == pytest.approx(held["power_out"], rel=1e-12)
    code, out, _ = run(capsys, *CAR)
    assert code == 0 and "power_out" in out


def test_out_file_written(capsys, tmp_path):
    f = tmp_path / "o.json"
    code, out, _ = run(capsys, *CAR, "--format", "json", "--out", str(f))
    assert code == 0 and out == "" and set(json.loads(f.read_text())) == KEYS


@pytest.mark.parametrize(
    ("extra", "words"),
    [
        (["--turns", "1e9"], ["--turns", "at most 10^7"]),
        (["--turns", "1e5"], ["--turns", "--steps-per-turn", "cap 10^7"]),
        (["--steps-per-turn", "100000000"], ["--steps-per-turn", "at most 10^7"]),
        (["--turns", "20000", "--steps-per-turn", "1000"], ["cap 10^7"]),
        (["--n7", "10000000"], ["--n7", "at most 10^6"]),
        (["--step", "0.1"], ["--step", "--waypoints"]),
    ],
)
def test_simulate_caps_refuse_with_the_cap_named(capsys, extra, words):
    code, out, err = run(capsys, "chariot", "simulate", *TEETH, *extra)
    assert code == 2 and out == "" and err.count("\n") == 1
    assert all(w in err for w in words), err


@pytest.mark.parametrize("flag", [["--turns", "3"], ["--seed", "1"], ["--steps-per-turn", "10"], ["--heading", "1"]])
def test_random_path_options_with_waypoints_are_refused(capsys, tmp_path, flag):
    f = tmp_path / "pts.txt"
    f.write_text("0 0\n1 0\n")
    code, _, err = run(capsys, "chariot", "simulate", *TEETH, "--waypoints", str(f), *flag)
    assert code == 2 and flag[0] in err and "--waypoints" in err and err.count("\n") == 1


def test_waypoint_step_too_small_is_refused_before_allocating(capsys, tmp_path):
    f = tmp_path / "pts.txt"
    f.write_text("0 0\n1 0\n1 1\n")
    code, _, err = run(capsys, "chariot", "simulate", *TEETH, "--waypoints", str(f), "--step", "1e-9")
    assert code == 2 and err.startswith("gearlever: error: --step") and "10,000,000" in err


def test_waypoint_step_within_the_cap_runs(capsys, tmp_path):
    f = tmp_path / "pts.txt"
    f.write_text("0 0\n1 0\n")
    code, out, _ = run(
        capsys, "chariot", "simulate", *TEETH, "--waypoints", str(f), "--step", "1e-6", "--format", "json"
    )
    assert code == 0 and json.loads(out)["steps"] == 1_000_000


@pytest.mark.parametrize("name", ["/dev/zero", "/proc", "/etc/hostname/x", "{tmp}/empty.txt", "{tmp}/garbage.bin"])
def test_unreadable_or_empty_waypoint_files_exit_2(capsys, tmp_path, name):
    (tmp_path / "empty.txt").write_text("")
    (tmp_path / "garbage.bin").write_bytes(b"\xff\xfe\x00garbage")
    name = name.replace("{tmp}", str(tmp_path))
    code, out, err = run(capsys, "chariot", "simulate", *TEETH, "--waypoints", name)
    assert code == 2 and out == "" and err.count("\n") == 1 and "waypoints" in err


def test_waypoint_file_above_the_byte_cap_is_refused(capsys, tmp_path, monkeypatch):
    import gearlever.cli.chariot as cli_chariot

    monkeypatch.setattr(cli_chariot, "MAX_WAYPOINT_BYTES", 100)
    f = tmp_path / "big.txt"
    f.write_text("0 0\n" * 100)
    code, _, err = run(capsys, "chariot", "simulate", *TEETH, "--waypoints", str(f))
    assert code == 2 and "cap of 100 bytes" in err
