"""Every public function and class has a numpydoc ``Examples`` section with a doctest.

Public means: named in ``gearlever.__all__`` or in the ``__all__`` of one of
its subpackages (``gearlever.gears``, ``gearlever.mechanism``...).  The
doctests themselves run with the rest of the suite (``--doctest-modules``).

:data:`WITHOUT_EXAMPLE` is the explicit list of the names still lacking one.
It may only shrink: a new public name without an example fails
:func:`test_every_public_name_has_an_example`, and a listed name that gained
one fails :func:`test_the_allow_list_holds_only_names_still_without_an_example`
until it is taken off the list.
"""

from __future__ import annotations

import importlib
import inspect
import pkgutil
import re

import pytest

import gearlever

#: Public names (module of definition + qualified name) still without an Examples section.
WITHOUT_EXAMPLE: set[str] = set()

EXAMPLES = re.compile(r"^Examples\n-{8,}\n(?:.*\n)*?\s*>>> ", re.M)


def _packages() -> list[str]:
    names = ["gearlever"]
    for info in pkgutil.walk_packages(gearlever.__path__, "gearlever."):
        if info.ispkg and not any(part.startswith("_") for part in info.name.split(".")):
            names.append(info.name)
    return names


def _public() -> dict[str, object]:
    """``{module.qualname: object}`` of every function and class named in a package's ``__all__``."""
    out = {}
    for package in _packages():
        module = importlib.import_module(package)
        for name in getattr(module, "__all__", ()):
            obj = getattr(module, name)
            if inspect.isfunction(obj) or inspect.isclass(obj):
                out.setdefault(f"{obj.__module__}.{obj.__qualname__}", obj)
    return out


PUBLIC = _public()


def _has_example(obj) -> bool:
    return bool(EXAMPLES.search((inspect.getdoc(obj) or "") + "\n"))


def test_the_public_api_is_found():
    assert len(PUBLIC) >= 80
    assert "gearlever.mechanism.core.Mechanism" in PUBLIC and "gearlever.loops.fourbar.fourbar" in PUBLIC


@pytest.mark.parametrize("name", sorted(set(PUBLIC) - WITHOUT_EXAMPLE))
def test_every_public_name_has_an_example(name):
    assert _has_example(PUBLIC[name]), f"{name}: add an Examples section with a doctest (numpydoc)"


def test_the_allow_list_holds_only_names_still_without_an_example():
    unknown = sorted(WITHOUT_EXAMPLE - set(PUBLIC))
    done = sorted(n for n in WITHOUT_EXAMPLE & set(PUBLIC) if _has_example(PUBLIC[n]))
    assert unknown == [], f"not public (any more): {unknown}"
    assert done == [], f"these have an example now: take them off WITHOUT_EXAMPLE: {done}"


def test_the_examples_pattern_needs_a_section_and_a_doctest():
    def with_section():
        """Do.

        Examples
        --------
        >>> 1
        1
        """

    def bare_doctest():
        """Do.

        >>> 1
        1
        """

    def section_without_doctest():
        """Do.

        Examples
        --------
        Call it.
        """

    assert [_has_example(f) for f in (with_section, bare_doctest, section_without_doctest)] == [True, False, False]
