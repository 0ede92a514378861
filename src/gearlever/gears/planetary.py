"""Planetary gear sets: exact speed ratios, assembly conditions and an exhaustive tooth search.

Two kinds, all gears of one module (standard, unshifted teeth):

``simple``
    sun ``z_s`` meshes planet ``z_p``, which meshes the ring ``z_r`` (internal).
``compound``
    sun ``z_s`` meshes planet gear ``z_p1``; ``z_p2`` on the same planet
    shaft meshes the ring ``z_r``.

:func:`design_planetary` searches every tooth set in a range and returns all
sets with the least ratio error; :func:`planetary_network` writes a set as a
:class:`~gearlever.gears.networks.Network` (meshes on the carrier), so the
closed forms here are checked against the general solver.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from decimal import Decimal, localcontext
from fractions import Fraction
from functools import cache

import numpy as np

from gearlever._result import Result
from gearlever.errors import GearleverError
from gearlever.gears.networks import FRAME, Gear, Mesh, Network, SameShaft

__all__ = [
    "KINDS",
    "MEMBERS",
    "MAX_TEETH",
    "MAX_PLANETS",
    "PlanetarySet",
    "PlanetaryDesign",
    "basic_ratio",
    "speed_ratio",
    "planetary_network",
    "design_planetary",
]

#: Kinds of planetary set.
KINDS = ("simple", "compound")
#: The three coaxial members.
MEMBERS = ("sun", "ring", "carrier")
#: Largest tooth number the search accepts, per kind (it visits ~max^2/4 simple and ~max^3/6 compound sets).
MAX_TEETH = {"simple": 2000, "compound": 300}
#: Largest number of planets.
MAX_PLANETS = 64

_PI50 = Decimal("3.14159265358979323846264338327950288419716939937510582097494459")


@cache
def _sin_pi_over(n: int) -> Decimal:
    """sin(pi/n) to 60 digits (Taylor series in :mod:`decimal`)."""
    with localcontext() as ctx:
        ctx.prec = 70
        x = _PI50 / n
        term, total, k = x, x, 1
        while abs(term) > Decimal(10) ** -66:
            term = -term * x * x / ((2 * k) * (2 * k + 1))
            total += term
            k += 1
        return +total


def _less_than_sin(num: int, den: int, n: int) -> bool:
    """Exactly ``num/den < sin(pi/n)``.

    sin(pi/n) is rational only for n = 1, 2, 6 (Niven's theorem), where the
    test is done in integers; otherwise it is irrational and 60 digits decide.
    """
    if n == 2:
        return num < den
    if n == 6:
        return 2 * num < den
    with localcontext() as ctx:
        ctx.prec = 70
        return Decimal(num) / Decimal(den) < _sin_pi_over(n)


def _check_int(name: str, value, lo: int, hi: int | None = None) -> int:
    ok = isinstance(value, (int, np.integer)) and not isinstance(value, bool)
    if not ok or value < lo or (hi is not None and value > hi):
        rng = f">= {lo}" if hi is None else f"in [{lo}, {hi}]"
        raise GearleverError(f"{name} must be an integer {rng}, got {value!r}")
    return int(value)


def basic_ratio(sun: int, ring: int, planet1: int | None = None, planet2: int | None = None) -> Fraction:
    """Willis' basic ratio ``i0 = (w_sun - w_carrier)/(w_ring - w_carrier)`` of a simple or compound set.

    Simple set: leave ``planet1``, ``planet2`` out (or equal): ``i0 = -z_r/z_s``.
    Compound: ``i0 = -(z_p1 z_r)/(z_s z_p2)``.

    Examples
    --------
    >>> basic_ratio(24, 60)
    Fraction(-5, 2)
    >>> basic_ratio(20, 80, 40, 20)
    Fraction(-8, 1)

    Notes
    -----
    Willis' equation, the carrier held: the sun drives the planet (external,
    reversal), the planet drives the ring (internal, same sense); R. Willis,
    *Principles of Mechanism*, 2nd ed., 1870, epicyclic trains; J. E. Shigley
    and J. J. Uicker, *Theory of Machines and Mechanisms*, planetary trains
    (train value e = (w_L - w_A)/(w_F - w_A)).
    """
    zs = _check_int("sun teeth", sun, 1)
    zr = _check_int("ring teeth", ring, 1)
    if planet1 is None and planet2 is None:
        return Fraction(-zr, zs)
    p1 = _check_int("planet1 teeth", planet1, 1)
    p2 = _check_int("planet2 teeth", planet2, 1)
    return Fraction(-p1 * zr, zs * p2)


def _role_coefs(i0):
    # w_s - w_c - i0 (w_r - w_c) = 0
    return {"sun": 1, "ring": -i0, "carrier": i0 - 1}


def _roles(fixed: str, input: str, output: str | None) -> tuple[str, str, str]:
    for what, v in (("fixed", fixed), ("input", input)):
        if v not in MEMBERS:
            raise GearleverError(f"{what} must be one of {', '.join(MEMBERS)}, got {v!r}")
    if output is None:
        rest = [m for m in MEMBERS if m not in (fixed, input)]
        if len(rest) != 1:
            raise GearleverError(f"fixed and input must be different members, got {fixed!r} for both")
        output = rest[0]
    if output not in MEMBERS:
        raise GearleverError(f"output must be one of {', '.join(MEMBERS)}, got {output!r}")
    if len({fixed, input, output}) != 3:
        raise GearleverError(f"fixed, input and output must be three different members, got {fixed}, {input}, {output}")
    return fixed, input, output


def speed_ratio(i0: Fraction, fixed: str = "ring", input: str = "sun", output: str | None = None) -> Fraction:
    """Exact speed ratio ``w_input / w_output`` with ``fixed`` held, from the basic ratio ``i0``.

    Examples
    --------
    >>> speed_ratio(Fraction(-5, 2))  # ring fixed, sun in, carrier out: 1 - i0
    Fraction(7, 2)
    >>> speed_ratio(Fraction(-5, 2), fixed="carrier")  # sun in, ring out: i0
    Fraction(-5, 2)

    Notes
    -----
    Willis' equation ``w_s - w_c = i0 (w_r - w_c)`` with the fixed member's
    speed set to 0 (sources as for :func:`basic_ratio`).
    """
    fixed, input, output = _roles(fixed, input, output)
    c = _role_coefs(Fraction(i0))
    return -Fraction(c[output]) / c[input]


def planetary_network(
    sun: int,
    ring: int,
    planet: int | None = None,
    planet1: int | None = None,
    planet2: int | None = None,
    fixed: str | None = "ring",
) -> Network:
    """The set as a gear network: members sun, planet (or planet1, planet2), ring, carrier; ``fixed`` tied to the frame.

    Examples
    --------
    >>> net = planetary_network(24, 60, planet=18)
    >>> net.solve(["sun"]).relation("carrier")
    'rot_carrier = 2/7*rot_sun'
    """
    gears = [Gear("sun", sun), Gear("ring", ring), Gear("carrier")]
    if planet is not None:
        gears.append(Gear("planet", planet))
        cons = [
            Mesh("sun_planet", "sun", "planet", 1, carrier="carrier"),
            Mesh("planet_ring", "planet", "ring", -1, carrier="carrier"),
        ]
    else:
        gears += [Gear("planet1", planet1), Gear("planet2", planet2)]
        cons = [
            Mesh("sun_planet1", "sun", "planet1", 1, carrier="carrier"),
            SameShaft("planet_shaft", "planet1", "planet2"),
            Mesh("planet2_ring", "planet2", "ring", -1, carrier="carrier"),
        ]
    if fixed is not None:
        if fixed not in MEMBERS:
            raise GearleverError(f"fixed must be one of {', '.join(MEMBERS)} or None, got {fixed!r}")
        cons.append(SameShaft("fixed", fixed, FRAME))
    return Network(gears, cons)


@dataclass(frozen=True)
class PlanetarySet(Result):
    """One tooth set of a search: teeth, exact ratio, its error and the conditions it meets (as text).

    ``planet`` is set for a simple set, ``planet1`` and ``planet2`` for a compound one.

    Examples
    --------
    >>> s = design_planetary("9/2", planets=3, limit=1).solutions[0]
    >>> s.ratio, s.error, s.conditions[0]
    (Fraction(9, 2), Fraction(0, 1), 'coaxial: 12 + 2*15 = 42')
    """

    sun: int
    ring: int
    ratio: Fraction
    error: Fraction
    conditions: tuple[str, ...]
    planet: int | None = None
    planet1: int | None = None
    planet2: int | None = None

    def record(self) -> dict:
        """JSON-ready dict: teeth, ``ratio`` as ``"p/q"``, ``error`` as a float, ``conditions``."""
        out = {"sun": self.sun}
        if self.planet is not None:
            out["planet"] = self.planet
        else:
            out["planet1"], out["planet2"] = self.planet1, self.planet2
        out["ring"] = self.ring
        out["ratio"] = f"{self.ratio.numerator}/{self.ratio.denominator}"
        out["error"] = float(self.error)
        out["conditions"] = list(self.conditions)
        return out


@dataclass(frozen=True)
class PlanetaryDesign(Result):
    """Result of :func:`design_planetary`.

    Attributes
    ----------
    kind, target, planets, fixed, input, output, min_teeth, max_teeth : the request.
    candidates : coaxial tooth sets in the range (every one was examined).
    feasible : those meeting equal spacing and neighbour clearance.
    count : feasible sets with the least error (all of them, even beyond ``limit``).
    solutions : the first ``limit`` of those, by ring size, then sun, then planet(s).
    ratio_range : least and greatest ratio over the feasible sets.
    note : why the target cannot be approached, or None.

    Examples
    --------
    >>> d = design_planetary("9/2", planets=3, limit=1)
    >>> d.count, d.solutions[0].sun, d.solutions[0].planet, d.solutions[0].ring
    (8, 12, 15, 42)
    """

    kind: str
    target: Fraction
    planets: int
    fixed: str
    input: str
    output: str
    min_teeth: int
    max_teeth: int
    candidates: int
    feasible: int
    count: int
    solutions: tuple[PlanetarySet, ...]
    ratio_range: tuple[Fraction, Fraction]
    note: str | None = None


def _as_fraction(name: str, value) -> Fraction:
    try:
        f = Fraction(value) if not isinstance(value, float) else Fraction(str(value))
    except (ValueError, ZeroDivisionError, TypeError):
        raise GearleverError(f"{name} must be a number or a fraction p/q, got {value!r}") from None
    if f == 0:
        raise GearleverError(f"{name} must be non-zero, got {value!r}")
    return f


def _conditions(kind, n, zs, zr, p1, p2) -> tuple[str, ...]:
    s = math.sin(math.pi / n)
    big = max(p1, p2)
    if kind == "simple":
        return (
            f"coaxial: {zs} + 2*{p1} = {zr}",
            f"equal spacing: ({zs} + {zr})/{n} = {(zs + zr) // n}",
            f"clearance: {p1} + 2 < ({zs} + {p1}) sin(pi/{n}) = {(zs + p1) * s:.4f}",
        )
    g = math.gcd(p1, p2)
    q = zs * p2 + zr * p1
    return (
        f"coaxial: {zs} + {p1} = {zr} - {p2}",
        f"equal spacing: ({zs}*{p2} + {zr}*{p1})/({n}*gcd({p1}, {p2})) = {q // (n * g)}",
        f"clearance: {big} + 2 < ({zs} + {p1}) sin(pi/{n}) = {(zs + p1) * s:.4f}",
    )


def design_planetary(
    ratio,
    planets: int,
    kind: str = "simple",
    fixed: str = "ring",
    input: str = "sun",
    output: str | None = None,
    min_teeth: int = 12,
    max_teeth: int = 150,
    limit: int | None = None,
) -> PlanetaryDesign:
    """Every tooth set with the least ratio error, searched exhaustively over a tooth range.

    Parameters
    ----------
    ratio : target ``w_input / w_output`` (number or ``"p/q"``; exact).
    planets : number of equally spaced planets N (2 .. :data:`MAX_PLANETS`).
    kind : ``"simple"`` or ``"compound"``.
    fixed, input, output : roles of sun, ring and carrier (output defaults to the third).
    min_teeth, max_teeth : bounds for every gear, the ring included
        (``max_teeth`` at most ``MAX_TEETH[kind]``).
    limit : keep at most this many solutions (``count`` still gives them all).

    Returns
    -------
    PlanetaryDesign

    Examples
    --------
    >>> d = design_planetary("7/2", 3, min_teeth=12, max_teeth=60)
    >>> [(s.sun, s.planet, s.ring, str(s.ratio)) for s in d.solutions]
    [(24, 18, 60, '7/2')]

    Notes
    -----
    Simple set (standard gears, one module, addendum one module): coaxial
    ``z_r = z_s + 2 z_p``; equal spacing of N planets ``(z_s + z_r)/N`` an
    integer; neighbouring planets clear ``z_p + 2 < (z_s + z_p) sin(pi/N)``
    (tip circle against the planet-centre spacing ``2 a sin(pi/N)``).  These
    are the standard assembly conditions of planetary sets as treated, for
    instance, in H. W. Müller, *Epicyclic Drive Trains* (Wayne State
    University Press, 1982), chapter on the geometry of planetary sets (page
    not checked here); the spacing condition is re-derived below as the
    special case ``z_p1 = z_p2`` of the compound one.

    Compound set (stepped planets, one module, identical planets with the
    same relative phase of p1 and p2): coaxial ``z_s + z_p1 = z_r - z_p2``;
    equal spacing ``(z_s z_p2 + z_r z_p1) / (N gcd(z_p1, z_p2))`` an integer;
    clearance ``max(z_p1, z_p2) + 2 < (z_s + z_p1) sin(pi/N)``.  The spacing
    condition is derived here, not quoted: hold the ring, roll the assembled
    first planet on to the next station 2 pi/N; the sun turns
    ``(2 pi/N)(1 + z_p1 z_r/(z_s z_p2))``, and an identical planet fits there
    iff the sun's remaining tooth offset is a multiple of the joint pitch
    ``2 pi gcd(z_p1, z_p2)/(z_p1 z_p2)`` of the planet's two gears, which
    gives the condition above; with ``z_p1 = z_p2`` it is the simple one (no
    published statement of it was checked for this module).

    Ratio: Willis' equation ``w_s - w_c = i0 (w_r - w_c)``
    (:func:`basic_ratio`, :func:`speed_ratio`).  The search visits every
    coaxial set (count returned as ``candidates``), screens ratios in
    float64 and decides the least error, the ties and the clearance exactly
    (fractions; the sine to 60 digits).
    """
    if kind not in KINDS:
        raise GearleverError(f"kind must be one of {', '.join(KINDS)}, got {kind!r}")
    fixed, input, output = _roles(fixed, input, output)
    target = _as_fraction("ratio", ratio)
    n = _check_int("planets", planets, 2, MAX_PLANETS)
    cap = MAX_TEETH[kind]
    lo = _check_int("min_teeth", min_teeth, 1)
    hi = _check_int("max_teeth", max_teeth, 1)
    if hi > cap:
        raise GearleverError(f"max_teeth must be at most {cap} for a {kind} set (MAX_TEETH), got {hi}")
    if lo > hi:
        raise GearleverError(f"the tooth range is empty: min_teeth {lo} > max_teeth {hi}")
    if limit is not None:
        limit = _check_int("limit", limit, 1)
    s_float = math.sin(math.pi / n)

    chunks = []
    candidates = 0
    for zs in range(lo, hi + 1):
        if kind == "simple":
            zp = np.arange(lo, hi + 1, dtype=np.int64)
            zr = zs + 2 * zp
            ok = zr <= hi
            zp, zr = zp[ok], zr[ok]
            p1 = p2 = zp
        else:
            a = np.arange(lo, hi + 1, dtype=np.int64)
            p1, p2 = np.meshgrid(a, a, indexing="ij")
            p1, p2 = p1.ravel(), p2.ravel()
            zr = zs + p1 + p2
            ok = zr <= hi
            p1, p2, zr = p1[ok], p2[ok], zr[ok]
        if zr.size == 0:
            break
        candidates += zr.size
        if kind == "simple":
            spaced = (zs + zr) % n == 0
        else:
            spaced = (zs * p2 + zr * p1) % (n * np.gcd(p1, p2)) == 0
        big = np.maximum(p1, p2)
        lhs, rhs = big + 2, (zs + p1) * s_float
        clear = lhs < rhs * (1 - 1e-12)
        border = np.abs(lhs - rhs) <= 1e-12 * rhs
        for k in np.flatnonzero(border & spaced):
            clear[k] = _less_than_sin(int(lhs[k]), int(zs + p1[k]), n)
        keep = spaced & clear
        if keep.any():
            chunks.append((np.full(int(keep.sum()), zs), p1[keep], p2[keep], zr[keep]))
    if not chunks:
        raise GearleverError(
            f"no {kind} tooth set with every gear in [{lo}, {hi}] meets the assembly conditions for {n} planets "
            "(equal spacing and neighbour clearance): widen the tooth range or use fewer planets"
        )
    zs_a, p1_a, p2_a, zr_a = (np.concatenate(x) for x in zip(*chunks))
    i0 = -(p1_a * zr_a) / (zs_a * p2_a)
    coef = {"sun": np.ones_like(i0), "ring": -i0, "carrier": i0 - 1}
    r = -coef[output] / coef[input]
    err = np.abs(r - float(target))
    best = err.min()
    near = np.flatnonzero(err <= best + 1e-9 * max(1.0, abs(float(target)), best))

    def exact(k):
        zs, a, b, zr = int(zs_a[k]), int(p1_a[k]), int(p2_a[k]), int(zr_a[k])
        i = basic_ratio(zs, zr) if kind == "simple" else basic_ratio(zs, zr, a, b)
        return zs, a, b, zr, speed_ratio(i, fixed, input, output)

    exacts = [exact(k) for k in near]
    least = min(abs(e[4] - target) for e in exacts)
    winners = sorted((e for e in exacts if abs(e[4] - target) == least), key=lambda e: (e[3], e[0], e[1], e[2]))
    kept = winners if limit is None else winners[:limit]
    sols = tuple(
        PlanetarySet(
            sun=zs,
            ring=zr,
            ratio=rr,
            error=abs(rr - target),
            conditions=_conditions(kind, n, zs, zr, a, b),
            planet=a if kind == "simple" else None,
            planet1=a if kind == "compound" else None,
            planet2=b if kind == "compound" else None,
        )
        for zs, a, b, zr, rr in kept
    )
    kmin, kmax = int(np.argmin(r)), int(np.argmax(r))
    rmin, rmax = exact(kmin)[4], exact(kmax)[4]
    note = None
    if target < rmin or target > rmax:
        note = (
            f"the target {target} is outside the ratios [{rmin}, {rmax}] a {kind} set reaches with "
            f"{fixed} fixed, {input} in, {output} out, teeth in [{lo}, {hi}] and {n} planets: "
            "the nearest sets are shown"
        )
    return PlanetaryDesign(
        kind=kind,
        target=target,
        planets=n,
        fixed=fixed,
        input=input,
        output=output,
        min_teeth=lo,
        max_teeth=hi,
        candidates=candidates,
        feasible=int(zs_a.size),
        count=len(winners),
        solutions=sols,
        ratio_range=(rmin, rmax),
        note=note,
    )
