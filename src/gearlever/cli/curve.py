"""``gearlever curve score``: score linkages in the challenge's form against a target curve.

    gearlever curve score DESIGNS... --target TARGET.csv [--format csv|json] [--out FILE]

Each DESIGN is a ``.links.json`` file (``x0``, ``edges``, ``fixed_joints``,
``motor``, ``target_joint``; see :mod:`gearlever.curves.links`).  One row per
design: distance and material as the MIT 2.156 linkage challenge defines them
(:mod:`gearlever.curves.score`), joints, links and whether it is feasible;
the JSON form adds the hypervolume of the feasible designs against the
reference point (0.75, 10).  At most :data:`MAX_DESIGNS` designs.
"""

from __future__ import annotations

from gearlever.cli._common import emit, table_text

#: Most designs scored at once.
MAX_DESIGNS = 10_000


def register(sub) -> None:
    p = sub.add_parser("curve", help="traced curves: score linkages in the challenge's form against a target")
    cs = p.add_subparsers(dest="curve_command", metavar="ACTION")
    cs.required = True
    s = cs.add_parser("score", help="distance, material and feasibility of .links.json designs, and hypervolume")
    s.add_argument("designs", nargs="+", metavar="DESIGN", help=".links.json files")
    s.add_argument("--target", required=True, help="CSV of the target curve: x,y rows")
    s.add_argument("--format", choices=("csv", "json"), default="csv")
    s.add_argument("--out", help="file to write (default stdout)")
    s.set_defaults(func=_score)


def _score(args) -> int:
    import numpy as np

    from gearlever.curves.links import read_linkage, solve_plan
    from gearlever.curves.score import distance, feasible, hypervolume, material
    from gearlever.curves.simulate import simulate
    from gearlever.curves.targets import read_target
    from gearlever.errors import GearleverError

    if len(args.designs) > MAX_DESIGNS:
        raise GearleverError(f"DESIGN: at most {MAX_DESIGNS} designs, got {len(args.designs)}")
    target = read_target(args.target, "--target")
    links = [read_linkage(p) for p in args.designs]
    dist, mat = [], []
    for lk in links:
        x = simulate(lk.x0[None], solve_plan(lk))
        dist.append(float(distance(x[:, lk.target_joint], target)[0]))
        mat.append(float(material(lk.x0[None], lk.edges)[0]))
    joints = [lk.n_joints for lk in links]
    ok = feasible(dist, mat, joints)
    cols = {
        "design": list(args.designs),
        "distance": dist,
        "material": mat,
        "joints": joints,
        "links": [len(lk.edges) for lk in links],
        "feasible": [bool(v) for v in ok],
    }
    hv = hypervolume(np.column_stack([dist, mat])[ok]) if ok.any() else 0.0
    meta = {"target": args.target, "reference": [0.75, 10.0], "hypervolume": hv}
    emit(table_text(cols, args.format, meta=meta), args.out)
    return 0
