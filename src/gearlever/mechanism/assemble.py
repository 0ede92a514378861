"""Assembly from lengths: a rough sketch closed to exact link lengths.

A model may give, besides its sketch, the exact lengths of its links in a
``[lengths]`` table (schema in :mod:`gearlever.mechanism.schema`).
:func:`assemble` moves the sketch points the least needed to make every
length exact, on the assembly branch of the sketch, and returns the model as
a dict whose sketch is exact (write it with
:func:`gearlever.mechanism.modelfile.model_toml`).

The equations, in the coordinates of every point not on ground (ground
points stay where sketched):

- every moving link is rigid: the distance between its first two points is
  the one of ``[lengths]`` or, when not given, the sketch's; a further point
  with two lengths given is placed by them, with one by it and its sketch
  distance to the first (or second) point, with none at its sketch
  body-fixed coordinates (along and across the line from the first point to
  the second, as in :class:`~gearlever.mechanism.model.Link`);
- a gear mesh keeps its centre distance (``m (z1 +- z2) / 2`` when the module
  is given);
- a slider's point stays on its guide (through its sketch position, along
  its direction, turning with the guide's link); a sliding link with two or
  more points keeps its angle to the guide;
- with ``hold_inputs`` (the default) every link input keeps its sketch angle
  (the direction of its first two points, relative to ground or to
  ``relative_to``), so the assembled model starts where the sketch does.

Pure numpy.
"""

from __future__ import annotations

import math
from collections import deque
from dataclasses import dataclass

import numpy as np

from gearlever.errors import GearleverError
from gearlever.mechanism.model import GROUND, MechanismModel, model_from_dict, parse_lengths

__all__ = ["assemble", "model_dict"]

#: Largest residual accepted as closed, times the model's length scale.
CLOSE_TOL = 1e-13
#: Iterations of the nearest-point Newton method before giving up.
MAX_ITER = 100


@dataclass(frozen=True)
class _Row:
    kind: str  # "dist" | "local" | "line" | "guide" | "angle"
    pts: tuple  # point names used
    value: float  # target length (dist), guide offset (guide, line), angle (angle)
    label: str  # what the user sees: 'crank = 10', 'links.coupler A-P (sketch) = 30.41'
    data: tuple = ()  # kind-specific constants


def model_dict(model: MechanismModel) -> dict:
    """The model-file dict of a parsed model (the inverse of :func:`~gearlever.mechanism.model.model_from_dict`).

    Examples
    --------
    >>> d = {"points": {"O": [0.0, 0.0], "A": [1.0, 0.0]}, "links": {"ground": ["O"], "crank": ["O", "A"]},
    ...      "inputs": [{"link": "crank"}]}
    >>> model_dict(model_from_dict(d))["links"]
    {'ground': ['O'], 'crank': ['O', 'A']}
    """
    mech: dict = {"name": model.name}
    if model.units:
        mech["units"] = model.units
    if model.module is not None:
        mech["module"] = model.module
    for k in ("gravity", "pressure_angle"):
        if k in model.extra:
            mech[k] = model.extra[k]
    d: dict = {
        "mechanism": mech,
        "points": {p: [float(x), float(y)] for p, (x, y) in model.points.items()},
        "links": {k: list(link.points) for k, link in model.links.items()},
    }
    if model.sliders:
        d["sliders"] = [
            {"name": s.name, "link": s.link, "on": s.on, "point": s.point, "direction": list(s.direction)}
            for s in model.sliders
        ]
    if model.gears:
        d["gears"] = {}
        for g in model.gears.values():
            d["gears"][g.name] = {"link": g.link, "centre": g.centre, "teeth": g.teeth}
            if g.internal:
                d["gears"][g.name]["internal"] = True
    if model.meshes:
        d["meshes"] = [{"gears": [m.a, m.b], "carrier": m.carrier} for m in model.meshes]
    inputs = []
    for spec in model.inputs:
        if spec.kind == "slider":
            inputs.append({"slider": spec.name})
        else:
            inputs.append({"link": spec.name} | ({"relative_to": spec.relative_to} if spec.relative_to else {}))
    d["inputs"] = inputs
    for k in ("masses", "loads", "lengths"):
        if k in model.extra:
            d[k] = model.extra[k]
    return d


