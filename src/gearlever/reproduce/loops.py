"""Figures of the vector-loop engine and the ZRDPM acceleration plan (paper eqs. 19-20)."""

from __future__ import annotations

from pathlib import Path

#: the stated configuration of the figures
ZRDPM_L1_CM, ZRDPM_PHI_DEG, ZRDPM_EPS9 = 21.0, 30.0, 0.5
FOURBAR = (9.0, 5.0, 8.0, 8.0)  # ground, crank, coupler, rocker (cm)
FOURBAR_THETA2_DEG = 60.0


def run(tables_dir: Path, figures_dir: Path) -> list[str]:
    from gearlever.loops import fourbar, grashof
    from gearlever.plotting._common import save
    from gearlever.plotting.animation import animate_fourbar
    from gearlever.plotting.fourbar import fourbar_curves
    from gearlever.plotting.plans import fourbar_plans, zrdpm_plans_figure

    figures_dir = Path(figures_dir)
    out = []
    save(
        zrdpm_plans_figure(ZRDPM_L1_CM, 0.0, ZRDPM_PHI_DEG, 1.0, ZRDPM_EPS9),
        figures_dir / "loops_zrdpm_acceleration_plan.png",
    )
    out.append(
        f"loops: ZRDPM contour-1 acceleration plan (eqs. 19-20) at phi = {ZRDPM_PHI_DEG:g} deg, "
        f"l1 = {ZRDPM_L1_CM:g} cm -> {figures_dir / 'loops_zrdpm_acceleration_plan.png'}"
    )
    save(fourbar_plans(*FOURBAR, FOURBAR_THETA2_DEG), figures_dir / "loops_fourbar_plans.png")
    save(fourbar_curves(*FOURBAR), figures_dir / "loops_fourbar_curves.png")
    animate_fourbar(*FOURBAR, figures_dir / "loops_fourbar.gif", frames=18)
    import numpy as np

    r = fourbar(*FOURBAR, np.linspace(0, 2 * np.pi, 3600, endpoint=False))
    out.append(
        f"loops: four-bar {'/'.join(f'{v:g}' for v in FOURBAR)} ({grashof(*FOURBAR).kind}): "
        f"max |dtheta4/dphi| = {np.abs(r.dtheta4_dphi).max():.6f}, "
        f"max |d2theta4/dphi2| = {np.abs(r.d2theta4_dphi2).max():.6f} "
        f"-> {figures_dir / 'loops_fourbar'}_{{plans,curves}}.png, loops_fourbar.gif"
    )
    return out
