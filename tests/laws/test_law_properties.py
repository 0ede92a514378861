"""Property tests of segment laws: for random valid segment lists, the values at the boundaries
are the cumulative rises, v is the derivative of s (central differences), and the continuity report
flags exactly the boundaries where the motions' end velocities disagree."""

import math

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from gearlever.laws import law_from_segments
from gearlever.laws.motions import MOTIONS

RISING = [n for n, m in MOTIONS.items() if m.rises]


@st.composite
def segment_lists(draw):
    n = draw(st.integers(1, 6))
    cuts = sorted(draw(st.lists(st.integers(5, 355), min_size=n - 1, max_size=n - 1, unique=True)))
    ends = [*cuts, 360]
    segs = []
    for to in ends:
        name = draw(st.sampled_from(list(MOTIONS)))
        seg = {"to": to, "motion": name}
        if MOTIONS[name].rises:
            seg["rise"] = draw(st.floats(-50, 50, allow_nan=False).map(lambda x: round(x, 3)))
        segs.append(seg)
    return segs


@settings(max_examples=60, deadline=None)
@given(segment_lists())
def test_boundary_values_are_cumulative_rises_and_v_is_ds(segs):
    law = law_from_segments("displacement", "mm", segs)
    cum = np.concatenate([[0.0], np.cumsum(law.rises)])
    at = law.evaluate(law.breaks[:-1]).s
    np.testing.assert_allclose(at, cum[:-1], atol=1e-9)
    # v against central differences inside each segment
    for k in range(len(segs)):
        lo, hi = law.breaks[k], law.breaks[k + 1]
        th = np.linspace(lo, hi, 9)[1:-1]
        th = th[np.min(np.abs((th[:, None] - lo) / (hi - lo) - np.arange(1, 8)[None, :] / 8), axis=1) > 1e-3]
        h = 1e-6
        fd = (law.evaluate(th + h).s - law.evaluate(th - h).s) / (2 * h)
        np.testing.assert_allclose(fd, law.evaluate(th).v, atol=1e-5 * max(1.0, np.abs(law.rises).max() * 50))


@settings(max_examples=60, deadline=None)
@given(segment_lists())
def test_continuity_flags_exactly_the_velocity_jumps(segs):
    law = law_from_segments("displacement", "mm", segs)
    rep = law.continuity()
    n = len(segs)
    for k in range(n):
        prev = (k - 1) % n
        beta_p = law.breaks[prev + 1] - law.breaks[prev]
        beta_k = law.breaks[k + 1] - law.breaks[k]
        v_left = law.rises[prev] * float(MOTIONS[law.motions[prev]].derivs(1.0)[1]) / beta_p
        v_right = law.rises[k] * float(MOTIONS[law.motions[k]].derivs(0.0)[1]) / beta_k
        jumps = abs(v_right - v_left) > rep.tolerance
        assert jumps == (law.breaks[k] in rep.infinite_acceleration), (k, v_left, v_right)
    assert math.isfinite(rep.tolerance)
