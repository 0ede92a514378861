#!/bin/sh
# Move the topology synthesis of closed curves, gearlever.curves, to gearlever.synthesis.curve (beside
# gearlever.synthesis.law): every family of synthesis (function, motion, path, law, curve) then lives in one
# package, as gearlever.synthesis.kinds() already lists them.  Issue 30, "Names that explain themselves".
#
# Run once, from the repository root, on a clean tree after the round's merges (another helper edited
# curves/search.py this round), then: make .venv/.installed-test (the editable install's file list),
# .venv/bin/python -m pytest -n 0 tests/test_imports.py tests/synthesis/curve, ruff, make docs, and
# `make reproduce && git diff --exit-code --stat tables figures` (module paths are in no output).
set -eu
test -d src/gearlever/curves || { echo "src/gearlever/curves is gone already" >&2; exit 1; }
test -z "$(git status --porcelain --untracked-files=no)" || { echo "commit or stash first: the tree is not clean" >&2; exit 1; }

git mv src/gearlever/curves src/gearlever/synthesis/curve
git mv tests/curves tests/synthesis/curve

# module paths, in code and prose (docs, benchmarks; the changelog's history is left as it was)
files=$(git grep -l -E 'gearlever\.curves\b|gearlever/curves\b|tests\.curves\b|tests/curves\b' -- \
    src tests docs benchmarks README.md pyproject.toml Makefile ':!CHANGELOG.md' || true)
for f in $files; do
    sed -i -E \
        -e 's/gearlever\.curves\b/gearlever.synthesis.curve/g' \
        -e 's#gearlever/curves\b#gearlever/synthesis/curve#g' \
        -e 's/tests\.curves\b/tests.synthesis.curve/g' \
        -e 's#tests/curves\b#tests/synthesis/curve#g' \
        "$f"
done

# the layering: curves is no longer a unit of its own; synthesis already may import all it imported
python3 - <<'EOF'
import pathlib, re

p = pathlib.Path("tests/test_imports.py")
s = p.read_text()
s = s.replace(', "synthesis", "curves"}', ', "synthesis"}')
s = re.sub(r'\n    "curves": _BASE \| \{[^}]*\},', "", s)
p.write_text(s)

p = pathlib.Path("docs/guide/architecture.rst")
out = []
for line in p.read_text().splitlines(keepends=True):
    m = re.match(r"^``(\w+)``(\s{2,})(.*)$", line.rstrip("\n"))
    if m:
        if m.group(1) == "curves":
            continue
        items = [i for i in re.findall(r"``(\w+)``", m.group(3)) if i != "curves"]
        rest = ", ".join(f"``{i}``" for i in items) if items else m.group(3)
        line = f"``{m.group(1)}``".ljust(15) + rest + "\n"
    out.append(line)
s = "".join(out)
a = s.index("- ``curves``: topology synthesis")
b = s.index("- ``tables``:", a)
s = s[:a] + s[b:]
old = (
    "- ``synthesis``: function, motion, path and law synthesis, written as model\n"
    "  files; ``synthesis.report`` checks target pairs and summarizes a function\n"
    "  synthesis.\n"
)
assert s.count(old) == 1, "the synthesis item of the architecture page changed: edit it by hand"
s = s.replace(
    old,
    "- ``synthesis``: function, motion, path, law and curve synthesis\n"
    "  (``synthesis.curve``: the topology synthesis of a linkage for a traced\n"
    "  curve), written as model files; ``synthesis.report`` checks target pairs\n"
    "  and summarizes a function synthesis.\n",
)
p.write_text(s)

p = pathlib.Path("CHANGELOG.md")
s = p.read_text()
head = "### Moved (old -> new)\n\n"
s = s.replace(
    head,
    head + "- `gearlever.curves` -> `gearlever.synthesis.curve` (the topology synthesis of a linkage for a traced\n"
    "  curve, beside `gearlever.synthesis.law`: every family of `gearlever.synthesis.kinds()` in one package).\n",
    1,
)
p.write_text(s)
EOF

# imports re-sorted (gearlever.synthesis.curve sorts elsewhere than gearlever.curves), then formatted
.venv/bin/ruff check --fix --select I src tests benchmarks docs/gallery
.venv/bin/ruff format src tests benchmarks docs/gallery

echo "moved: gearlever.curves -> gearlever.synthesis.curve (architecture page and CHANGELOG updated); run the checks"
echo "named at the top of this script, then commit"
