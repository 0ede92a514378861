"""ZRDPM tables and the reproduce step: columns, deviations, determinism."""

import numpy as np
import pandas as pd
import pytest

from gearlever.reproduce import zrdpm as step
from gearlever.tables import zrdpm as tabs
from gearlever.tables._common import write_csv

TOL_CM = 0.005  # issue 2: every published value within 0.005 cm


@pytest.fixture(scope="module")
def reps():
    return [tabs.reproduce("I"), tabs.reproduce("II")]


@pytest.fixture(scope="module")
def written(tmp_path_factory, reps):
    tdir, fdir = tmp_path_factory.mktemp("tables"), tmp_path_factory.mktemp("figures")
    lines = step.run(tdir, fdir)
    return tdir, fdir, lines


def test_comparison_frame_has_published_computed_deviation_and_self_consistent(reps):
    df = tabs.comparison_frame(reps[0])
    for c in ("a_B", "a_A"):
        for suffix in (
            "printed",
            "corrected",
            "published_cm",
            "computed_cm",
            "deviation_cm",
            "selfconsistent_cm",
        ):
            assert f"{c}_{suffix}" in df.columns
        np.testing.assert_allclose(df[f"{c}_deviation_cm"], df[f"{c}_computed_cm"] - df[f"{c}_published_cm"])
        assert df[f"{c}_deviation_cm"].abs().max() < TOL_CM
        # the self-consistent model is shown, and it is far from the print
        assert (df[f"{c}_selfconsistent_cm"] - df[f"{c}_published_cm"]).abs().max() > 1.0
    assert len(df) == 12 and list(df["phi_deg"]) == list(range(30, 361, 30))
    assert {"u_1_selfconsistent", "e_1_selfconsistent", "l_u2_recovered_cm"} <= set(df.columns)


def test_table2_uses_contour2_names(reps):
    df = tabs.comparison_frame(reps[1])
    assert "a_D_published_cm" in df.columns and "u_2_selfconsistent" in df.columns


def test_constants_frame_lists_both_models_with_residuals(reps):
    df = tabs.constants_frame(reps)
    tables_rows = df[(df.model == "tables") & (df.parameter == "l_u2")]
    assert len(tables_rows) == 2
    assert (tables_rows["max_abs_residual_cm"] < TOL_CM).all()
    assert set(df.model) == {"tables", "self-consistent"}


def test_mobility_frame_agrees_with_the_paper():
    df = tabs.mobility_frame()
    assert len(df) == 3 and df["agrees"].all()
    assert (df["w_computed"] == df["w_published"]).all()


def test_analogue_frame_columns():
    from gearlever import zrdpm

    df = tabs.analogue_frame(zrdpm.ZrdpmContour(contour=2), [0.0, 90.0])
    assert list(df.columns) == ["phi_deg", "u_2", "u_7", "e_2", "e_7", "a_D_cm", "a_E_cm"]


def test_reproduce_writes_every_file_and_summarises_each_table(written):
    tdir, fdir, lines = written
    for name in step.TABLE_FILES:
        assert (tdir / name).stat().st_size > 100
    for name in step.FIGURE_FILES:
        assert (fdir / name).read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert len(lines) == 3
    assert lines[0].startswith("zrdpm: table1.csv: 24 values, max |deviation| 0.00")
    assert "l*u^2 = 21.00" in lines[0] and "l*e = -2.240" in lines[1]


def test_reproduced_csv_reads_back_and_is_byte_identical_on_rewrite(written, reps, tmp_path):
    tdir, _, _ = written
    df = pd.read_csv(tdir / "table1.csv")
    assert df["a_B_deviation_cm"].abs().max() < TOL_CM
    write_csv(tabs.comparison_frame(reps[0]), tmp_path / "again.csv")
    assert (tmp_path / "again.csv").read_bytes() == (tdir / "table1.csv").read_bytes()
    write_csv(tabs.constants_frame(reps), tmp_path / "c.csv")
    assert (tmp_path / "c.csv").read_bytes() == (tdir / "identified_constants.csv").read_bytes()


def test_written_numbers_carry_the_decimals_their_data_support(written):
    # Regeneration must be byte-identical on any machine: every float in the
    # ZRDPM CSVs is rounded (5 decimals for closed forms and the linear fit,
    # 4 / 3 for the nonlinear self-consistent fit in cm / degrees), so that
    # last-bit differences of BLAS or scipy between machines cannot show.
    tdir, _, _ = written
    for name in ("table1.csv", "table2.csv", "identified_constants.csv"):
        df = pd.read_csv(tdir / name)
        for col in df.select_dtypes("float").columns:
            v = df[col].to_numpy()
            assert np.array_equal(v, np.round(v, tabs.DECIMALS_CM)), (name, col)
    const = pd.read_csv(tdir / "identified_constants.csv")
    sc = const[const["model"] == "self-consistent"]
    assert np.array_equal(sc["value"], np.round(sc["value"], tabs.DECIMALS_SELF_CONSISTENT_CM))


def test_tables_constants_come_from_a_linear_solve_equal_to_the_normal_equations(reps):
    # the tables model is linear in (l u^2, l e): the fit equals the solution of
    # the normal equations built independently from paper eq. 16 / 35
    for rep in reps:
        pub, k = rep.table, rep.fit.constants
        th = pub.phi + np.radians(k.lever_angle0_deg)
        sgn = -1.0 if pub.contour == 1 else 1.0
        M = np.concatenate(
            [np.stack([-sgn * np.cos(th), -sgn * np.sin(th)], 1), np.stack([-np.sin(th), np.cos(th)], 1)]
        )
        y = np.concatenate([pub.a_x, pub.a_y])
        ref = np.linalg.solve(M.T @ M, M.T @ y)
        np.testing.assert_allclose([k.l_u2, k.l_e], ref, rtol=1e-12)
