"""Gear-lever differential for a law: the ZRDPM's carrier swung by a linkage, its driven gear the output.

The gear-lever differential of Alimukhamedov et al. ("Structural and
kinematic analysis of gear and lever differential mechanisms ...", 2020):
a leading gear ``9`` turns about the pivot ``O1`` of a lever ``1`` (the
carrier) that carries the driven gear ``8``; by Willis' equation (paper
eqs. 2-4) ``theta8 = (1 + rho) theta1 - rho phi9``, ``rho = z9 / z8``.  The
lever is swung by a linkage whose ground pivot sits on the adjusting slide
(the paper's horizontal guides, which change the centre distance).

The paper's lever drive (two sliders pushing the lever at radii ``rA,
rB``, eq. 8) is an instantaneous relation, not a closed chain the engine
can assemble, and its figures are lost; so the kind is the nearest closed
one-input chain of the same structure, a Watt six-bar with gears:

- ground pivots ``O1 = (0, 0)`` (input crank, lever and gear 9 coaxial) and
  ``O3 = (1, 0)`` on the adjusting slide, so the centre distance
  ``O1 O3`` is the unit of the lengths (the model is scaled by
  :data:`~gearlever.synthesis.law.fourbar.SIZE`);
- crank-rocker ``O1 A B O3`` (crank ``a`` from ``u2`` as in the four-bar
  kind, coupler ``b``, rocker ``c``), the crank at ``alpha`` at law input 0;
- the rocker's second arm ``O3 D`` (``c2``, at ``beta`` from ``O3 B``), the
  link ``D E`` (``b2``) and the lever ``O1 E`` (``l``), branch ``branch2``;
- gear 9 (``z9``) about ``O1``, gear 8 (``z8``) about ``E`` on the lever:
  the assembly constraint of the mesh is the centre distance ``l = m (z9 +
  z8) / 2`` (the module follows from the lever length and the teeth);
- ``"held"`` variant (a returning law): gear 9 held by the ground (the
  differential's second input at rest): ``theta8 = (1 + rho) theta1``;
  ``"driven"`` variant (a law whose output turns on by ``net`` per cycle):
  gear 9 turns with the crank (the paper's leading link): ``theta8 = (1 +
  rho) theta1 - rho phi``, so ``rho = -net / (2 pi)`` must be a ratio of
  whole teeth within the bounds.

Exact constraints: the four-bar's as in the four-bar kind; the dyad ``D E
O1`` closes at every sample with no dead point and ``D`` does not wind
about ``O1``; the transmission angle of both loops within the bound
(sampled for the dyad); integer teeth within ``teeth``.
:meth:`GearLeverLaw.slide_sweep` gives the law at other slide settings.

Pure numpy.
"""

from __future__ import annotations

import math

import numpy as np

from gearlever.errors import GearleverError
from gearlever.mechanism.modelfile import mechanism_table, xy_pair
from gearlever.synthesis.law._core import LawKind, atan2c, register
from gearlever.synthesis.law.fourbar import LENGTHS, SIZE, crank_rocker, fourbar_angles, transmission_range
from gearlever.synthesis.law.geared_fourbar import teeth_for_ratio

__all__ = ["GearLeverLaw", "SLIDE_RANGE", "ARM", "DYAD"]

#: Bounds of the rocker's second arm ``c2`` and of the lever ``l``, in centre distances.
ARM = (0.1, 3.0)
#: Bounds of the link ``b2``.
DYAD = (0.1, 6.0)
#: Settings of the adjusting slide swept by the report, as fractions of the design's centre distance.
SLIDE_RANGE = (0.9, 1.1)
#: Rows of the sweep.
SLIDE_ROWS = 9


