"""ZRDPM figures: the paper's Fig. 3, analogue curves of both contours, table comparison."""

from __future__ import annotations

import numpy as np

from gearlever import zrdpm
from gearlever.plotting._common import axes, plt

#: Angles (degrees) at which curves are drawn: one point per degree.
_PHI_DEG = np.linspace(0.0, 360.0, 361)


def _degree_axis(ax):
    ax.set_xlim(0, 360)
    ax.set_xticks(np.arange(0, 361, 60))
    ax.grid(True, alpha=0.3)


def plot_u1_turn(params: zrdpm.ZrdpmContour | None = None, ax=None):
    """The paper's Fig. 3: velocity analogue ``u_1`` of lever 1 over a full turn.

    Parameters
    ----------
    params : ZrdpmContour, optional
        Contour 1 parameters (default: ``l = rA + rB``, so ``u_1 = sin + cos``).
    ax : matplotlib Axes, optional

    Returns
    -------
    Axes
    """
    params = zrdpm.ZrdpmContour(contour=1) if params is None else params
    ax = axes(ax)
    kin = zrdpm.analogues(params, np.deg2rad(_PHI_DEG))
    c = params.lever_gain
    ax.plot(_PHI_DEG, kin.u_carrier, color="C0", label=rf"$u_1 = {c:g}\,(\sin\varphi + \cos\varphi)$ (eq. 9)")
    ax.axhline(c * np.sqrt(2), color="0.5", ls=":", lw=1, label=rf"$\pm{c:g}\sqrt{{2}}$ (amplitude)")
    ax.axhline(-c * np.sqrt(2), color="0.5", ls=":", lw=1)
    _degree_axis(ax)
    ax.set_xlabel(r"angle of leading link 9, $\varphi$ (deg)")
    ax.set_ylabel(r"$u_1 = \omega_1/\omega_9$ (-)")
    ax.set_title("Fig. 3: velocity analogue of lever 1 over one turn")
    ax.legend(loc="lower left", fontsize=8)
    return ax


def plot_analogues(params1: zrdpm.ZrdpmContour | None = None, params2: zrdpm.ZrdpmContour | None = None):
    """Velocity and acceleration analogues of carriers and driven gears, both contours.

    Parameters
    ----------
    params1, params2 : ZrdpmContour, optional
        Contour 1 and 2 parameters.  Defaults (ours; the paper states no
        dimensions): ``l = rA + rB``, ``r9/r8 = 0.5`` and ``r6/r7 = 2``, two
        different ratios so that the panels show the ratio's effect.

    Returns
    -------
    Figure
        Two panels, one per contour.
    """
    params1 = zrdpm.ZrdpmContour(contour=1) if params1 is None else params1
    params2 = zrdpm.ZrdpmContour(contour=2).with_ratio(2.0) if params2 is None else params2
    fig, axs = plt.subplots(1, 2, figsize=(11.0, 4.2), layout="constrained", sharey=True)
    phi = np.deg2rad(_PHI_DEG)
    for ax, p, lead, ratio_name in ((axs[0], params1, "9", "r_9/r_8"), (axs[1], params2, "6", "r_6/r_7")):
        kin = zrdpm.analogues(p, phi)
        uc, ug, ec, eg = (n.replace("_", "_{") + "}" for n in p.names[:4])
        for arr, name, style in (
            (kin.u_carrier, uc, "-"),
            (kin.u_gear, ug, "-"),
            (kin.e_carrier, ec, "--"),
            (kin.e_gear, eg, "--"),
        ):
            ax.plot(_PHI_DEG, arr, ls=style, label=f"${name}$")
        _degree_axis(ax)
        ax.set_xlabel(rf"angle of leading link {lead}, $\varphi$ (deg)")
        ax.set_title(
            f"contour {p.contour}: ${ratio_name} = {p.ratio:g}$, $l/(r_A+r_B) = {p.lever_gain:g}$",
            fontsize=10,
        )
        ax.set_ylabel("analogue u, e (-)")
        ax.legend(fontsize=8, loc="lower center", ncol=4)
    lo, hi = axs[0].get_ylim()
    axs[0].set_ylim(lo - 0.25 * (hi - lo), hi)
    axs[0].set_ylabel("velocity analogue u (-), acceleration analogue e (-)")
    fig.suptitle("ZRDPM analogues of carriers and driven gears (self-consistent model, eqs. 9-14, 28-33)")
    return fig


def plot_table_comparison(reps):
    """Published points, the reproduction and the self-consistent model, all four columns.

    Parameters
    ----------
    reps : sequence of gearlever.tables.zrdpm.Reproduction
        One per table (I and II).

    Returns
    -------
    Figure
        One panel per published column.
    """
    reps = list(reps)
    fig, axs = plt.subplots(len(reps), 2, figsize=(11.0, 3.6 * len(reps)), layout="constrained", squeeze=False)
    phi = np.deg2rad(_PHI_DEG)
    for row, rep in zip(axs, reps):
        pub, fit, sc = rep.table, rep.fit, rep.self_consistent
        ax_t, ay_t = zrdpm.tables_point_accelerations(fit.constants, phi)
        kin = zrdpm.analogues(sc.params, phi)
        k = fit.constants
        for ax, name, published, model, selfc in (
            (row[0], pub.columns[0], pub.a_x, ax_t, kin.a_x),
            (row[1], pub.columns[1], pub.a_y, ay_t, kin.a_y),
        ):
            ax.plot(
                _PHI_DEG,
                model,
                color="C0",
                label=f"reproduction: eq. {16 if pub.contour == 1 else 35}, l u² = {k.l_u2:.3f}, l e = {k.l_e:.3f} cm",
            )
            ax.plot(
                _PHI_DEG,
                selfc,
                color="C3",
                ls="--",
                label=f"self-consistent model, best fit l = {sc.params.l:.2f} cm",
            )
            ax.plot(pub.phi_deg, published, "ko", ms=4, label=f"published, Table {pub.table}")
            corr = pub.corrected_x if name == pub.columns[0] else pub.corrected_y
            if corr.any():
                ax.plot(pub.phi_deg[corr], published[corr], "o", mfc="none", mec="C1", ms=9, label="OCR corrected")
            _degree_axis(ax)
            sub = name.split("_")[1]
            ax.set_xlabel(r"angle of leading link, $\varphi$ (deg)")
            ax.set_ylabel(rf"$a_{sub}/\omega^2$ (cm)")
            ax.set_title(f"Table {pub.table}: $a_{sub}$ (max |dev| {fit.max_abs:.4f} cm)", fontsize=10)
            lo, hi = ax.get_ylim()
            ax.set_ylim(lo - 0.45 * (hi - lo), hi)  # room for the legend under the curves
            ax.legend(fontsize=7, loc="lower center", ncol=2)
    fig.suptitle("ZRDPM Tables I and II: published, reproduced, and the self-consistent model")
    return fig