def _rows(model: MechanismModel, lengths: dict, hold_inputs: bool) -> list:
    """The equations of the module docstring, given lengths first."""
    P = {k: np.array(v, dtype=float) for k, v in model.points.items()}
    L = model.length_scale
    rows: list = []
    given = {}
    for key, (lname, p, q, value) in lengths.items():
        label = f'"{key}" = {value:g}' if "." in key else f"{key} = {value:g}"
        given.setdefault(lname, []).append((p, q, value, label))
    # ground: fixed points; a given ground length must be the sketch's
    for p, q, value, label in given.get(GROUND, []):
        d = float(np.linalg.norm(P[p] - P[q]))
        if abs(d - value) > 1e-9 * L:
            raise GearleverError(
                f"lengths: {label}: ground points stay where sketched ({p}-{q} = {d:.12g}); "
                "give their exact positions in [points] instead"
            )
    for lname, link in model.links.items():
        if lname == GROUND or len(link.points) < 2:
            continue
        rows += _link_rows(P, lname, link.points, given.get(lname, []))
    for m in model.meshes:
        ga, gb = model.gears[m.a], model.gears[m.b]
        if model.module is not None:
            zsum = abs(ga.teeth - gb.teeth) if model.mesh_internal(m) else ga.teeth + gb.teeth
            d = model.module * zsum / 2.0
            lab = f"meshes ({m.name}) centre distance m (z1 {'-' if model.mesh_internal(m) else '+'} z2) / 2 = {d:g}"
        else:
            d = float(np.linalg.norm(P[ga.centre] - P[gb.centre]))
            lab = f"meshes ({m.name}) centre distance (sketch) = {d:.10g}"
        rows.append(_Row("dist", (ga.centre, gb.centre), d, lab))
    for s in model.sliders:
        n = np.array([-s.direction[1], s.direction[0]])
        if s.on == GROUND:
            rows.append(_Row("line", (s.point,), float(n @ P[s.point]), f"sliders ({s.name}) guide line", (n,)))
        else:
            on = model.links[s.on].points
            if len(on) < 2:
                raise GearleverError(
                    f"sliders ({s.name}): assembly needs the guide's link {s.on!r} to carry two points"
                )
            a_loc, n_loc = _local(P[on[0]], P[on[1]], P[s.point]), _local_dir(P[on[0]], P[on[1]], n)
            rows.append(
                _Row(
                    "guide",
                    (s.point, on[0], on[1]),
                    float(n_loc @ a_loc),
                    f"sliders ({s.name}) guide on {s.on}",
                    (n_loc,),
                )
            )
        link = model.links[s.link].points
        if len(link) >= 2:
            ref = model.links[s.on].points if s.on != GROUND else ()
            rows.append(_angle_row(P, link, ref, f"sliders ({s.name}) angle of {s.link} to {s.on}"))
    if hold_inputs:
        for spec in model.inputs:
            if spec.kind != "link" or len(model.links[spec.name].points) < 2:
                continue
            ref = ()
            if spec.relative_to not in (None, GROUND):
                ref = model.links[spec.relative_to].points
                if len(ref) < 2:
                    continue
            rows.append(_angle_row(P, model.links[spec.name].points, ref, f"inputs ({spec.label}) sketch angle"))
    return rows


