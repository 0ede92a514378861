"""``gearlever network FILE --inputs A,B [--teeth n2=30,...] [--tabular CARRIER [--turned M]] [--format table|json]``.

Solve a gear network given as CSV records (see :func:`gearlever.gears.networks.parse_network`):
counts, redundant constraints, and every member's rotation as an exact linear
function of the inputs; with ``--tabular`` the textbook table of the
epicyclic train on that carrier (see :func:`gearlever.gears.epicyclic.tabular_method`).
An empty file, an inconsistent network, an unknown gear or a bad
tooth number ends with exit 2 and one line naming it.
"""

from __future__ import annotations

from gearlever._io import read_text_capped
from gearlever.cli._common import emit, to_json
from gearlever.errors import GearleverError


def register(sub) -> None:
    p = sub.add_parser("network", help="solve a gear network given as data (exact fractions)")
    p.add_argument("file", metavar="FILE", help="network records: member/constraint lines (CSV)")
    p.add_argument(
        "--inputs",
        default=None,
        action="append",
        metavar="A,B",
        help="input members, comma separated (default: counts and redundancy only)",
    )
    p.add_argument(
        "--teeth",
        default=None,
        action="append",
        metavar="SYM=N,...",
        help="values of tooth-number symbols used in FILE, e.g. n2=30,n5=24",
    )
    p.add_argument(
        "--tabular",
        default=None,
        metavar="CARRIER",
        help="also print the tabular method: CARRIER fixed and one member turned +1, then all turned with it",
    )
    p.add_argument(
        "--turned",
        default=None,
        metavar="MEMBER",
        help="with --tabular: the member turned +1 (default: the first gear meshing on CARRIER)",
    )
    p.add_argument("--torque", action="append", metavar="M=T,...", help="applied torques, e.g. sun=100 (with --loads)")
    p.add_argument("--loads", action="append", metavar="A,B", help="members whose torques are unknown (one per dof)")
    p.add_argument(
        "--speeds", action="append", metavar="M=W,...", help="speeds of independent members (default: the inputs at 1)"
    )
    p.add_argument("--efficiency", default="1", metavar="ETA", help="mesh efficiency in (0, 1] (default 1)")
    p.add_argument("--format", choices=("table", "json"), default="table")
    p.add_argument("--out", default=None, metavar="FILE", help="write to FILE instead of stdout")
    p.set_defaults(func=_run)


def _joined(given) -> str:
    """The values of a flag given once or more (``--teeth n2=30 --teeth n5=24``) as one comma list."""
    return ",".join(given or ())


def _names(given, flag: str) -> list[str]:
    """Member names of ``--inputs``/``--loads`` (given once or more, comma separated), none twice."""
    out: list[str] = []
    for name in filter(None, (x.strip() for x in _joined(given).split(","))):
        if name in out:
            raise GearleverError(f"{flag}: member {name!r} is given twice")
        out.append(name)
    return out


def _teeth(text: str) -> dict[str, int]:
    out = {}
    for item in filter(None, (x.strip() for x in text.split(","))):
        name, sep, value = item.partition("=")
        if not sep or not name.strip():
            raise GearleverError(f"--teeth must be SYMBOL=INTEGER pairs, got {item!r}")
        if name.strip() in out:
            raise GearleverError(f"--teeth: symbol {name.strip()!r} is given twice")
        try:
            out[name.strip()] = int(value)
        except ValueError:
            raise GearleverError(f"--teeth {name.strip()} must be an integer, got {value.strip()!r}") from None
    return out


def _frac(f) -> str:
    return f"{f.numerator}/{f.denominator}" if f.denominator != 1 else str(f.numerator)


def _run(args) -> int:
    from gearlever.gears.networks import format_linear, parse_network

    text = read_text_capped(args.file, "network file")
    net = parse_network(text, teeth=_teeth(_joined(args.teeth)))
    a = net.analyse()
    result = {
        "unknowns": a.unknowns,
        "rank": a.rank,
        "dof": a.dof,
        "redundant": list(a.redundant),
        "dependencies": {k: {j: _frac(v) for j, v in dep.items()} for k, dep in a.dependencies.items()},
        "locked": dict(a.locked),
    }
    lines = [
        f"unknown rotations {a.unknowns}, rank {a.rank}, degrees of freedom {a.dof}",
        "redundant constraints: "
        + (
            ", ".join(
                f"({k}) = " + format_linear({f"({j})": v for j, v in dep.items()}).replace("rot_", "")
                for k, dep in a.dependencies.items()
            )
            or "none"
        ),
    ]
    if a.locked:
        lines.append("members forced to stand still: " + ", ".join(f"{m} (by ({c}))" for m, c in a.locked.items()))
    if args.inputs:
        inputs = _names(args.inputs, "--inputs")
        sol = net.solve(inputs)
        result["inputs"] = list(sol.inputs)
        result["coefficients"] = {n: [_frac(c) for c in cs] for n, cs in sol.coefficients.items()}
        lines += [sol.relation(n) for n in net.names]
    if args.tabular is not None or args.turned is not None:
        from gearlever.gears.epicyclic import tabular_method

        if args.tabular is None:
            raise GearleverError("--turned needs --tabular CARRIER")
        if not args.inputs:
            raise GearleverError("--tabular needs --inputs (as many as the degrees of freedom)")
        tab = tabular_method(net, args.tabular, result["inputs"], turned=args.turned)
        result["tabular"] = {
            "carrier": tab.carrier,
            "turned": tab.turned,
            "x": [_frac(v) for v in tab.x],
            "y": [_frac(v) for v in tab.y],
            "rows": [
                {
                    "member": r.member,
                    "teeth": r.teeth,
                    "relative": None if r.relative is None else _frac(r.relative),
                    "total": [_frac(v) for v in r.total],
                }
                for r in tab.rows
            ],
        }
        lines += [""] + tab.lines()
    if args.torque or args.loads:
        from gearlever.cli._common import flagged
        from gearlever.gears.torques import parse_assignments, parse_number, torque_report

        inputs = result.get("inputs", [])
        speeds = parse_assignments(_joined(args.speeds), "--speeds") or ({k: 1 for k in inputs} if inputs else None)
        loads = _names(args.loads, "--loads")
        try:
            rep = torque_report(
                net,
                parse_assignments(_joined(args.torque), "--torque"),
                loads,
                speeds=speeds,
                efficiency=parse_number(args.efficiency, "--efficiency"),
            )
        except GearleverError as exc:
            flags = {"applied": "--torque", "loads": "--loads", "speeds": "--speeds", "efficiency": "--efficiency"}
            if speeds is not None and not args.speeds:
                flags["speeds"] = "--inputs (their speeds, 1 each)"
            raise flagged(exc, flags) from None
        result.update(rep)
        lines += [""] + [f"torque on {k}: {v}" for k, v in rep["torques"].items()]
        lines += [f"frame reaction ({k}): {v}" for k, v in rep["frame_reactions"].items()]
        lines += [f"power of {k}: {v}" for k, v in (rep.get("power") or {}).items()]
    if args.format == "json":
        emit(to_json(result), args.out)
    else:
        emit("\n".join(lines), args.out)
    return 0
