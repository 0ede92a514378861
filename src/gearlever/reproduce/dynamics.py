"""Figures of the forces and dynamics of the shipped engine model: input torque, crank-pin load, flywheel."""

from __future__ import annotations

from pathlib import Path

#: Speed (rpm), points per turn and coefficient of fluctuation of the engine figures.
RPM = 3000.0
POINTS = 360
FLUCTUATION = 0.02
BEARING = "A"


def run(tables_dir: Path, figures_dir: Path) -> list[str]:
    import math

    import numpy as np

    from gearlever.data import example_path
    from gearlever.flywheels.flywheel import flywheel
    from gearlever.mechanism import Mechanism
    from gearlever.plotting._common import save
    from gearlever.plotting.dynamics import forces_figure, turning_moment_figure

    mech = Mechanism.load(example_path("engine.toml"))
    w = RPM * math.pi / 30.0
    q = mech.sketch_inputs[0] + np.linspace(0.0, 2 * np.pi, POINTS, endpoint=False)
    d = mech.inverse_dynamics(q, np.full_like(q, w), np.zeros_like(q))

    fig = forces_figure(d, BEARING, label=f"input torque at {RPM:g} rpm")
    save(fig, Path(figures_dir) / "dynamics_engine_forces.png", dpi=90)

    tau = d.input_force[:, 0]
    # a motor giving the mean torque drives a machine that needs tau: tau is the resisting curve
    drive = np.full_like(tau, float(np.mean(tau)))
    fw = flywheel(q, drive, RPM, fluctuation=FLUCTUATION, load=tau, period=2 * np.pi)
    save(turning_moment_figure(fw), Path(figures_dir) / "dynamics_engine_flywheel.png", dpi=90)
    peak = float(np.max(np.hypot(*d.reaction[BEARING].T)))
    return [
        f"{Path(figures_dir) / 'dynamics_engine_forces.png'}: engine at {RPM:g} rpm, input torque {tau.min():.1f} .. "
        f"{tau.max():.1f} N m, peak crank-pin load {peak:.0f} N",
        f"{Path(figures_dir) / 'dynamics_engine_flywheel.png'}: dE = {fw.energy_fluctuation:.2f} J, "
        f"I = {fw.inertia:.4f} kg m^2 for Cs = {FLUCTUATION}",
    ]