def _link_rows(P, lname, pts, given) -> list:
    """Rows making link ``lname`` rigid: its given lengths, then the sketch for what they leave free."""
    rows = [_Row("dist", (p, q), v, lab) for p, q, v, lab in given]
    have = {frozenset((p, q)) for p, q, _, _ in given}
    base = (pts[0], pts[1])
    if frozenset(base) not in have:
        d = float(np.linalg.norm(P[base[0]] - P[base[1]]))
        rows.append(_Row("dist", base, d, f"links.{lname} {base[0]}-{base[1]} (sketch) = {d:.10g}"))
    for j in range(2, len(pts)):
        pj = pts[j]
        used = [q for pair in have if pj in pair for q in pair if q != pj]
        if not used:  # body-fixed coordinates of the sketch (Link.local), from the first point
            loc = _local(P[base[0]], P[base[1]], P[pj])
            for c in (0, 1):
                rows.append(
                    _Row("local", (pj,) + base, float(loc[c]), f"links.{lname} {pj} (sketch, body-fixed)", (c,))
                )
        elif len(used) == 1:
            q = base[0] if base[0] != used[0] else base[1]
            d = float(np.linalg.norm(P[pj] - P[q]))
            rows.append(_Row("dist", (pj, q), d, f"links.{lname} {pj}-{q} (sketch) = {d:.10g}"))
    # the distance rows of a rigid link are independent (rigidity matrix at the sketch), at most 2k - 3
    col = {p: i for i, p in enumerate(pts)}
    dist = [r for r in rows if r.kind == "dist"]
    R = np.zeros((len(dist), 2 * len(pts)))
    for i, r in enumerate(dist):
        p, q = r.pts
        u = P[p] - P[q]
        nu = float(np.linalg.norm(u))
        if nu == 0.0:
            raise GearleverError(f"links.{lname}: points {p} and {q} coincide in the sketch")
        R[i, 2 * col[p] : 2 * col[p] + 2] = u / nu
        R[i, 2 * col[q] : 2 * col[q] + 2] = -u / nu
    if len(dist) > 2 * len(pts) - 3 or np.linalg.matrix_rank(R, tol=1e-9) < len(dist):
        labels = ", ".join(lab for _, _, _, lab in given)
        raise GearleverError(
            f"lengths: link {lname!r} is over-determined by {labels} "
            f"(a rigid link of {len(pts)} points takes {2 * len(pts) - 3} independent lengths)"
        )
    return rows


def _local(o, e, x):
    u = (e - o) / np.linalg.norm(e - o)
    d = x - o
    return np.array([u @ d, u[0] * d[1] - u[1] * d[0]])


def _local_dir(o, e, n):
    u = (e - o) / np.linalg.norm(e - o)
    return np.array([u @ n, u[0] * n[1] - u[1] * n[0]])


def _angle_row(P, link, ref, label):
    u = P[link[1]] - P[link[0]]
    v = P[ref[1]] - P[ref[0]] if ref else np.array([1.0, 0.0])
    ang = math.atan2(v[0] * u[1] - v[1] * u[0], v @ u)
    return _Row("angle", (link[0], link[1]) + tuple(ref[:2]), ang, label)


