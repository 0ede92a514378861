"""One worked example per kind of law synthesis, against the cam that gives the same law.

Not a step of ``make reproduce``: the minimax polish of a law synthesis
(Lawson's reweighting) amplifies the last digits of its least-squares solves,
which differ between OpenBLAS kernels, so the six-bar's error comes out 0.3726
deg under one kernel and 0.3724 deg under another (the same design to 1e-4).
``benchmarks/bench_law.py --examples DIR`` runs it and the guide shows its
output from ``docs/_static/law_synthesis/``.

Writes ``law_synthesis_<kind>.png`` (the wanted and achieved law over
the turn, and the error, segments shaded) and ``law_synthesis.csv``:
per kind, the law, the error over the cycle and over each dwell, the dwell
excursion, the peak acceleration analogue achieved against the law's, the
transmission angle range, and the cam for the same law (default roller
follower sized for a 30 deg pressure angle: base radius, largest pressure
angle, smallest radius of curvature).  The angle kinds are given the shipped
dwell law (a 120 deg dwell, a 45 deg cycloidal rise, a 3-4-5 return); the
slider-crank the shipped lift law.  The budget is a quarter of the command's
default: the guide's dwell benchmark with the default budget does better
(see :doc:`/guide/law-synthesis`).  Numbers are written at 4 significant
digits.
"""

from __future__ import annotations

from pathlib import Path

#: Kind -> shipped law it is shown on.
CASES = {
    "fourbar": "law_dwell_rocker",
    "geared-fourbar": "law_dwell_rocker",
    "sixbar-dwell": "law_dwell_rocker",
    "gear-lever": "law_dwell_rocker",
    "slider-crank": "law_lift",
}
#: Evaluations per kind, polishes included (a quarter of ``synthesize law``'s default; the searches get 100 000).
BUDGET = 200_000
SEED = 0
DIGITS = 4


def run(tables_dir: Path, figures_dir: Path) -> list[str]:
    from gearlever._format import rounded
    from gearlever.data import example_path
    from gearlever.laws import load_law
    from gearlever.plotting._common import save
    from gearlever.plotting.law_synthesis import law_synthesis_figure
    from gearlever.synthesis.law import synthesize_law
    from gearlever.synthesis.law.measure import cam_comparison, law_report
    from gearlever.tables._common import frame, write_csv

    rows, out = [], []
    cams: dict = {}
    for kind, name in CASES.items():
        law = load_law(example_path(f"{name}.toml"))
        res = synthesize_law(law, kind=kind, seed=SEED, budget=BUDGET, workers=2)
        rep = law_report(res)
        cam = cams.setdefault(name, cam_comparison(law))
        u = "_deg" if law.output == "angle" else ""
        unit = "deg" if u else law.units
        dwell = [s for s in rep["segments"] if s["motion"] == "dwell"]
        pa = rep[f"peak_acceleration{u}_per_rad2"]
        row = {
            "law": name,
            "kind": kind,
            "unit": unit,  # of the output: the errors, excursions and analogues below (per rad^2)
            "error_max": rep[f"error_max{u}"],
            "error_rms": rep[f"error_rms{u}"],
            "dwell_error_max": max((s[f"error_max{u}"] for s in dwell), default=float("nan")),
            "dwell_excursion": max((s[f"dwell_excursion{u}"] for s in dwell), default=float("nan")),
            "peak_acceleration_per_rad2": pa["achieved"],
            "law_peak_acceleration_per_rad2": pa["wanted"],
            "transmission_min_deg": rep["transmission_deg"][0],
            "transmission_max_deg": rep["transmission_deg"][1],
            "cam_follower": cam["follower"],
            "cam_base_radius": cam.get("base_radius", float("nan")),
            "cam_pressure_angle_max_deg": cam.get("pressure_angle_max_deg", float("nan")),
            "cam_curvature_radius_min": cam.get("curvature_radius_min", float("nan")),
        }
        rows.append(rounded(row, DIGITS))
        target = Path(figures_dir) / f"law_synthesis_{kind.replace('-', '_')}.png"
        save(law_synthesis_figure(res), target, dpi=80)
        out.append(
            f"law synthesis: {kind} for {name}: error max {row['error_max']:.4g} {unit}"
            + (f", dwell excursion {row['dwell_excursion']:.4g} {unit}" if dwell else "")
            + f"; cam base radius {row['cam_base_radius']:.4g} -> {target}"
        )
    table = frame({k: [r[k] for r in rows] for k in rows[0]})
    path = Path(tables_dir) / "law_synthesis.csv"
    write_csv(table, path, float_format=f"%.{DIGITS}g")
    out.append(f"law synthesis: {path}: {len(rows)} kinds, against the cam for the same law")
    return out
