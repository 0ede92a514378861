"""``gearlever mechanism ...`` on a linkage in the challenge's form (.links.json): runs, or exits 2 in one line."""

from __future__ import annotations

import csv
import io
import json

import numpy as np
import pytest

from gearlever.cli import main
from gearlever.mechanism.linkage import linkage_from_dict, solve_plan
from gearlever.synthesis.curve.simulate import simulate
from tests.synthesis.curve._designs import SIXBAR


def test_analyze_and_structure_open_a_links_json(tmp_path, capsys):
    p = tmp_path / "0001.links.json"
    p.write_text(json.dumps(SIXBAR))
    assert main(["mechanism", "analyze", str(p), "--points", "4", "--input", "0", "270"]) == 0
    rows = list(csv.DictReader(io.StringIO(capsys.readouterr().out)))
    lk = linkage_from_dict(SIXBAR)
    x = simulate(lk.x0[None], solve_plan(lk), thetas=np.radians([0, 90, 180, 270]))[0, 6]
    got = np.array([[float(r["P_x_len"]), float(r["P_y_len"])] for r in rows])
    np.testing.assert_allclose(got, x, rtol=0, atol=1e-9)
    assert main(["mechanism", "structure", str(p), "--format", "json"]) == 0
    assert json.loads(capsys.readouterr().out)["dof"] == 1


@pytest.mark.parametrize(
    "command", [["analyze"], ["structure"], ["draw", "--out", "d.png"], ["view", "--out", "v.html"]]
)
@pytest.mark.parametrize(
    "edit, needle",
    [
        ({"motor": [1, 0]}, "motor"),
        ({"edges": [[0, 1], [1, 9]]}, "edges[1]"),
        ({"fixed_joints": [0]}, "edges"),
    ],
)
def test_a_bad_links_json_exits_2_with_one_line_and_no_file(tmp_path, capsys, monkeypatch, command, edit, needle):
    monkeypatch.chdir(tmp_path)
    p = tmp_path / "bad.links.json"
    p.write_text(json.dumps({**SIXBAR, **edit}))
    before = sorted(tmp_path.iterdir())
    assert main(["mechanism", command[0], str(p), *command[1:]]) == 2
    err = capsys.readouterr().err.strip()
    assert "\n" not in err and "bad.links.json" in err and needle in err
    assert sorted(tmp_path.iterdir()) == before
