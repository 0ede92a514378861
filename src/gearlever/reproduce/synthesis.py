"""Linkage synthesis: the log10 function generator, the five-pose Burmester four-bar, the published checks.

Writes ``figures/synthesis_function_log10.png`` (Freudenstein's log10 generator:
targets, wanted and generated output over the whole design range, structural
error, the linkage), ``figures/synthesis_motion_five_poses.png`` (the four-bar
through the five poses of ``examples/motion_poses.csv`` from its Burmester
points) and ``tables/synthesis_checks.csv`` (every printed answer of the
published worked examples in ``synthesis_published.csv`` beside the value
:func:`gearlever.synthesis.function.synthesize_function` computes).
"""

from __future__ import annotations

import math
from pathlib import Path

#: Significant digits of computed values in the table (the answers are printed with at most four).
FLOAT_FORMAT = "%.9g"
#: The log10 generator: y = log10(x), 1 <= x <= 2, crank 45..105 deg, rocker 135..225 deg, three
#: Chebyshev-spaced precision points (the classic example of Freudenstein, Trans. ASME 77, 1955).
LOG10 = {"expression": "log10(x)", "x_range": (1.0, 2.0), "input_deg": (45.0, 105.0), "output_deg": (135.0, 225.0)}
#: Figure resolution (dots per inch).
DPI = 90


def published_problems() -> dict:
    """Problem data of the published function-generation examples (``synthesis_published.toml``).

    Examples
    --------
    >>> p = published_problems()["su-lecture-12"]
    >>> p["ground"], p["input_angle_deg"]
    (4.5, [35.02, 67.5, 100.0])
    """
    import tomllib

    from gearlever.data import read_text

    return tomllib.loads(read_text("synthesis_published.toml"))["function"]


def _quantities(result) -> dict:
    """The quantities the published examples print, from a synthesis result.

    ``z1, z2, z3`` are the design unknowns of the lecture with the ground set to 1:
    Freudenstein's ``K3``, ``K1 = d/a`` and ``K2 = d/c``; then the link lengths.
    """
    K1, K2, K3 = (float(k) for k in result.coefficients)
    return {"z1": K3, "z2": K1, "z3": K2, **{k: float(result.lengths[k]) for k in ("crank", "coupler", "rocker")}}


def published_checks():
    """One row per printed answer: source, example, slide, quantity, unit, published, computed, deviation, ...

    Each example is solved by :func:`~gearlever.synthesis.function.synthesize_function`
    from its printed angles (converted to radians; the data file states the angle
    convention) and ground length.

    Notes
    -----
    Freudenstein's equation ``K1 cos(psi) - K2 cos(phi) + K3 = cos(phi - psi)``
    (F. Freudenstein, "Approximate synthesis of four-bar linkages", Trans. ASME
    77, 1955, pp. 853-861) through the three printed precision pairs; the
    tolerances (conditioning of the printed angles) are in the data file.

    Examples
    --------
    >>> df = published_checks()
    >>> bool(df.within.all()), list(df.quantity)
    (True, ['z1', 'z2', 'z3', 'crank', 'coupler', 'rocker'])
    """
    import numpy as np

    from gearlever.data import read_records
    from gearlever.synthesis.function import synthesize_function
    from gearlever.tables._common import frame

    problems = published_problems()
    computed = {}
    for key, p in problems.items():
        r = synthesize_function(
            np.radians(p["input_angle_deg"]), np.radians(p["output_angle_deg"]), kind=p["kind"], ground=p["ground"]
        )
        computed[key] = _quantities(r)
    rows = read_records("synthesis_published.csv")
    pub = [float(r["published"]) for r in rows]
    comp = [computed[r["example"]][r["quantity"]] for r in rows]
    tol = [float(r["tolerance"]) for r in rows]
    dev = [c - p for c, p in zip(comp, pub, strict=True)]
    return frame(
        {
            "source": [f"{problems[r['example']]['short']}, slide {r['slide']}" for r in rows],
            "example": [r["example"] for r in rows],
            "slide": [int(r["slide"]) for r in rows],
            "quantity": [r["quantity"] for r in rows],
            "unit": [r["unit"] for r in rows],
            "published": pub,
            "computed": [float(f"{c:.9g}") for c in comp],
            "deviation": [float(f"{d:.3g}") for d in dev],  # 3 digits: machine-independent
            "tolerance": tol,
            "within": [abs(d) <= t for d, t in zip(dev, tol, strict=True)],
            "basis": [r["basis"] for r in rows],
        }
    )


def _log10():
    """Targets and the synthesized four-bar of :data:`LOG10`, its structural error over the whole range."""
    import numpy as np

    from gearlever.synthesis.function import function_targets, synthesize_function

    t = function_targets(
        LOG10["expression"], LOG10["x_range"], np.radians(LOG10["input_deg"]), np.radians(LOG10["output_deg"])
    )
    return t, synthesize_function(t.input_angle, t.target, target_at=t.target_at, input_range=t.input_range)


def _poses_path() -> Path:
    """The shipped five poses, ``examples/motion_poses.csv`` (package data)."""
    from gearlever.data import example_path

    return example_path("motion_poses.csv")