@register
class GearLeverLaw(LawKind):
    """Gear-lever differential (ZRDPM) at one slide setting, output the driven gear 8 (module docstring).

    Notes
    -----
    Driven gear by Willis' equation, ``theta8 = (1 + z9/z8) theta1 - (z9/z8)
    phi9`` (Alimukhamedov et al. 2020, eqs. 2-4); the lever angle
    ``theta1`` by the closed forms of the crank-rocker and of the dyad
    ``D E O1``.

    Examples
    --------
    >>> from gearlever.synthesis.law import law_target
    >>> th = np.linspace(0, 2 * np.pi, 36, endpoint=False)
    >>> kind = GearLeverLaw(law_target(th, np.zeros(36)))
    >>> z = np.array([0.3627, 1.0966, 0.6747, 0.4434, 0.5598, 2.8402, 0.624, 1.5799, 31, 91, -1.0, -1.0])
    >>> G, ok = kind.generate(z[None, :], th)
    >>> bool(ok[0]), kind.variant, round(float(np.degrees(np.ptp(G))), 3)
    (True, 'held', 10.273)
    """

    name = "gear-lever"
    order = 2
    example = {"power": 2, "kwargs": {"teeth": (20, 40)}}
    outputs = ("angle",)
    names = ("b", "c", "u2", "alpha", "c2", "beta", "b2", "l", "z9", "z8", "branch", "branch2")
    fixed = ("z9", "z8", "branch", "branch2")

    def __init__(self, target, teeth=(17, 120)):
        super().__init__(target, teeth)
        zl, zh = self.teeth
        if not 1 <= zl <= zh:
            raise GearleverError(f"teeth must be 1 <= zmin <= zmax, got {teeth!r}")
        L, A, D = LENGTHS, ARM, DYAD
        self.lo = np.array([L[0], L[0], 0.0, -math.pi, A[0], -math.pi, D[0], A[0], zl - 0.499, zl - 0.499, -1, -1])
        self.hi = np.array([L[1], L[1], 1.0, math.pi, A[1], math.pi, D[1], A[1], zh + 0.499, zh + 0.499, 1, 1])
        self.variant = "held" if abs(target.net) <= 1e-9 * max(target.scale, 1.0) else "driven"
        self._why = None
        if self.variant == "driven":
            tz = teeth_for_ratio(-target.net / (2 * math.pi), self.teeth)
            if tz is None:
                self._why = (
                    f"the law's output turns {math.degrees(target.net):.6g} deg per cycle: a gear-lever's driven "
                    f"gear turns -360 z9/z8 deg, whole teeth {zl}..{zh}; no such teeth give it"
                )
            else:
                self.lo[8:10] = self.hi[8:10] = tz

    def check(self):
        if self.target.output != "angle":
            raise GearleverError(f"a {self.name} gives an output angle, the law is {self.target.output}")
        if self._why:
            raise GearleverError(self._why)

    # --- closed form --------------------------------------------------------------------------------
    def _teeth(self, Z):
        return np.round(np.real(Z[:, 8:9])), np.round(np.real(Z[:, 9:10]))

    def _rocker(self, Z, theta, slide=1.0):
        """Crank angle ``phi``, rocker angle ``psi`` and the pin ``D`` (n, N); crank ``a`` (n, 1)."""
        b, c, u2 = Z[:, 0:1], Z[:, 1:2], Z[:, 2:3]
        a = crank_rocker(b, c, u2)
        sig = np.where(np.real(Z[:, 10:11]) >= 0, 1.0, -1.0)
        phi = Z[:, 3:4] + theta
        psi, _ = fourbar_angles(a / slide, b / slide, c / slide, phi, sig)
        ang = psi + Z[:, 5:6]
        return phi, psi, slide + Z[:, 4:5] * np.cos(ang), Z[:, 4:5] * np.sin(ang), a

    def _outputs(self, Z, theta, slide=1.0):
        """Output ``theta8`` (n, N), feasibility (n,), dyad ``cos mu`` (n, N) and the lever angle."""
        with np.errstate(invalid="ignore", divide="ignore"):
            return self._outputs_raw(Z, theta, slide)

    def _outputs_raw(self, Z, theta, slide):
        phi, psi, Dx, Dy, a = self._rocker(Z, theta, slide)
        b2, ell = Z[:, 6:7], Z[:, 7:8]
        f2 = Dx * Dx + Dy * Dy
        f = np.sqrt(f2)
        cg = (ell * ell + f2 - b2 * b2) / (2.0 * ell * f)
        cm = (b2 * b2 + ell * ell - f2) / (2.0 * b2 * ell)
        ang = atan2c(Dy, Dx)
        ar = np.real(ang)
        un = np.unwrap(ar, axis=1)
        ang = ang + (un - ar)
        close = np.mod(ar[:, 0] - un[:, -1] + math.pi, 2 * math.pi) - math.pi
        winding = np.round((un[:, -1] + close - un[:, 0]) / (2 * math.pi))
        cgr = np.real(cg)
        sig2 = np.where(np.real(Z[:, 11:12]) >= 0, 1.0, -1.0)
        ok = np.isfinite(np.real(a[:, 0])) & (winding == 0) & np.all(np.abs(cgr) < 1.0 - 1e-9, axis=1)
        ok &= np.all(np.isfinite(np.real(psi)), axis=1)
        gam = np.arccos(np.where(np.abs(cgr) < 1.0, cg, 0.0))
        th1 = ang + sig2 * gam
        z9, z8 = self._teeth(Z)
        rho = z9 / np.where(z8 > 0, z8, np.nan)
        th8 = (1.0 + rho) * th1 - (rho * phi if self.variant == "driven" else 0.0)
        return th8, ok, cm, th1

    def generate(self, Z, theta):
        G, ok, _, _ = self._outputs(Z, theta)
        return G, ok

    def evaluate(self, Z, theta):
        G, ok, cm, _ = self._outputs(Z, theta)
        mn, mx = self._transmission(Z, cm)
        return G, ok, mn, mx

    def _transmission(self, Z, cm, slide=1.0):
        Zr = np.real(Z)
        a = np.real(crank_rocker(Zr[:, 0], Zr[:, 1], Zr[:, 2]))
        m1, M1 = transmission_range(a / slide, Zr[:, 0] / slide, Zr[:, 1] / slide)
        with np.errstate(invalid="ignore"):
            cr = np.real(cm)
            lo, hi = np.arccos(np.clip(cr.max(axis=1), -1, 1)), np.arccos(np.clip(cr.min(axis=1), -1, 1))
        return np.minimum(m1, lo), np.maximum(M1, hi)

    def transmission(self, Z):
        Z = np.real(np.atleast_2d(Z))
        _, _, cm, _ = self._outputs(Z, self.target.theta)
        return self._transmission(Z, cm)

    # --- search: the link b2 as a fraction of the interval in which the dyad closes --------------------
    def search_box(self):
        """The search's variables: the design's with ``b2`` replaced by its fraction ``v`` of the closing interval.

        For each candidate, ``b2`` must lie in ``(max |f - l|, min (f + l))``
        over the turn (``f = |O1 D|``) for the dyad to close at every
        sample with no dead point; :meth:`to_full` maps ``v`` into it.
        """
        lo, hi = self.lo.copy(), self.hi.copy()
        lo[6], hi[6] = 0.02, 0.98
        return lo, hi

    def to_full(self, Zs):
        Zs = np.asarray(Zs, dtype=float)
        with np.errstate(invalid="ignore"):
            _, _, Dx, Dy, _ = self._rocker(Zs, self.target.theta)
            f = np.hypot(Dx, Dy)
            ell = Zs[:, 7:8]
            blo, bhi = np.max(np.abs(f - ell), axis=1), np.min(f + ell, axis=1)
            Z = Zs.copy()
            Z[:, 6] = blo + Zs[:, 6] * (bhi - blo)
            bad = ~(bhi > blo) | ~np.all((Z >= self.lo) & (Z <= self.hi), axis=1)
        Z[bad] = np.nan
        return Z

    def search_sample(self, rng, m):
        lo, hi = self.search_box()
        return lo + rng.random((m, lo.size)) * (hi - lo)

    # --- report and model ------------------------------------------------------------------------------
    def slide_sweep(self, z, settings=None) -> list:
        """The law at other settings of the adjusting slide: one row per setting.

        ``settings`` are centre distances ``O1 O3`` in units of the
        design's (default :data:`SLIDE_ROWS` from :data:`SLIDE_RANGE`).
        Each row: the setting (ratio and model length), whether the
        mechanism still assembles over the turn, the largest error against
        the wanted law with the output zero refitted (weighted mean, as the
        search), the output swing over the turn with the net change removed,
        and the smallest transmission angle.
        """
        z = np.asarray(z, dtype=float)[None, :]
        t = self.target
        if settings is None:
            settings = np.linspace(SLIDE_RANGE[0], SLIDE_RANGE[1], SLIDE_ROWS)
        rows = []
        for s in np.asarray(settings, dtype=float):
            G, ok, cm, _ = self._outputs(z, t.theta, float(s))
            mn, _ = self._transmission(z, cm, float(s))
            row = {"slide": float(s), "centre_distance": float(s) * SIZE, "feasible": bool(ok[0])}
            if ok[0] and np.isfinite(mn[0]):
                R = G[0] - t.s
                w2 = t.weight**2
                R = R - (R @ w2) / w2.sum()
                drift = G[0] - t.net * t.theta / (2 * math.pi)
                row.update(
                    error_max_deg=math.degrees(float(np.max(np.abs(R)))),
                    output_swing_deg=math.degrees(float(np.ptp(drift))),
                    transmission_min_deg=math.degrees(float(mn[0])),
                )
            else:
                row.update(error_max_deg=None, output_swing_deg=None, transmission_min_deg=None)
            rows.append(row)
        return rows

    def details(self, z):
        z = np.asarray(z, dtype=float)
        a = float(crank_rocker(z[0], z[1], z[2]))
        z9, z8 = (int(v[0, 0]) for v in self._teeth(z[None, :]))
        S = SIZE
        return {
            "lengths": {
                "centre_distance": S,
                "crank": a * S,
                "coupler": z[0] * S,
                "rocker": z[1] * S,
                "rocker_arm2": z[4] * S,
                "link5": z[6] * S,
                "lever": z[7] * S,
            },
            "rocker_arm_angle_deg": math.degrees(z[5]),
            "teeth": {"g9 (leading)": z9, "g8 (driven, output)": z8},
            "module": 2 * z[7] * S / (z9 + z8),
            "variant": self.variant,
            "branch": "+" if z[10] >= 0 else "-",
            "branch2": "+" if z[11] >= 0 else "-",
            "crank_deg_at_input_0": math.degrees(z[3]),
            "slide_range": self.slide_sweep(z),
        }

    def model(self, z, k):
        z = np.asarray(z, dtype=float)
        th = np.zeros(1)
        phi, psi, Dx, Dy, a = self._rocker(z[None, :], th)
        G, _, _, th1 = self._outputs(z[None, :], th)
        a, phi, psi = float(a[0, 0]), float(phi[0, 0]), float(psi[0, 0])
        th1, th8 = float(th1[0, 0]), float(G[0, 0])
        z9, z8 = (int(v[0, 0]) for v in self._teeth(z[None, :]))
        S, ell = SIZE, float(z[7])
        r8 = S * ell * z8 / (z9 + z8)
        E = (S * ell * math.cos(th1), S * ell * math.sin(th1))
        pts = {
            "O1": (0.0, 0.0),
            "O3": (S, 0.0),
            "A": (S * a * math.cos(phi), S * a * math.sin(phi)),
            "B": (S + S * z[1] * math.cos(psi), S * z[1] * math.sin(psi)),
            "D": (S * float(Dx[0, 0]), S * float(Dy[0, 0])),
            "E": E,
            "P": (E[0] + r8 * math.cos(th8), E[1] + r8 * math.sin(th8)),
        }
        return {
            # the module makes the engine check the mesh's assembly constraint |O1 E| = m (z9 + z8) / 2
            "mechanism": {
                **mechanism_table(f"law gear-lever differential (ZRDPM, gear 9 {self.variant})", ""),
                "module": 2.0 * S * ell / (z9 + z8),
            },
            "points": {n: xy_pair(n, p) for n, p in pts.items()},
            "links": {
                "ground": ["O1", "O3"],
                "crank": ["O1", "A"],
                "coupler": ["A", "B"],
                "rocker": ["O3", "B", "D"],
                "link5": ["D", "E"],
                "lever": ["O1", "E"],
                "output": ["E", "P"],
            },
            "gears": {
                "g9": {"link": "crank" if self.variant == "driven" else "ground", "centre": "O1", "teeth": z9},
                "g8": {"link": "output", "centre": "E", "teeth": z8},
            },
            "meshes": [{"gears": ["g9", "g8"], "carrier": "lever"}],
            "inputs": [{"link": "crank"}],
        }
