"""gearlever against the PMKS+ verification cases: kinematics and, for the six-bars, input torque and pin forces.

Source: PMKS-Web, "PMKS Verification", reference-data v1 (MATLAB R2024a values cross-checked against the PMKS+
solver; the six-bars' forces checked by Newton-Euler balance), https://github.com/PMKS-Web/PMKS_Verification,
cases watt_i, stephenson_iii_example_2, teaching_four_bar, teaching_slider_crank, slider_crank_tracer,
steep_slider_crank.  The values (a subset of rows) are in ``gearlever/data/pmks_verification.csv`` with that source
in its header.  The rocking six-bars are swept as PMKS+ sweeps them: the input in 1-degree steps from the sketch
up to its last step before the upper dead point, down to the last before the lower one, up to the sketch again
(``direction`` +1, -1, +1), at 10 rpm signed by the direction.

Conventions: the reference's link rotation is from the sketch (as gearlever's ``x``); a pin force is the force on
the link that PMKS+ owns it with sign +1 (column ``on``); gearlever's ``reaction[p]`` is the force on the second
link of ``pins[p]`` from the first, so it is compared with a sign.  PMKS+ writes a slider's velocity and
acceleration as minus the derivative of its position (its ``prismatic`` tables); the MATLAB joint values used
here are derivatives, as gearlever's.
"""

from __future__ import annotations

import math
from collections import defaultdict
from pathlib import Path

import numpy as np
import pytest

from gearlever.data import example_path, read_records
from gearlever.mechanism import Mechanism, input_limits, sweep_rows

DATA = Path(__file__).parent / "data"
#: Model of each case: the two rocking six-bars ship as examples, the others are test data.
MODELS = {
    "watt_i": example_path("watt_i.toml"),
    "stephenson_iii_example_2": example_path("stephenson_iii.toml"),
    "teaching_four_bar": DATA / "pmks_teaching_four_bar.toml",
    "teaching_slider_crank": DATA / "pmks_teaching_slider_crank.toml",
    "slider_crank_tracer": DATA / "pmks_slider_crank_tracer.toml",
    "steep_slider_crank": DATA / "pmks_steep_slider_crank.toml",
}
#: Input speed of each case (rev/min), from its definition in the source.
RPM = {"teaching_four_bar": 10.31, "teaching_slider_crank": 15.1}
#: Tolerances, relative to the largest value of each quantity over the rows (positions: to the model's size).
TOL = {"position": 1e-12, "velocity": 1e-12, "acceleration": 1e-11, "force": 1e-11}


def _records():
    out = defaultdict(list)
    for r in read_records("pmks_verification.csv"):
        out[r["case"]].append(r)
    return out


RECORDS = _records()


def _rows(case):
    """Samples of a case in sweep order: ids, input angles (rad) and directions."""
    seen = {}
    for r in RECORDS[case]:
        seen.setdefault(r["sample"], (float(r["input_rad"]), int(r["direction"])))
    ids = sorted(seen)
    return ids, np.array([seen[i][0] for i in ids]), np.array([seen[i][1] for i in ids])


def _values(case, quantity):
    """``name -> (N, k)`` reference values of one quantity, rows in the order of :func:`_rows`."""
    ids = _rows(case)[0]
    got = defaultdict(dict)
    on = {}
    for r in RECORDS[case]:
        if r["quantity"] == quantity:
            got[r["name"]][r["sample"]] = [float(r[f"v{j}"]) for j in range(1, 7) if r[f"v{j}"] != ""]
            on[r["name"]] = r["on"]
    return {k: np.array([v[i] for i in ids]) for k, v in got.items()}, on


def _solve(case):
    m = Mechanism.load(MODELS[case])
    ids, q, d = _rows(case)
    w = RPM.get(case, 10.0) * math.pi / 30.0
    r = m.solve(q[:, None], (w * d)[:, None], np.zeros((q.size, 1)))
    assert r.closed.all() and not r.dead_rows.size
    return m, r, q, d, w


def _close(name, got, ref, scale, tol):
    err = float(np.max(np.abs(got - ref)))
    assert err <= tol * scale, f"{name}: max difference {err:.3g} > {tol:g} x {scale:.3g}"
    return err


def _com(m, r, link, local):
    """Centre of mass of ``link`` at ``local`` in the link's frame (:attr:`pose`): position, velocity, acceleration."""
    i = list(m.model.moving).index(link)
    P, V, A = r.pose[:, i], r.pose_velocity[:, i], r.pose_acceleration[:, i]
    c, s = np.cos(P[:, 2]), np.sin(P[:, 2])
    rx = c * local[0] - s * local[1]
    ry = s * local[0] + c * local[1]
    w, al = V[:, 2], A[:, 2]
    pos = np.stack([P[:, 0] + rx, P[:, 1] + ry], axis=1)
    vel = np.stack([V[:, 0] - w * ry, V[:, 1] + w * rx], axis=1)
    acc = np.stack([A[:, 0] - al * ry - w * w * rx, A[:, 1] + al * rx - w * w * ry], axis=1)
    return np.concatenate([pos, vel, acc], axis=1)