def _read_poses(path: Path):
    """Poses of a CSV ``x, y, angle_deg``: ``(points (N, 2), angles (N,) in radians)``."""
    import numpy as np

    from gearlever._io import read_csv_table

    cols = read_csv_table(path, "poses", columns=("x", "y", "angle_deg")).columns(["x", "y", "angle_deg"])
    return np.column_stack([cols["x"], cols["y"]]), np.radians(cols["angle_deg"])


def run(tables_dir: Path, figures_dir: Path) -> list[str]:
    import numpy as np

    from gearlever.mechanism import Mechanism
    from gearlever.plotting._common import save
    from gearlever.plotting.synthesis import function_figure, motion_figure
    from gearlever.synthesis.motion import burmester_curves, synthesize_motion
    from gearlever.tables._common import write_csv

    out = []
    # --- the log10 function generator
    t, r = _log10()
    fig = function_figure(r)
    ax = fig.axes[0]
    err = ax.twinx()
    (line,) = err.plot(
        np.degrees(r.dense_input),
        np.degrees(r.dense_achieved - r.dense_target),
        color="0.45",
        lw=1,
        label="structural error (right axis)",
    )
    err.axhline(0.0, color="0.7", lw=0.8)
    err.set_ylabel("structural error, generated - wanted (deg)")
    handles, labels = ax.get_legend_handles_labels()
    ax.legend(handles + [line], labels + [line.get_label()], fontsize=8, loc="lower right")
    ax.set_title(
        f"y = log10 x, 1 <= x <= 2, Chebyshev targets: max structural error "
        f"{math.degrees(r.structural_error_max):.3f} deg",
        fontsize=10,
    )
    target = Path(figures_dir) / "synthesis_function_log10.png"
    save(fig, target, dpi=DPI)
    L = r.lengths
    out.append(
        f"synthesis: {target}: log10 generator ground {L['ground']:.4g}, crank {L['crank']:.4g}, "
        f"coupler {L['coupler']:.4g}, rocker {L['rocker']:.4g} ({r.grashof}); max structural error "
        f"{math.degrees(r.structural_error_max):.3f} deg over {LOG10['input_deg'][0]:g}..{LOG10['input_deg'][1]:g} deg"
    )

    # --- five poses: Burmester points and the best four-bar
    poses = _poses_path()
    if poses.is_file():
        pts, ang = _read_poses(poses)
        res = synthesize_motion(pts, ang)
        best = res.best
        q0 = best.input_angle[0]
        sweep = q0 + np.linspace(0.0, 2 * np.pi if best.crank_turns else best.input_angle[-1] - q0, 361)
        path = Mechanism.from_dict(best.model).solve(sweep[:, None]).point["P"]
        fig = motion_figure(res, burmester_curves(pts[:4], ang[:4]), path)
        a0, a1 = fig.axes[0], fig.axes[1]
        resid = "below 1e-12" if best.residual < 1e-12 else f"{best.residual:.1e}"
        a0.set_title(
            f"Four-bar through {len(ang)} poses from its Burmester points: residual {resid}, {best.grashof}",
            fontsize=9,
        )
        cen = np.array([d.ground_pivot for d in res.dyads])
        cir = np.array([d.moving_pivot for d in res.dyads])
        a1.plot(cen[:, 0], cen[:, 1], "*", color="tab:blue", mec="k", ms=13, label="Burmester centre points")
        a1.plot(cir[:, 0], cir[:, 1], "*", color="tab:orange", mec="k", ms=13, label="Burmester circle points")
        allxy = np.vstack([cen, cir, pts])
        lo, hi = allxy.min(axis=0), allxy.max(axis=0)
        x0, x1 = a1.get_xlim()
        y0, y1 = a1.get_ylim()
        pad = 0.08 * float((hi - lo).max())
        a1.set_xlim(min(x0, lo[0] - pad), max(x1, hi[0] + pad))
        a1.set_ylim(min(y0, lo[1] - pad), max(y1, hi[1] + pad))
        a1.set_title(f"Burmester curves of poses 1-4; the {len(res.dyads)} Burmester points of all five", fontsize=9)
        a1.legend(fontsize=8, markerscale=1, loc="best")
        a1.grid(True, alpha=0.3)
        target = Path(figures_dir) / "synthesis_motion_five_poses.png"
        save(fig, target, dpi=DPI)
        Lm = best.lengths
        out.append(
            f"synthesis: {target}: {len(res.dyads)} Burmester point pairs, {len(res.solutions)} "
            f"four-bars; best ground {Lm['ground']:.6g}, crank {Lm['crank']:.6g}, coupler {Lm['coupler']:.6g}, "
            f"rocker {Lm['rocker']:.6g} ({best.grashof}, crank turns fully: {'yes' if best.crank_turns else 'no'})"
        )
    else:
        out.append("synthesis: examples/motion_poses.csv not found (installed package): five-pose figure skipped")

    # --- published checks
    df = published_checks()
    write_csv(df, Path(tables_dir) / "synthesis_checks.csv", float_format=FLOAT_FORMAT)
    worst = float((df.deviation.abs() / df.tolerance).max())
    out.append(
        f"synthesis: {Path(tables_dir) / 'synthesis_checks.csv'}: {int(df.within.sum())}/{len(df)} published answers "
        f"({df.example.nunique()} worked example(s), function generation) within tolerance; "
        f"worst at {worst:.2f} of its tolerance"
    )
    return out
