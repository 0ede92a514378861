"""Tables and figures of the gear-network issue: written, sane, deterministic."""

import csv

import matplotlib

matplotlib.use("Agg")

from gearlever.gears.chariot import NuttallTeeth, design_nuttall, random_path, simulate  # noqa: E402
from gearlever.plotting.chariot import plot_chariot_path, plot_drift  # noqa: E402
from gearlever.reproduce import networks  # noqa: E402
from gearlever.tables.chariot import car_cases_table, nuttall_designs_table  # noqa: E402


def test_nuttall_table_worked_designs():
    df = nuttall_designs_table()
    eq = df[df["design"].str.startswith("all teeth equal")].iloc[0]
    up = df[df["design"].str.startswith("geared up by two")].iloc[0]
    assert (eq["d1_per_t"], eq["d12_per_t"]) == (1.0, 1.0)
    assert (up["d1_per_t_fraction"], up["d12_per_t_fraction"]) == ("1/2", "1/2")
    assert df["closed_form_agrees"].all()
    assert (df["dof"] == 2).all() and (df["redundant"] == "e").all()


def test_car_table_power_balance_and_held_wheel():
    df = car_cases_table()
    assert ((df["power_in_W"] - df["power_out_W"]).abs() < 1e-9).all()
    held = df[df["case"] == "left wheel held"].iloc[0]
    assert held["right_speed_rad_s"] == 2 * held["carrier_speed_rad_s"]


def test_reproduce_writes_deterministic_tables_and_sane_figures(tmp_path):
    (tmp_path / "t").mkdir(), (tmp_path / "f").mkdir()  # the registry creates the folders, not the step
    lines = networks.run(tmp_path / "t", tmp_path / "f")
    assert any("nuttall.csv" in x and "5/5" in x for x in lines)
    first = {p.name: p.read_bytes() for p in (tmp_path / "t").iterdir()}
    figs = {p.name: p.stat().st_size for p in (tmp_path / "f").iterdir()}
    assert set(first) == {"nuttall.csv", "car_differential.csv"}
    assert set(figs) == {"chariot_path.png", "chariot_drift.png"}
    assert all(size > 10_000 for size in figs.values())
    with open(tmp_path / "t" / "nuttall.csv", newline="") as fh:
        rows = list(csv.DictReader(fh))
    assert rows[0]["d1_per_t_fraction"] == "1"
    networks.run(tmp_path / "t", tmp_path / "f")
    assert {p.name: p.read_bytes() for p in (tmp_path / "t").iterdir()} == first


def test_plot_functions_take_ax_and_label_everything():
    d = design_nuttall(NuttallTeeth.uniform(20))
    dl, dr = random_path(1, seed=0, steps_per_turn=50)
    runs = {"exact": simulate(d, dl, dr)}
    ax = plot_drift(runs)
    assert ax.get_title() and ax.get_xlabel() and ax.get_ylabel() and ax.get_legend() is not None
    ax2 = plot_chariot_path(runs, arrows=4)
    assert ax2.get_title() and "track" in ax2.get_xlabel() and ax2.get_legend() is not None
    matplotlib.pyplot.close("all")
