"""``gearlever curve``: score linkages in the challenge's form against a target curve; the retrieval library.

Usage::

    gearlever curve score DESIGNS... --target TARGET.csv [--scoring relative|challenge] [--format csv|json]
        [--out FILE]
    gearlever curve library build [--size N] [--seed S]
    gearlever curve library info

Each DESIGN is a ``.links.json`` file (``x0``, ``edges``, ``fixed_joints``,
``motor``, ``target_joint``; see :mod:`gearlever.mechanism.linkage`).  One row per
design: distance and material as the MIT 2.156 linkage challenge defines them
(:mod:`gearlever.synthesis.curve.score`), joints, links and whether it is feasible;
the JSON form adds the hypervolume of the feasible designs against the
reference point (0.75, 10).  At most :data:`MAX_DESIGNS` designs.
``--scoring relative`` (default, as ``synthesize curve``) closes the target
and measures material at the size of the challenge's targets;
``--scoring challenge`` applies the challenge's rules as they are
(:mod:`gearlever.synthesis.curve.score`).

``library build`` simulates the retrieval library of ``gearlever synthesize
curve`` (``--size`` mechanisms, default the synthesis' 14400, at most
:data:`gearlever.synthesis.curve.search.MAX_LIBRARY_SIZE`; ``--seed`` of its draws)
and stores it in the cache folder (``$GEARLEVER_CACHE``, else
``$XDG_CACHE_HOME/gearlever``, else ``~/.cache/gearlever``), written
atomically; ``synthesize curve --library-size N --library-seed S`` then loads
it instead of building it (same designs).  ``library info`` prints the cache
folder and each stored library: size, seed, entries, file bytes.  See
:mod:`gearlever.synthesis.curve.library`.
"""

from __future__ import annotations

from gearlever._io import table_text
from gearlever.cli._common import capped_int, emit

#: Most designs scored at once.
MAX_DESIGNS = 10_000


def register(sub) -> None:
    p = sub.add_parser("curve", help="traced curves: score linkages in the challenge's form against a target")
    cs = p.add_subparsers(dest="curve_command", metavar="ACTION")
    cs.required = True
    s = cs.add_parser("score", help="distance, material and feasibility of .links.json designs, and hypervolume")
    s.add_argument("designs", nargs="+", metavar="DESIGN", help=".links.json files")
    s.add_argument("--target", required=True, help="CSV of the target curve: x,y rows")
    s.add_argument(
        "--scoring",
        choices=("relative", "challenge"),
        default="relative",
        help="relative (default): closed target, material at the size of the challenge's targets; challenge: the "
        "MIT 2.156 challenge's absolute rules",
    )
    s.add_argument("--format", choices=("csv", "json"), default="csv")
    s.add_argument("--out", help="file to write (default stdout)")
    s.set_defaults(func=_score)

    from gearlever.synthesis.curve.library import LIBRARY_SKETCHES, LIBRARY_TOPOLOGIES, MAX_LIBRARY_SIZE

    lib = cs.add_parser("library", help="the retrieval library of synthesize curve, kept in the cache folder")
    ls = lib.add_subparsers(dest="library_command", metavar="ACTION")
    ls.required = True
    b = ls.add_parser("build", help="simulate the library once and store it in the cache folder")
    b.add_argument(
        "--size",
        type=capped_int(MAX_LIBRARY_SIZE),
        default=LIBRARY_TOPOLOGIES * LIBRARY_SKETCHES,
        help=f"mechanisms simulated (default {LIBRARY_TOPOLOGIES * LIBRARY_SKETCHES}, the synthesis' own)",
    )
    b.add_argument("--seed", type=capped_int(2**31 - 1, low=0), default=0, help="seed of the library's draws")
    b.set_defaults(func=_library_build)
    i = ls.add_parser("info", help="the cache folder and the stored libraries: size, seed, entries, bytes")
    i.set_defaults(func=_library_info)


def _score(args) -> int:
    import numpy as np

    from gearlever.errors import GearleverError
    from gearlever.mechanism.linkage import read_linkage, solve_plan
    from gearlever.synthesis.curve.score import feasible, hypervolume, material, material_scale, score_distance
    from gearlever.synthesis.curve.simulate import simulate
    from gearlever.synthesis.curve.targets import read_target

    if len(args.designs) > MAX_DESIGNS:
        raise GearleverError(f"DESIGN: at most {MAX_DESIGNS} designs, got {len(args.designs)}")
    target = read_target(args.target, "--target")
    links = [read_linkage(p) for p in args.designs]
    k = material_scale(target, args.scoring)
    dist, mat = [], []
    for lk in links:
        x = simulate(lk.x0[None], solve_plan(lk))
        dist.append(float(score_distance(x[:, lk.target_joint], target, args.scoring)[0]))
        mat.append(float(material(lk.x0[None], lk.edges)[0]) * k)
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
    meta = {
        "target": args.target,
        "scoring": args.scoring,
        "material_scale": k,
        "reference": [0.75, 10.0],
        "hypervolume": hv,
    }
    emit(table_text(cols, args.format, meta=meta), args.out)
    return 0


def _library_build(args) -> int:
    from gearlever._progress import TerminalProgress
    from gearlever.cli._common import check_output_folder, commit_outputs
    from gearlever.synthesis.curve.library import build_cached, library_path

    # refused before any work, naming the folder; made if missing (and removed again if the build fails)
    check_output_folder(library_path(args.size, args.seed).parent, "cache folder", create=True)
    bar = TerminalProgress("gearlever curve library build")
    try:
        lib, path = build_cached(args.size, args.seed, progress=bar)
    finally:
        bar.close()
    commit_outputs()
    emit(f"{path}: {args.size} mechanisms, seed {args.seed}, {lib.rms.size} entries, {path.stat().st_size} bytes")
    return 0


def _library_info(args) -> int:
    from gearlever.synthesis.curve.library import cache_folder, library_files

    lines = [f"cache folder: {cache_folder()}"]
    rows = library_files()
    for r in rows:
        what = f"{r['entries']} entries" if r["problem"] is None else r["problem"]
        lines.append(f"{r['path'].name}: {r['size']} mechanisms, seed {r['seed']}, {what}, {r['bytes']} bytes")
    if not rows:
        lines.append("no library stored (gearlever curve library build --size N)")
    emit("\n".join(lines))
    return 0
