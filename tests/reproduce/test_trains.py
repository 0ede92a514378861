"""Tables, figures and the reproduce step of the trains / Hooke modules."""

import math

import numpy as np
import pytest

from gearlever.plotting import hooke as hplot
from gearlever.plotting._common import save
from gearlever.reproduce import trains as rtrains
from gearlever.tables import trains as ttab


def test_hooke_table_columns_and_values():
    df = ttab.hooke_table(step_deg=15.0)
    assert len(df) == 25 and df.input_deg.iloc[-1] == 360.0
    c30 = math.cos(math.radians(30.0))
    assert df.ratio_single_b30deg.max() == pytest.approx(1 / c30)
    assert df.ratio_single_b30deg.min() == pytest.approx(c30)
    np.testing.assert_allclose(df["ratio_double_b30_30_p0deg"], 1.0, atol=1e-12)
    assert df["ratio_double_b30_30_p90deg"].max() == pytest.approx(1 / c30**2)


def test_hooke_extremes_table_closed_forms():
    df = ttab.hooke_extremes_table()
    single = df[df.coupling == "single"]
    np.testing.assert_allclose(single.min_ratio, np.cos(np.radians(single.beta1_deg)))
    row = df[(df.coupling == "double") & (df.beta2_deg == 20.0)].iloc[0]
    c = math.cos(math.radians(30.0)) / math.cos(math.radians(20.0))
    assert (row.min_ratio, row.max_ratio) == (pytest.approx(c, rel=1e-9), pytest.approx(1 / c, rel=1e-9))


def test_design_and_sandgren_tables():
    d = ttab.design_table()
    row = d[d.target == "1/6.931"].iloc[0]
    assert (row.drivers, row.followers, row.approximation) == ("16 19", "43 49", "304/2107")
    s = ttab.sandgren_table(pairs=(2, 3))
    k2 = s[s.pairs == 2]
    assert len(k2) == 1 and k2.squared_error.iloc[0] == pytest.approx(2.700857e-12, rel=1e-6)
    assert (s[s.pairs == 3].abs_error < k2.abs_error.iloc[0]).all()


def test_plots_return_axes_and_save(tmp_path):
    for fn in (hplot.plot_single_ratio, hplot.plot_double_ratio):
        ax = fn(n=61)
        assert ax.get_title() and ax.get_xlabel() and ax.get_ylabel()
        assert ax.get_legend() is not None and len(ax.get_lines()) >= 4
        path = save(ax.figure, tmp_path / f"{fn.__name__}.png")
        assert path.stat().st_size > 5000 and path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_reproduce_writes_deterministic_files(tmp_path):
    for sub in ("t", "f", "again"):  # the registry creates the folders, not the step
        (tmp_path / sub).mkdir()
    lines = rtrains.run(tmp_path / "t", tmp_path / "f")
    assert any("sandgren" in ln for ln in lines)
    names = ["hooke.csv", "hooke_extremes.csv", "train_designs.csv", "sandgren.csv"]
    first = {n: (tmp_path / "t" / n).read_bytes() for n in names}
    assert (tmp_path / "f" / "hooke_single.png").exists() and (tmp_path / "f" / "hooke_double.png").exists()
    # a second writing of the tables gives the same bytes
    from gearlever.tables._common import write_csv

    again = {
        "hooke.csv": ttab.hooke_table(),
        "hooke_extremes.csv": ttab.hooke_extremes_table(),
        "train_designs.csv": ttab.design_table(),
        "sandgren.csv": ttab.sandgren_table(),
    }
    for n, df in again.items():
        assert write_csv(df, tmp_path / "again" / n).read_bytes() == first[n]
