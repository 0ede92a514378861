"""The one registry of synthesis kinds: every kind of every family, listed by :func:`kinds`.

A *kind* is a :class:`Kind` record: its family (``function``, ``motion``,
``path``, ``law``, ``curve``), its name, one line of description, the
family's driver it runs (``entry``, ``"module:function"``), whether it is a
seeded search with a budget (:attr:`Kind.searched`) and a tiny problem
(:attr:`Kind.example`) on which the contract tests
(``tests/synthesis/test_contract.py``) run every kind.  Each family
registers its kinds with :func:`register` when its module is imported:

- :mod:`gearlever.synthesis.function`: ``fourbar``, ``slider-crank``
  (Freudenstein's equation; exact for three precision points, least squares
  for more);
- :mod:`gearlever.synthesis.motion`: ``3-poses``, ``4-poses``, ``5-poses``
  (Burmester);
- the path kinds' modules (:mod:`~gearlever.synthesis.path_fourbar`,
  :mod:`~gearlever.synthesis.fivebar`, :mod:`~gearlever.synthesis.sixbar`):
  ``fourbar``, ``geared-fivebar``, ``sixbar`` (through
  :func:`gearlever.synthesis.path_kinds.register`);
- :mod:`gearlever.synthesis.law`: ``fourbar``, ``geared-fourbar``,
  ``gear-lever``, ``sixbar-dwell``, ``slider-crank``, ``slotted-lever``,
  ``sixbar-slider`` (each kind's module registers its
  :class:`~gearlever.synthesis.law.LawKind` class, the record's ``spec``,
  through :func:`gearlever.synthesis.law._core.register`: the law family has
  no registry of its own);
- :mod:`gearlever.synthesis.curve.search`: ``topology`` (the curve synthesis).

:func:`kinds` imports the family modules of :data:`FAMILIES` first (by name,
so this module imports none of them: it is a leaf that every family may
import), and a kind's driver is imported when the kind is called
(:attr:`Kind.synthesize`).  The command line takes its ``--type`` choices
from :func:`names`.

Imports :mod:`gearlever.errors` only.
"""

from __future__ import annotations

import functools
import importlib
import math
import sys
import types
from collections.abc import Callable
from dataclasses import dataclass

from gearlever.errors import GearleverError

__all__ = ["FAMILIES", "Kind", "get", "kinds", "names", "register"]

#: The families and the modules that register each one's kinds (imported by :func:`kinds`).
FAMILIES = {
    "function": ("gearlever.synthesis.function",),
    "motion": ("gearlever.synthesis.motion",),
    "path": ("gearlever.synthesis.path_fourbar", "gearlever.synthesis.fivebar", "gearlever.synthesis.sixbar"),
    "law": ("gearlever.synthesis.law",),
    "curve": ("gearlever.synthesis.curve.search",),
}

#: (family, name) -> :class:`Kind`, filled by :func:`register`.  The dict is kept in a module of its own
#: without a file (``sys.modules[STORE]``), so it outlives a second execution of this file (pytest's
#: importlib import mode runs a collected module's file again): the kinds the family modules registered
#: at their import stay known.
STORE = "gearlever.synthesis._registered_kinds"
if STORE not in sys.modules:
    sys.modules[STORE] = types.ModuleType(STORE, "The registered synthesis kinds (gearlever.synthesis.registry).")
    sys.modules[STORE].kinds = {}
_KINDS: dict = sys.modules[STORE].kinds


