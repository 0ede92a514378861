"""ZRDPM tables: Tables I and II published vs computed, identified constants, mobility."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pandas as pd

from gearlever import zrdpm
from gearlever.mechanism.mobility import mobility, published_mobility_cases, redundant_constraints

#: Decimals written, each at the precision its data supports, so that the CSVs
#: are byte-identical on any machine (the published tables carry 2-3 decimals):
#: values computed by closed forms or by the linear fit and their deviations
#: (rounding ~1e-14 cm) with 5; the identified constants and their residuals
#: with 5; the nonlinear self-consistent fit (converged to ~1e-9) with 4 in cm
#: and 3 in degrees.
DECIMALS_CM = 5
DECIMALS_SELF_CONSISTENT_CM = 4
DECIMALS_SELF_CONSISTENT_DEG = 3


def _r(values, decimals):
    """``values`` rounded to ``decimals`` (arrays or floats), with -0.0 written as 0."""
    return np.round(np.asarray(values, dtype=float), decimals) + 0.0


@dataclass(frozen=True)
class Reproduction:
    """Everything the ZRDPM tables and figures are built from (one table).

    Attributes
    ----------
    table : zrdpm.PublishedTable
    fit : zrdpm.TablesFit
        The tables model with its least-squares constants.
    self_consistent : zrdpm.SelfConsistentFit
        The section-2 model with its best-fitting ``l`` and lever phase.
    """

    table: zrdpm.PublishedTable
    fit: zrdpm.TablesFit
    self_consistent: zrdpm.SelfConsistentFit


def reproduce(table: str) -> Reproduction:
    """Read a published table and fit both models to it.

    >>> reproduce("I").fit.max_abs < 0.005
    True
    """
    pub = zrdpm.published_table(table)
    return Reproduction(pub, zrdpm.identify_tables_constants(pub), zrdpm.fit_self_consistent(pub))


def comparison_frame(rep: Reproduction) -> pd.DataFrame:
    """Per angle: printed, published, computed (tables model), deviation, self-consistent model.

    Columns (contour 1 names shown; Table II uses a_D, a_E, u_2, e_2):
    ``phi_deg``; for each of a_B, a_A: ``<c>_printed``, ``<c>_corrected``,
    ``<c>_published_cm``, ``<c>_computed_cm``, ``<c>_deviation_cm``
    (computed - published), ``<c>_selfconsistent_cm``; then the
    self-consistent lever's ``u_1_selfconsistent``, ``e_1_selfconsistent``,
    and ``l_u2_recovered_cm``, ``l_e_recovered_cm``: the lever's ``l u**2``
    and ``l e`` recovered from the two published columns at each angle.
    Numbers are rounded as :data:`DECIMALS_CM` and
    :data:`DECIMALS_SELF_CONSISTENT_CM` say.
    """
    pub, fit, sc = rep.table, rep.fit, rep.self_consistent
    phi = pub.phi
    ax, ay = zrdpm.tables_point_accelerations(fit.constants, phi)
    kin = zrdpm.analogues(sc.params, phi)
    l_u2, l_e = zrdpm.recover_tables_constants(pub.contour, phi, pub.a_x, pub.a_y, fit.constants.lever_angle0)
    cx, cy = pub.columns
    uc, _, ec, _, _, _ = zrdpm.PAPER_NAMES[pub.contour]
    data = {"phi_deg": pub.phi_deg}
    for name, printed, corrected, published, computed, selfc in (
        (cx, pub.printed_x, pub.corrected_x, pub.a_x, ax, kin.a_x),
        (cy, pub.printed_y, pub.corrected_y, pub.a_y, ay, kin.a_y),
    ):
        data[f"{name}_printed"] = list(printed)
        data[f"{name}_corrected"] = corrected.astype(int)
        data[f"{name}_published_cm"] = published
        computed = _r(computed, DECIMALS_CM)
        data[f"{name}_computed_cm"] = computed
        data[f"{name}_deviation_cm"] = _r(computed - published, DECIMALS_CM)  # of the numbers as written
        data[f"{name}_selfconsistent_cm"] = _r(selfc, DECIMALS_SELF_CONSISTENT_CM)
    data[f"{uc}_selfconsistent"] = _r(kin.u_carrier, DECIMALS_CM)
    data[f"{ec}_selfconsistent"] = _r(kin.e_carrier, DECIMALS_CM)
    data["l_u2_recovered_cm"] = _r(l_u2, DECIMALS_CM)
    data["l_e_recovered_cm"] = _r(l_e, DECIMALS_CM)
    return pd.DataFrame(data)


def constants_frame(reps) -> pd.DataFrame:
    """Identified constants of both models for every table, with their residuals.

    One row per (model, table, parameter): ``model`` (``tables`` or
    ``self-consistent``), ``table``, ``contour``, ``parameter``, ``value``,
    ``unit``, ``n_values``, ``rms_residual_cm``, ``max_abs_residual_cm``,
    rounded as the ``DECIMALS_*`` constants of this module say.
    """
    rows = []
    for rep in reps:
        pub, k, sc = rep.table, rep.fit.constants, rep.self_consistent
        common = dict(table=pub.table, contour=pub.contour, n_values=pub.size)
        cm, scm, sdeg = DECIMALS_CM, DECIMALS_SELF_CONSISTENT_CM, DECIMALS_SELF_CONSISTENT_DEG
        tstats = dict(rms_residual_cm=_r(rep.fit.rms, cm), max_abs_residual_cm=_r(rep.fit.max_abs, cm))
        sstats = dict(rms_residual_cm=_r(sc.rms, scm), max_abs_residual_cm=_r(sc.max_abs, scm))
        for par, val, unit, dec in (
            ("l_u2", k.l_u2, "cm", cm),
            ("l_e", k.l_e, "cm", cm),
            ("A", k.A, "cm", cm),
            ("B", k.B, "cm", cm),
            ("lever_angle0_fixed", k.lever_angle0_deg, "deg", sdeg),
        ):
            rows.append(dict(model="tables", **common, parameter=par, value=_r(val, dec), unit=unit, **tstats))
        for par, val, unit, dec in (
            ("l", sc.params.l, "cm", scm),
            ("lever_angle0", sc.params.lever_angle0_deg, "deg", sdeg),
        ):
            rows.append(dict(model="self-consistent", **common, parameter=par, value=_r(val, dec), unit=unit, **sstats))
    return pd.DataFrame(rows)


def mobility_frame() -> pd.DataFrame:
    """The paper's three mobility cases: published W and q beside the computed ones.

    Notes
    -----
    Paper eq. 1 (:func:`gearlever.mechanism.mobility.mobility`) on the cases of the data
    file ``zrdpm_mobility.csv``.

    Examples
    --------
    >>> mobility_frame()[["case", "w_computed", "q_computed"]].to_dict("list")["w_computed"]
    [1, 2, 2]
    """
    rows = []
    for case in published_mobility_cases():
        w = mobility(case["n"], case["p5"], case["p4"], case["q"])
        q = redundant_constraints(case["n"], case["p5"], case["p4"], case["w"])
        rows.append(
            dict(
                case=case["case"],
                n=case["n"],
                p5=case["p5"],
                p4=case["p4"],
                q_published=case["q"],
                w_published=case["w"],
                w_computed=w,
                q_computed=q,
                agrees=bool(w == case["w"] and q == case["q"]),
            )
        )
    return pd.DataFrame(rows)


def analogue_frame(params: zrdpm.ZrdpmContour, phi_deg) -> pd.DataFrame:
    """Self-consistent analogues of one contour over the given angles (degrees).

    Notes
    -----
    :func:`gearlever.zrdpm.analogues` (paper eqs. 9-16 / 28-35).

    Examples
    --------
    >>> analogue_frame(zrdpm.ZrdpmContour(contour=1), [45.0])["u_1"].round(4).tolist()
    [1.4142]
    """
    phi_deg = np.asarray(phi_deg, dtype=float)
    kin = zrdpm.analogues(params, np.deg2rad(phi_deg))
    names = zrdpm.PAPER_NAMES[params.contour]
    data = {"phi_deg": phi_deg}
    for name, arr in zip(names, kin):
        data[f"{name}_cm" if name.startswith("a_") else name] = arr
    return pd.DataFrame(data)
