"""Package layout rules: a pure numeric core, pandas and pyplot each in one place."""

import pathlib
import re
import subprocess
import sys

import gearlever

SRC = pathlib.Path(gearlever.__file__).parent


def _modules_importing(pattern):
    rx = re.compile(pattern, re.MULTILINE)
    return sorted(str(p.relative_to(SRC)) for p in SRC.rglob("*.py") if rx.search(p.read_text(encoding="utf-8")))


def test_import_gearlever_loads_neither_matplotlib_pandas_scipy_nor_numba():
    mods = "('matplotlib', 'pandas', 'scipy', 'numba')"
    code = f"import sys, gearlever; print(sorted(m for m in {mods} if m in sys.modules))"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.strip() == "[]"


def test_pyplot_is_imported_only_in_plotting():
    users = _modules_importing(r"^\s*(import matplotlib\.pyplot|from matplotlib import pyplot)")
    assert users and all(u.startswith("plotting/") for u in users), users


def test_numba_is_imported_only_by_the_compiled_kernels():
    users = _modules_importing(r"^\s*(import numba|from numba)")
    assert users == ["loops/compiled.py", "zrdpm/_kernels.py"], users


def test_pandas_is_imported_only_in_tables():
    """And lazily in ``_frame.py``, the leaf that builds ``Result.to_frame`` (the base must not import tables)."""
    users = _modules_importing(r"^\s*(import pandas|from pandas)")
    assert users and all(u.startswith("tables/") or u == "_frame.py" for u in users), users


def test_nothing_in_the_package_reads_the_shared_folder():
    assert _modules_importing(r"shared/(seeds|reference)") == []


def test_public_names_are_exported():
    for name in gearlever.__all__:
        assert hasattr(gearlever, name), name