class _Equations:
    """Residuals of the rows, batched over columns of complex coordinates (for the complex-step Jacobian)."""

    def __init__(self, model: MechanismModel, rows: list):
        self.rows = rows
        self.L = model.length_scale
        moving_pts = {p for k, link in model.links.items() if k != GROUND for p in link.points}
        fixed = set(model.links[GROUND].points) | (set(model.points) - moving_pts)
        self.free = [p for p in model.points if p not in fixed]
        self.col = {p: i for i, p in enumerate(self.free)}
        self.fixed = {p: np.array(model.points[p], dtype=float) for p in fixed}
        self.x0 = np.array([c for p in self.free for c in model.points[p]], dtype=float)
        self.shift = np.zeros(len(rows))
        self.shift = self.residual(self.x0[:, None])[:, 0]  # model value minus sketch value, per row
        self.shift[[r.kind == "angle" for r in rows]] = 0.0

    def _pt(self, X, p):
        if p in self.col:
            i = self.col[p]
            return X[2 * i], X[2 * i + 1]
        x, y = self.fixed[p]
        return np.full(X.shape[1], x, dtype=X.dtype), np.full(X.shape[1], y, dtype=X.dtype)

    def residual(self, X, t: float = 1.0):
        """``(m, B)`` residuals at ``X`` ``(n, B)``; lengths in length units, angles times the length scale.

        ``t`` moves the values from the sketch's (0) to the model's (1): the homotopy of :func:`_close`.
        """
        out = np.zeros((len(self.rows), X.shape[1]), dtype=X.dtype)
        if t != 1.0:
            out += self.shift[:, None] * (t - 1.0)  # zero at the sketch when t = 0
        for r, row in enumerate(self.rows):
            if row.kind == "dist":
                (ax, ay), (bx, by) = self._pt(X, row.pts[0]), self._pt(X, row.pts[1])
                out[r] = np.sqrt((ax - bx) ** 2 + (ay - by) ** 2) - row.value + out[r]
            elif row.kind == "line":
                x, y = self._pt(X, row.pts[0])
                n = row.data[0]
                out[r] = n[0] * x + n[1] * y - row.value + out[r]
            elif row.kind == "local":
                (px, py), (ox, oy), (ex, ey) = (self._pt(X, p) for p in row.pts)
                ux, uy = ex - ox, ey - oy
                nu = np.sqrt(ux * ux + uy * uy)
                dx, dy = px - ox, py - oy
                v = (ux * dx + uy * dy) if row.data[0] == 0 else (ux * dy - uy * dx)
                out[r] = v / nu - row.value + out[r]
            elif row.kind == "guide":
                (ax, ay), (ox, oy), (ex, ey) = (self._pt(X, p) for p in row.pts)
                ux, uy = ex - ox, ey - oy
                nu = np.sqrt(ux * ux + uy * uy)
                ux, uy = ux / nu, uy / nu
                dx, dy = ax - ox, ay - oy
                nl = row.data[0]
                out[r] = nl[0] * (ux * dx + uy * dy) + nl[1] * (ux * dy - uy * dx) - row.value + out[r]
            else:  # angle: sin(theta_link - theta_ref - value), times L
                (px, py), (qx, qy) = self._pt(X, row.pts[0]), self._pt(X, row.pts[1])
                ux, uy = qx - px, qy - py
                if len(row.pts) == 4:
                    (rx, ry), (sx, sy) = self._pt(X, row.pts[2]), self._pt(X, row.pts[3])
                    vx, vy = sx - rx, sy - ry
                else:
                    vx, vy = np.ones_like(ux), np.zeros_like(ux)
                nn = np.sqrt((ux * ux + uy * uy) * (vx * vx + vy * vy))
                s, c = (vx * uy - vy * ux) / nn, (vx * ux + vy * uy) / nn
                out[r] = self.L * (s * math.cos(row.value) - c * math.sin(row.value))
        return out

    def jacobian(self, x):
        """``(m, n)`` Jacobian at ``x`` by the complex step (exact to rounding), all columns in one batch.

        Notes
        -----
        J. N. Lyness and C. B. Moler, "Numerical differentiation of analytic
        functions", SIAM J. Numer. Anal. 4 (1967) 202-210;
        ``f'(x) = Im f(x + i h) / h`` with no subtraction error.
        """
        h = 1e-30 * self.L
        n = x.size
        X = x[:, None] + 1j * h * np.eye(n)
        return self.residual(X).imag / h


