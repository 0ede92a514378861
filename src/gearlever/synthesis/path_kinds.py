"""The registry of path-generation kinds: each linkage type one module, the driver a loop over them.

A *kind* is a :class:`PathKind`: its name, its place in ``auto``
(:attr:`PathKind.order`), the problem class of its search space (same
interface as :class:`gearlever.synthesis.path_fourbar.FourBarPathProblem`:
box, exact constraints, batched objective, polish), the builder of its
:class:`PathSynthesis` from a polished start and the writer of its model dict
(:mod:`gearlever.synthesis.model`).  Each kind module registers its kind with
:func:`register` when it is imported:

- :mod:`~gearlever.synthesis.path_fourbar`: ``fourbar``, the Grashof
  crank-rocker (and the base problem of the others);
- :mod:`~gearlever.synthesis.fivebar`: ``geared-fivebar``;
- :mod:`~gearlever.synthesis.sixbar`: ``sixbar``, the Stephenson III six-bar.

The driver :func:`gearlever.synthesis.path.synthesize_path` knows no kind by
name: it takes the problem, the result and the model from here, and ``auto``
tries :func:`names` in order.  A new kind plugs in by a module that
subclasses :class:`PathKind` and calls :func:`register` (listed in
:data:`BUILTIN` to be loaded with the others).

The kinds are kept in the one registry of every synthesis family,
:mod:`gearlever.synthesis.registry` (family ``path``, the :class:`PathKind`
as the record's ``spec``): :func:`register` adds them there, :func:`names`
and :func:`get` read them from there.  The registry imports no kind module
at import time (:func:`names` and :func:`get` load :data:`BUILTIN` on first
use), so a kind module may import it, and the four-bar module, without an
import circle.

Imports numpy, :mod:`gearlever._format`, :mod:`gearlever._result`, :mod:`gearlever.errors` and
:mod:`gearlever.synthesis.registry`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from gearlever._result import Result
from gearlever.errors import GearleverError
from gearlever.synthesis import registry

__all__ = ["BUILTIN", "PathKind", "PathSynthesis", "get", "names", "register"]

#: The modules of the kinds shipped with gearlever, loaded by :func:`names` and :func:`get`.
BUILTIN = registry.FAMILIES["path"]
#: Targets and ranges of the tiny problem of every path kind (:attr:`gearlever.synthesis.registry.Kind.example`).
EXAMPLE = [[1.0, 2.0], [1.5, 2.4], [1.8, 3.0], [1.2, 3.5], [0.8, 2.8]]


class PathKind:
    """A path-generation linkage type: search space, result builder and model writer.

    Subclasses set :attr:`name`, :attr:`order` and :attr:`problem` and
    override :meth:`result` and :meth:`model`; :func:`register` makes them
    known to the driver.

    Attributes
    ----------
    name : str
        The kind's name (``--type`` of ``gearlever synthesize path``).
    description : str
        One line for :func:`gearlever.synthesis.kinds` (default: the class docstring's first line).
    order : float
        Place in ``auto`` (smallest first); ties by name.
    problem : type
        Problem class, called with the problem's keyword arguments (targets,
        timing, angles, ranges...).
    options : frozenset of str
        Optional constraints only this kind takes (``min_transmission``).
    closed_path : bool
        The motion repeats after one crank turn, so a last target equal to
        the first is met one turn later (the driver then searches without it).

    Examples
    --------
    >>> get("fourbar").name, get("fourbar").problem.__name__
    ('fourbar', 'FourBarPathProblem')
    """

    name: str = ""
    description: str = ""
    order: float = math.inf
    problem: type = None
    options: frozenset = frozenset()
    closed_path: bool = False

    def make_problem(self, **spec):
        """The problem of this kind for keyword arguments ``spec`` (checked by the problem)."""
        return self.problem(**spec)

    def result(self, pb, w, mode, evals, seed, starts, seconds) -> PathSynthesis:
        """The :class:`PathSynthesis` of polish vector ``w`` with discrete ``mode`` on problem ``pb``."""
        raise NotImplementedError

    def model(self, result: PathSynthesis, name: str, units: str) -> dict:
        """The model dict of ``result`` (crank input, assembled at the first target)."""
        raise NotImplementedError


def _example() -> tuple:
    """``(args, kwargs)`` of the tiny problem of every path kind (five targets, small ranges)."""
    return (EXAMPLE,), {"length_range": (0.2, 5), "coord_range": (-5, 5)}


def register(kind):
    """Add a :class:`PathKind` (subclass or instance) to the registry under its name; returns ``kind``.

    Usable as a class decorator.  Registering a name again replaces the kind.
    The kind is a record of family ``path`` of :mod:`gearlever.synthesis.registry`,
    run by :func:`gearlever.synthesis.path.synthesize_path`.

    Examples
    --------
    >>> @register
    ... class Probe(PathKind):
    ...     name, order = "probe", 1e9
    >>> names()[-1]
    'probe'
    >>> _ = registry._KINDS.pop(("path", "probe"))
    """
    inst = kind() if isinstance(kind, type) else kind
    if not isinstance(inst, PathKind) or not isinstance(inst.name, str) or not inst.name:
        raise GearleverError(f"kind must be a PathKind with a name, got {kind!r}")
    if inst.name == "auto":
        raise GearleverError("kind name 'auto' is the driver's (try every kind)")
    doc = (type(inst).__doc__ or "").strip().splitlines()
    registry.register(
        registry.Kind(
            "path",
            inst.name,
            inst.description or (doc[0] if doc else inst.name),
            "gearlever.synthesis.path:synthesize_path",
            min_budget=480,
            order=inst.order,
            example=_example,
            spec=inst,
        )
    )
    return kind


def names() -> tuple:
    """Names of the registered kinds, in ``auto`` order (:attr:`PathKind.order`, then name).

    Examples
    --------
    >>> names()
    ('fourbar', 'geared-fivebar', 'sixbar')
    """
    return registry.names("path")


def get(name: str) -> PathKind:
    """The registered kind ``name``, or a refusal naming ``kind`` and the kinds known.

    Examples
    --------
    >>> get("sixbar").problem.__name__
    'StephensonSixBarPathProblem'
    """
    return registry.get("path", name).spec


@dataclass(frozen=True)
class PathSynthesis(Result):
    """A synthesized path generator and how well it meets the targets.

    Attributes
    ----------
    kind : str
        Linkage type (a registered kind: ``"fourbar"``, ``"geared-fivebar"``, ``"sixbar"``).
    target, achieved : ndarray (N, 2)
        Target points and the traced (coupler) point at the targets' crank angles.
    error : ndarray (N,)
        Distance target to traced point (the per-target error).
    objective : float
        ``sum(error**2)``.
    crank_angles : ndarray (N,)
        Crank angles from the ground line at the targets, radians, increasing.
    input_angles : ndarray (N,)
        The model's input (crank angle from +x) at the targets, radians,
        from the first target counter-clockwise (increasing).
    points : dict
        ``O2, O4, A, B, P`` at the first target.
    links : dict
        ``ground, crank, coupler, rocker`` lengths.
    branch : str
        ``"open"`` or ``"crossed"`` (as in :func:`gearlever.loops.fourbar`).
    grashof : str
        Grashof kind (``"crank-rocker"`` for a buildable result).
    transmission_range : tuple
        Smallest and largest transmission angle over a crank turn, radians.
    feasible : bool
        Every constraint holds.
    evaluations, seed, starts : int
    timing : str
    seconds : float
        Wall time of the synthesis.

    Examples
    --------
    >>> from gearlever.synthesis.path import synthesize_path
    >>> t = [[1.0, 2.0], [1.5, 2.4], [1.8, 3.0], [1.2, 3.5]]
    >>> r = synthesize_path(t, length_range=(0.2, 5), coord_range=(-5, 5), budget=4000, workers=1)
    >>> r.kind, sorted(r.model()["links"])
    ('fourbar', ['coupler', 'crank', 'ground', 'rocker'])
    """

    kind: str
    target: np.ndarray
    achieved: np.ndarray
    error: np.ndarray
    objective: float
    crank_angles: np.ndarray
    input_angles: np.ndarray
    points: dict
    links: dict
    branch: str
    grashof: str
    transmission_range: tuple
    feasible: bool
    evaluations: int
    seed: int
    starts: int
    timing: str
    seconds: float = field(default=0.0, compare=False)
    params: dict = field(default_factory=dict, compare=False)
    path: np.ndarray = field(default=None, compare=False)
    teeth: tuple = ()
    tried: dict = field(default_factory=dict)

    def model(self, name: str = "synthesized path generator", units: str = "") -> dict:
        """Model dict (crank input) assembled at the first target, written by the kind's model writer."""
        return get(self.kind).model(self, name=name, units=units)

    def curve(self) -> np.ndarray:
        """The traced point's closed path (K, 2) from the first target over the period of the motion."""
        return self.path

    def summary(self) -> dict:
        """The JSON-ready summary (degrees for angles), each number at the digits its computation determines.

        Keys: ``type``, ``objective``, ``feasible``, ``timing``,
        ``per_target_error`` (:attr:`error`), ``input_deg``,
        ``crank_deg_from_ground``, ``grashof``, ``teeth``, ``branch``,
        ``links``, ``transmission_deg`` (:attr:`transmission_range`),
        ``evaluations``, ``seed``, ``types_tried`` (:attr:`tried`), ``starts``,
        ``time_s`` (to 0.01 s); the command line writes it as its report.

        Notes
        -----
        The digits rule of :mod:`gearlever._format`
        (:func:`~gearlever._format.rounded_report`, :data:`~gearlever._format.DIGITS_DESIGN`
        digits): distances at the digits of the targets' size ``S`` (the
        diagonal of their bounding box), objectives (sums of squared
        distances) at those of ``S**2``, angles of 360 deg, link lengths of
        the longest link, so that an exact fit is written 0, not its rounding
        noise; NaN is None (strict JSON).

        Examples
        --------
        >>> from gearlever.synthesis.path import synthesize_path
        >>> t = [[1.0, 2.0], [1.5, 2.4], [1.8, 3.0], [1.2, 3.5]]
        >>> s = synthesize_path(t, length_range=(0.2, 5), coord_range=(-5, 5), budget=4000, workers=1).summary()
        >>> s["type"], s["feasible"], len(s["per_target_error"])
        ('fourbar', True, 4)
        """
        from gearlever._format import DIGITS_DESIGN, rounded_report

        rep = {
            "type": self.kind,
            "objective": self.objective,
            "feasible": self.feasible,
            "timing": self.timing,
            "per_target_error": self.error.tolist(),
            "input_deg": np.degrees(self.input_angles).tolist(),
            "crank_deg_from_ground": np.degrees(self.crank_angles).tolist(),
            "grashof": self.grashof,
            "teeth": list(self.teeth) if self.teeth else None,
            "branch": self.branch,
            "links": dict(self.links),
            "transmission_deg": [math.degrees(v) for v in self.transmission_range],
            "evaluations": self.evaluations,
            "seed": self.seed,
            "types_tried": dict(self.tried),
            "starts": self.starts,
            "time_s": round(float(self.seconds), 2),
        }
        S = float(np.hypot(*np.ptp(np.asarray(self.target, dtype=float), axis=0))) or 1.0
        links = [abs(float(v)) for v in rep["links"].values() if isinstance(v, (int, float))]
        scales = {"objective": S * S, "per_target_error": S, "types_tried": S * S}
        scales["links"] = max(links) if links else 0.0
        scales.update(dict.fromkeys(("input_deg", "crank_deg_from_ground", "transmission_deg"), 360.0))
        return rounded_report(rep, DIGITS_DESIGN, scales)
