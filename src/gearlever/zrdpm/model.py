"""The gear-lever differential mechanism (ZRDPM) of Alimukhamedov et al. (2020).

Two mirror-image contours, each a double-slider vector contour driving a lever
(the carrier of a two-gear differential):

* contour 1: leading gear 9 (angle ``phi``), carrier (lever) 1, driven gear 8,
  sliders B (on x) and A (on a y guide); analogues ``u_1, u_8, e_1, e_8`` and
  point accelerations ``a_B, a_A`` (paper eqs. 2-20, Table I);
* contour 2: leading gear 6, carrier (lever) 2, driven gear 7, points D (x)
  and E (y); ``u_2, u_7, e_2, e_7`` and ``a_D, a_E`` (eqs. 21-39, Table II).

Two models are provided, because the paper's own tables do not follow its
section-2 formulas (see the README's ZRDPM section):

* the **self-consistent model** (:func:`analogues`): the lever's analogues
  vary with ``phi`` (eq. 9 and its derivative), the lever angle is their
  integral, and eq. 16/35 gives the point accelerations from them;
* the **tables model** (:func:`tables_outputs`): eq. 16/35 evaluated with
  *constant* ``l u**2`` and ``l e`` and the lever at ``phi + theta0``; this is
  what Tables I and II were computed with.  Its constants are identified from
  the published values by least squares (:func:`identify_tables_constants`).

Angles are radians unless a name ends in ``_deg``.  Lengths in cm.  All
kinematic functions take an array of angles and return arrays of its shape.
Contour 1 is drawn (and tabulated in the paper) with its x axis reversed
with respect to contour 2, the two contours being mirror images; this is the
``x_sign`` of :class:`ZrdpmContour` (-1 for contour 1, +1 for contour 2).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from typing import NamedTuple

import numpy as np

from gearlever._validate import finite, finite_array, positive, positive_int
from gearlever.errors import GearleverError
from gearlever.gears import willis as differential
from gearlever.loops import vector_loop

#: Paper names of the outputs per contour: (u carrier, u gear, e carrier,
#: e gear, point on x, point on y), and the published table of the contour.
PAPER_NAMES = {
    1: ("u_1", "u_8", "e_1", "e_8", "a_B", "a_A"),
    2: ("u_2", "u_7", "e_2", "e_7", "a_D", "a_E"),
}
TABLE_OF_CONTOUR = {1: "I", 2: "II"}
CONTOUR_OF_TABLE = {"I": 1, "II": 2}


def _check_contour(contour) -> int:
    if isinstance(contour, bool) or contour not in (1, 2):
        raise GearleverError(f"contour must be 1 or 2, got {contour!r}")
    return int(contour)


def x_sign(contour) -> float:
    """Direction of the x axis the contour is tabulated in: -1 for contour 1, +1 for 2.

    Notes
    -----
    zrdpm-paper.md section 5: Table I equals Table II with the x axis reversed
    (``a_B = -a_D``, ``a_A = a_E``), the two contours being mirror images.

    >>> x_sign(1), x_sign(2)
    (-1.0, 1.0)
    """
    return -1.0 if _check_contour(contour) == 1 else 1.0


@dataclass(frozen=True)
class ZrdpmContour:
    """Parameters of one ZRDPM contour (lengths in cm).

    Parameters
    ----------
    contour : {1, 2}
        1: gears 9 (leading) and 8, lever 1, points B, A.  2: gears 6
        (leading) and 7, lever 2, points D, E.
    l : float
        Contour link length ``l1`` (or ``l2``), > 0.  The paper states none;
        the default 10 cm is ours.
    r : float
        Offset ``r1`` (``r2``) of the y guide (positions only).
    r_a, r_b : float or None
        Radii at which the two sliders act on the lever (``rA``, ``rB``;
        ``rE``, ``rD``), > 0.  None (the default) means ``l/2``, so that
        ``l = rA + rB`` and eq. 9 holds as printed (``u_1 = sin + cos``).
        The default is resolved at construction: ``dataclasses.replace(p,
        l=...)`` keeps the radii of ``p``.
    r_lead, r_driven : float
        Pitch radii of the leading and the driven gear (``r9, r8`` or
        ``r6, r7``), > 0.  Stated default: 2 and 4 cm, ratio 0.5.
    mesh : {"external", "internal"}
        Mesh of the gear pair (the paper's is external).
    lever_angle0_deg : float
        Lever angle at ``phi = 0``, degrees (default -90, the tables' phase).

    Examples
    --------
    >>> p = ZrdpmContour(contour=2)
    >>> p.ratio, p.x_sign
    (0.5, 1.0)
    >>> ZrdpmContour(l=20.0).r_a, ZrdpmContour(l=20.0).lever_gain
    (10.0, 1.0)
    """

    contour: int = 1
    l: float = 10.0
    r: float = 0.0
    r_a: float | None = None
    r_b: float | None = None
    r_lead: float = 2.0
    r_driven: float = 4.0
    mesh: str = "external"
    lever_angle0_deg: float = -90.0

    def __post_init__(self):
        object.__setattr__(self, "contour", _check_contour(self.contour))
        ell = positive("l", self.l)
        for name in ("r_a", "r_b"):
            if getattr(self, name) is None:
                object.__setattr__(self, name, ell / 2)
        for name in ("l", "r_a", "r_b", "r_lead", "r_driven"):
            object.__setattr__(self, name, positive(name, getattr(self, name)))
        for name in ("r", "lever_angle0_deg"):
            object.__setattr__(self, name, finite(name, getattr(self, name)))
        if self.mesh not in differential.MESHES:
            raise GearleverError(f"mesh must be 'external' or 'internal', got {self.mesh!r}")

    @classmethod
    def from_teeth(cls, contour, z_lead, z_driven, module=1.0, **kwargs):
        """Build from tooth numbers: pitch radius = module * z / 2.

        >>> ZrdpmContour.from_teeth(1, 20, 40).ratio
        0.5
        """
        z_lead = positive_int("z_lead", z_lead)
        z_driven = positive_int("z_driven", z_driven)
        module = positive("module", module)
        return cls(contour=contour, r_lead=module * z_lead / 2, r_driven=module * z_driven / 2, **kwargs)

    def with_ratio(self, ratio):
        """A copy whose leading gear is resized to give ``r_lead/r_driven = ratio``.

        >>> ZrdpmContour().with_ratio(2.0).r_lead
        8.0
        """
        ratio = positive("ratio", ratio)
        return replace(self, r_lead=ratio * self.r_driven)

    @property
    def ratio(self) -> float:
        """``r_lead / r_driven`` (``r9/r8`` or ``r6/r7``)."""
        return self.r_lead / self.r_driven

    @property
    def x_sign(self) -> float:
        """See :func:`x_sign`."""
        return x_sign(self.contour)

    @property
    def lever_gain(self) -> float:
        """``c = l / (r_a + r_b)``, the amplitude factor of eq. 9."""
        return self.l / (self.r_a + self.r_b)

    @property
    def names(self) -> tuple:
        """Paper names of the six outputs, see :data:`PAPER_NAMES`."""
        return PAPER_NAMES[self.contour]


@dataclass(frozen=True)
class TablesConstants:
    """Constant analogues with which the paper's tables were computed.

    Parameters
    ----------
    contour : {1, 2}
    l_u2 : float
        ``l * u**2`` of the lever, cm (>= 0).
    l_e : float
        ``l * e`` of the lever, cm.
    lever_angle0_deg : float
        The lever's angle is ``phi + lever_angle0_deg``.

    Notes
    -----
    zrdpm-paper.md section 5; identified by :func:`identify_tables_constants`.
    In the form ``a_x = A sin(phi) + B cos(phi)`` (Table I) the constants are
    ``A = l_u2`` and ``B = -l_e`` (see :attr:`A`, :attr:`B`).
    """

    contour: int
    l_u2: float
    l_e: float
    lever_angle0_deg: float = -90.0

    def __post_init__(self):
        object.__setattr__(self, "contour", _check_contour(self.contour))
        if not isinstance(self.l_u2, (int, float)) or not math.isfinite(self.l_u2) or self.l_u2 < 0:
            raise GearleverError(f"l_u2 must be a non-negative finite number, got {self.l_u2!r}")
        object.__setattr__(self, "l_u2", float(self.l_u2))
        object.__setattr__(self, "l_e", finite("l_e", self.l_e))
        object.__setattr__(self, "lever_angle0_deg", finite("lever_angle0_deg", self.lever_angle0_deg))

    @property
    def A(self) -> float:
        """Amplitude of the sine term of Table I's a_B (= ``l_u2``)."""
        return self.l_u2

    @property
    def B(self) -> float:
        """Amplitude of the cosine term of Table I's a_B (= ``-l_e``)."""
        return -self.l_e


class ContourKinematics(NamedTuple):
    """The six outputs of a contour, each an array shaped like ``phi``.

    ``u_carrier, u_gear, e_carrier, e_gear`` are ``u_1, u_8, e_1, e_8``
    (contour 1) or ``u_2, u_7, e_2, e_7`` (contour 2); ``a_x, a_y`` are
    ``a_B, a_A`` or ``a_D, a_E`` (cm, over the leading link's ``omega**2``).
    """

    u_carrier: np.ndarray
    u_gear: np.ndarray
    e_carrier: np.ndarray
    e_gear: np.ndarray
    a_x: np.ndarray
    a_y: np.ndarray

    def named(self, contour) -> dict:
        """The outputs keyed by their paper names (``u_1``, ..., ``a_A``)."""
        return dict(zip(PAPER_NAMES[_check_contour(contour)], self))


# --------------------------------------------------------------------------
# the self-consistent model (paper section 2 as written)


def lever_angle(params: ZrdpmContour, phi):
    """Angle of the lever (carrier 1 or 2) over the leading link's angle.

    Parameters
    ----------
    params : ZrdpmContour
    phi : array_like
        Leading link angle(s), radians.

    Returns
    -------
    ndarray
        ``theta(phi) = theta0 + c (sin(phi) - cos(phi) + 1)``, radians.

    Notes
    -----
    The integral of eq. 9 (eq. 28-29 for lever 2), see
    :func:`gearlever.loops.vector_loop.slider_lever`.

    Examples
    --------
    >>> float(lever_angle(ZrdpmContour(lever_angle0_deg=0.0), 0.0))
    0.0
    """
    dtheta, _, _ = vector_loop.slider_lever(params.l, params.r_a, params.r_b, phi)
    return math.radians(params.lever_angle0_deg) + dtheta


def analogues(params: ZrdpmContour, phi, *, block=None, out=None):
    """All six outputs of a contour by the self-consistent model.

    Parameters
    ----------
    params : ZrdpmContour
    phi : array_like
        Leading link angle(s) (``phi_9`` or ``phi_6``), radians.
    block : int, optional
        If given, use the blocked in-place fast path with blocks of this many
        angles (same results to rounding; see :func:`tables_outputs`).
    out : ndarray, optional
        Fast path only: a C-contiguous float64 array of shape
        ``(6, *phi.shape)`` to write the six outputs into (its rows are
        returned).

    Returns
    -------
    ContourKinematics

    Notes
    -----
    ``u_c = c (sin + cos)``, ``e_c = du_c/dphi`` (eqs. 9, 28-29); driven gear
    by Willis (eqs. 4, 14; 23, 33) with a uniformly turning leading link;
    point accelerations by eq. 16 / 35 at the lever angle of
    :func:`lever_angle`, x axis signed by :attr:`ZrdpmContour.x_sign`.

    Examples
    --------
    >>> k = analogues(ZrdpmContour(), [0.0])
    >>> float(k.u_carrier[0]), float(k.e_carrier[0]), float(k.u_gear[0])
    (1.0, 1.0, 1.0)
    """
    if not isinstance(params, ZrdpmContour):
        raise GearleverError(f"params must be a ZrdpmContour, got {type(params).__name__}")
    if block is not None:
        return _fast(params, phi, None, block, out)
    if out is not None:
        raise GearleverError("out must be None unless block is given (the fast path)")
    dtheta, u_c, e_c = vector_loop.slider_lever(params.l, params.r_a, params.r_b, phi)
    theta = math.radians(params.lever_angle0_deg) + dtheta
    u_g, e_g = differential.driven_analogues(u_c, e_c, params.ratio, params.mesh)
    a_x, a_y = vector_loop.point_acceleration(params.l, theta, u_c, e_c)
    return ContourKinematics(u_c, u_g, e_c, e_g, params.x_sign * a_x, a_y)


def _named_contour(contour: int, params: ZrdpmContour | None, phi) -> dict:
    """The self-consistent model of ``contour`` (default parameters when None), by paper names."""
    params = ZrdpmContour(contour=contour) if params is None else params
    if params.contour != contour:
        raise GearleverError(f"params.contour must be {contour} for contour{contour}, got {params.contour}")
    return analogues(params, phi).named(contour)


def contour1(params: ZrdpmContour | None, phi) -> dict:
    """Contour 1 (gears 9, 8; lever 1) by the self-consistent model, by paper names.

    ``params`` None means the default ``ZrdpmContour(contour=1)``.  Returns a
    dict with ``u_1, u_8, e_1, e_8, a_B, a_A``, arrays shaped like ``phi``.

    >>> sorted(contour1(None, [0.0]))
    ['a_A', 'a_B', 'e_1', 'e_8', 'u_1', 'u_8']
    """
    return _named_contour(1, params, phi)


def contour2(params: ZrdpmContour | None, phi) -> dict:
    """Contour 2 (gears 6, 7; lever 2) by the self-consistent model, by paper names.

    ``params`` None means the default ``ZrdpmContour(contour=2)``.  Returns a
    dict with ``u_2, u_7, e_2, e_7, a_D, a_E``, arrays shaped like ``phi``.

    >>> sorted(contour2(None, [0.0]))
    ['a_D', 'a_E', 'e_2', 'e_7', 'u_2', 'u_7']
    """
    return _named_contour(2, params, phi)


# --------------------------------------------------------------------------
# the tables model (what Tables I and II were computed with)


def tables_point_accelerations(constants: TablesConstants, phi):
    """Point accelerations of the tables model: eq. 16/35 with constant analogues.

    Parameters
    ----------
    constants : TablesConstants
    phi : array_like
        Leading link angle(s), radians.

    Returns
    -------
    a_x, a_y : ndarray
        ``a_B, a_A`` (contour 1) or ``a_D, a_E`` (contour 2), cm.

    Notes
    -----
    Paper eq. 16 (35) with ``l u**2`` and ``l e`` held constant and the lever
    at ``theta = phi + theta0`` (zrdpm-paper.md section 5)::

        a_x = x_sign * (-(l u**2) cos(theta) - (l e) sin(theta))
        a_y = -(l u**2) sin(theta) + (l e) cos(theta)

    Evaluated with :func:`gearlever.loops.vector_loop.point_acceleration` at unit
    length and ``u = sqrt(l u**2)``.

    Examples
    --------
    >>> ax, ay = tables_point_accelerations(TablesConstants(2, 1.0, 0.0), [math.pi / 2])
    >>> round(float(ax[0]), 12), round(float(ay[0]), 12)
    (-1.0, 0.0)
    """
    if not isinstance(constants, TablesConstants):
        raise GearleverError(f"constants must be TablesConstants, got {type(constants).__name__}")
    phi = finite_array("phi", phi)
    theta = phi + math.radians(constants.lever_angle0_deg)
    a_x, a_y = vector_loop.point_acceleration(1.0, theta, math.sqrt(constants.l_u2), constants.l_e)
    return x_sign(constants.contour) * a_x, a_y


def tables_outputs(params: ZrdpmContour, constants: TablesConstants, phi, *, block=None, out=None):
    """All six outputs of a contour as the paper computed them for its tables.

    The carrier's and the gear's analogues follow eqs. 9-14 (they vary with
    ``phi``); the point accelerations use the constant analogues of
    :func:`tables_point_accelerations`.

    Parameters
    ----------
    params : ZrdpmContour
    constants : TablesConstants
        Same contour as ``params``.
    phi : array_like
        Radians.
    block : int, optional
        If given, use the fast path: one sine and one cosine evaluation per
        angle, then the six outputs as a 6 x 2 matrix product per block of
        this many angles, written in place; the results equal the plain
        path's to rounding.
    out : ndarray, optional
        Fast path only: a C-contiguous float64 array of shape
        ``(6, *phi.shape)`` to write the six outputs into (saves the
        allocation when called repeatedly).

    Returns
    -------
    ContourKinematics

    Notes
    -----
    Eqs. 9, 11, 14 (contour 1) / 29, 30, 33 (contour 2) and eq. 16 / 35 with
    constants.

    Examples
    --------
    >>> k = tables_outputs(ZrdpmContour(2), TablesConstants(2, 1.0, 0.0), [0.0, 1.0])
    >>> k2 = tables_outputs(ZrdpmContour(2), TablesConstants(2, 1.0, 0.0), [0.0, 1.0], block=1)
    >>> all(np.allclose(a, b, rtol=1e-12, atol=1e-12) for a, b in zip(k, k2))
    True
    """
    if not isinstance(params, ZrdpmContour):
        raise GearleverError(f"params must be a ZrdpmContour, got {type(params).__name__}")
    if not isinstance(constants, TablesConstants):
        raise GearleverError(f"constants must be TablesConstants, got {type(constants).__name__}")
    if constants.contour != params.contour:
        raise GearleverError(f"constants.contour must equal params.contour ({params.contour}), got {constants.contour}")
    if block is not None:
        return _fast(params, phi, constants, block, out)
    if out is not None:
        raise GearleverError("out must be None unless block is given (the fast path)")
    _, u_c, e_c = vector_loop.slider_lever(params.l, params.r_a, params.r_b, phi)
    u_g, e_g = differential.driven_analogues(u_c, e_c, params.ratio, params.mesh)
    a_x, a_y = tables_point_accelerations(constants, phi)
    return ContourKinematics(u_c, u_g, e_c, e_g, a_x, a_y)


def _check_out(out, shape):
    want = (6, *shape)
    if (
        not isinstance(out, np.ndarray)
        or out.dtype != np.float64
        or out.shape != want
        or not out.flags.c_contiguous
        or not out.flags.writeable
    ):
        got = f"{out.dtype} array of shape {out.shape}" if isinstance(out, np.ndarray) else type(out).__name__
        raise GearleverError(f"out must be a writeable C-contiguous float64 array of shape {want}, got {got}")
    return out


def _fast(params: ZrdpmContour, phi, constants, block, out=None):
    """Fast evaluation of :func:`analogues` / :func:`tables_outputs` (same results to rounding).

    Tables model: one pass over the angles, block by block (``block``
    angles; ~32768 keeps the (3, block) buffer in a 1-2 MB L2 cache): ``sin``
    and ``cos`` of the block into the buffer (whose third row is ones), then
    the six outputs as one 6 x 3 matrix product, every output being
    ``alpha sin + beta cos + gamma`` with the coefficients of eqs. 9, 11, 14
    and 16.  Self-consistent
    model: per block, in-place ufuncs, with a second sin/cos pair for the lever
    angle.  The six outputs are rows of one ``(6, *phi.shape)`` array, which
    may be given as ``out`` to reuse memory.
    """
    block = positive_int("block", block)
    phi = finite_array("phi", phi)
    shape = phi.shape
    flat = np.ascontiguousarray(phi).reshape(-1)
    n = flat.size
    out = np.empty((6, *shape)) if out is None else _check_out(out, shape)
    rows = out.reshape(6, n)
    c = params.lever_gain
    i = -params.ratio if params.mesh == "external" else params.ratio
    g = 1.0 - i
    sgn = params.x_sign
    bs = min(block, max(n, 1))
    if constants is not None:
        th0 = math.radians(constants.lever_angle0_deg)
        c0, s0 = math.cos(th0), math.sin(th0)
        L, E = constants.l_u2, constants.l_e
        # every output is alpha sin(phi) + beta cos(phi) + gamma; cos(theta) = C c0 - S s0,
        # sin(theta) = S c0 + C s0.  Columns: coefficient of sin, of cos, constant.
        coef = np.array(
            [
                [c, c, 0.0],  # u_c = c (S + C)                     eq. 9
                [g * c, g * c, i],  # u_g = (1 - i) u_c + i         eq. 11
                [-c, c, 0.0],  # e_c = c (C - S)
                [-g * c, g * c, 0.0],  # e_g = (1 - i) e_c          eq. 14
                [-sgn * (E * c0 - L * s0), -sgn * (L * c0 + E * s0), 0.0],  # a_x   eq. 16
                [-(L * c0 + E * s0), E * c0 - L * s0, 0.0],  # a_y
            ]
        )
        # one pass over the angles: per block, sin and cos go into a cache-resident
        # (3, block) buffer whose third row is ones, and one 6 x 3 matrix product writes
        # the block of all six outputs (nothing is written twice, no full-size scratch)
        x = np.ones((3, bs))
        for start in range(0, n, bs):
            stop = min(start + bs, n)
            xb = x[:, : stop - start]
            np.sin(flat[start:stop], out=xb[0])
            np.cos(flat[start:stop], out=xb[1])
            np.matmul(coef, xb, out=rows[:, start:stop])
        return ContourKinematics(*out)
    u_c, u_g, e_c, e_g, a_x, a_y = rows
    th0 = math.radians(params.lever_angle0_deg)
    ell = params.l
    s, co, t1, t2 = (np.empty(bs) for _ in range(4))
    for start in range(0, n, bs):
        stop = min(start + bs, n)
        m = stop - start
        S, C, T1, T2 = s[:m], co[:m], t1[:m], t2[:m]
        np.sin(flat[start:stop], out=S)
        np.cos(flat[start:stop], out=C)
        uc, ug, ec, eg, ax, ay = (
            u_c[start:stop],
            u_g[start:stop],
            e_c[start:stop],
            e_g[start:stop],
            a_x[start:stop],
            a_y[start:stop],
        )
        np.add(S, C, out=uc)
        uc *= c
        np.subtract(C, S, out=ec)
        ec *= c
        np.multiply(uc, g, out=ug)
        ug += i
        np.multiply(ec, g, out=eg)
        # theta = th0 + c (S - C + 1); then S, C are reused for sin/cos(theta)
        np.subtract(S, C, out=T1)
        T1 += 1.0
        T1 *= c
        T1 += th0
        np.cos(T1, out=C)
        np.sin(T1, out=S)
        np.multiply(uc, uc, out=T2)  # u**2
        # eq. 16: a_x = -l (cos u2 + sin e), a_y = l (cos e - sin u2)
        np.multiply(C, T2, out=ax)
        np.multiply(S, ec, out=T1)
        ax += T1
        ax *= -ell * sgn
        np.multiply(C, ec, out=ay)
        np.multiply(S, T2, out=T1)
        ay -= T1
        ay *= ell
    return ContourKinematics(*out)


# --------------------------------------------------------------------------
# recovery of the lever's analogues from the point accelerations


def recover_lever_analogues(params: ZrdpmContour, phi, a_x, a_y):
    """Lever's ``u**2`` and ``e`` from both point accelerations (self-consistent geometry).

    Parameters
    ----------
    params : ZrdpmContour
    phi : array_like
        Leading link angle(s), radians.
    a_x, a_y : array_like
        ``a_B, a_A`` (contour 1) or ``a_D, a_E`` (contour 2), cm, in the
        contour's own x direction.

    Returns
    -------
    u_squared, e : ndarray

    Notes
    -----
    Replaces the paper's eq. 17 (36), which uses only ``a_B`` and divides by
    ``sin(phi_1)``: both projections of eq. 16 are used
    (:func:`gearlever.loops.vector_loop.recover_analogues`), finite for every angle,
    including lever angles of 0 and 180 degrees.

    Examples
    --------
    >>> p = ZrdpmContour()
    >>> k = analogues(p, [0.0, math.pi])
    >>> u2, e = recover_lever_analogues(p, [0.0, math.pi], k.a_x, k.a_y)
    >>> bool(np.allclose(u2, k.u_carrier**2) and np.allclose(e, k.e_carrier))
    True
    """
    theta = lever_angle(params, phi)
    a_x = np.asarray(a_x, dtype=float) * params.x_sign
    return vector_loop.recover_analogues(params.l, theta, a_x, a_y)


def gear_acceleration_from_points(params: ZrdpmContour, phi, a_x, a_y):
    """Driven gear's acceleration analogue from the point accelerations (eq. 18 / 37, regular).

    Parameters
    ----------
    params : ZrdpmContour
    phi : array_like
        Radians.
    a_x, a_y : array_like
        ``a_B, a_A`` (contour 1) or ``a_D, a_E`` (contour 2), cm.

    Returns
    -------
    ndarray
        ``e_8`` (contour 1) or ``e_7`` (contour 2).

    Notes
    -----
    The paper substitutes eq. 17 into eq. 14 (eq. 18; eqs. 36-37 for gear 7).
    Here the lever's ``e`` comes from :func:`recover_lever_analogues` (both
    projections), so the result is finite where ``sin(phi_1) = 0``.

    Examples
    --------
    >>> p = ZrdpmContour()
    >>> k = analogues(p, [0.3])
    >>> bool(np.allclose(gear_acceleration_from_points(p, [0.3], k.a_x, k.a_y), k.e_gear))
    True
    """
    _, e = recover_lever_analogues(params, phi, a_x, a_y)
    return differential.driven_analogues(0.0, e, params.ratio, params.mesh)[1]


def recover_tables_constants(contour, phi, a_x, a_y, lever_angle0_deg=-90.0):
    """``l u**2`` and ``l e`` at every angle from a table's two columns.

    Parameters
    ----------
    contour : {1, 2}
    phi : array_like
        Radians.
    a_x, a_y : array_like
        Published ``a_B, a_A`` (Table I) or ``a_D, a_E`` (Table II), cm.
    lever_angle0_deg : float
        Lever angle at ``phi = 0`` (the tables model's -90 by default).

    Returns
    -------
    l_u2, l_e : ndarray
        Per angle, cm.  Constant (to the print's rounding) for the paper's
        tables, which is how the tables model is recognised.

    Notes
    -----
    :func:`gearlever.loops.vector_loop.recover_analogues` at unit length with the
    lever at ``phi + theta0``: both projections, no division by ``sin``.

    Examples
    --------
    >>> L, E = recover_tables_constants(2, [0.0], *tables_point_accelerations(
    ...     TablesConstants(2, 3.0, -1.0), [0.0]))
    >>> round(float(L[0]), 12), round(float(E[0]), 12)
    (3.0, -1.0)
    """
    sgn = x_sign(contour)
    phi = finite_array("phi", phi)
    theta = phi + math.radians(finite("lever_angle0_deg", lever_angle0_deg))
    a_x = np.asarray(a_x, dtype=float) * sgn
    return vector_loop.recover_analogues(1.0, theta, a_x, a_y)


# --------------------------------------------------------------------------
# the published tables and the identification of their constants


@dataclass(frozen=True)
class PublishedTable:
    """One published table (I or II): two columns over 12 angles.

    Attributes
    ----------
    table : {"I", "II"}
    contour : {1, 2}
    columns : tuple of str
        Paper names of the x and y columns (``a_B, a_A`` or ``a_D, a_E``).
    phi_deg : ndarray
    a_x, a_y : ndarray
        Values as read, cm.
    printed_x, printed_y : tuple of str
        Cells exactly as printed (OCR, decimal commas).
    corrected_x, corrected_y : ndarray of bool
        True where the reading corrects the print.
    """

    table: str
    contour: int
    columns: tuple
    phi_deg: np.ndarray = field(repr=False)
    a_x: np.ndarray = field(repr=False)
    a_y: np.ndarray = field(repr=False)
    printed_x: tuple = field(repr=False)
    printed_y: tuple = field(repr=False)
    corrected_x: np.ndarray = field(repr=False)
    corrected_y: np.ndarray = field(repr=False)

    @property
    def phi(self) -> np.ndarray:
        """Angles in radians."""
        return np.deg2rad(self.phi_deg)

    @property
    def size(self) -> int:
        """Number of published values (both columns)."""
        return int(self.a_x.size + self.a_y.size)


def published_table(table) -> PublishedTable:
    """Read Table I or II from the package data file ``zrdpm_published.csv``.

    Parameters
    ----------
    table : {"I", "II"}

    Returns
    -------
    PublishedTable

    Notes
    -----
    Source, page and units are in the data file's header.  Loaded on demand.

    Examples
    --------
    >>> t = published_table("I")
    >>> t.columns, t.size, float(t.a_x[0])
    (('a_B', 'a_A'), 24, 12.44)
    """
    if table not in CONTOUR_OF_TABLE:
        raise GearleverError(f"table must be 'I' or 'II', got {table!r}")
    from gearlever.data import read_records

    contour = CONTOUR_OF_TABLE[table]
    cx, cy = PAPER_NAMES[contour][4:]
    cols = {cx: [], cy: []}
    for rec in read_records("zrdpm_published.csv"):
        if rec["table"] == table:
            cols[rec["column"]].append(
                (float(rec["phi_deg"]), rec["printed"], float(rec["value_cm"]), rec["corrected"] == "1")
            )
    for name in (cx, cy):
        cols[name].sort()
    phx = [r[0] for r in cols[cx]]
    if phx != [r[0] for r in cols[cy]] or not phx:
        raise GearleverError(f"zrdpm_published.csv: columns {cx} and {cy} of table {table} do not match")
    return PublishedTable(
        table=table,
        contour=contour,
        columns=(cx, cy),
        phi_deg=np.array(phx),
        a_x=np.array([r[2] for r in cols[cx]]),
        a_y=np.array([r[2] for r in cols[cy]]),
        printed_x=tuple(r[1] for r in cols[cx]),
        printed_y=tuple(r[1] for r in cols[cy]),
        corrected_x=np.array([r[3] for r in cols[cx]]),
        corrected_y=np.array([r[3] for r in cols[cy]]),
    )


@dataclass(frozen=True)
class TablesFit:
    """Result of :func:`identify_tables_constants`.

    Attributes
    ----------
    constants : TablesConstants
    residual_x, residual_y : ndarray
        Model minus published, cm, per angle.
    rms, max_abs : float
        Over all values of the table, cm.
    success : bool
        True when the design matrix has full rank (both constants identified).
    """

    constants: TablesConstants
    residual_x: np.ndarray = field(repr=False)
    residual_y: np.ndarray = field(repr=False)
    rms: float
    max_abs: float
    success: bool


def _residual_stats(rx, ry):
    r = np.concatenate([rx, ry])
    return float(np.sqrt(np.mean(r * r))), float(np.max(np.abs(r)))


def _tables_design(contour, phi, lever_angle0):
    """The 2N x 2 matrix ``M`` of the tables model, linear in ``(l u**2, l e)``: ``[a_x; a_y] = M @ (L, E)``."""
    theta = phi + lever_angle0
    c, s = np.cos(theta), np.sin(theta)
    sgn = x_sign(contour)
    return np.concatenate([np.stack([-sgn * c, -sgn * s], axis=-1), np.stack([-s, c], axis=-1)])


def identify_tables_constants(table: PublishedTable, lever_angle0_deg=-90.0) -> TablesFit:
    """Identify ``l u**2`` and ``l e`` of a published table by linear least squares.

    Parameters
    ----------
    table : PublishedTable
    lever_angle0_deg : float
        Phase of the lever, held fixed (a free phase would make the problem
        degenerate: only the amplitude and phase of each column are
        identifiable, i.e. two numbers).

    Returns
    -------
    TablesFit

    Notes
    -----
    The tables model (paper eq. 16 / 35 with constant analogues) is linear
    in ``(l u**2, l e)``, so the fit is one linear least-squares solve
    (``numpy.linalg.lstsq``, an SVD of the 24 x 2 design matrix), with
    ``l u**2 >= 0`` enforced by refitting ``l e`` alone in the (never met)
    case of a negative solution.  No iteration and no tolerances: the same
    numbers to rounding on any machine.  zrdpm-paper.md section 5 reads
    ``A = 21.00``, ``B = 2.24`` cm off the tables, i.e. ``l u**2 = 21``,
    ``l e = -2.24``.

    Examples
    --------
    >>> fit = identify_tables_constants(published_table("II"))
    >>> round(fit.constants.l_u2, 2), round(fit.constants.l_e, 2), fit.max_abs < 0.005
    (21.0, -2.24, True)
    """
    if not isinstance(table, PublishedTable):
        raise GearleverError(f"table must be a PublishedTable, got {type(table).__name__}")
    th0 = math.radians(finite("lever_angle0_deg", lever_angle0_deg))
    phi = table.phi
    M = _tables_design(table.contour, phi, th0)
    y = np.concatenate([table.a_x, table.a_y])
    (L, E), _, rank, _ = np.linalg.lstsq(M, y, rcond=None)
    if L < 0:  # the bound l u**2 >= 0 is active: best l e with l u**2 = 0
        L, E = 0.0, float(M[:, 1] @ y / (M[:, 1] @ M[:, 1]))
    k = TablesConstants(table.contour, float(L), float(E), lever_angle0_deg)
    ax, ay = tables_point_accelerations(k, phi)
    rx, ry = ax - table.a_x, ay - table.a_y
    rms, mx = _residual_stats(rx, ry)
    return TablesFit(k, rx, ry, rms, mx, bool(rank == 2))


@dataclass(frozen=True)
class SelfConsistentFit:
    """Result of :func:`fit_self_consistent`: the best the section-2 model can do.

    Attributes
    ----------
    params : ZrdpmContour
        With the fitted ``l`` and ``lever_angle0_deg`` (and ``r_a = r_b = l/2``).
    residual_x, residual_y : ndarray
    rms, max_abs : float
        cm.
    """

    params: ZrdpmContour
    residual_x: np.ndarray = field(repr=False)
    residual_y: np.ndarray = field(repr=False)
    rms: float
    max_abs: float


def fit_self_consistent(table: PublishedTable, base: ZrdpmContour | None = None) -> SelfConsistentFit:
    """Fit the self-consistent model's ``l`` and initial lever angle to a table.

    Parameters
    ----------
    table : PublishedTable
    base : ZrdpmContour, optional
        Gear data to carry along (they do not affect the point accelerations).

    Returns
    -------
    SelfConsistentFit

    Notes
    -----
    ``l = r_a + r_b`` as in eq. 9; the model is nonlinear in ``l`` and the
    phase, so ``scipy.optimize.least_squares`` (tolerances 1e-12) runs from
    eight starting phases and the best is kept.  Converged to ~1e-9, its
    results are written with 4 decimals (cm) and 3 (degrees).  Its residuals measure how far the tables
    are from the paper's own section-2 formulas.

    Examples
    --------
    >>> fit = fit_self_consistent(published_table("II"))
    >>> fit.max_abs > 1.0
    True
    """
    from scipy.optimize import least_squares

    if not isinstance(table, PublishedTable):
        raise GearleverError(f"table must be a PublishedTable, got {type(table).__name__}")
    base = ZrdpmContour(contour=table.contour) if base is None else replace(base, contour=table.contour)
    phi = table.phi

    def make(x):
        ell = float(x[0])
        return replace(base, l=ell, r_a=ell / 2, r_b=ell / 2, lever_angle0_deg=float(x[1]))

    def resid(x):
        k = analogues(make(x), phi)
        return np.concatenate([k.a_x - table.a_x, k.a_y - table.a_y])

    scale = float(np.sqrt(np.mean(table.a_x**2 + table.a_y**2)))
    best = None
    for start_deg in range(-180, 180, 45):
        sol = least_squares(
            resid,
            x0=[scale, float(start_deg)],
            bounds=([1e-6, -720.0], [np.inf, 720.0]),
            x_scale=[scale, 90.0],
            xtol=1e-12,
            ftol=1e-12,
            gtol=1e-12,
        )
        if best is None or sol.cost < best.cost - 1e-12:
            best = sol
    ell, deg = float(best.x[0]), float(best.x[1])
    deg = (deg + 180.0) % 360.0 - 180.0
    params = make([ell, deg])
    k = analogues(params, phi)
    rx, ry = k.a_x - table.a_x, k.a_y - table.a_y
    rms, mx = _residual_stats(rx, ry)
    return SelfConsistentFit(params, rx, ry, rms, mx)
