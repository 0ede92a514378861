"""The worked examples of law synthesis (bench_law.py --examples): a figure per kind, the table against the cam."""

import math

import pandas as pd
import pytest

from gearlever.data import example_path
from gearlever.laws import load_law
from gearlever.reproduce import _law_synthesis as step
from gearlever.synthesis.law import synthesize_law
from gearlever.synthesis.law.measure import cam_comparison, law_report


@pytest.fixture(scope="module")
def written(tmp_path_factory):
    folder = tmp_path_factory.mktemp("law")
    mp = pytest.MonkeyPatch()
    mp.setattr(step, "BUDGET", 3000)  # the step's logic at a test's budget; make reproduce runs the real one
    try:
        lines = step.run(folder, folder)
    finally:
        mp.undo()
    return folder, lines


def test_a_figure_per_kind_and_one_table_row_each(written):
    folder, lines = written
    assert len(lines) == len(step.CASES) + 1
    for kind in step.CASES:
        assert (folder / f"law_synthesis_{kind.replace('-', '_')}.png").read_bytes()[:4] == b"\x89PNG"
    df = pd.read_csv(folder / "law_synthesis.csv")
    assert list(df.kind) == list(step.CASES) and list(df.law) == list(step.CASES.values())


def test_table_values_are_the_synthesis_report_and_the_cam_at_four_digits(written):
    folder, _ = written
    df = pd.read_csv(folder / "law_synthesis.csv").set_index("kind")
    for kind in ("fourbar", "slider-crank"):
        law = load_law(example_path(f"{step.CASES[kind]}.toml"))
        rep = law_report(synthesize_law(law, kind=kind, seed=step.SEED, budget=3000, workers=1))
        u = "_deg" if law.output == "angle" else ""
        assert df.loc[kind, "error_max"] == pytest.approx(rep[f"error_max{u}"], rel=6e-4)
        assert df.loc[kind, "transmission_min_deg"] == pytest.approx(rep["transmission_deg"][0], rel=6e-4)
        cam = cam_comparison(law)
        assert df.loc[kind, "cam_base_radius"] == pytest.approx(cam["base_radius"], rel=6e-4)
        assert df.loc[kind, "cam_pressure_angle_max_deg"] == pytest.approx(30.0, abs=0.01)
    # a dwell's excursion is the achieved output's spread over it: never more than twice the error there
    ang = df[df.unit == "deg"]
    assert (ang.dwell_excursion <= 2 * ang.dwell_error_max + 1e-3).all()
    assert math.isclose(df.loc["fourbar", "law_peak_acceleration_per_rad2"], 64.46, rel_tol=1e-3)
