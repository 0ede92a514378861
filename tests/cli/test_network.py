"""CLI runs: gearlever network FILE."""

import json

import pytest

from gearlever.cli import main

NUTTALL = """member,1,wheel
member,2,gear,n2
member,4,carrier
member,5,gear,n5
member,6,gear,n6
member,7,gear,n7
member,8,gear,n8
member,9,gear,n9
member,11,gear,n11
member,12,wheel
constraint,a,differential,2,5,4
constraint,b,differential,9,11,4
constraint,c,differential,6,8,frame
constraint,d,mesh,7,8,,1
constraint,e,mesh,7,6,,-1
constraint,f,shaft,1,2
constraint,g,shaft,5,6
constraint,h,shaft,8,9
constraint,i,shaft,11,12
"""
TEETH = "n2=30,n5=24,n6=18,n7=36,n8=20,n9=25,n11=40"


@pytest.fixture
def nuttall_file(tmp_path):
    f = tmp_path / "nuttall.csv"
    f.write_text(NUTTALL)
    return str(f)


def test_network_solves_nuttall_and_prints_relation_l(capsys, nuttall_file):
    assert main(["network", nuttall_file, "--teeth", TEETH, "--inputs", "1,12"]) == 0
    out = capsys.readouterr().out
    assert "degrees of freedom 2" in out and "(e) = -(c) + (d)" in out
    assert "rot_7 = -13/37*rot_1 + 72/185*rot_12" in out


def test_network_json(capsys, nuttall_file):
    assert main(["network", nuttall_file, "--teeth", TEETH, "--inputs", "1,12", "--format", "json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert (data["dof"], data["redundant"], data["dependencies"]) == (2, ["e"], {"e": {"c": "-1", "d": "1"}})
    assert data["coefficients"]["7"] == ["-13/37", "72/185"]


@pytest.mark.parametrize(
    "text, extra, needle",
    [
        (
            "member,a,gear,10\nmember,b,gear,20\nmember,c,gear,30\n"
            "constraint,ab,mesh,a,b\nconstraint,bc,mesh,b,c\nconstraint,ca,mesh,c,a\n",
            [],
            "constraint (ca) locks",
        ),
        ("member,a,gear,10\nconstraint,k,mesh,a,zz\n", [], "unknown gear 'zz'"),
        ("member,a,gear,-4\n", [], "gear 'a': teeth must be a positive integer"),
        ("member,a,gear,n\n", ["--teeth", "n=x"], "--teeth n must be an integer"),
        (
            "member,a,gear,10\nmember,b,gear,20\nconstraint,ab,mesh,a,b\n",
            ["--inputs", "a,b"],
            "needs 1 input",
        ),
    ],
)
def test_network_bad_input_exit_2_one_line(capsys, tmp_path, text, extra, needle):
    f = tmp_path / "net.csv"
    f.write_text(text)
    assert main(["network", str(f), *extra]) == 2
    err = capsys.readouterr().err
    assert needle in err and len(err.strip().splitlines()) == 1


def test_network_missing_file_exit_2(capsys, tmp_path):
    assert main(["network", str(tmp_path / "none.csv")]) == 2
    assert "cannot be read" in capsys.readouterr().err


EXAMPLES = __import__("pathlib").Path(__file__).resolve().parents[2] / "examples"


def test_network_tabular_ferguson_table_and_json(capsys):
    f = str(EXAMPLES / "ferguson_paradox.csv")
    assert main(["network", f, "--inputs", "arm", "--tabular", "arm"]) == 0
    out = capsys.readouterr().out
    assert "rot_w99 = -1/99*rot_arm" in out and "rot_w101 = 1/101*rot_arm" in out and "rot_w100 = 0" in out
    assert "tabular method: carrier arm" in out
    line = next(ln for ln in out.splitlines() if ln.startswith("w99 "))
    assert [c.strip() for c in line.split("|")] == [
        "w99",
        "99",
        "100/99",
        "-100/99*rot_arm",
        "rot_arm",
        "-1/99*rot_arm",
    ]
    assert main(["network", f, "--inputs", "arm", "--tabular", "arm", "--format", "json"]) == 0
    data = json.loads(capsys.readouterr().out)
    rows = {r["member"]: r for r in data["tabular"]["rows"]}
    assert rows["w101"] == {"member": "w101", "teeth": 101, "relative": "100/101", "total": ["1/101"]}
    assert data["tabular"]["x"] == ["-1"] and data["tabular"]["y"] == ["1"]


@pytest.mark.parametrize(
    "text, extra, needle",
    [
        ("", [], "no member records"),
        ("# nothing\n", [], "no member records"),
        (
            "member,s,gear,30\nmember,p,gear,20\nconstraint,m,mesh,s,p,arm,1\n",
            [],
            "constraint (m): unknown gear 'arm'",
        ),
        ("member,s,gear,30\nmember,p,gear,20\nconstraint,m,mesh,s,p,p,1\n", [], "carrier 'p' must differ"),
        ("member,s,gear,30\nmember,c\nconstraint,d,differential,s,frame,c\n", [], "frame cannot be a side gear"),
        ("member,p,gear,20\nmember,a\nconstraint,m,mesh,frame,p,a\n", [], "frame cannot mesh on carrier 'a'"),
        ("member,s,gear,0\n", [], "teeth must be a positive integer"),
        (
            "member,s,gear,30\nmember,p,gear,20\nmember,a\nconstraint,m,mesh,s,p,a\n",
            ["--inputs", "s,a", "--tabular", "zz"],
            "carrier 'zz' is not a member",
        ),
        (
            "member,s,gear,30\nmember,p,gear,20\nmember,a\nconstraint,m,mesh,s,p,a\n",
            ["--tabular", "a"],
            "--tabular needs --inputs",
        ),
    ],
)
def test_network_carrier_and_empty_file_errors_exit_2_one_line(capsys, tmp_path, text, extra, needle):
    f = tmp_path / "net.csv"
    f.write_text(text)
    assert main(["network", str(f), *extra]) == 2
    err = capsys.readouterr().err
    assert needle in err and len(err.strip().splitlines()) == 1


def test_network_torques_of_a_planetary_with_the_ring_held(capsys):
    """Sun 24, ring 60 held: carrier torque -T_sun (1 + z_r/z_s); with mesh efficiency eta the
    sun-planet-ring path in the carrier's frame loses eta^2 (Macmillan 1961)."""
    argv = ["network", str(EXAMPLES / "simple_planetary.csv"), "--inputs", "sun"]
    argv += ["--torque", "sun=100", "--loads", "carrier", "--format", "json"]
    assert main(argv) == 0
    d = json.loads(capsys.readouterr().out)
    assert d["torques"]["carrier"] == -350 and d["frame_reactions"]["fix"] == 250
    assert sum(d["power"].values()) == 0
    assert main(argv + ["--efficiency", "0.98"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert d["torques"]["carrier"] == pytest.approx(-100 * (1 + 0.98**2 * 60 / 24), rel=1e-12)


def test_network_torque_efficiency_outside_the_unit_interval_exits_2(capsys):
    argv = ["network", str(EXAMPLES / "simple_planetary.csv"), "--inputs", "sun", "--torque", "sun=1"]
    assert main(argv + ["--loads", "carrier", "--efficiency", "1.5"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "--efficiency" in err