@pytest.mark.parametrize("case", list(MODELS))
def test_joints_points_links_and_centres_of_mass_match_pmks(case):
    m, r, q, d, w = _solve(case)
    L = m.model.length_scale
    worst = {}
    for quantity in ("joint", "point"):
        ref, _ = _values(case, quantity)
        for name, v in ref.items():
            got = np.concatenate([r.point[name], r.velocity[name], r.acceleration[name]], axis=1)
            for k, kind in ((0, "position"), (2, "velocity"), (4, "acceleration")):
                scale = L if kind == "position" else max(np.abs(v[:, k : k + 2]).max(), 1.0)
                e = _close(f"{case} {name} {kind}", got[:, k : k + 2], v[:, k : k + 2], scale, TOL[kind])
                worst[kind] = max(worst.get(kind, 0.0), e)
    ref, _ = _values(case, "link")
    assert ref
    for name, v in ref.items():
        rot = r.x[:, m.system.idx[name]]
        turn = np.arctan2(np.sin(rot - v[:, 0]), np.cos(rot - v[:, 0]))  # rotations compared on the circle
        _close(f"{case} {name} rotation", turn, 0.0 * turn, 1.0, TOL["position"])
        _close(f"{case} {name} omega", r.omega[name], v[:, 1], max(np.abs(v[:, 1]).max(), 1.0), TOL["velocity"])
        _close(f"{case} {name} alpha", r.alpha[name], v[:, 2], max(np.abs(v[:, 2]).max(), 1.0), TOL["acceleration"])
    ref, _ = _values(case, "com")
    if ref:
        from gearlever.mechanism.loads import parse_masses

        masses = parse_masses(m.model, None)
        for name, v in ref.items():
            got = _com(m, r, name, masses[name].centre)  # the centre in the link's frame
            for k, kind in ((0, "position"), (2, "velocity"), (4, "acceleration")):
                scale = L if kind == "position" else max(np.abs(v[:, k : k + 2]).max(), 1.0)
                _close(f"{case} centre of {name} {kind}", got[:, k : k + 2], v[:, k : k + 2], scale, TOL[kind])


@pytest.mark.parametrize("case", ["watt_i", "stephenson_iii_example_2"])
@pytest.mark.parametrize("scenario", ["gravity", "no_gravity"])
def test_input_torque_and_pin_forces_of_the_six_bars_match_pmks(case, scenario):
    m, r, q, d, w = _solve(case)
    g = None if scenario == "gravity" else [0.0, 0.0]
    f = m.inverse_dynamics(q[:, None], (w * d)[:, None], np.zeros((q.size, 1)), gravity=g)
    ref, _ = _values(case, f"torque_{scenario}")
    (tq,) = ref.values()
    scale = max(np.abs(tq).max(), 1.0)
    _close(f"{case} {scenario} input torque", f.input_force[:, 0], tq[:, 0], scale, TOL["force"])
    ref, on = _values(case, f"pin_{scenario}")
    assert set(ref) == set(f.reaction)
    for name, v in ref.items():
        first, second = f.pins[name]
        sign = 1.0 if second == on[name] else -1.0
        assert (first if sign < 0 else second) == on[name]
        scale = max(np.abs(v).max(), 1.0)
        _close(f"{case} {scenario} pin {name}", sign * f.reaction[name], v, scale, TOL["force"])


@pytest.mark.parametrize("case, upper_rows", [("watt_i", 6), ("stephenson_iii_example_2", 42)])
def test_the_rocking_six_bars_sweep_as_pmks_sweeps_them(case, upper_rows):
    """PMKS+ steps 1 degree from the sketch while the next step stays before the dead point, then reverses."""
    m = Mechanism.load(MODELS[case])
    lim = input_limits(m)
    assert lim.rocks
    ids, q, d = _rows(case)
    step = math.radians(1.0)
    # rows up from the sketch: the sketch and every whole degree below the upper limit
    assert upper_rows == 1 + math.floor((lim.upper - lim.start) / step)
    assert q.max() <= lim.upper and q.min() >= lim.lower
    assert lim.upper - q.max() < step and q.min() - lim.lower < step
    assert d[0] == 1 and d[-1] == 1 and -1 in d
    s = sweep_rows(m, 360)
    assert s.oscillates and s.direction[0] == 1
    assert np.all(np.diff(np.flatnonzero(np.diff(s.direction))) > 0)
    assert np.count_nonzero(np.diff(s.direction)) == 2
