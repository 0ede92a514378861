"""
Tooth outlines and tooth stresses over a cycle
==============================================

Two 12-tooth pinions cut by the ISO 53 rack: unshifted (undercut: the root
fillet cuts into the involute) and shifted by x = 0.4 (no undercut, a thicker
root, a pointier tip).  Then the geared five-bar driven at constant speed with
a 100 N load at its coupler point: the tooth force that ``mechanism forces``
computes at its mesh becomes a Lewis root stress per gear and a Hertz contact
stress over the crank's turn, with the worst angle marked.
"""

import matplotlib.pyplot as plt
import numpy as np

import gearlever
from gearlever.data import example_path
from gearlever.gears.geometry import tooth_outline, tooth_profile
from gearlever.gears.strength import mesh_stresses

fig, axes = plt.subplots(1, 2, figsize=(9, 4.5))
for ax, x in zip(axes, (0.0, 0.4)):
    xy = tooth_outline(2.0, 12, x, points=60)
    p = tooth_profile(2.0, 12, x)
    ax.plot(*np.vstack([xy, xy[:1]]).T, lw=1.0)
    t = np.linspace(0, 2 * np.pi, 400)
    for r, style, label in ((p.base_radius, ":", "base circle"), (p.reference_radius, "--", "reference circle")):
        ax.plot(r * np.cos(t), r * np.sin(t), style, lw=0.7, label=label)
    ax.set_aspect("equal")
    ax.set_xlim(0.55 * p.tip_radius, 1.08 * p.tip_radius)
    ax.set_ylim(-0.3 * p.tip_radius, 0.3 * p.tip_radius)
    ax.set_title(f"z = 12, x = {x}: form circle {p.form_radius:.3f} mm")
    ax.legend(loc="lower left", fontsize=8)
fig.tight_layout()

# %%
# Stresses over the cycle of the geared five-bar (module 2, z = 20/30, face
# width 8 mm; allowables 200 MPa in bending and 900 MPa in contact).
mech = gearlever.Mechanism.load(example_path("geared_fivebar.toml"))
q = np.linspace(0, 2 * np.pi, 181)
res = mech.inverse_dynamics(q, 1.0, 0.0, loads=[{"link": "link4", "point": "C", "force": [0, -100.0]}])
(ms,) = mesh_stresses(mech, res, face_width=8.0, allowables={"bending": 200.0, "contact": 900.0}).values()
deg = np.degrees(ms.angle)
fig, ax = plt.subplots(figsize=(8, 4))
ax.plot(deg, ms.bending_stress[:, 0], label="root bending, g1 (Lewis)")
ax.plot(deg, ms.bending_stress[:, 1], label="root bending, g2 (Lewis)")
ax.plot(deg, ms.contact_stress, label="contact (Hertz)")
w = ms.worst_row
ax.axvline(deg[w], color="k", lw=0.6, ls="--")
ax.annotate(f"worst {deg[w]:.0f} deg", (deg[w], ms.contact_stress[w]), textcoords="offset points", xytext=(5, -12))
ax.set_xlabel("crank angle (deg)")
ax.set_ylabel("stress (MPa)")
ax.set_title(
    f"mesh {ms.mesh}: least safety {np.min(ms.bending_safety):.1f} (bending), {np.min(ms.contact_safety):.2f} (contact)"
)
ax.legend(loc="lower right", bbox_to_anchor=(1.0, 0.12), fontsize=8)  # clear of the curves
fig.tight_layout()
print(f"worst angle {deg[w]:.1f} deg, tooth force {ms.tangential_force[w]:.2f} N")
print(
    f"bending {ms.bending_stress[w, 0]:.3f} / {ms.bending_stress[w, 1]:.3f} MPa, contact {ms.contact_stress[w]:.2f} MPa"
)
