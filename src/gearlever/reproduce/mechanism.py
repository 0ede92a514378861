"""Figures of the shipped mechanism models (package data): sketch, joints, gears and point paths of each."""

from __future__ import annotations

from pathlib import Path

#: Sweeps (degrees) of the examples whose inputs do not simply make a full turn.
SWEEPS_DEG = {
    "zrdpm_gear_contour": [(0.0, 360.0), (0.0, 60.0)],
    "parallel_levers": [(20.0, 160.0)],
}
POINTS = 181


def run(tables_dir: Path, figures_dir: Path) -> list[str]:
    from gearlever.data import example_path, list_examples
    from gearlever.mechanism import Mechanism
    from gearlever.mechanism.sweep import sweep
    from gearlever.plotting._common import save
    from gearlever.plotting.mechanism import draw_mechanism

    out = []
    paths = [example_path(n) for n in list_examples() if n.endswith(".toml")]
    for path in [p for p in paths if "[law]" not in p.read_text(encoding="utf-8")]:  # laws: see reproduce.cams
        mech = Mechanism.load(path)
        q, qdot = sweep(mech, POINTS, SWEEPS_DEG.get(path.stem))
        r = mech.solve(q, qdot)
        s = mech.structure()
        target = Path(figures_dir) / f"mechanism_{path.stem}.png"
        save(draw_mechanism(mech, r).figure, target, dpi=80)
        out.append(
            f"mechanism: {path.stem}: n={s.n} P5={s.P5} P4={s.P4} W_formula={s.W_formula} dof={s.dof} "
            f"redundant={s.redundant}; {int(r.closed.sum())}/{r.closed.size} rows closed -> {target}"
        )
    return out