@dataclass(frozen=True)
class Kind:
    """A registered synthesis kind.

    Attributes
    ----------
    family : str
        One of :data:`FAMILIES`.
    name : str
        The kind's name within its family (``--type`` of ``gearlever synthesize FAMILY``).
    description : str
        One line: what the kind synthesizes, and how.
    entry : str
        ``"module:function"``: the family's driver.
    kind_arg : str or None
        The driver's keyword that selects this kind (``"kind"``), or None
        when the driver serves this kind alone or tells it from its input
        (motion: the number of poses).
    searched : bool
        A seeded multistart search with a budget
        (:func:`gearlever.synthesis.driver.multistart`): the result has
        ``seed`` and ``evaluations`` and the call takes ``seed``,
        ``budget`` and ``workers``.  Otherwise a closed form or an exact
        solve (function, motion): no seed, no budget.
    polish_counted : bool
        The result's ``evaluations`` count the polish too, inside the
        budget (law: at most ``budget`` per kind tried, searches and
        polishes together); otherwise the polish is not counted (path,
        curve).  Either way ``evaluations <= budget``.
    min_budget : int
        Smallest budget of the tiny problem (searched kinds).
    order : float
        Place among the family's kinds (smallest first; then by name).
    example : callable or None
        ``example()`` returns ``(args, kwargs)`` of a tiny problem of this
        kind (seconds to solve), for the contract tests and the docs.
    spec : object
        The family's own description of the kind (a
        :class:`~gearlever.synthesis.path_kinds.PathKind`, a
        :class:`~gearlever.synthesis.law.LawKind` class), or None.

    Examples
    --------
    >>> k = get("path", "sixbar")
    >>> k.family, k.entry, k.searched
    ('path', 'gearlever.synthesis.path:synthesize_path', True)
    """

    family: str
    name: str
    description: str
    entry: str
    kind_arg: str | None = "kind"
    searched: bool = True
    polish_counted: bool = False
    min_budget: int = 0
    order: float = math.inf
    example: Callable | None = None
    spec: object = None

    @property
    def synthesize(self) -> Callable:
        """The driver bound to this kind: ``kind.synthesize(*args, **kwargs)`` runs it."""
        module, _, name = self.entry.partition(":")
        fn = getattr(importlib.import_module(module), name)
        return functools.partial(fn, **{self.kind_arg: self.name}) if self.kind_arg else fn

    def __call__(self, *args, **kwargs):
        """Run the kind: ``self.synthesize(*args, **kwargs)``."""
        return self.synthesize(*args, **kwargs)


def register(kind: Kind) -> Kind:
    """Add ``kind`` to the registry (a kind of the same family and name is replaced); returns it.

    Examples
    --------
    >>> k = register(Kind("path", "probe", "a probe", "gearlever.synthesis.path:synthesize_path", order=1e9))
    >>> names("path")[-1]
    'probe'
    >>> _ = _KINDS.pop(("path", "probe"))
    """
    if not all(hasattr(kind, a) for a in ("family", "name", "entry", "kind_arg")):  # a Kind (of any copy of it)
        raise GearleverError(f"kind must be a Kind record, got {kind!r}")
    if kind.family not in FAMILIES:
        raise GearleverError(f"family must be one of {', '.join(FAMILIES)}, got {kind.family!r}")
    if not isinstance(kind.name, str) or not kind.name or kind.name == "auto":
        raise GearleverError(f"kind name must be a non-empty name other than 'auto', got {kind.name!r}")
    _KINDS.pop((kind.family, kind.name), None)
    _KINDS[(kind.family, kind.name)] = kind
    return kind


def _load(family: str | None = None) -> None:
    for fam, modules in FAMILIES.items():
        if family is None or fam == family:
            for module in modules:
                importlib.import_module(module)


def kinds(family: str | None = None) -> tuple:
    """Every registered :class:`Kind` (of ``family`` alone if given), by family then order.

    Examples
    --------
    >>> [(k.family, k.name) for k in kinds("motion")]
    [('motion', '3-poses'), ('motion', '4-poses'), ('motion', '5-poses')]
    >>> sorted({k.family for k in kinds()})
    ['curve', 'function', 'law', 'motion', 'path']
    """
    if family is not None and family not in FAMILIES:
        raise GearleverError(f"family must be one of {', '.join(FAMILIES)}, got {family!r}")
    _load(family)
    rank = {f: i for i, f in enumerate(FAMILIES)}
    out = sorted(
        (k for k in _KINDS.values() if family is None or k.family == family),
        key=lambda k: (rank[k.family], k.order, k.name),
    )
    return tuple(out)


def names(family: str) -> tuple:
    """Names of ``family``'s kinds, in order (the ``--type`` choices, before ``auto`` where a family has it).

    >>> names("function")
    ('fourbar', 'slider-crank')
    """
    return tuple(k.name for k in kinds(family))


def get(family: str, name: str) -> Kind:
    """The kind ``name`` of ``family``, or a refusal naming ``kind`` and the family's kinds."""
    known = names(family)
    if name not in known:
        raise GearleverError(f"kind must be one of {', '.join(known)}, got {name!r}")
    return _KINDS[(family, name)]
