"""Turning-moment diagram and flywheel sizing over one cycle.

The driving torque ``T(theta)`` of an engine (or the torque a machine needs)
varies over its cycle while the load ``L(theta)`` resists.  Their difference
speeds the rotating parts up and slows them down; the kinetic energy swings by
the maximum fluctuation of energy

    ``dE = max E - min E``,  ``E(theta) = integral (T - L) dtheta``,

and a flywheel of moment of inertia ``I`` at the mean speed ``omega`` keeps
the coefficient of fluctuation of speed ``Cs = (omega_max - omega_min)/omega``
to ``Cs = dE / (I omega^2)``.

The samples are taken as the turning-moment diagram itself: torque linear
between them.  The integral is then exact (trapezoids), and the extremes of
``E`` are found exactly, at the samples or where the excess torque changes
sign inside an interval.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from gearlever import _validate as V
from gearlever._result import Result
from gearlever.errors import GearleverError

__all__ = ["Flywheel", "flywheel", "MAX_SAMPLES", "MEAN_MISMATCH"]

#: Largest number of samples of one cycle.
MAX_SAMPLES = 1_000_000
#: Largest relative difference between the mean driving and mean load torque taken as rounding.
MEAN_MISMATCH = 1e-3
#: Longest cycle (rad): 1000 turns, far beyond any engine's (a four-stroke cycle is 2 turns).
MAX_PERIOD = 2000.0 * math.pi


def _representable(name: str, value: float, what: str, nonzero: bool = False) -> float:
    """Refuse a result that overflowed (inf) or underflowed to 0 (when it cannot be 0), naming ``name``."""
    if not math.isfinite(value) or (nonzero and value == 0.0):
        raise GearleverError(f"{name}: {what} is {value:g}, beyond double precision: give values of more moderate size")
    return value


@dataclass(frozen=True)
class Flywheel(Result):
    """Turning-moment diagram integrated over one cycle, and the flywheel it needs.

    Attributes
    ----------
    theta : (N,) crank angles of the samples (rad).
    torque : (N,) driving torque.
    load : (N,) resisting torque, as used (shifted by ``load_shift``).
    energy : (N,) ``E(theta) - E(theta_0)``, the integral of ``torque - load`` (J for N m).
    mean_torque : mean driving torque over the cycle.
    mean_speed : mean speed (rad/s).
    power : ``mean_torque * mean_speed`` (W for N m).
    work_per_cycle : integral of the driving torque over the cycle.
    energy_fluctuation : ``dE = max E - min E``.
    energy_max, energy_min : the extremes of ``E`` (same origin as ``energy``).
    theta_max_speed, theta_min_speed : crank angles (rad) where ``E``, hence the speed, is largest and smallest.
    inertia : flywheel moment of inertia ``dE / (omega^2 Cs)`` (kg m^2), or the one given.
    fluctuation : coefficient of fluctuation of speed ``Cs``, given or ``dE / (I omega^2)``.
    period : length of the cycle (rad).
    load_shift : constant added to the given load so that its mean equals the driving one (0 when they agree).
    angular_acceleration : (N,) ``(torque - load) / inertia`` (rad/s^2), the flywheel's acceleration at the
        samples (property; None without an inertia).

    Examples
    --------
    >>> import numpy as np
    >>> theta = np.linspace(0.0, 2 * np.pi, 3601)
    >>> fw = flywheel(theta, 100 + 30 * np.sin(2 * theta), 300, fluctuation=0.02)
    >>> round(fw.energy_fluctuation, 3)          # 2 A / k = 2 * 30 / 2
    30.0
    """

    theta: np.ndarray
    torque: np.ndarray
    load: np.ndarray
    energy: np.ndarray
    mean_torque: float
    mean_speed: float
    power: float
    work_per_cycle: float
    energy_fluctuation: float
    energy_max: float
    energy_min: float
    theta_max_speed: float
    theta_min_speed: float
    inertia: float | None
    fluctuation: float | None
    period: float
    load_shift: float

    @property
    def angular_acceleration(self) -> np.ndarray | None:
        """Angular acceleration ``(T - L) / I`` at the samples (rad/s^2); None without an inertia.

        The rotating parts are taken as one rigid flywheel of constant inertia, as in the
        turning-moment method (the excess torque accelerates it, the deficit retards it).
        """
        if self.inertia is None:
            return None
        return (self.torque - self.load) / self.inertia

    @property
    def theta_max_speed_deg(self) -> float:
        """Crank angle of the maximum speed in degrees."""
        return math.degrees(self.theta_max_speed)

    @property
    def theta_min_speed_deg(self) -> float:
        """Crank angle of the minimum speed in degrees."""
        return math.degrees(self.theta_min_speed)

    def summary(self) -> dict:
        """Scalar results as plain floats (the CLI's json keys)."""
        return {
            "mean_torque": self.mean_torque,
            "power": self.power,
            "energy_fluctuation": self.energy_fluctuation,
            "inertia": self.inertia,
            "fluctuation": self.fluctuation,
            "theta_max_speed_deg": self.theta_max_speed_deg,
            "theta_min_speed_deg": self.theta_min_speed_deg,
            "mean_speed_rpm": self.mean_speed * 30.0 / math.pi,
            "work_per_cycle": self.work_per_cycle,
            "period_deg": math.degrees(self.period),
            "load_shift": self.load_shift,
            "samples": int(self.theta.size),
        }


def _curve(name: str, values, n: int) -> np.ndarray:
    arr = V.finite_array(name, values)
    if arr.ndim == 0:
        return np.full(n, float(arr))
    if arr.shape != (n,):
        raise GearleverError(f"{name} must be a number or an array of the shape of theta ({n},), got {arr.shape}")
    return arr


def _energy_extremes(th: np.ndarray, e: np.ndarray):
    """Energy at the samples and its exact extremes for torque linear between samples."""
    h = np.diff(th)
    E = np.concatenate(([0.0], np.cumsum(0.5 * h * (e[:-1] + e[1:]))))
    e0, e1 = e[:-1], e[1:]
    cross = (e0 * e1) < 0
    s = np.zeros_like(h)
    s[cross] = e0[cross] / (e0[cross] - e1[cross]) * h[cross]
    Ec = E[:-1][cross] + 0.5 * e0[cross] * s[cross]
    thc = th[:-1][cross] + s[cross]
    cand_E = np.concatenate((E[:-1], Ec))  # the closing sample is the next cycle's first
    cand_t = np.concatenate((th[:-1], thc))
    order = np.argsort(cand_t, kind="stable")
    cand_E, cand_t = cand_E[order], cand_t[order]
    i_max, i_min = int(np.argmax(cand_E)), int(np.argmin(cand_E))
    return E, cand_E[i_max], cand_E[i_min], cand_t[i_max], cand_t[i_min]


def flywheel(
    theta,
    torque,
    mean_speed_rpm: float,
    fluctuation: float | None = None,
    inertia: float | None = None,
    load=None,
    period: float | None = None,
) -> Flywheel:
    """Integrate a turning-moment diagram over one cycle; size the flywheel (or find its fluctuation).

    Parameters
    ----------
    theta : array_like, shape (N,)
        Crank angles of the samples (rad), strictly increasing, N >= 2.
    torque : array_like, shape (N,)
        Driving torque at the samples (e.g. N m).
    mean_speed_rpm : float
        Mean speed of the flywheel shaft (rev/min).
    fluctuation : float, optional
        Coefficient of fluctuation of speed ``Cs = (omega_max - omega_min)/omega``
        allowed; the inertia that holds it is returned.
    inertia : float, optional
        Moment of inertia of the flywheel and rotating parts (kg m^2); the
        coefficient of fluctuation it gives is returned.  Give at most one
        of ``fluctuation`` and ``inertia`` (neither: ``dE`` only).
    load : float or array_like, shape (N,), optional
        Resisting torque; default the mean driving torque (constant).  Its
        mean over the cycle must equal the driving one within
        :data:`MEAN_MISMATCH` (relative); a smaller difference is taken as
        rounding and removed by shifting the load by a constant.
    period : float, optional
        Length of the cycle (rad).  Default: the samples close the cycle, the
        last one being the first of the next cycle (``theta[-1] - theta[0]``,
        e.g. 0 to 4 pi for a four-stroke engine).  Given, it must exceed
        ``theta[-1] - theta[0]`` and the diagram runs on linearly from the
        last sample to the first one a period later.

    Returns
    -------
    Flywheel

    Examples
    --------
    Torque ``1000 + 300 sin 2 theta`` N m at 250 rpm, constant load: the
    swing is ``dE = 2 * 300 / 2 = 300`` J (the area of one loop).

    >>> import numpy as np
    >>> th = np.linspace(0.0, 2 * np.pi, 3601)
    >>> f = flywheel(th, 1000 + 300 * np.sin(2 * th), 250.0, fluctuation=0.01)
    >>> round(f.mean_torque, 6), round(f.energy_fluctuation, 2), round(f.theta_max_speed_deg, 3)
    (1000.0, 300.0, 90.0)
    >>> round(f.inertia, 3)   # 300 / ((250 * 2 pi / 60)^2 * 0.01)
    43.771

    Notes
    -----
    Fluctuation of energy and flywheel size, e.g. R. G. Budynas and J. K.
    Nisbett, *Shigley's Mechanical Engineering Design*, 9th ed., McGraw-Hill
    (2011), chapter 16, section "Flywheels":
    ``Cs = (omega_2 - omega_1)/omega``, ``E_2 - E_1 = Cs I omega^2``.
    ``Cs I omega^2`` is exact for
    ``omega = (omega_max + omega_min)/2``:
    ``I (omega_max^2 - omega_min^2)/2 = I omega (omega_max - omega_min)``.

    The excess torque ``T - L`` is linear between samples, so ``E`` is the
    cumulative trapezoid sum at the samples and a parabola between them;
    its interior extremes lie where ``T - L`` changes sign, at
    ``s = e_i h / (e_i - e_{i+1})`` with ``E = E_i + e_i s / 2``.
    """
    th = V.finite_array("theta", theta)
    if th.size and float(np.max(np.abs(th))) > 1e15:
        raise GearleverError("theta must be crank angles of at most 1e15 rad in size")
    if th.ndim != 1 or th.size < 2:
        raise GearleverError(f"theta must be a 1-D array of at least 2 crank angles, got shape {th.shape}")
    n = th.size
    if n > MAX_SAMPLES:
        raise GearleverError(f"theta must hold at most {MAX_SAMPLES} samples, got {n}")
    steps = np.diff(th)
    if np.any(steps <= 0):
        k = int(np.argmax(steps <= 0)) + 1
        raise GearleverError(f"theta must be strictly increasing (sample {k} is not above sample {k - 1})")
    T = _curve("torque", torque, n)
    omega = V.positive("mean_speed_rpm", mean_speed_rpm) * math.pi / 30.0
    if fluctuation is not None and inertia is not None:
        raise GearleverError("fluctuation and inertia: give one of them, not both")
    cs = None if fluctuation is None else V.positive("fluctuation", fluctuation)
    inert = None if inertia is None else V.positive("inertia", inertia)

    span = float(th[-1] - th[0])
    if period is None:
        P = span
        th_c, T_c = th, T
    else:
        P = V.positive("period", period)
        if P > MAX_PERIOD:
            raise GearleverError(f"period must be at most {MAX_PERIOD:g} rad (1000 turns, the cap), got {period!r}")
        if P <= span:
            raise GearleverError(
                f"period must exceed theta[-1] - theta[0] = {span!r} (the samples lie within one cycle), got {period!r}"
            )
        th_c, T_c = np.append(th, th[0] + P), np.append(T, T[0])
    L = None if load is None else _curve("load", load, n)
    # torques are scaled by a power of two (exact) so that sums of torques near the
    # float limit do not overflow; energies are scaled back at the end
    big = max(float(np.max(np.abs(T))), 0.0 if L is None else float(np.max(np.abs(L))))
    k2 = math.frexp(big)[1] if big > 0 else 0
    T_c = np.ldexp(T_c, -k2)
    work = float(np.sum(0.5 * np.diff(th_c) * (T_c[:-1] + T_c[1:])))
    mean_T = work / P
    if L is None:
        Lc = np.full(th_c.size, mean_T)
        shift = 0.0
    else:
        L = np.ldexp(L, -k2)
        Lc = L if period is None else np.append(L, L[0])
        mean_L = float(np.sum(0.5 * np.diff(th_c) * (Lc[:-1] + Lc[1:]))) / P
        scale = max(abs(mean_T), abs(mean_L), float(np.mean(np.abs(T))), float(np.mean(np.abs(L))))
        if abs(mean_T - mean_L) > MEAN_MISMATCH * scale:
            raise GearleverError(
                f"load: its mean over the cycle ({mean_L:.6g}) must equal the mean driving torque "
                f"({mean_T:.6g}); otherwise the speed does not repeat from cycle to cycle"
            )
        shift = mean_T - mean_L
        Lc = Lc + shift
    e = T_c - Lc
    E, e_max, e_min, t_max, t_min = _energy_extremes(th_c, e)
    dE_scaled = float(e_max - e_min)

    def back(name, x, what):  # undo the power-of-two scaling, refusing an overflow
        with np.errstate(over="ignore"):
            return _representable(name, float(np.ldexp(x, k2)), what)

    dE = back("torque", dE_scaled, "the energy fluctuation")
    work = back("torque", work, "the work per cycle")
    mean_T = back("torque", mean_T, "the mean torque")
    shift = back("load", shift, "the load shift")
    Lc = np.ldexp(Lc, k2)
    with np.errstate(over="ignore"):
        E = np.ldexp(E, k2)
    if not np.all(np.isfinite(E)):
        raise GearleverError(
            "torque: the energy E(theta) overflows double precision: give torques of more moderate size"
        )
    if cs is not None:
        inert = dE / cs / omega / omega
        _representable("mean_speed_rpm", inert, "with this fluctuation the flywheel inertia", nonzero=dE > 0)
    elif inert is not None:
        cs = dE / inert / omega / omega
        _representable("mean_speed_rpm", cs, "with this inertia the coefficient of fluctuation", nonzero=dE > 0)
    power = _representable("mean_speed_rpm", mean_T * omega, "the power", nonzero=mean_T != 0)
    return Flywheel(
        theta=th,
        torque=T,
        load=Lc[:n],
        energy=E[:n],
        mean_torque=mean_T,
        mean_speed=omega,
        power=power,
        work_per_cycle=work,
        energy_fluctuation=dE,
        energy_max=back("torque", float(e_max), "the largest energy"),
        energy_min=back("torque", float(e_min), "the smallest energy"),
        theta_max_speed=float(t_max),
        theta_min_speed=float(t_min),
        inertia=inert,
        fluctuation=cs,
        period=P,
        load_shift=shift,
    )
