"""The measures of issue 30 ("one house"), printed for a closing note: run from the repository root.

    .venv/bin/python tools/house_metrics.py

Prints the import circles between modules and between top-level units (the graph of
``tests/test_imports.py``: imports inside functions count), the command line's share of the package's
lines, the ten longest functions (``end_lineno - lineno + 1``, docstrings included), the CSV readers,
rounding helpers and argument validators outside their one home (``_io``, ``_format``, ``_validate``),
``gearlever.synthesis.kinds()``, and the round trip of every shipped model
(``Mechanism.loads(m.dumps())``: the same text again and the same solve).  Everything is read with
:mod:`ast` except the last two, which import the package.
"""

from __future__ import annotations

import ast
import importlib.util
import pathlib
import re
import sys

import numpy as np

ROOT = pathlib.Path(__file__).resolve().parents[1]
SRC = ROOT / "src" / "gearlever"

#: Calls that parse CSV text (the one home is gearlever._io).
CSV_CALLS = {"csv.reader", "csv.DictReader", "np.loadtxt", "np.genfromtxt", "numpy.loadtxt", "pd.read_csv"}
#: Calls that round numbers to digits (the one home is gearlever._format).
ROUND_CALLS = {"round", "np.round", "np.around", "numpy.round"}
#: Generic argument checks (the one home is gearlever._validate): a function of that name elsewhere.
VALIDATOR = re.compile(
    r"^_?(check_)?(is_)?(finite|positive|nonnegative|non_negative|real_number|posint|positive_int|nonnegative_int|"
    r"finite_array|nonempty_array|positive_float|finite_float|positive_number|number)(_value|_arg)?$"
)


def _files():
    return sorted(p for p in SRC.rglob("*.py"))


def _rel(p: pathlib.Path) -> str:
    return str(p.relative_to(SRC.parent))


def _dotted(node) -> str:
    if isinstance(node, ast.Name):
        return node.id
    if isinstance(node, ast.Attribute):
        return f"{_dotted(node.value)}.{node.attr}"
    return ""


def circles() -> tuple[list, list]:
    spec = importlib.util.spec_from_file_location("_test_imports", ROOT / "tests" / "test_imports.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod.circles(mod.GRAPH), mod.circles(mod.UNITS)


def cli_share() -> tuple[int, int]:
    total = cli = 0
    for p in _files():
        n = len(p.read_text(encoding="utf-8").splitlines())
        total += n
        cli += n if "cli" in p.relative_to(SRC).parts[:1] else 0
    return cli, total


def longest(k: int = 10) -> list:
    rows = []
    for p in _files():
        tree = ast.parse(p.read_text(encoding="utf-8"))
        stack = [(tree, "")]
        while stack:
            node, prefix = stack.pop()
            for child in ast.iter_child_nodes(node):
                if isinstance(child, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
                    name = f"{prefix}{child.name}"
                    if not isinstance(child, ast.ClassDef):
                        rows.append((child.end_lineno - child.lineno + 1, f"{_rel(p)}:{child.lineno} {name}"))
                    stack.append((child, name + "."))
                else:
                    stack.append((child, prefix))
    return sorted(rows, key=lambda r: (-r[0], r[1]))[:k]


def outside_homes() -> dict:
    found = {"csv readers": [], "rounding helpers": [], "validators": []}
    for p in _files():
        rel = _rel(p)
        tree = ast.parse(p.read_text(encoding="utf-8"))
        for node in ast.walk(tree):
            if isinstance(node, ast.Call) and _dotted(node.func) in CSV_CALLS and not rel.endswith("/_io.py"):
                found["csv readers"].append(f"{rel}:{node.lineno} {_dotted(node.func)}")
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
                if VALIDATOR.match(node.name) and not rel.endswith("/_validate.py"):
                    found["validators"].append(f"{rel}:{node.lineno} {node.name}")
                # a rounding helper: a function with its own significant-digits rule (the decimals from
                # floor(log10(scale)), rounded with round or np.round) instead of calling gearlever._format
                if rel.endswith("/_format.py"):
                    continue
                body = [c for c in ast.walk(node) if isinstance(c, ast.Call)]
                digits_rule = any(_dotted(c.func) == "math.floor" and "log10" in ast.unparse(c) for c in body)
                rounds = any(_dotted(c.func) in ROUND_CALLS and len(c.args) + len(c.keywords) >= 2 for c in body)
                if digits_rule and rounds:
                    found["rounding helpers"].append(f"{rel}:{node.lineno} {node.name}")
    return found


def kinds() -> list:
    from gearlever.synthesis import kinds as _kinds

    return [(k.family, k.name) for k in _kinds()]


def round_trips() -> list:
    from gearlever.mechanism import Mechanism

    rows = []
    for path in sorted((SRC / "data" / "examples").glob("*.toml")):
        if "[law]" in path.read_text(encoding="utf-8"):
            continue
        m = Mechanism.load(path)
        text = m.dumps()
        m2 = Mechanism.loads(text)
        q0 = m.sketch_inputs
        q = q0[None, :] + np.linspace(0.0, 1.0, 5)[:, None] * (1.0 if q0.size else 0.0)
        r1, r2 = m.solve(q), m2.solve(q)
        gaps = [np.nanmax(np.abs(r1.point[p] - r2.point[p]), initial=0.0) for p in m.model.points]
        diff = float(max(gaps, default=0.0))
        same = bool(np.array_equal(r1.closed, r2.closed))
        rows.append((path.name, m2.dumps() == text, same, diff))
    return rows


def main() -> int:
    mod, units = circles()
    print(f"import circles: {len(mod)} between modules, {len(units)} between units")
    for c in mod + units:
        print("  ", sorted(c))
    cli, total = cli_share()
    print(f"cli share: {cli} of {total} lines ({100 * cli / total:.1f} %)")
    print("ten longest functions (lines):")
    for n, where in longest():
        print(f"  {n:4d}  {where}")
    for what, rows in outside_homes().items():
        print(f"{what} outside their home: {len(rows)}")
        for r in rows:
            print("  ", r)
    ks = kinds()
    print(f"synthesis.kinds(): {len(ks)}")
    fams: dict = {}
    for fam, name in ks:
        fams.setdefault(fam, []).append(name)
    for fam, names in fams.items():
        print(f"  {fam}: {', '.join(names)}")
    rt = round_trips()
    ok = sum(1 for _, text, same, d in rt if text and same and d <= 1e-12)
    print(f"round trip of the shipped models: {ok} of {len(rt)} (same text, same closed rows, points within 1e-12)")
    for name, text, same, d in rt:
        said = f"text {'same' if text else 'DIFFERS'}, closed {'same' if same else 'DIFFERS'}"
        print(f"  {name}: {said}, max |dp| {d:.3g}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
