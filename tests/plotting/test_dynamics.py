"""Turning-moment figures: drawn, titled, labelled, with a legend and the energy band, and saved (Agg)."""

import matplotlib

matplotlib.use("Agg")

import numpy as np  # noqa: E402

from gearlever.flywheels.flywheel import flywheel  # noqa: E402
from gearlever.plotting import dynamics as plots  # noqa: E402
from gearlever.plotting._common import save  # noqa: E402


def _res(period=None):
    th = np.linspace(0, 4 * np.pi, 145)
    T = 200 + 900 * np.maximum(np.sin(th / 2), 0) ** 3 - 150 * np.sin(th)
    if period:
        th, T = th[:-1], T[:-1]
    return flywheel(th, T, 1500.0, fluctuation=0.02, period=period)


def test_turning_moment_and_energy_panels(tmp_path):
    res = _res()
    ax = plots.plot_turning_moment(res)
    assert "(deg)" in ax.get_xlabel() and ax.get_title() and ax.get_legend() is not None
    ax2 = plots.plot_energy(res)
    band = [p for p in ax2.patches]
    assert band, "the dE band is drawn"
    ext = band[0].get_window_extent()  # the band spans E_min..E_max in data coordinates
    y0, y1 = ax2.transData.inverted().transform([[0, ext.y0], [0, ext.y1]])[:, 1]
    assert np.isclose(y1 - y0, res.energy_fluctuation, rtol=1e-6)
    fig = plots.turning_moment_figure(_res(period=4 * np.pi))
    path = save(fig, tmp_path / "tm.png")
    assert path.stat().st_size > 1000


def test_mechanism_forces_figure_has_torque_and_polar_panels(tmp_path):
    from gearlever.mechanism import Mechanism

    mech = Mechanism.from_dict(
        {
            "points": {"O": [0, 0], "A": [1, 0]},
            "links": {"ground": ["O"], "crank": ["O", "A"]},
            "inputs": [{"link": "crank"}],
            "masses": {"crank": {"mass": 1.0, "centre": "A"}},
        }
    )
    q = np.linspace(0, 2 * np.pi, 36, endpoint=False)
    d = mech.inverse_dynamics(q, 10.0, 0.0)
    fig = plots.forces_figure(d, "O")
    ax1, ax2 = fig.axes
    assert "(deg)" in ax1.get_xlabel() and ax2.name == "polar"
    r = ax2.lines[0].get_ydata()
    assert np.allclose(r, 100.0)  # centripetal m w^2 R, constant
    assert save(fig, tmp_path / "f.png").stat().st_size > 1000