def _close(eq: _Equations):
    """Follow the sketch from its own lengths (``t = 0``) to the model's (``t = 1``); ``(x, t reached, ok)``.

    Notes
    -----
    Natural-parameter continuation (E. L. Allgower and K. Georg, *Numerical
    Continuation Methods*, Springer, 1990, ch. 2): the values of the rows
    move linearly from the sketch's to the model's; each step is predicted
    by the secant of the last two solutions and corrected by minimum-norm
    Newton steps (least-squares, ``x -= J^+ F``), accepted when it converges
    with a correction below a tenth of the length scale, otherwise halved.
    The points so move continuously from the sketch and stay on its branch.
    """
    L = eq.L
    x, xprev, t, tprev = eq.x0.copy(), None, 0.0, 0.0
    dt = 0.125
    while t < 1.0:
        tn = min(1.0, t + dt)
        pred = x if xprev is None or t == tprev else x + (x - xprev) * (tn - t) / (t - tprev)
        y = pred.copy()
        ok = False
        for _ in range(8):
            F = eq.residual(y[:, None], tn)[:, 0]
            if float(np.max(np.abs(F), initial=0.0)) <= 1e-11 * L:
                ok = True
                break
            step = _newton_step(eq.jacobian(y), F)
            if step is None:
                break
            y = y - step
        if ok and float(np.max(np.abs(y - pred), initial=0.0)) <= 0.1 * L:
            xprev, tprev, x, t = x, t, y, tn
            dt = min(2 * dt, 0.25)
        else:
            dt /= 2
            if dt < 1e-6:
                return x, t, False
    for _ in range(4):  # to rounding
        F = eq.residual(x[:, None])[:, 0]
        if float(np.max(np.abs(F), initial=0.0)) <= 0.1 * CLOSE_TOL * L:
            break
        step = _newton_step(eq.jacobian(x), F)
        if step is None:
            break
        x = x - step
    F = eq.residual(x[:, None])[:, 0]
    return x, 1.0, float(np.max(np.abs(F), initial=0.0)) <= CLOSE_TOL * L


def _newton_step(J: np.ndarray, F: np.ndarray):
    """The minimum-norm Newton step ``J^+ F``, or None when ``J`` or ``F`` is not finite.

    LAPACK is never handed an infinity or NaN (lengths near 1e308 overflow
    when squared): its ``DLASCL`` refuses them by printing a line on the C
    stdout, which would corrupt the output of the command line.
    """
    if not (np.isfinite(J).all() and np.isfinite(F).all()):
        return None
    return np.linalg.lstsq(J, F, rcond=None)[0]


def _why_not(model: MechanismModel, eq: _Equations, x: np.ndarray, t: float) -> str:
    """Which lengths cannot close: a loop breaking the polygon inequality, or the rows a best fit misses."""
    edges = []  # (p, q, length, label)
    for row in eq.rows:
        if row.kind == "dist":
            edges.append((row.pts[0], row.pts[1], row.value, row.label))
    g = list(model.links[GROUND].points)
    for i in range(1, len(g)):
        for j in range(i):
            d = math.dist(model.points[g[i]], model.points[g[j]])
            edges.append((g[j], g[i], d, f"ground {g[j]}-{g[i]} = {d:.10g}"))
    adj: dict = {}
    for e, (p, q, _, _) in enumerate(edges):
        adj.setdefault(p, []).append((q, e))
        adj.setdefault(q, []).append((p, e))
    worst = None
    for e, (p, q, _, _) in enumerate(edges):
        # shortest loop through edge e: a path from q back to p avoiding e
        prev = {q: None}
        queue = deque([q])
        while queue and p not in prev:
            u = queue.popleft()
            for v, f in adj[u]:
                if f != e and v not in prev:
                    prev[v] = (u, f)
                    queue.append(v)
        if p not in prev:
            continue
        loop, u = [e], p
        while prev[u] is not None:
            u, f = prev[u]
            loop.append(f)
        lens = [edges[f][2] for f in loop]
        k = int(np.argmax(lens))
        excess = lens[k] - (sum(lens) - lens[k])
        if excess > 1e-9 * eq.L and (worst is None or excess > worst[0]):
            worst = (excess, [loop[k]] + [f for i, f in enumerate(loop) if i != k])
    if worst is not None:
        longest, *others = worst[1]
        total = sum(edges[f][2] for f in others)
        return (
            f"the loop {' -> '.join(_loop_points(edges, worst[1]))} cannot close: {edges[longest][3]} is longer "
            f"than the others together ({' + '.join(edges[f][3] for f in others)} = {total:.10g}; "
            "polygon inequality)"
        )
    moving = [eq.rows[i].label for i in np.flatnonzero(eq.shift) if eq.rows[i].kind == "dist"]
    return (
        f"the sketch cannot be deformed to {', '.join(moving) or 'these lengths'}: it reaches {100 * t:.3g}% of "
        "the way from its own lengths and then a link would have to break (a dead point of the assembly)"
    )


