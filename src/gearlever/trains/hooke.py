"""Hooke's coupling (universal joint), single and double.

Convention.  All angles are in radians.  ``shaft_angle`` beta is the angle
between the two shafts of a joint (0 <= beta < pi/2).  The input angle phi is
measured about the input shaft from the position in which the input fork
lies in the plane of the two shafts; the output angle psi is measured about
the output shaft from the matching position of the output shaft, so that
psi = phi at phi = 0, pi/2, pi, ...  Then (c = cos beta)

    tan psi = tan phi / c,

and psi is taken continuous in phi (psi - phi stays within (-pi/2, pi/2)),
so angles over several turns are handled.  The angular velocity ratio
omega_out / omega_in = dpsi/dphi lies between cos beta (at phi = pi/2) and
1 / cos beta (at phi = 0), the limits given by the classic text on trains of
wheelwork, section 70 "Double Hooke's Coupling", from its section 66.  The angular acceleration ratio is d2psi/dphi2:
the output's angular acceleration divided by omega_in**2 for a uniformly
turning input.

Double coupling.  The first joint (shaft angle beta1) drives a short
intermediate shaft, which drives the last shaft through the second joint
(shaft angle beta2).  ``phase`` delta is the angle by which the
intermediate shaft's second fork is turned about its axis away from the
plane of its first fork.  With delta = 0 (forks in one plane) the second
joint undoes the first: tan psi3 = (cos beta2 / cos beta1) tan phi, which is
the identity when beta1 = beta2 (section 70 of the text: alpha3 = alpha1 at
each instant).  Any other arrangement leaves a residual fluctuation,
computed by :func:`double_fluctuation`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from gearlever import _validate
from gearlever._result import Result
from gearlever.errors import GearleverError

__all__ = [
    "DoubleFluctuation",
    "HookeJoint",
    "HookeTurn",
    "acceleration_ratio",
    "d2psi_dphi2",
    "double_acceleration_ratio",
    "double_fluctuation",
    "double_output_angle",
    "double_velocity_ratio",
    "dpsi_dphi",
    "output_angle",
    "ratio_extremes",
    "velocity_ratio",
]


def _shaft_angle(name: str, value) -> float:
    beta = _validate.finite(name, value)
    if not 0.0 <= beta < math.pi / 2:
        raise GearleverError(f"{name} must be at least 0 and below pi/2 rad (90 deg), got {value!r}")
    return beta


# Closed forms of the map tan h = tan x / c (c > 0), continuous in x.
def _h(x, c):
    s, co = np.sin(x), np.cos(x)
    return x + np.arctan2(s * co * (1.0 - c), c * co * co + s * s)


def _dh(x, c):
    s, co = np.sin(x), np.cos(x)
    return c / (c * c * co * co + s * s)


def _d2h(x, c):
    s, co = np.sin(x), np.cos(x)
    den = c * c * co * co + s * s
    return -c * (1.0 - c * c) * np.sin(2.0 * x) / (den * den)


def output_angle(phi, shaft_angle):
    """Output-shaft angle of a single Hooke's joint.

    Parameters
    ----------
    phi : array_like
        Input-shaft angle(s), rad.
    shaft_angle : float
        Angle beta between the shafts, rad, 0 <= beta < pi/2.

    Returns
    -------
    ndarray
        psi, rad, same shape as ``phi``, continuous in ``phi``.

    Notes
    -----
    tan psi = tan phi / cos beta (module docstring for the convention;
    the classic text on trains of wheelwork, sections 66 and 70).  Written as
    psi = phi + atan2(sin phi cos phi (1 - c), c cos^2 phi + sin^2 phi), whose
    denominator stays positive, so psi is continuous over any number of turns.

    Examples
    --------
    >>> float(np.degrees(output_angle(np.radians(45.0), np.radians(60.0))))  # tan psi = 2
    63.43494882292201
    """
    phi = _validate.finite_array("phi", phi)
    beta = _shaft_angle("shaft_angle", shaft_angle)
    return _h(phi, math.cos(beta))


def velocity_ratio(phi, shaft_angle):
    """Angular velocity ratio omega_out / omega_in = dpsi/dphi of a single joint.

    Parameters
    ----------
    phi : array_like
        Input angle(s), rad.
    shaft_angle : float
        beta, rad, 0 <= beta < pi/2.

    Returns
    -------
    ndarray
        Same shape as ``phi``; between cos beta and 1 / cos beta.

    Notes
    -----
    dpsi/dphi = cos beta / (1 - sin^2 beta cos^2 phi)
    = c / (c^2 cos^2 phi + sin^2 phi), from differentiating
    tan psi = tan phi / c.  Extremes 1/c at phi = 0 and c at phi = pi/2
    (the classic text on trains of wheelwork, section 70: the ratio swings
    between cos theta and 1/cos theta).

    Examples
    --------
    >>> velocity_ratio([0.0, np.pi / 2], np.pi / 3).round(12).tolist()
    [2.0, 0.5]
    """
    phi = _validate.finite_array("phi", phi)
    beta = _shaft_angle("shaft_angle", shaft_angle)
    return _dh(phi, math.cos(beta))


def acceleration_ratio(phi, shaft_angle):
    """Angular acceleration ratio d2psi/dphi2 of a single joint.

    For a uniformly turning input this is alpha_out / omega_in**2.

    Parameters
    ----------
    phi : array_like
        Input angle(s), rad.
    shaft_angle : float
        beta, rad, 0 <= beta < pi/2.

    Returns
    -------
    ndarray

    Notes
    -----
    d2psi/dphi2 = -cos beta sin^2 beta sin 2phi / (1 - sin^2 beta cos^2 phi)^2,
    the derivative of :func:`velocity_ratio`.

    Examples
    --------
    >>> float(acceleration_ratio(np.pi / 4, np.pi / 3))  # -0.5*0.75/0.625**2
    -0.96
    """
    phi = _validate.finite_array("phi", phi)
    beta = _shaft_angle("shaft_angle", shaft_angle)
    return _d2h(phi, math.cos(beta))


def ratio_extremes(shaft_angle) -> tuple[float, float]:
    """Least and greatest velocity ratio of a single joint: (cos beta, 1 / cos beta).

    Notes
    -----
    The classic text on trains of wheelwork, section 70 (from its section 66).

    Examples
    --------
    >>> [round(v, 12) for v in ratio_extremes(np.pi / 3)]
    [0.5, 2.0]
    """
    beta = _shaft_angle("shaft_angle", shaft_angle)
    c = math.cos(beta)
    return c, 1.0 / c


def _double_args(phi, shaft_angle, second_angle, phase):
    phi = _validate.finite_array("phi", phi)
    b1 = _shaft_angle("shaft_angle", shaft_angle)
    b2 = b1 if second_angle is None else _shaft_angle("second_angle", second_angle)
    delta = _validate.finite("phase", phase)
    return phi, math.cos(b1), math.cos(b2), delta


def double_output_angle(phi, shaft_angle, second_angle=None, phase=0.0):
    """Last-shaft angle of a double Hooke's coupling.

    Parameters
    ----------
    phi : array_like
        First-shaft angle(s), rad.
    shaft_angle : float
        beta1, angle between the first and intermediate shafts, rad.
    second_angle : float, optional
        beta2, angle between the intermediate and last shafts, rad;
        default beta1.
    phase : float
        delta, turn of the intermediate shaft's second fork out of the plane
        of its first fork, rad (0: forks in one plane).

    Returns
    -------
    ndarray
        psi3, rad, same shape as ``phi``.

    Notes
    -----
    psi2 = h(phi; c1), psi3 = delta + h(psi2 - delta; 1/c2), with
    tan h(x; c) = tan x / c and c_i = cos beta_i.  The second joint is driven
    by a fork of the "output" kind, hence 1/c2.  With delta = 0 and
    beta1 = beta2, psi3 = phi (the classic text on trains of wheelwork,
    section 70: the intermediate shaft at equal angles, its forks in one
    plane, makes the last shaft turn with the first).

    Examples
    --------
    >>> phi = np.linspace(0.0, 2 * np.pi, 7)
    >>> bool(np.allclose(double_output_angle(phi, 0.5), phi))
    True
    """
    phi, c1, c2, delta = _double_args(phi, shaft_angle, second_angle, phase)
    psi2 = _h(phi, c1)
    return delta + _h(psi2 - delta, 1.0 / c2)


def double_velocity_ratio(phi, shaft_angle, second_angle=None, phase=0.0):
    """Velocity ratio omega_last / omega_first of a double Hooke's coupling.

    Parameters
    ----------
    phi, shaft_angle, second_angle, phase
        As in :func:`double_output_angle`.

    Returns
    -------
    ndarray

    Notes
    -----
    dpsi3/dphi = h'(psi2 - delta; 1/c2) h'(phi; c1), with
    h'(x; c) = c / (c^2 cos^2 x + sin^2 x).  Equal to 1 for every phi when
    beta1 = beta2 and delta = 0 (the classic text on trains of wheelwork,
    section 70).

    Examples
    --------
    >>> double_velocity_ratio([0.3, 1.1], 0.4).round(12).tolist()
    [1.0, 1.0]
    """
    phi, c1, c2, delta = _double_args(phi, shaft_angle, second_angle, phase)
    psi2 = _h(phi, c1)
    return _dh(psi2 - delta, 1.0 / c2) * _dh(phi, c1)


def double_acceleration_ratio(phi, shaft_angle, second_angle=None, phase=0.0):
    """Angular acceleration ratio d2psi3/dphi2 of a double Hooke's coupling.

    Notes
    -----
    d2psi3/dphi2 = h''(psi2 - delta; 1/c2) h'(phi; c1)^2
    + h'(psi2 - delta; 1/c2) h''(phi; c1) (chain rule on
    :func:`double_output_angle`).

    Examples
    --------
    >>> bool(np.allclose(double_acceleration_ratio([0.2, 0.9], 0.4), 0.0))
    True
    """
    phi, c1, c2, delta = _double_args(phi, shaft_angle, second_angle, phase)
    psi2 = _h(phi, c1)
    x = psi2 - delta
    d1 = _dh(phi, c1)
    return _d2h(x, 1.0 / c2) * d1 * d1 + _dh(x, 1.0 / c2) * _d2h(phi, c1)


@dataclass(frozen=True)
class DoubleFluctuation(Result):
    """Residual fluctuation of a double coupling over a turn.

    Attributes
    ----------
    min_ratio, max_ratio : float
        Least and greatest omega_last / omega_first.
    phi_min, phi_max : float
        Input angles (rad, in [0, pi)) where they occur.
    """

    min_ratio: float
    max_ratio: float
    phi_min: float
    phi_max: float

    @property
    def fluctuation(self) -> float:
        """max_ratio - min_ratio."""
        return self.max_ratio - self.min_ratio


def double_fluctuation(shaft_angle, second_angle=None, phase=0.0, samples: int = 2048) -> DoubleFluctuation:
    """Least and greatest velocity ratio of a double coupling over a turn.

    Parameters
    ----------
    shaft_angle, second_angle, phase
        As in :func:`double_output_angle` (rad).
    samples : int
        Grid points over one period [0, pi) before refinement.

    Returns
    -------
    DoubleFluctuation

    Notes
    -----
    The ratio has period pi in phi.  Its extremes are located on a grid and
    refined by a bounded scalar minimisation (scipy) within one grid step.
    Closed forms for checking: delta = 0 gives a single joint with
    c = cos beta1 / cos beta2, delta = pi/2 one with c = cos beta1 cos beta2.

    Examples
    --------
    >>> f = double_fluctuation(0.5, 0.5, np.pi / 2)
    >>> abs(f.min_ratio - math.cos(0.5) ** 2) < 1e-9, abs(f.max_ratio - 1 / math.cos(0.5) ** 2) < 1e-9
    (True, True)
    """
    from scipy.optimize import minimize_scalar

    samples = _validate.positive_int("samples", samples)
    _double_args(0.0, shaft_angle, second_angle, phase)
    grid = np.linspace(0.0, np.pi, samples, endpoint=False)
    vals = double_velocity_ratio(grid, shaft_angle, second_angle, phase)
    step = np.pi / samples

    def refine(i, sign):
        def f(x):
            return sign * float(double_velocity_ratio(x, shaft_angle, second_angle, phase))

        res = minimize_scalar(f, bounds=(grid[i] - step, grid[i] + step), method="bounded", options={"xatol": 1e-12})
        x = float(res.x) % np.pi
        best = sign * float(res.fun)
        if sign * best > sign * vals[i]:  # never worse than the grid value
            x, best = float(grid[i]), float(vals[i])
        return x, best

    i_min, i_max = int(np.argmin(vals)), int(np.argmax(vals))
    phi_min, vmin = refine(i_min, 1.0)
    phi_max, vmax = refine(i_max, -1.0)
    return DoubleFluctuation(vmin, vmax, phi_min, phi_max)


@dataclass(frozen=True)
class HookeTurn(Result):
    """Angles and ratios of a Hooke's coupling at given input angles (all angles in radians).

    Attributes
    ----------
    phi : ndarray
        Input (first-shaft) angles, rad.
    psi : ndarray
        Output (last-shaft) angles, rad.
    velocity_ratio : ndarray
        omega_out / omega_in.
    acceleration_ratio : ndarray
        d2psi/dphi2.

    Examples
    --------
    >>> import numpy as np
    >>> turn = HookeJoint.from_degrees(30).turn(np.radians([0.0, 90.0]))
    >>> np.round(turn.velocity_ratio, 6)
    array([1.154701, 0.866025])
    """

    phi: np.ndarray
    psi: np.ndarray
    velocity_ratio: np.ndarray
    acceleration_ratio: np.ndarray

    def as_records_deg(self) -> list[dict]:
        """One dict per input angle, angles in degrees (input_deg, output_deg, ratio, acceleration_ratio)."""
        # "+ 0.0" turns a negative zero into 0.0
        return [
            {
                "input_deg": float(a) + 0.0,
                "output_deg": float(b) + 0.0,
                "ratio": float(c) + 0.0,
                "acceleration_ratio": float(d) + 0.0,
            }
            for a, b, c, d in zip(
                np.degrees(self.phi).ravel(),
                np.degrees(self.psi).ravel(),
                self.velocity_ratio.ravel(),
                self.acceleration_ratio.ravel(),
            )
        ]


_UNSET = object()


@dataclass(frozen=True, init=False)
class HookeJoint:
    """A single or double Hooke's coupling as a parameter object (angles in radians).

    Parameters
    ----------
    shaft_angle : float
        beta1, rad, 0 <= beta1 < pi/2.
    second_angle : float or None
        beta2, rad, for a double coupling; None for a single joint.
    phase : float
        delta of the double coupling, rad.
    shaft_angle_deg, second_angle_deg, phase_deg : float, optional
        The same in degrees (keyword only; give each angle once, in one unit).
        :meth:`from_degrees` does the same.

    Notes
    -----
    The coupling of the classic text on trains of wheelwork, its section 70
    ("Double Hooke's Coupling"), which cites its section 66 for the single
    joint; the equations are those of :func:`output_angle` and
    :func:`double_output_angle`.

    Examples
    --------
    >>> HookeJoint(np.radians(30.0)).velocity_ratio([np.pi / 2]).round(6).tolist()
    [0.866025]
    >>> HookeJoint.from_degrees(30.0) == HookeJoint(shaft_angle_deg=30.0)
    True
    """

    shaft_angle: float
    second_angle: float | None
    phase: float

    def __init__(
        self,
        shaft_angle=_UNSET,
        second_angle=_UNSET,
        phase=_UNSET,
        *,
        shaft_angle_deg=_UNSET,
        second_angle_deg=_UNSET,
        phase_deg=_UNSET,
    ):
        def pick(name, rad, deg, default):
            if rad is not _UNSET and deg is not _UNSET:
                raise GearleverError(f"{name} is given twice: give {name} (rad) or {name}_deg, not both")
            if deg is not _UNSET:
                if deg is None:
                    return None
                value = _validate.finite(f"{name}_deg", deg)
                if name != "phase" and not 0.0 <= value < 90.0:
                    raise GearleverError(f"{name}_deg must be at least 0 and below 90 degrees, got {deg!r}")
                return math.radians(value)
            return default if rad is _UNSET else rad

        if shaft_angle is _UNSET and shaft_angle_deg is _UNSET:
            raise GearleverError("shaft_angle is required (rad; or shaft_angle_deg in degrees)")
        b1 = pick("shaft_angle", shaft_angle, shaft_angle_deg, None)
        b2 = pick("second_angle", second_angle, second_angle_deg, None)
        delta = pick("phase", phase, phase_deg, 0.0)
        b1 = _shaft_angle("shaft_angle", b1)
        b2 = None if b2 is None else _shaft_angle("second_angle", b2)
        delta = _validate.finite("phase", delta)
        object.__setattr__(self, "shaft_angle", b1)
        object.__setattr__(self, "second_angle", b2)
        object.__setattr__(self, "phase", delta)

    @classmethod
    def from_degrees(cls, shaft_angle_deg, second_angle_deg=None, phase_deg=0.0) -> HookeJoint:
        """The coupling with its angles given in degrees."""
        return cls(shaft_angle_deg=shaft_angle_deg, second_angle_deg=second_angle_deg, phase_deg=phase_deg)

    @property
    def double(self) -> bool:
        """True for a double coupling."""
        return self.second_angle is not None

    @property
    def shaft_angle_deg(self) -> float:
        return math.degrees(self.shaft_angle)

    @property
    def second_angle_deg(self) -> float | None:
        return None if self.second_angle is None else math.degrees(self.second_angle)

    @property
    def phase_deg(self) -> float:
        return math.degrees(self.phase)

    def output_angle(self, phi):
        """Output angle(s) psi, rad, for input angle(s) phi, rad."""
        if self.double:
            return double_output_angle(phi, self.shaft_angle, self.second_angle, self.phase)
        return output_angle(phi, self.shaft_angle)

    def velocity_ratio(self, phi):
        """omega_out / omega_in at input angle(s) phi, rad."""
        if self.double:
            return double_velocity_ratio(phi, self.shaft_angle, self.second_angle, self.phase)
        return velocity_ratio(phi, self.shaft_angle)

    def acceleration_ratio(self, phi):
        """d2psi/dphi2 at input angle(s) phi, rad."""
        if self.double:
            return double_acceleration_ratio(phi, self.shaft_angle, self.second_angle, self.phase)
        return acceleration_ratio(phi, self.shaft_angle)

    def turn(self, phi) -> HookeTurn:
        """Output angle, velocity and acceleration ratio at input angle(s) phi, rad."""
        phi = _validate.finite_array("phi", phi)
        return HookeTurn(phi, self.output_angle(phi), self.velocity_ratio(phi), self.acceleration_ratio(phi))

    def output_angle_deg(self, input_deg):
        """Output angle(s), degrees, for input angle(s) in degrees."""
        phi = np.radians(_validate.finite_array("input_deg", input_deg))
        return np.degrees(self.output_angle(phi))

    def velocity_ratio_deg(self, input_deg):
        """omega_out / omega_in at input angle(s) given in degrees."""
        return self.velocity_ratio(np.radians(_validate.finite_array("input_deg", input_deg)))

    def acceleration_ratio_deg(self, input_deg):
        """d2psi/dphi2 at input angle(s) given in degrees."""
        return self.acceleration_ratio(np.radians(_validate.finite_array("input_deg", input_deg)))


#: Alias of :func:`velocity_ratio` named by what it is, dpsi/dphi.
dpsi_dphi = velocity_ratio
#: Alias of :func:`acceleration_ratio` named by what it is, d2psi/dphi2.
d2psi_dphi2 = acceleration_ratio
