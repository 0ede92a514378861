"""Function generation's pairs check and summary (gearlever.synthesis.report) against the CLI's report."""

import json
import math

import numpy as np
import pytest

from gearlever.cli import main
from gearlever.errors import GearleverError
from gearlever.synthesis.function import synthesize_function
from gearlever.synthesis.report import MAX_PAIR_DEG, angle_offsets, check_pairs, function_summary


@pytest.mark.parametrize(
    "inputs, outputs, slider, needle",
    [
        ([10, 20], [1, 2], False, "PAIRS: function generation needs at least 3 targets, got 2"),
        ([10, 20, 1e6], [1, 2, 3], False, f"PAIRS row 4 column input_deg: must be at most {MAX_PAIR_DEG:g} in size"),
        ([10, 20, 30], [1, 2, 1e300], True, "PAIRS row 4 column output: must be at most 1e+12 in size"),
        ([0, 200, 400], [1, 2, 3], False, "PAIRS column input_deg: the targets span 400 deg"),
        ([10, 20, 10], [1, 2, 3], False, "PAIRS row 4 column input_deg: repeats row 2 (10)"),
    ],
)
def test_check_pairs_refuses_naming_row_and_column(inputs, outputs, slider, needle):
    with pytest.raises(GearleverError) as err:
        check_pairs(inputs, outputs, slider=slider, where="PAIRS")
    assert needle in str(err.value)


def test_check_pairs_names_the_files_lines_when_given():
    with pytest.raises(GearleverError, match="row 9 column input_deg: repeats row 5"):
        check_pairs([10, 20, 10], [1, 2, 3], slider=False, where="PAIRS", lines=[5, 7, 9])


def test_summary_is_the_cli_report_without_the_time(tmp_path, capsys):
    pairs = tmp_path / "p.csv"
    pairs.write_text("input_deg,output_deg\n30,40\n60,55\n90,75\n120,90\n")
    rep = tmp_path / "r.json"
    assert main(["synthesize", "function", str(pairs), "--out", str(tmp_path / "m.toml"), "--report", str(rep)]) == 0
    cli = json.loads(rep.read_text())
    res = synthesize_function(np.radians([30, 60, 90, 120]), np.radians([40, 55, 75, 90]), kind="fourbar")
    lib = json.loads(json.dumps(function_summary(res, warnings=cli["warnings"], time_s=cli["time_s"])))
    assert lib == cli


def test_offsets_are_whole_degrees_of_the_result():
    res = synthesize_function(np.radians([30, 60, 90]), np.radians([40, 55, 75]), kind="fourbar")
    off = angle_offsets(res)
    assert off["crank"] == round(math.degrees(res.input_offset)) and off["crank"] % 180 == 0
    assert off["rocker"] in (0, 180)