def _loop_points(edges, loop):
    """The points of a loop of edges, in order around it."""
    chain = [edges[loop[0]][0], edges[loop[0]][1]]
    rest = list(loop[1:])
    while rest:
        for f in rest:
            p, q = edges[f][0], edges[f][1]
            if chain[-1] in (p, q):
                chain.append(q if chain[-1] == p else p)
                rest.remove(f)
                break
        else:
            break
    return chain


def assemble(model, *, hold_inputs: bool = True) -> dict:
    """Close a rough sketch to the exact lengths of its ``[lengths]`` table.

    Parameters
    ----------
    model : MechanismModel or dict
        Parsed model, or a dict with the model file's structure.
    hold_inputs : bool
        Keep the sketch angle of every link input (default).  When the
        lengths cannot close at that angle (a link that cannot reach it), the
        input is freed and the nearest assembly taken.

    Returns
    -------
    dict
        The model with exact point coordinates, in the model file's
        structure (accepted by :func:`~gearlever.mechanism.model.model_from_dict`;
        :func:`gearlever.mechanism.modelfile.model_toml` writes it).

    Raises
    ------
    GearleverError
        When no assembly has these lengths, naming the loop and the lengths
        that cannot close (e.g. one longer than the others together), or
        the lengths a best fit misses.

    Notes
    -----
    The equations are listed in the module docstring.  Their values are
    moved continuously from the sketch's own to the model's and the points
    follow by continuation with minimum-norm Newton corrections (Allgower and
    Georg, *Numerical Continuation Methods*, 1990, ch. 2), so the assembly is
    the sketch deformed the least at every step, on its branch (open or
    crossed four-bar, the side of each dyad).  Jacobians by the complex
    step (Lyness and Moler, SIAM J. Numer. Anal. 4, 1967).  Before giving
    up, every short loop of lengths is checked against the polygon
    inequality (no side longer than the others together), naming the loop.

    Examples
    --------
    >>> d = {"points": {"O2": [0, 0], "O4": [40, 0], "A": [11, 1], "B": [44, 31]},
    ...      "links": {"ground": ["O2", "O4"], "crank": ["O2", "A"], "coupler": ["A", "B"], "rocker": ["O4", "B"]},
    ...      "inputs": [{"link": "crank"}], "lengths": {"crank": 10, "coupler": 45, "rocker": 30}}
    >>> exact = assemble(d)
    >>> import math
    >>> p = exact["points"]
    >>> [round(math.dist(p[a], p[b]), 12) for a, b in (("O2", "A"), ("A", "B"), ("O4", "B"))]
    [10.0, 45.0, 30.0]
    """
    if isinstance(model, dict):
        model = model_from_dict(model)
    if not isinstance(model, MechanismModel):
        raise GearleverError(f"model must be a MechanismModel or a model dict, got {type(model).__name__}")
    if "lengths" not in model.extra:
        raise GearleverError("[lengths]: the model gives no lengths to assemble to")
    lengths = parse_lengths(model.extra["lengths"], model.links)
    tries = (True, False) if hold_inputs else (False,)
    for hold in tries:
        eq = _Equations(model, _rows(model, lengths, hold))
        x, t, ok = _close(eq)
        if ok:
            break
    else:
        raise GearleverError(f"lengths: {_why_not(model, eq, x, t)}")
    d = model_dict(model)
    for p, i in eq.col.items():
        d["points"][p] = [float(x[2 * i]) + 0.0, float(x[2 * i + 1]) + 0.0]
    return d
