"""The reproduce step of linkage synthesis writes its two figures and the published checks, from the library."""

import numpy as np
import pandas as pd
import pytest

from gearlever.data import example_path, read_records
from gearlever.reproduce import synthesis
from gearlever.synthesis.function import function_targets, synthesize_function
from gearlever.synthesis.motion import synthesize_motion

FILES = ("synthesis_function_log10.png", "synthesis_motion_five_poses.png", "synthesis_checks.csv")


@pytest.fixture(scope="module")
def step(tmp_path_factory):
    folder = tmp_path_factory.mktemp("synthesis")
    lines = synthesis.run(folder, folder)
    return folder, lines


def test_synthesis_step_writes_both_figures_and_the_table(step):
    folder, lines = step
    for name in FILES:
        assert (folder / name).is_file() and (folder / name).stat().st_size > 0, name
    assert (folder / FILES[0]).read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert len(lines) == 3 and all(line.startswith("synthesis: ") for line in lines)


def test_synthesis_checks_table_agrees_with_the_library_and_the_data_file(step):
    folder, lines = step
    df = pd.read_csv(folder / "synthesis_checks.csv")
    published = read_records("synthesis_published.csv")
    assert len(df) == len(published) and bool(df.within.all())
    assert list(df.quantity) == [r["quantity"] for r in published]
    np.testing.assert_array_equal(df.published, [float(r["published"]) for r in published])
    np.testing.assert_array_equal(df.tolerance, [float(r["tolerance"]) for r in published])
    # computed: the library directly, from the printed problem data
    p = synthesis.published_problems()["su-lecture-12"]
    r = synthesize_function(np.radians(p["input_angle_deg"]), np.radians(p["output_angle_deg"]), ground=p["ground"])
    K1, K2, K3 = r.coefficients
    want = {"z1": K3, "z2": K1, "z3": K2, **r.lengths}
    np.testing.assert_allclose(df.computed, [want[q] for q in df.quantity], rtol=1e-8)
    np.testing.assert_allclose(df.deviation, df.computed - df.published, rtol=2e-3, atol=1e-12)
    assert df.source.str.contains("Lecture 12, slide 13").all()
    assert f"{len(df)}/{len(df)} published answers" in lines[2]


def test_synthesis_step_lines_report_the_library_results(step):
    _, lines = step
    t = function_targets("log10(x)", (1, 2), np.radians([45, 105]), np.radians([135, 225]))
    r = synthesize_function(t.input_angle, t.target, target_at=t.target_at, input_range=t.input_range)
    assert f"max structural error {np.degrees(r.structural_error_max):.3f} deg over 45..105 deg" in lines[0]
    poses = pd.read_csv(example_path("motion_poses.csv"))
    m = synthesize_motion(poses[["x", "y"]].to_numpy(), np.radians(poses.angle_deg.to_numpy()))
    assert f"{len(m.dyads)} Burmester point pairs" in lines[1]
    assert f"crank {m.best.lengths['crank']:.6g}" in lines[1] and m.best.residual < 1e-9


def test_synthesis_step_output_is_identical_on_a_second_run(step):
    folder, _ = step
    first = {name: (folder / name).read_bytes() for name in FILES}
    synthesis.run(folder, folder)
    for name in FILES:
        assert (folder / name).read_bytes() == first[name], name
