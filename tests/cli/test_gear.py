"""``gearlever gear mesh|interference|profile``: JSON keys as issue 32 lists them, text with units, files, refusals."""

from __future__ import annotations

import json

import pytest

from gearlever.cli import main

KEYS = [
    "working_pressure_angle_deg",
    "center_distance",
    "center_distance_modification",
    "tip_shortening",
    "shift",
    "reference_diameter",
    "base_diameter",
    "tip_diameter",
    "root_diameter",
    "contact_ratio_transverse",
    "contact_ratio_overlap",
    "contact_ratio_total",
    "undercut",
    "min_teeth_no_undercut",
    "interference",
    "tip_thickness",
]


def test_mesh_json_keys_and_khk_values(capsys):
    """KHK's shifted pair (m 3, z 12/24, x 0.6/0.36) as printed on bolsover.com (Profile Shifted External Spur
    Gears): centre distance 56.500 and tip diameters 44.840, 79.400; the shifts' working angle is 26.0886 deg."""
    assert main(["gear", "mesh", "--module", "3", "--teeth", "12", "24", "--shift", "0.6", "0.36", "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert list(d) == KEYS
    assert d["working_pressure_angle_deg"] == pytest.approx(26.0886, abs=1e-4)
    assert d["center_distance"] == pytest.approx(56.4999, abs=0.5e-4)
    assert d["tip_diameter"] == pytest.approx([44.84, 79.40], abs=0.5e-3)
    for key in KEYS[4:]:
        if key not in ("contact_ratio_transverse", "contact_ratio_overlap", "contact_ratio_total"):
            assert isinstance(d[key], list) and len(d[key]) == 2, key
    assert d["contact_ratio_overlap"] is None  # no face width


def test_mesh_text_names_units_and_centre_distance_search(capsys):
    assert main(["gear", "mesh", "--module", "3", "--teeth", "12", "24", "--center-distance", "56.5"]) == 0
    out = capsys.readouterr().out
    assert "center distance                       56.5 mm" in out
    assert "working pressure angle (transverse)   26.0888" in out and " deg" in out
    assert "tip diameter" in out and out.count(" mm") >= 6


def test_mesh_helical_internal_and_rack(capsys):
    assert (
        main(["gear", "mesh", "--module", "2", "--teeth", "20", "40", "--helix", "15", "--face-width", "20", "--json"])
        == 0
    )
    d = json.loads(capsys.readouterr().out)
    assert d["contact_ratio_overlap"] > 0.8 and d["contact_ratio_total"] > d["contact_ratio_transverse"]
    assert (
        main(["gear", "mesh", "--module", "2", "--teeth", "20", "60", "--internal", "--shift", "0", "0.5", "--json"])
        == 0
    )
    d = json.loads(capsys.readouterr().out)
    assert d["tip_diameter"][1] < d["reference_diameter"][1] < d["root_diameter"][1]
    assert d["min_teeth_no_undercut"][1] is None
    assert main(["gear", "mesh", "--module", "1", "--teeth", "20", "--rack", "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert d["reference_diameter"][1] is None and d["working_pressure_angle_deg"] == pytest.approx(20.0)


def test_interference(capsys):
    """Shigley 9th ed. eq. 13-11: a 16-tooth 20 deg pinion meshes at most 101 teeth; 18 teeth take a rack."""
    assert main(["gear", "interference", "--teeth", "16"]) == 0
    assert "101 teeth" in capsys.readouterr().out
    assert main(["gear", "interference", "--teeth", "18", "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["rack_fits"] is True


@pytest.mark.parametrize("suffix", ["dxf", "svg", "csv"])
def test_profile_files(suffix, tmp_path):
    out = tmp_path / f"g.{suffix}"
    assert main(["gear", "profile", "--module", "2", "--teeth", "17", "--shift", "0.2", "--out", str(out)]) == 0
    if suffix == "dxf":
        import ezdxf

        doc = ezdxf.readfile(out)
        assert not doc.audit().has_errors
        (poly,) = doc.modelspace()
        assert poly.dxftype() == "LWPOLYLINE" and poly.closed and doc.header["$INSUNITS"] == 4
    elif suffix == "svg":
        assert out.read_text().startswith("<svg") and "<polygon" in out.read_text()
    else:
        rows = out.read_text().splitlines()
        assert rows[0] == "x_mm,y_mm" and len(rows) > 17 * 40


@pytest.mark.parametrize(
    "args, words",
    [
        (["mesh", "--module", "3", "--teeth", "12", "24", "--shift", "1.2", "0"], "--shift 1.2 points the tooth"),
        (["mesh", "--module", "0", "--teeth", "12", "24"], "--module"),
        (["mesh", "--module", "1", "--teeth", "12.5", "24"], "--teeth"),
        (["mesh", "--module", "1", "--teeth", "-3", "24"], "--teeth"),
        (["mesh", "--module", "1", "--teeth", "12", "24", "--face-width", "0"], "--face-width"),
        (["mesh", "--module", "1", "--teeth", "12", "24", "--helix", "45"], "--helix must be below 45 deg"),
        (["mesh", "--module", "1", "--teeth", "20", "26", "--internal"], "internal pair's tips interfere"),
        (["mesh", "--module", "1", "--teeth", "12", "24", "--center-distance", "10"], "--center-distance 10 cannot"),
        (
            ["mesh", "--module", "1", "--teeth", "12", "12", "--addendum", "0.6", "--dedendum", "0.85"],
            "--teeth 12 and 12 with --shift 0 and 0 and --addendum 0.6: contact ratio 0.9341 < 1, not a mesh",
        ),
        (["mesh", "--module", "1", "--teeth", "12", "--rack", "--addendum", "0.5"], "--teeth 12 with --shift 0 and"),
        (["mesh", "--module", "1", "--teeth", "12", "24", "--center-distance", "100"], "--center-distance 100 is not"),
        (
            ["mesh", "--module", "1", "--teeth", "12", "24", "--center-distance", "19.5"],
            "--center-distance 19.5 is not",
        ),
        (["mesh", "--module", "1", "--teeth", "0", "24"], "--teeth: must be a positive integer"),
        (["mesh", "--module", "-2", "--teeth", "12", "24"], "--module: must be a positive number"),
        (["mesh", "--module", "1", "--teeth", "12", "24", "--face-width", "-1"], "--face-width: must be a positive"),
        (["mesh", "--module", "1", "--teeth", "12", "24", "--helix", "-45"], "--helix must be below 45 deg"),
        (["mesh", "--module", "1", "--teeth", "30", "20", "--internal"], "--teeth: the ring's (the second) must"),
        (["mesh", "--module", "1", "--teeth", "12", "24", "--shift", "0.1"], "--shift takes 2 number(s), got 1"),
        (["profile", "--module", "1", "--teeth", "12", "--helix", "45", "--out", "g.csv"], "--helix must be below"),
        (["interference", "--teeth", "0"], "--teeth: must be a positive integer"),
        (["mesh", "--module", "1", "--teeth", "12"], "--teeth takes two"),
        (["profile", "--module", "1", "--teeth", "12", "--out", "g.txt"], "--out must end with"),
        (["profile", "--module", "1", "--teeth", "12", "--shift", "2", "--out", "g.csv"], "--shift 2 points"),
    ],
)
def test_bad_input_exits_2_with_one_line(args, words, capsys, tmp_path, monkeypatch):
    """Issue 32's bad input, each refused with exit 2 and one line naming the flag, no file written: a shift that
    points the tooth (with the largest shift that keeps 0.2 module), a contact ratio below 1 (with its value and
    the flags that set it), teeth that are not positive integers, a module or face width not above 0, a helix of
    45 deg or more, an internal pair whose tips interfere, a centre distance the shifts cannot reach (or reach
    only with pointed teeth or a contact ratio below 1)."""
    monkeypatch.chdir(tmp_path)
    assert main(["gear", *args]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and words in err, err
    assert not list(tmp_path.iterdir())


def test_mesh_reproduces_khks_helical_normal_system_table(capsys):
    """KHK's helical pair in the normal system as printed on bolsover.com (Profile Shifted External Helical Gear -
    Normal): --center-distance 125 with the shift on the pinion gives x 0.09809, alpha_wt 23.1126 deg, tips 48.154
    and 213.842 mm and contact ratios 1.294, 1.061 (half a unit of the printed digit)."""
    args = ["gear", "mesh", "--module", "3", "--teeth", "12", "60", "--helix", "30", "--center-distance", "125"]
    assert main([*args, "--split", "pinion", "--face-width", "20", "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert d["shift"] == pytest.approx([0.09809, 0.0], abs=0.5e-5)
    assert d["working_pressure_angle_deg"] == pytest.approx(23.1126, abs=0.5e-4)
    assert d["tip_diameter"] == pytest.approx([48.154, 213.842], abs=0.5e-3)
    assert d["contact_ratio_transverse"] == pytest.approx(1.294, abs=0.5e-3)
    assert d["contact_ratio_overlap"] == pytest.approx(1.061, abs=0.5e-3)
