"""The published Tables I and II of the ZRDPM paper, and what is identified from them.

:func:`published_table` reads them from the package data file;
:func:`identify_tables_constants` (linear least squares) and
:func:`fit_self_consistent` (nonlinear) fit the two models to them;
:func:`recover_lever_analogues`, :func:`gear_acceleration_from_points` and
:func:`recover_tables_constants` invert paper eq. 16 / 35 from both point
accelerations (the regular replacement of eqs. 17-18 / 36-37).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace

import numpy as np

from gearlever._result import Result
from gearlever._validate import finite, finite_array
from gearlever.errors import GearleverError
from gearlever.gears import willis
from gearlever.loops import closed
from gearlever.zrdpm.model import analogues, lever_angle, tables_point_accelerations
from gearlever.zrdpm.parameters import (
    CONTOUR_OF_TABLE,
    PAPER_NAMES,
    TablesConstants,
    ZrdpmContour,
    x_sign,
)

__all__ = [
    "PublishedTable",
    "SelfConsistentFit",
    "TablesFit",
    "fit_self_consistent",
    "gear_acceleration_from_points",
    "identify_tables_constants",
    "published_table",
    "recover_lever_analogues",
    "recover_tables_constants",
]


def _lever_angle0(lever_angle0, lever_angle0_deg) -> float:
    """The lever angle in radians from the radian argument or its degree alias."""
    if lever_angle0_deg is not None:
        return math.radians(finite("lever_angle0_deg", lever_angle0_deg))
    return finite("lever_angle0", lever_angle0)


# --------------------------------------------------------------------------
# recovery of the lever's analogues from the point accelerations


def recover_lever_analogues(params: ZrdpmContour, phi, a_x, a_y) -> tuple[np.ndarray, np.ndarray]:
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
    (:func:`gearlever.loops.closed.recover_analogues`), finite for every angle,
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
    return closed.recover_analogues(params.l, theta, a_x, a_y)


def gear_acceleration_from_points(params: ZrdpmContour, phi, a_x, a_y) -> np.ndarray:
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
    return willis.driven_analogues(0.0, e, params.ratio, params.mesh)[1]


def recover_tables_constants(
    contour: int, phi, a_x, a_y, lever_angle0: float = -math.pi / 2, *, lever_angle0_deg: float | None = None
) -> tuple[np.ndarray, np.ndarray]:
    """``l u**2`` and ``l e`` at every angle from a table's two columns.

    Parameters
    ----------
    contour : {1, 2}
    phi : array_like
        Radians.
    a_x, a_y : array_like
        Published ``a_B, a_A`` (Table I) or ``a_D, a_E`` (Table II), cm.
    lever_angle0 : float
        Lever angle at ``phi = 0``, radians (the tables model's ``-pi/2`` by
        default).
    lever_angle0_deg : float, optional
        The same in degrees (the old keyword, kept as an alias).

    Returns
    -------
    l_u2, l_e : ndarray
        Per angle, cm.  Constant (to the print's rounding) for the paper's
        tables, which is how the tables model is recognised.

    Notes
    -----
    :func:`gearlever.loops.closed.recover_analogues` at unit length with the
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
    theta = phi + _lever_angle0(lever_angle0, lever_angle0_deg)
    a_x = np.asarray(a_x, dtype=float) * sgn
    return closed.recover_analogues(1.0, theta, a_x, a_y)


# --------------------------------------------------------------------------
# the published tables and the identification of their constants


@dataclass(frozen=True)
class PublishedTable(Result):
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

    Examples
    --------
    >>> t = published_table("I")
    >>> t.contour, len(t.phi_deg)
    (1, 12)
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


def published_table(table: str) -> PublishedTable:
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
class TablesFit(Result):
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

    Examples
    --------
    >>> fit = identify_tables_constants(published_table("II"))
    >>> round(fit.constants.l_u2, 3), round(fit.max_abs, 4)
    (21.001, 0.0025)
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


def identify_tables_constants(table: PublishedTable, lever_angle0=-math.pi / 2, *, lever_angle0_deg=None) -> TablesFit:
    """Identify ``l u**2`` and ``l e`` of a published table by linear least squares.

    Parameters
    ----------
    table : PublishedTable
    lever_angle0 : float
        Phase of the lever, radians, held fixed (a free phase would make the
        problem degenerate: only the amplitude and phase of each column are
        identifiable, i.e. two numbers).
    lever_angle0_deg : float, optional
        The same in degrees (the old keyword, kept as an alias).

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
    numbers to rounding on any machine.  Alimukhamedov et al. (2020), Tables I and II, read off
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
    th0 = _lever_angle0(lever_angle0, lever_angle0_deg)
    phi = table.phi
    M = _tables_design(table.contour, phi, th0)
    y = np.concatenate([table.a_x, table.a_y])
    (L, E), _, rank, _ = np.linalg.lstsq(M, y, rcond=None)
    if L < 0:  # the bound l u**2 >= 0 is active: best l e with l u**2 = 0
        L, E = 0.0, float(M[:, 1] @ y / (M[:, 1] @ M[:, 1]))
    k = TablesConstants(table.contour, float(L), float(E), th0)
    ax, ay = tables_point_accelerations(k, phi)
    rx, ry = ax - table.a_x, ay - table.a_y
    rms, mx = _residual_stats(rx, ry)
    return TablesFit(k, rx, ry, rms, mx, bool(rank == 2))


@dataclass(frozen=True)
class SelfConsistentFit(Result):
    """Result of :func:`fit_self_consistent`: the best the section-2 model can do.

    Attributes
    ----------
    params : ZrdpmContour
        With the fitted ``l`` and ``lever_angle0`` (and ``r_a = r_b = l/2``).
    residual_x, residual_y : ndarray
    rms, max_abs : float
        cm.

    Examples
    --------
    >>> fit = fit_self_consistent(published_table("I"))
    >>> round(fit.params.l, 2), round(fit.max_abs, 2)      # cannot match the tables (see the Notes)
    (4.6, 22.16)
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
        return replace(base, l=ell, r_a=ell / 2, r_b=ell / 2, lever_angle0=math.radians(float(x[1])))

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
