"""What the workbench computes: pure functions from a model's TOML text to JSON-ready answers.

Every route of :mod:`gearlever.workbench.app` that computes calls one
function here, in a worker process (:mod:`gearlever.workbench.app` says why);
nothing here imports a web framework, and nothing here touches a file of the
workspace.  The functions take the model as the TOML text of the model file
(:mod:`gearlever.mechanism.model`) and answer plain dicts of lists, numbers,
strings and None (strict JSON: NaN is None), or raise
:class:`WorkbenchError` (a :class:`~gearlever.errors.GearleverError`) with one
line naming the field, and for a TOML syntax error the line.

- :func:`parse`, :func:`dump`: TOML text <-> the model as a JSON object
  (:func:`gearlever.mechanism.model.model_from_dict` validates;
  :func:`gearlever.mechanism.modelfile.model_toml` writes, plus the
  ``[lengths]`` table it does not write).
- :func:`solve_frames`: one cycle of every point, link and slider
  (:meth:`gearlever.mechanism.Mechanism.solve`, all frames in one batched
  call), the instant centres (:func:`gearlever.mechanism.centres.instant_centres`)
  with the triples of Kennedy's lines, the dyads' assembly branches
  (:func:`branches`) and where and why the model does not assemble;
  :func:`dump_solve`, the page's edit (a model object written and solved in
  one call).
- :func:`flip_branch`: the sketch moved onto another assembly branch of a dyad.
- :func:`structure`, :func:`forces`, :func:`export` (DXF and outline SVG by
  :mod:`gearlever.export`).
- :func:`check_job` and :func:`run_job`: the synthesis families path, curve,
  function, motion and law, each job's kind the one synthesis registry's
  (:mod:`gearlever.synthesis.registry`), with a ``progress(stage, done,
  total)`` callback and a cancel flag, answering ranked designs as model TOML
  texts.
- :func:`cam`, :func:`law_examples`: a disc cam and its follower for a motion
  law, sized and designed by :mod:`gearlever.cams` (a mechanism of its own:
  the model file has no cam pair).

Caps (each named in the refusal): :data:`MAX_MODEL_CHARS` characters of
model text, :data:`MAX_LINKS` moving links, :data:`MAX_POINTS` points,
:data:`MAX_FRAMES` frames, :data:`MAX_WORK` link-frames, :data:`MAX_TARGET`
target points; the seconds per solve are the app's
(:data:`gearlever.workbench.app.SOLVE_SECONDS`).

The CSV export uses :func:`gearlever._io.table_text`, the writer of
``gearlever mechanism analyze``: it lives in the command-line package, and
the workbench, an application like the command line, imports it from there.
"""

from __future__ import annotations

import collections
import functools
import math
import re
import tomllib

import numpy as np

from gearlever.errors import GearleverError

__all__ = [
    "WorkbenchError",
    "parse",
    "dump",
    "solve_frames",
    "dump_solve",
    "structure",
    "forces",
    "branches",
    "flip_branch",
    "export",
    "check_job",
    "run_job",
    "examples",
    "example",
    "cam",
    "law_examples",
    "EXPORT_FORMATS",
    "JOB_KINDS",
    "MAX_MODEL_CHARS",
    "MAX_LINKS",
    "MAX_POINTS",
    "MAX_FRAMES",
    "MAX_WORK",
    "MAX_TARGET",
]

#: Longest model text (characters): real models are a few kB.
MAX_MODEL_CHARS = 256_000
#: Most moving links of a model the bench solves (the viewer's cap).
MAX_LINKS = 150
#: Most points of a model.
MAX_POINTS = 600
#: Most frames of a cycle (the viewer's cap).
MAX_FRAMES = 3600
#: Most link-frames (frames x moving links) of one solve: the solve time grows with both.
MAX_WORK = 250_000
#: Compiled models kept by :func:`load`.
CACHED_MODELS = 32
#: Most target points of a path or curve synthesis.
MAX_TARGET = 2000
#: Significant digits of the numbers of a cycle (the viewer page's).
DIGITS = 6
#: Instant centres are answered by default for models of at most this many bodies (ground included).
AUTO_CENTRE_BODIES = 8
#: Formats of :func:`export`.
EXPORT_FORMATS = ("svg", "png", "gif", "csv", "html", "toml", "dxf", "svg-outline")
#: Synthesis kinds of :func:`run_job`.
JOB_KINDS = ("path", "curve", "function", "motion", "law")
#: Frames of a GIF export (a GIF of 360 frames is megabytes and seconds to draw).
GIF_FRAMES = 36
#: Most designs a job answers.
MAX_RESULTS = 10


class WorkbenchError(GearleverError):
    """A refusal of the bench: one line naming the field; ``line`` is the TOML line of a syntax error."""

    def __init__(self, message: str, line: int | None = None):
        super().__init__(message)
        self.line = line


class Cancelled(Exception):
    """Raised inside a job when its cancel flag is set (the job then ends as cancelled)."""


# --------------------------------------------------------------------------- model text
def _text(where: str, text) -> str:
    if not isinstance(text, str):
        raise WorkbenchError(f"{where} must be the model's TOML text (a string), got {type(text).__name__}")
    if len(text) > MAX_MODEL_CHARS:
        raise WorkbenchError(f"{where}: {len(text)} characters, more than the cap of {MAX_MODEL_CHARS}")
    return text


def _toml(text: str, where: str = "model") -> dict:
    """The TOML text as a dict; a syntax error names its line."""
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        msg = str(exc).splitlines()[0] if str(exc) else "invalid TOML"
        line = getattr(exc, "lineno", None)
        if line is None:
            found = re.search(r"line (\d+)", msg)
            line = (
                int(found.group(1)) if found else (max(1, len(text.splitlines())) if "end of document" in msg else None)
            )
        raise WorkbenchError(f"{where}: TOML syntax error: {msg}", line) from None
    except RecursionError:
        raise WorkbenchError(f"{where}: nested too deeply") from None


def _check_size(d: dict) -> None:
    pts = d.get("points")
    if isinstance(pts, dict) and len(pts) > MAX_POINTS:
        raise WorkbenchError(f"model: [points] has {len(pts)} points, more than the bench's cap of {MAX_POINTS}")
    links = d.get("links")
    if isinstance(links, dict) and len(links) > MAX_LINKS + 1:
        raise WorkbenchError(
            f"model: [links] has {len(links) - 1} moving links, more than the bench's cap of {MAX_LINKS}"
        )


def _mechanism(d: dict, where: str = "model"):
    from gearlever.mechanism import Mechanism

    _check_size(d)
    try:
        return Mechanism.from_dict(d)
    except RecursionError:
        raise WorkbenchError(f"{where}: nested too deeply") from None
    except GearleverError as exc:
        raise WorkbenchError(f"{where}: {exc}") from None


def load(text, where: str = "model"):
    """The :class:`~gearlever.mechanism.Mechanism` of a model's TOML text (refusals name ``where``).

    The last :data:`CACHED_MODELS` models are kept compiled (a model played,
    scrubbed or re-solved from another start is parsed once); a
    :class:`~gearlever.mechanism.Mechanism` is not changed by solving it.
    """
    text = _text(where, text)
    key = (text, where)
    mech = _CACHE.get(key)
    if mech is None:
        mech = _remember(key, _mechanism(_toml(text, where), where))
    else:
        _CACHE.move_to_end(key)
    return mech


#: ``(text, where) -> Mechanism``, the newest last (:func:`load`).
_CACHE: collections.OrderedDict = collections.OrderedDict()


def _remember(key: tuple, mech):
    _CACHE[key] = mech
    while len(_CACHE) > CACHED_MODELS:
        _CACHE.popitem(last=False)
    return mech


def _jsonable(v):
    """A TOML value as JSON (dates as their text)."""
    if isinstance(v, dict):
        return {str(k): _jsonable(x) for k, x in v.items()}
    if isinstance(v, list):
        return [_jsonable(x) for x in v]
    if isinstance(v, float) and not math.isfinite(v):
        return None
    if isinstance(v, (str, int, float, bool)) or v is None:
        return v
    return str(v)


def _inputs(mech) -> list:
    return [s.label for s in mech.model.inputs]


def parse(text) -> dict:
    """The model as a JSON object, its mobility and inputs.

    Parameters
    ----------
    text : str
        A model file's TOML text.

    Returns
    -------
    dict
        ``model`` (the TOML as a JSON object), ``dof``, ``inputs`` (names).

    Raises
    ------
    WorkbenchError
        A TOML syntax error (``line`` set) or a refused element.

    Examples
    --------
    >>> r = parse('[points]\\nO = [0, 0]\\nA = [1, 0]\\n[links]\\nground = ["O"]\\ncrank = ["O", "A"]\\n'
    ...           '[[inputs]]\\nlink = "crank"\\n')
    >>> r["dof"], r["inputs"], r["model"]["links"]["crank"]
    (1, ['crank'], ['O', 'A'])
    >>> try:
    ...     parse("[points]\\nO = [0, 0\\n")
    ... except WorkbenchError as exc:
    ...     print(exc.line)
    2
    """
    d = _toml(_text("model", text))
    mech = _mechanism(d)
    return {"model": _jsonable(d), "dof": int(mech.structure().dof), "inputs": _inputs(mech)}


def dump(obj) -> str:
    """The TOML text (model-file schema) of a model given as a JSON object; :func:`parse` reads it back.

    The model is validated first (:func:`gearlever.mechanism.model.model_from_dict`),
    then written by the one model writer, :func:`gearlever.mechanism.modelfile.model_toml`,
    with every float in its shortest exact form (the model the page holds is
    the model saved), ``[lengths]`` included.

    Examples
    --------
    >>> d = {"points": {"O": [0, 0], "A": [1.5, 0]}, "links": {"ground": ["O"], "crank": ["O", "A"]},
    ...      "inputs": [{"link": "crank"}], "lengths": {"crank": 1.5}}
    >>> parse(dump(d))["model"] == {**d, "points": {"O": [0.0, 0.0], "A": [1.5, 0.0]}}
    True
    """
    from gearlever.mechanism.modelfile import model_toml

    if not isinstance(obj, dict):
        raise WorkbenchError(f"model must be a JSON object of the model file's tables, got {type(obj).__name__}")
    mech = _mechanism(obj)  # the edit's one build: every refusal names its element
    try:
        text = model_toml(obj, exact=True)
    except GearleverError as exc:
        raise WorkbenchError(f"model: {exc}") from None
    # the text holds the model exactly (every float in its shortest exact form), so the mechanism built from
    # the object is the text's: kept under it, the page's solve of this text, which follows its dump, finds it
    # compiled (``Mechanism.loads(m.dumps())`` is the same model: the library's round-trip tests)
    _remember((_text("model", text), "model"), mech)
    return text


# --------------------------------------------------------------------------- cycle
def _frames(frames) -> int:
    if isinstance(frames, bool) or not isinstance(frames, int) or not 2 <= frames <= MAX_FRAMES:
        raise WorkbenchError(f"frames must be an integer from 2 to {MAX_FRAMES}, got {frames!r}")
    return frames


def _work(mech, frames: int) -> None:
    K = len(mech.model.moving)
    if K > MAX_LINKS:
        raise WorkbenchError(f"model: {K} moving links, more than the bench's cap of {MAX_LINKS}")
    if frames * max(K, 1) > MAX_WORK:
        raise WorkbenchError(
            f"frames: {frames} frames x {K} moving links is more than the cap of {MAX_WORK} link-frames; "
            f"use at most {MAX_WORK // max(K, 1)} frames"
        )


def _start(mech, inputs) -> np.ndarray:
    """Start values (rad, or length for a slider) from the sketch and ``inputs`` ({name: deg or length})."""
    m = mech.model
    labels = _inputs(mech)
    start = mech.sketch_inputs.astype(float)
    if inputs is None:
        return start
    if not isinstance(inputs, dict):
        raise WorkbenchError("inputs must be an object {input name: start value (deg, or length for a slider)}")
    for name, value in inputs.items():
        if name not in labels:
            raise WorkbenchError(f"inputs: unknown input {name!r} (inputs: {', '.join(labels)})")
        if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
            raise WorkbenchError(f"inputs.{name} must be a finite number, got {value!r}")
        i = labels.index(name)
        if m.inputs[i].kind == "link":
            if abs(value) > 360 * 1000:
                raise WorkbenchError(f"inputs.{name} must be at most 360000 deg in size, got {value!r}")
            start[i] = math.radians(value)
        else:
            if abs(value - start[i]) > 1000 * m.length_scale:
                raise WorkbenchError(f"inputs.{name} is more than 1000 model sizes from the sketch, got {value!r}")
            start[i] = float(value)
    return start


def _cycle(mech, frames: int, start: np.ndarray):
    """Input rows of one cycle: a full turn of the first input (a slider: a stroke of +-L/2 and back)."""
    m = mech.model
    W = len(m.inputs)
    k = np.arange(frames) / frames
    q = np.tile(start, (frames, 1))
    qd = np.zeros((frames, W))
    if m.inputs[0].kind == "link":
        q[:, 0] = start[0] + 2 * np.pi * k
        qd[:, 0] = 1.0
        direction = np.ones(frames, dtype=int)
    else:
        half = 0.5 * m.length_scale
        q[:, 0] = start[0] + half * np.sin(2 * np.pi * k)
        qd[:, 0] = 1.0
        c = np.cos(2 * np.pi * k)
        direction = np.where(c >= 0, 1, -1)
    return q, qd, direction


def _oscillation(mech, frames: int, start: np.ndarray):
    """Rows of one oscillation of the first input between its dead points (the library's sweep rule), or None.

    None when the first input turns fully, cannot move, has no dead point on
    one side, or the start does not assemble (the answer's message says so).
    """
    from gearlever.mechanism.limits import input_limits
    from gearlever.mechanism.sweep import oscillation

    try:
        lim = input_limits(mech, 0, start=start)
    except GearleverError:
        return None
    if lim.full_turn or lim.locked or not lim.rocks:
        return None
    v, d = oscillation(lim.start, lim.lower, lim.upper, frames, 1)
    q = np.tile(start, (frames, 1))
    qd = np.zeros_like(q)
    q[:, 0] = v
    qd[:, 0] = d
    return q, qd, d.astype(int), lim


def _cycle_solved(mech, frames: int, start: np.ndarray):
    """``(q, qd, direction, result)`` of one cycle: a full turn (a slider: its stroke), or one oscillation.

    The full turn is solved first; only when some frame does not assemble are
    the first input's limits found (:func:`gearlever.mechanism.limits.input_limits`)
    and, if it rocks between two dead points, the cycle is one oscillation
    from the start to one limit, back to the other and back (the sweep rule
    of :mod:`gearlever.mechanism.sweep`, as ``gearlever mechanism analyze``
    sweeps it), with ``direction`` -1 on the way back.
    """
    q, qd, direction = _cycle(mech, frames, start)
    r = _solve(mech, q, qd)
    lim = None
    if not r.closed.all():
        osc = _oscillation(mech, frames, start)
        if osc is not None:
            q, qd, direction, lim = osc
            r = _solve(mech, q, qd)
    return q, qd, direction, r, lim


def _rocks_message(mech, lim) -> str:
    """The one line of a rocking first input, as ``gearlever mechanism analyze`` prints it, with the binding links."""
    unit = mech.model.units
    if lim.kind == "link":
        span = f"{math.degrees(lim.lower):.4f} and {math.degrees(lim.upper):.4f} deg"
    else:
        span = f"{lim.lower:.6g} and {lim.upper:.6g}{' ' + unit if unit else ''}"
    links = ", ".join(dict.fromkeys(lim.binding_lower + lim.binding_upper))
    return f"{lim.input} rocks between {span} (dead points: links {links}): one oscillation"


def _rounded(a, scale=None) -> tuple:
    """``a`` at :data:`DIGITS` significant digits of ``scale`` (default: its largest finite size); finite mask."""
    a = np.asarray(a, dtype=float)
    fin = np.isfinite(a)
    z = np.where(fin, a, 0.0)
    if scale is None:
        scale = float(np.max(np.abs(z))) if z.size else 0.0
    if not scale > 0 or not math.isfinite(scale):
        return z + 0.0, fin
    decimals = DIGITS - 1 - math.floor(math.log10(scale))
    return np.round(z, decimals) + 0.0, fin


def _num(a, scale=None, plain: bool = True) -> list:
    """Floats at :data:`DIGITS` significant digits of ``scale`` (default: the largest), NaN as None.

    ``plain=False``: the rounded array itself when every value is finite (for an encoder that writes numpy
    arrays, as orjson does: the same JSON text without a Python float per value).
    """
    out, fin = _rounded(a, scale)
    if fin.all():
        return out.tolist() if plain else out
    vals = out.tolist()
    return [v if f else None for v, f in zip(vals, fin.tolist())]


def _xy(a, scale=None, plain: bool = True) -> list:
    """(N, 2) -> [[x, y] or None, ...] (``plain=False``: the rounded array when every row is finite)."""
    out, fin = _rounded(a, scale)
    ok = fin.all(axis=1)
    if ok.all():
        return out.tolist() if plain else out
    vals = out.tolist()
    return [v if k else None for v, k in zip(vals, ok.tolist())]


def _xy_all(series: dict, scale: float, plain: bool = True) -> dict:
    """:func:`_xy` of every (N, 2) array of ``series`` at one ``scale``, rounded in one pass."""
    names = list(series)
    if not names:
        return {}
    out, fin = _rounded(np.stack([series[n] for n in names]), scale)
    ok = fin.all(axis=2)
    answer = {}
    for k, name in enumerate(names):
        if ok[k].all():
            answer[name] = out[k].tolist() if plain else out[k]
        else:
            answer[name] = [v if f else None for v, f in zip(out[k].tolist(), ok[k].tolist())]
    return answer


def _transmission(mech, r):
    """Transmission angle (deg, 0..180) of a four-bar-like model: one input crank, a coupler and a rocker pinned.

    The angle between the coupler and the rocker at their common pin
    (J. E. Shigley and J. J. Uicker, *Theory of Machines and Mechanisms*,
    sec. 2.11): None for any other model.
    """
    from gearlever.mechanism.model import GROUND

    m = mech.model
    if len(m.inputs) != 1 or m.inputs[0].kind != "link" or len(m.moving) != 3 or m.sliders or m.gears:
        return None
    crank = m.inputs[0].name
    ground = set(m.links[GROUND].points)
    others = [k for k in m.moving if k != crank]
    rocker = [k for k in others if ground & set(m.links[k].points)]
    coupler = [k for k in others if not ground & set(m.links[k].points)]
    if len(rocker) != 1 or len(coupler) != 1:
        return None
    rk, cp = m.links[rocker[0]], m.links[coupler[0]]
    common = [p for p in rk.points if p in cp.points]
    pivot = [p for p in rk.points if p in ground]
    crank_pin = [p for p in cp.points if p in m.links[crank].points]
    if len(common) != 1 or not pivot or not crank_pin:
        return None
    B, O4, A = r.point[common[0]], r.point[pivot[0]], r.point[crank_pin[0]]
    u, v = A - B, O4 - B
    cos = np.sum(u * v, axis=1) / (np.hypot(u[:, 0], u[:, 1]) * np.hypot(v[:, 0], v[:, 1]))
    return _num(np.degrees(np.arccos(np.clip(cos, -1.0, 1.0))))


def _message(mech, r, labels) -> str:
    """Where and why the cycle does not assemble: the first frame not closed, the input there, the reason."""
    if r.closed.all():
        return ""
    i = int(np.flatnonzero(~r.closed)[0])
    spec = mech.model.inputs[0]
    v = float(r.q[i, 0])
    value = f"{math.degrees(v):.4g} deg" if spec.kind == "link" else f"{v:.4g} {mech.model.units or ''}".rstrip()
    reason = _why(mech, r.q[i]) or str(r.reason[i]) or "the mechanism does not assemble"
    n = int((~r.closed).sum())
    return f"{labels[0]} at {value} (frame {i}): {reason}; {n} of {len(r.closed)} frames do not assemble"


def _why(mech, q) -> str:
    """Which dyad cannot close at the inputs ``q`` and by how much, for a model of drivers and dyads; else "".

    The model's plan of drivers and Assur dyads (:mod:`gearlever.mechanism.assur`) is replayed at ``q``,
    positions only, one group at a time: the first RRR dyad whose two links cannot meet (the circles of
    radius ``r1`` about ``P1`` and ``r2`` about ``P2`` do not intersect: ``d > r1 + r2`` or
    ``d < |r1 - r2|``, ``d = |P1 P2|``) is named with the length missing.
    """
    from gearlever.mechanism.assur import _RRP, _RRR, _Driver
    from gearlever.mechanism.model import GROUND

    plan = mech.system.dyad_plan
    if plan is None:
        return ""
    model, units = mech.model, (f" {mech.model.units}" if mech.model.units else "")
    dq = (np.asarray(q, dtype=float) - mech.system.q0)[:, None]
    st = {GROUND: (1.0, 0.0, None, 0.0, None)}
    pts = {n: (x, y, 0.0, 0.0, 0.0, 0.0) for n, (x, y) in model.points.items() if GROUND in model.carriers(n)}
    phi, slider = {}, {}
    with np.errstate(all="ignore"):
        for step in plan.steps:
            if isinstance(step, _Driver):
                a = dq[step.w]
                phi[step.link] = a
                st[step.link] = (np.cos(a), np.sin(a), None, None, step.pivot)
            elif isinstance(step, _RRR):
                X1, Y1 = plan._point(st, pts, step.k1, step.p1)[:2]
                X2, Y2 = plan._point(st, pts, step.k2, step.p2)[:2]
                margin = plan._rrr(step, st, pts, phi, False)
                if not np.isfinite(margin[0]):
                    d = float(np.hypot(X2 - X1, Y2 - Y1)[0])
                    if d > step.r1 + step.r2:
                        short = f"{d - step.r1 - step.r2:.3g}{units} short"
                    else:
                        short = f"{abs(step.r1 - step.r2) - d:.3g}{units} too unequal for pins {d:.3g}{units} apart"
                    return f"{step.p} cannot be reached, links {step.l1} and {step.l2} {short}"
            elif isinstance(step, _RRP):
                margin = plan._rrp(step, st, pts, phi, slider, False)
                if not np.isfinite(margin[0]):
                    return f"{step.p} cannot be reached, link {step.l1} does not reach the guide of {step.l2}"
    return ""


def _solve(mech, q, qd):
    """The one call of the library's solver for every cycle the bench answers (solve, export).

    The assembly branch is the sketch's (:func:`flip_branch` moves the sketch
    onto another one); a branch policy of the solver, once the library has
    one, is passed here and nowhere else.
    """
    try:
        return mech.solve(q, qd)
    except GearleverError as exc:
        raise WorkbenchError(f"model: {exc}") from None


# --------------------------------------------------------------------------- assembly branches
def branches(mech) -> list:
    """The assembly branches of the model's sketch: one entry per dyad of its plan of drivers and dyads.

    ``[{"joint", "links": [l1, l2], "kind": "RRR"|"RRP", "about": [p1, p2 or None], "sigma": +1|-1}]``:
    the joint the dyad places, its two links, and the side of the joint the
    sketch shows: for an RRR dyad the sign of ``cross(P2 - P1, P - P1)``
    (+1: the joint left of the line from ``p1`` to ``p2``), for an RRP dyad
    the sign of the joint's travel along the guide from ``p1``'s foot.  Empty
    for a model without such a plan (gears, slider inputs, other groups).

    Examples
    --------
    >>> b = branches(load(example("fourbar")))
    >>> [(x["joint"], x["links"], x["sigma"]) for x in b]
    [('B', ['coupler', 'rocker'], 1.0)]
    """
    from gearlever.mechanism.assur import _RRP, _RRR

    plan = mech.system.dyad_plan
    if plan is None:
        return []
    out = []
    for step in plan.steps:
        if isinstance(step, _RRR):
            out.append(
                {
                    "joint": step.p,
                    "links": [step.l1, step.l2],
                    "kind": "RRR",
                    "about": [step.p1, step.p2],
                    "sigma": step.sigma,
                }
            )
        elif isinstance(step, _RRP):
            out.append(
                {
                    "joint": step.p,
                    "links": [step.l1, step.l2],
                    "kind": "RRP",
                    "about": [step.p1, None],
                    "sigma": step.sigma,
                }
            )
    return out


def flip_branch(text, joint) -> str:
    """The model with the dyad that places ``joint`` on its other assembly branch, as TOML text.

    Parameters
    ----------
    text : str
        The model's TOML text.
    joint : str
        A joint of :func:`branches`.

    Returns
    -------
    str
        The model file with every point moved to where the mechanism stands
        at the sketch's inputs on the other branch of that dyad (every other
        dyad keeps its side); lengths, links and everything else unchanged.

    Notes
    -----
    The sketch is re-placed by the closed-form position analysis of the Assur
    groups (J. J. Uicker, G. R. Pennock and J. E. Shigley, *Theory of Machines
    and Mechanisms*, 5th ed., ch. 3-4): the second intersection of the two
    circles of an RRR dyad (the joint mirrored about the line of its two
    known pins), of the circle and the line of an RRP dyad; the points
    carried by a link move with it rigidly, and the dyads placed after it
    follow.

    Examples
    --------
    >>> t = flip_branch(example("fourbar"), "B")
    >>> [(x["joint"], x["sigma"]) for x in branches(load(t))]
    [('B', -1.0)]
    >>> flip_branch(t, "B") == dump(_toml(example("fourbar")))
    True
    """
    import dataclasses

    from gearlever.mechanism.assur import _RRP, _RRR, DyadPlan
    from gearlever.mechanism.model import GROUND

    mech = load(text)
    plan = mech.system.dyad_plan
    names = [b["joint"] for b in branches(mech)]
    if joint not in names:
        raise WorkbenchError(
            f"joint: {str(joint)[:60]!r} is not placed by a dyad of this model"
            + (f" (branches: {', '.join(names)})" if names else " (it has no assembly branch to choose)")
        )
    steps = tuple(
        dataclasses.replace(s, sigma=-s.sigma) if isinstance(s, (_RRR, _RRP)) and s.p == joint else s
        for s in plan.steps
    )
    flipped = DyadPlan(plan.model, plan.ks, steps)
    W = len(mech.model.inputs)
    with np.errstate(all="ignore"):
        _, st, _, pts, margin = flipped.run(np.zeros((W, 1)))
    if margin is not None and not np.all(np.isfinite(margin)):
        raise WorkbenchError(f"joint: the other branch of {joint} does not assemble at the sketch")
    m = mech.model
    d = _toml(text)
    new = {}
    for name, xy in m.points.items():
        if name in pts:
            X, Y = pts[name][:2]
        else:
            carrier = next((k for k in m.carriers(name) if k in st and (k == GROUND or st[k][4] is not None)), None)
            if carrier is None or carrier == GROUND:
                new[name] = [float(xy[0]), float(xy[1])]
                continue
            X, Y = flipped._point(st, pts, carrier, name)[:2]
        new[name] = [float(np.asarray(X).ravel()[0]), float(np.asarray(Y).ravel()[0])]
    # the sketch's digits: a point moved by the flip keeps the model's precision, not float noise
    L = m.length_scale
    for name, (x, y) in new.items():
        if [x, y] != [float(c) for c in m.points[name]]:
            new[name] = [_tidy(x, L), _tidy(y, L)]
    d["points"] = {name: new.get(name, v) for name, v in d["points"].items()}
    return dump(_jsonable(d))


def _tidy(v: float, scale: float) -> float:
    """``v`` rounded to 12 significant digits of ``scale`` (the sketch's positions, not their float noise)."""
    if not scale > 0:
        return float(v)
    return float(round(v, 11 - math.floor(math.log10(scale)))) + 0.0


def solve_frames(text, frames: int = 360, inputs=None, centres=None, plain: bool = True) -> dict:
    """One cycle of the model: every point, link, slider over a full turn of the first input, or one oscillation.

    Parameters
    ----------
    text : str
        The model's TOML text.
    frames : int
        Frames of the cycle, 2 to :data:`MAX_FRAMES`; frame ``k`` at the
        first input's start ``+ 360 k / frames`` deg (a slider input: the
        start ``+ L/2 sin(2 pi k / frames)``, ``L`` the model's size).  An
        input that rocks between two dead points (a frame of the full turn
        does not assemble) sweeps one oscillation instead, as ``gearlever
        mechanism analyze`` does: ``direction`` is -1 on the way back.
    inputs : dict, optional
        ``{input: start}`` in degrees (length for a slider): the first
        input's start and the held value of the others (default: the sketch).
    centres : bool, optional
        Answer the instant centres (one-input models only): None (default)
        for models of at most :data:`AUTO_CENTRE_BODIES` bodies, True for up
        to :data:`gearlever.plotting.viewer.MAX_CENTRE_BODIES` (``n (n - 1) / 2``
        centres a frame: 55 for 11 bodies, most of the answer), False never.
    plain : bool
        True (default): lists of floats.  False: a series whose values are
        all finite is answered as its rounded numpy array, for an encoder
        that writes arrays (the server's, orjson: the same JSON text, without
        a Python float per value).

    Returns
    -------
    dict
        The answer of ``POST /api/solve`` (see the module
        :mod:`gearlever.workbench`): positions, velocity and acceleration
        analogues per unit rate of the first input, link angles (deg),
        angular rates, slider travel, gears' pitch circles, instant centres
        (one input, at most 16 bodies), the transmission angle of a
        four-bar-like model, ``message`` and ``extent``.

    Notes
    -----
    All frames are solved by one call of
    :meth:`gearlever.mechanism.Mechanism.solve` (continuation from the
    sketch, E. L. Allgower and K. Georg, *Numerical Continuation Methods*,
    1990); instant centres by Kennedy's theorem
    (:func:`gearlever.mechanism.centres.instant_centres`).

    Examples
    --------
    >>> t = ('[points]\\nO = [0, 0]\\nA = [1, 0]\\n[links]\\nground = ["O"]\\ncrank = ["O", "A"]\\n'
    ...      '[[inputs]]\\nlink = "crank"\\n')
    >>> d = solve_frames(t, frames=4)
    >>> d["point"]["A"], d["input_deg"], d["message"]
    ([[1.0, 0.0], [0.0, 1.0], [-1.0, 0.0], [0.0, -1.0]], [0.0, 90.0, 180.0, 270.0], '')
    """
    from functools import partial

    from gearlever.mechanism.model import GROUND
    from gearlever.plotting.viewer import MAX_CENTRE_BODIES

    frames = _frames(frames)
    num = partial(_num, plain=plain)
    mech = load(text)
    _work(mech, frames)
    m = mech.model
    labels = _inputs(mech)
    start = _start(mech, inputs)
    q, qd, direction, r, rocking = _cycle_solved(mech, frames, start)
    L = m.length_scale
    s = mech.structure()
    kinds = {lab: ("angle" if sp.kind == "link" else "slider") for lab, sp in zip(labels, m.inputs)}
    inputs_deg = {
        lab: num(np.degrees(q[:, i]) if sp.kind == "link" else q[:, i])
        for i, (lab, sp) in enumerate(zip(labels, m.inputs))
    }
    points = list(r.point)
    out = {
        "dof": int(s.dof),
        "redundant": int(s.redundant),
        "inputs": labels,
        "input_kind": kinds,
        "frames": frames,
        "input_deg": inputs_deg[labels[0]],
        "inputs_deg": inputs_deg,
        "direction": direction.tolist(),
        "closed": r.closed.tolist(),
        "point": _xy_all({p: r.point[p] for p in points}, L, plain),
        "velocity": _xy_all({p: r.velocity[p] for p in points}, L, plain),
        "acceleration": _xy_all({p: r.acceleration[p] for p in points}, L, plain),
        "angle_deg": {k: num(np.degrees(r.angle[k])) for k in m.moving},
        "omega": {k: num(r.omega[k]) for k in m.moving},
        "alpha": {k: num(r.alpha[k]) for k in m.moving},
        "slider": {
            sl.name: {
                "s": num(r.displacement[sl.name]),
                "v": num(r.slider_velocity[sl.name]),
                "a": num(r.slider_acceleration[sl.name]),
            }
            for sl in m.sliders
        },
        "gears": [
            {"name": g.name, "link": g.link, "center": g.centre, "teeth": g.teeth, "radius": m.pitch_radius(g.name)}
            for g in m.gears.values()
        ],
        "centres": None,
        "centre_direction": None,
        "kennedy": None,
        "transmission_deg": _transmission(mech, r),
        "message": _message(mech, r, labels) or (_rocks_message(mech, rocking) if rocking is not None else ""),
        "ground_points": list(m.links[GROUND].points),
        "branches": branches(mech),
        "links": {k: list(m.links[k].points) for k in m.moving},
        "units": m.units or "",
    }
    if centres is not None and not isinstance(centres, bool):
        raise WorkbenchError(f"centres must be true or false, got {centres!r}")
    most = AUTO_CENTRE_BODIES if centres is None else (MAX_CENTRE_BODIES if centres else 0)
    if len(m.inputs) == 1 and len(m.moving) + 1 <= most:
        from gearlever.mechanism.centres import instant_centres

        ic = instant_centres(r)
        out["centres"] = _xy_all({str(k): ic.xy[:, p] for p, k in enumerate(ic.pairs)}, L, plain)
        out["centre_direction"] = _directions(ic)
        out["kennedy"] = _kennedy_triples(ic)
    xy = np.concatenate([r.point[p] for p in points]) if points else np.zeros((0, 2))
    xy = xy[np.all(np.isfinite(xy), axis=1)]
    if xy.size == 0:
        xy = np.array(list(m.points.values()), dtype=float)
    lo, hi = xy.min(axis=0), xy.max(axis=0)
    for g in m.gears.values():
        rad = m.pitch_radius(g.name)
        c = r.point[g.centre]
        c = c[np.all(np.isfinite(c), axis=1)]
        if rad is not None and c.size:
            lo, hi = np.minimum(lo, c.min(axis=0) - rad), np.maximum(hi, c.max(axis=0) + rad)
    out["extent"] = [float(lo[0]), float(lo[1]), float(hi[0]), float(hi[1])]
    return out


def _directions(ic) -> dict:
    """Centres at infinity: ``{"a/b": [[frame, ux, uy], ...]}`` (the unit direction towards the centre), sparse."""
    out = {}
    for p, key in enumerate(ic.pairs):
        d = ic.direction[:, p]
        rows = np.flatnonzero(np.all(np.isfinite(d), axis=1))
        if rows.size:
            u = np.round(d[rows], DIGITS) + 0.0
            out[str(key)] = [[int(i), float(x), float(y)] for i, (x, y) in zip(rows.tolist(), u.tolist())]
    return out


def _kennedy_triples(ic) -> list:
    """Kennedy's lines: every triple of bodies as the keys of its three centres ``[ij, ik, jk]``.

    By the Aronhold-Kennedy theorem the three instant centres of three bodies
    lie on one straight line (Uicker, Pennock and Shigley, *Theory of
    Machines and Mechanisms*, 5th ed., ch. 3); the page draws that line
    through the centres :func:`gearlever.mechanism.centres.instant_centres`
    answers (a centre at infinity gives the line's direction).
    """
    from itertools import combinations

    n = len(ic.links)
    key = ic.pairs.index
    name = lambda i, j: f"{ic.links[i]}/{ic.links[j]}"  # noqa: E731
    return [
        [ic.pairs[key(name(i, j))], ic.pairs[key(name(i, k))], ic.pairs[key(name(j, k))]]
        for i, j, k in combinations(range(n), 3)
    ]


def dump_solve(obj, frames: int = 360, inputs=None, centres=None, plain: bool = True) -> dict:
    """:func:`dump` then :func:`solve_frames` in one call: the page's edit in one round trip.

    The answer of :func:`solve_frames` with ``toml``, the model's TOML text,
    added (the text pane shows it, saving writes it).

    Examples
    --------
    >>> d = {"points": {"O": [0, 0], "A": [1, 0]}, "links": {"ground": ["O"], "crank": ["O", "A"]},
    ...      "inputs": [{"link": "crank"}]}
    >>> r = dump_solve(d, frames=4)
    >>> r["toml"] == dump(d), r["point"]["A"][1]
    (True, [0.0, 1.0])
    """
    text = dump(obj)
    out = solve_frames(text, frames, inputs, centres, plain=plain)
    out["toml"] = text
    return out


def structure(text) -> dict:
    """Mobility, redundant constraints, links, joints and inputs of the model (no solve).

    Examples
    --------
    >>> t = ('[points]\\nO = [0, 0]\\nA = [1, 0]\\n[links]\\nground = ["O"]\\ncrank = ["O", "A"]\\n'
    ...      '[[inputs]]\\nlink = "crank"\\n')
    >>> d = structure(t)
    >>> d["dof"], d["redundant"], d["links"], d["message"]
    (1, 0, ['ground', 'crank'], '')
    """
    mech = load(text)
    m = mech.model
    try:
        s = mech.structure()
    except GearleverError as exc:
        raise WorkbenchError(f"model: {exc}") from None
    W = len(m.inputs)
    msg = ""
    if s.dof != W:
        msg = (
            f"the model has {s.dof} degrees of freedom and {W} input{'s' if W != 1 else ''}: "
            "give one input per degree of freedom"
        )
    summary = {
        str(k): _jsonable(v) if not isinstance(v, (np.integer, np.floating)) else v.item()
        for k, v in s.summary().items()
    }
    return {
        "dof": int(s.dof),
        "redundant": int(s.redundant),
        "redundant_constraints": list(s.redundant_rows),
        "links": list(m.links),
        "joints": [{"point": p, "links": [a, b]} for p, a, b in m.joints],
        "inputs": _inputs(mech),
        "summary": summary,
        "message": msg,
    }


def forces(text, frames: int = 360, rpm=None) -> dict:
    """Input torques and pin forces over one cycle at constant input speeds (:meth:`Mechanism.inverse_dynamics`).

    One turn of the inputs, or for a single input that rocks between two dead
    points, one oscillation as :func:`solve_frames` draws it (the speed's sign
    that of the motion).

    Masses, loads and gravity come from the model's ``[masses]``,
    ``[[loads]]`` and ``[mechanism] gravity``, as for ``gearlever mechanism
    forces``; ``rpm`` gives each rotary input's speed (rev/min, default 1
    rad/s each: the torques at unit input speed).

    Notes
    -----
    The equilibrium of every link with its inertia forces (d'Alembert), solved
    for the driver torques and pair forces (:mod:`gearlever.mechanism.dynamics`).
    """
    from gearlever.mechanism.loads import force_units

    frames = _frames(frames)
    mech = load(text)
    _work(mech, frames)
    m = mech.model
    labels = _inputs(mech)
    if rpm is not None and not isinstance(rpm, dict):
        raise WorkbenchError("rpm must be an object {input name: rev/min}")
    w = np.ones(len(labels))
    if rpm:
        for name, value in rpm.items():
            if name not in labels:
                raise WorkbenchError(f"rpm: unknown input {name!r} (inputs: {', '.join(labels)})")
            if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
                raise WorkbenchError(f"rpm.{name} must be a finite number, got {value!r}")
            if abs(value) > 1e6:
                raise WorkbenchError(f"rpm.{name} must be at most 1e6 rev/min in size, got {value!r}")
            i = labels.index(name)
            w[i] = value * math.pi / 30.0 if m.inputs[i].kind == "link" else value / 60.0
    turning = [i for i, sp in enumerate(m.inputs) if sp.kind == "link" and w[i] != 0]
    if not turning:
        raise WorkbenchError("rpm: no rotary input turns (forces span one turn of a rotary input)")
    period = 2 * math.pi / abs(w[turning[0]])
    t = np.linspace(0.0, period, frames, endpoint=False)
    q = mech.sketch_inputs[None, :] + t[:, None] * w[None, :]
    qdot = np.broadcast_to(w, q.shape)
    if len(labels) == 1 and not _solve(mech, q, qdot).closed.all():
        osc = _oscillation(mech, frames, mech.sketch_inputs.astype(float))
        if osc is not None:  # a rocking input: one oscillation at the speed given, as the cycle drawn
            q, _, direction, _ = osc
            qdot = abs(w[0]) * direction[:, None].astype(float)
            t = np.cumsum(np.abs(np.diff(q[:, 0], prepend=q[0, 0]))) / abs(w[0])
    try:
        d = mech.inverse_dynamics(q, qdot, np.zeros_like(q))
    except GearleverError as exc:
        raise WorkbenchError(f"model: {exc}") from None
    F, T = force_units(m)
    return {
        "input_deg": _num(np.degrees(q[:, turning[0]])),
        "time_s": _num(t),
        "speeds": {lab: float(w[i]) for i, lab in enumerate(labels)},
        "units": {"force": F, "torque": T},
        "torque": {lab: _num(d.input_force[:, i]) for i, lab in enumerate(labels)},
        "pin": {str(k): _xy(v) for k, v in d.reaction.items()},
        "slider": {str(k): _num(v) for k, v in d.slider_force.items()},
        "mesh": {str(k): _num(v) for k, v in d.mesh_force.items()},
        "ground": _xy(d.ground_force),
        "ok": d.ok.tolist(),
        "indeterminate": list(d.indeterminate),
    }


# --------------------------------------------------------------------------- export
def _sweep_result(mech, frames: int):
    return _cycle_solved(mech, frames, mech.sketch_inputs.astype(float))[3]


def _safe_name(name: str) -> str:
    keep = "".join(c if c.isascii() and (c.isalnum() or c in "-_") else "_" for c in name)[:60].strip("_")
    return keep or "mechanism"


def export(text, fmt: str, frames: int = 360, inputs=None, cam=None, cam_angle_deg=0.0) -> tuple:
    """The model as a file: ``(body bytes, content type, file name)``.

    ``fmt``: ``svg``, ``png`` (the drawing of ``gearlever mechanism draw``),
    ``gif`` (its animation, :data:`GIF_FRAMES` frames), ``csv`` (the cycle as
    ``gearlever mechanism analyze`` writes it), ``html`` (the page of
    ``gearlever mechanism view``), ``toml`` (the model file, :func:`dump`),
    ``dxf`` and ``svg-outline`` (every link's outline, pin holes and gears for
    CAD, :func:`gearlever.export.mechanism_drawing`, one layer or group per
    link) at the pose of ``inputs`` (``{input: deg, or length for a
    slider}``, as for :func:`solve_frames`; default the sketch).  ``cam``, a
    CAM.toml text (the bench's cam, :func:`cam`'s ``cam_toml``), adds the
    cam's profile to those two as a part of its own (layer ``cam``): the
    library's surface (:func:`gearlever.cams.load_cam`) turned
    counterclockwise by ``cam_angle_deg`` about its ``centre``, with a bore
    of the pin diameter there.
    """
    if fmt not in EXPORT_FORMATS:
        raise WorkbenchError(f"format must be one of {', '.join(EXPORT_FORMATS)}, got {fmt!r}")
    frames = _frames(frames)
    mech = load(text)
    _work(mech, frames)
    stem = _safe_name(mech.model.name or "mechanism")
    if fmt in ("dxf", "svg-outline"):
        return _cad(mech, fmt, stem, inputs, cam, cam_angle_deg)
    if cam is not None:
        raise WorkbenchError(f"cam: the cam's profile is drawn in the dxf and svg-outline formats, not {fmt}")
    if inputs is not None:
        raise WorkbenchError(f"inputs: a pose is for the dxf and svg-outline formats, not {fmt}")
    if fmt == "toml":
        return dump(_toml(text)).encode("utf-8"), "application/toml; charset=utf-8", f"{stem}.toml"
    if fmt == "html":
        from gearlever.plotting.viewer import viewer_html

        if mech.model.inputs[0].kind != "link":
            raise WorkbenchError("format html: the page turns the first input a full turn; put a rotary input first")
        try:
            page = viewer_html(mech, frames=frames)
        except GearleverError as exc:
            raise WorkbenchError(str(exc)) from None
        return page.encode("utf-8"), "text/html; charset=utf-8", f"{stem}.html"
    r = _sweep_result(mech, frames)
    if fmt == "csv":
        from gearlever._io import table_text

        cols = r.columns(degrees=True, per=_inputs(mech)[0])
        cols["closed"] = r.closed
        cols["reason"] = [s.split(":")[0] for s in r.reason]
        return table_text(cols, "csv").encode("utf-8"), "text/csv; charset=utf-8", f"{stem}.csv"
    import tempfile
    from pathlib import Path

    # the worker process runs with MPLBACKEND=Agg; plotting alone imports pyplot
    from gearlever.plotting._common import save
    from gearlever.plotting.mechanism import animate_mechanism, draw_mechanism

    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / f"m.{fmt}"
        if fmt == "gif":
            animate_mechanism(mech, _sweep_result(mech, GIF_FRAMES), path, paths=r)
            return path.read_bytes(), "image/gif", f"{stem}.gif"
        save(draw_mechanism(mech, r).figure, path, dpi=120)
        data = path.read_bytes()
    ctype = "image/svg+xml" if fmt == "svg" else "image/png"
    return data, ctype, f"{stem}.{fmt}"


def _cad(mech, fmt: str, stem: str, inputs, cam=None, cam_angle_deg=0.0) -> tuple:
    """DXF or outline SVG of the mechanism at a pose (:mod:`gearlever.export`), with the bench's cam if given."""
    import tempfile
    from dataclasses import replace
    from pathlib import Path

    from gearlever.export import FORMATS, mechanism_drawing

    start = _start(mech, inputs)
    pose = {lab: float(v) for lab, v in zip(_inputs(mech), start)}
    try:
        drawing = mechanism_drawing(mech, pose)
    except GearleverError as exc:
        raise WorkbenchError(f"inputs: {exc}") from None
    if cam is not None:
        taken = {p.name for p in drawing.parts}
        drawing = replace(drawing, parts=(*drawing.parts, cam_part(cam, cam_angle_deg, drawing.pin_diameter, taken)))
    suffix = "dxf" if fmt == "dxf" else "svg"
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / f"m.{suffix}"
        FORMATS[suffix](drawing, path)
        data = path.read_bytes()
    if fmt == "dxf":
        return data, "application/dxf", f"{stem}.dxf"
    return data, "image/svg+xml", f"{stem}_outline.svg"


def cam_part(text, angle_deg=0.0, bore: float = 0.0, taken=()):
    """The bench's cam as a part of a CAD drawing: its profile and its bore, on a layer of its own.

    Parameters
    ----------
    text : str
        The CAM.toml text (:func:`cam`'s ``cam_toml``), read by
        :func:`gearlever.cams.load_cam` (the profile) and
        :func:`gearlever.cams.cam_centre` (where its pivot is).
    angle_deg : float
        The cam's turn (counterclockwise, deg), as the frame drawn.
    bore : float
        Diameter of the hole at the pivot (0: none).
    taken : collection of str
        Names of the drawing's parts: the layer is ``cam``, or ``cam_2``... when a link holds that name.

    Returns
    -------
    gearlever.export.outline.Part

    Examples
    --------
    >>> p = cam_part(cam({"example": "law_lift", "centre": [100, 0], "frames": 36})["cam_toml"], 0.0, 4.0)
    >>> p.name, p.outlines[0].shape, p.holes
    ('cam', (36, 2), (((100.0, 0.0), 2.0),))
    """
    import tempfile
    from pathlib import Path

    from gearlever.cams import cam_centre, load_cam
    from gearlever.export.outline import Part

    try:
        cam_file_params(text)  # every refusal of the CAM format, named
    except WorkbenchError as exc:
        raise WorkbenchError("cam: " + str(exc).removeprefix("file: ")) from None
    a = _float({"cam_angle_deg": angle_deg}, "cam_angle_deg", 0.0, -1e6, 1e6)
    with tempfile.TemporaryDirectory() as tmp:
        p = Path(tmp) / "cam.toml"
        p.write_text(text, encoding="utf-8")
        design, centre = load_cam(p), np.array(cam_centre(p))
    t = math.radians(a)
    turn = np.array([[math.cos(t), -math.sin(t)], [math.sin(t), math.cos(t)]])
    outline = design.surface @ turn.T + centre
    name, k = "cam", 1
    while name in taken:
        k += 1
        name = f"cam_{k}"
    holes = (((float(centre[0]), float(centre[1])), bore / 2),) if bore > 0 else ()
    return Part(name, (outline,), holes, origin=(float(centre[0]), float(centre[1])), angle=t)


# --------------------------------------------------------------------------- cams
#: Follower kinds of :func:`cam` (the library's registry, :data:`gearlever.cams.FOLLOWERS`).
CAM_KEYS = (
    "law",
    "example",
    "file",
    "follower",
    "centre",
    "base_radius",
    "roller_radius",
    "offset",
    "arm",
    "pivot_distance",
    "max_pressure_angle_deg",
    "frames",
    "angles_deg",
)
#: Profile points of a cam turned by given angles (``angles_deg``): each frame is the nearest of them (0.1 deg).
CAM_POINTS = 3600
#: Most profile points answered (the drawing's polygon).
CAM_PROFILE = 720
#: Default bound on the pressure angle of a roller follower when the bench sizes the base circle (deg):
#: the common design limit for translating roller followers (R. L. Norton, *Design of Machinery*, sec. 8.6).
CAM_PRESSURE_DEG = 30.0


def _shipped_examples() -> list:
    """``[(name, text, table)]`` of every shipped example file (``gearlever/data/examples/*.toml``) that parses."""
    from importlib import resources

    out = []
    folder = resources.files("gearlever.data").joinpath("examples")
    for entry in sorted(folder.iterdir(), key=lambda e: e.name):
        if not entry.name.endswith(".toml"):
            continue
        text = entry.read_text(encoding="utf-8")
        try:
            out.append((entry.name[: -len(".toml")], text, tomllib.loads(text)))
        except tomllib.TOMLDecodeError:
            continue
    return out


def law_examples() -> list:
    """The shipped example laws (files of ``gearlever/data/examples`` holding a ``[law]`` table).

    >>> [(e["name"], e["output"]) for e in law_examples()][:2]
    [('law_dwell_rocker', 'angle'), ('law_lift', 'displacement')]
    """
    out = []
    for name, text, d in _shipped_examples():
        law = d.get("law")
        if not isinstance(law, dict) or "segment" not in law:
            continue
        first = text.splitlines()[0].lstrip("# ").strip() if text.startswith("#") else ""
        out.append({"name": name, "output": str(law.get("output", "")), "title": first or name})
    return out


def _cam_law(params: dict):
    """The law of a cam request: its TOML text (``law``) or a shipped example's name (``example``)."""
    from importlib import resources

    if ("law" in params) == ("example" in params):
        raise WorkbenchError("law: give the law's TOML text (law) or a shipped example law's name (example), one")
    if "example" in params:
        names = [e["name"] for e in law_examples()]
        if not isinstance(params["example"], str) or params["example"] not in names:
            raise WorkbenchError(f"example: unknown law {str(params['example'])[:60]!r} (laws: {', '.join(names)})")
        text = resources.files("gearlever.data").joinpath("examples", f"{params['example']}.toml")
        return _law(text.read_text(encoding="utf-8"))
    law = params["law"]
    if not isinstance(law, str) or not 0 < len(law) <= 100_000:
        raise WorkbenchError("law must be the TOML text of a [law] table (at most 100000 characters)")
    return _law(law)


def cam(params) -> dict:
    """A disc cam and its follower for a motion law, placed on a ground pivot: one turn of frames.

    Parameters
    ----------
    params : dict
        ``law`` (a LAW.toml text with ``[[law.segment]]`` tables) or
        ``example`` (a name of :func:`law_examples`) or ``file`` (a CAM.toml
        text, as the bench saves it: its law, follower, dimensions and
        ``centre``, each overridden by the same key given beside it); ``follower`` (a kind of
        :data:`gearlever.cams.FOLLOWERS`; default ``translating-roller`` for a
        displacement law, ``oscillating-roller`` for an angle law);
        ``centre`` ``[x, y]`` (the cam's pivot, default the origin);
        ``roller_radius``, ``offset``, ``arm``, ``pivot_distance`` (the
        follower's dimensions; defaults: a roller of a quarter of the stroke,
        for an oscillating follower an arm of 40 and a pivot 100 from the cam
        centre, in the law's units); ``base_radius`` (default: sized by
        :func:`gearlever.cams.size_base_radius`, the smallest base circle with
        a roller's pressure angle at most ``max_pressure_angle_deg``,
        default :data:`CAM_PRESSURE_DEG`, and no undercut); ``frames`` (one
        turn in equal steps), or ``angles_deg``, the cam's angle at each frame
        (a cam rigid on a link turns with it: the link's angle from its first
        frame; each frame is the nearest of :data:`CAM_POINTS` cam angles).

    Returns
    -------
    dict
        ``profile`` (the cam surface at the first frame, model coordinates),
        ``cam_angle_deg`` (the cam's turn at each frame: the page turns the
        profile about ``centre`` by it), ``s`` (the follower's output, law
        units, per frame), ``contact``, ``roller_centre`` (rollers),
        ``follower`` (the follower's body per frame: a polyline of points),
        ``face`` (flat followers: the face segment per frame), ``pivot``
        (oscillating followers), the dimensions, ``pressure_angle_deg`` per
        frame and its maximum, ``undercut``, ``message`` and ``cam_toml``,
        the CAM.toml text of this cam (:func:`gearlever.cams.cam_toml`, its
        pivot as ``[cam] centre``) that the bench saves beside the model.

    Notes
    -----
    The profile, the contact and the pressure angle are
    :func:`gearlever.cams.design_cam`'s (R. L. Norton, *Design of Machinery*,
    sec. 8.6): the cam turns counterclockwise by the input angle, the
    follower's guide (or pivot) is fixed.  The model file has no cam pair
    (the schema of :mod:`gearlever.mechanism.schema` has no cam-follower
    higher pair and the solver no contact constraint), so the cam and its
    follower are a mechanism of their own beside the linkage.

    Examples
    --------
    >>> c = cam({"example": "law_lift", "centre": [100, 0], "frames": 36})
    >>> c["follower_kind"], round(c["base_radius"], 3), len(c["s"]), c["s"][0]
    ('translating-roller', 30.019, 36, 0.0)
    """
    from gearlever.cams import FOLLOWERS, design_cam, size_base_radius

    if not isinstance(params, dict):
        raise WorkbenchError("the cam must be a JSON object with a law or an example")
    unknown = [k for k in params if k not in CAM_KEYS]
    if unknown:
        raise WorkbenchError(f"{str(unknown[0])[:40]}: not a parameter of a cam ({', '.join(CAM_KEYS)})")
    if "file" in params:
        if "law" in params or "example" in params:
            raise WorkbenchError("file: a CAM.toml text holds its law; give file, law or example, one")
        params = {**cam_file_params(params["file"]), **{k: v for k, v in params.items() if k != "file"}}
    angles = params.get("angles_deg")
    if angles is not None:
        if (
            not isinstance(angles, list)
            or not 2 <= len(angles) <= MAX_FRAMES
            or not all(not isinstance(a, bool) and isinstance(a, (int, float)) and math.isfinite(a) for a in angles)
            or not all(abs(a) <= 1e6 for a in angles)
        ):
            raise WorkbenchError(f"angles_deg must be a list of 2 to {MAX_FRAMES} finite angles of at most 1e6 deg")
        if "frames" in params:
            raise WorkbenchError("frames: give frames or angles_deg, not both")
        frames, points = len(angles), CAM_POINTS
        rows = np.rint(np.mod(np.radians(angles), 2 * np.pi) / (2 * np.pi) * points).astype(int) % points
    else:
        frames = points = _frames(params.get("frames", 360))
        rows = np.arange(frames)
    law = _cam_law(params)
    angle_law = law.output == "angle"
    default = "oscillating-roller" if angle_law else "translating-roller"
    kind = params.get("follower", default)
    if not isinstance(kind, str) or kind not in FOLLOWERS:
        raise WorkbenchError(f"follower must be one of {', '.join(FOLLOWERS)}, got {str(kind)[:40]!r}")
    fk = FOLLOWERS[kind]
    if (fk.law_output == "angle") != angle_law:
        raise WorkbenchError(f"follower: {kind} follows an {fk.law_output} law; this law's output is {law.output}")
    centre = _pair_xy(params, "centre")
    stroke = float(np.ptp(law.evaluate(np.linspace(0, 2 * np.pi, 721)).s))
    length = 40.0 if angle_law else stroke
    dims = {
        "roller_radius": _float(params, "roller_radius", length / 4 if fk.contact == "roller" else 0.0, 0.0, 1e6),
        "offset": _float(params, "offset", 0.0, -1e6, 1e6),
        "arm": _float(params, "arm", 40.0 if kind == "oscillating-roller" else None, 1e-9, 1e6),
        "pivot_distance": _float(params, "pivot_distance", 100.0 if angle_law else None, 1e-9, 1e6),
    }
    if fk.contact == "flat":
        dims["roller_radius"] = 0.0
    phi = _float(params, "max_pressure_angle_deg", CAM_PRESSURE_DEG, 1.0, 89.0)
    rb = _float(params, "base_radius", None, 1e-9, 1e6)
    try:
        sized = rb is None
        if sized:
            roller = fk.contact == "roller"
            bound = {"max_pressure_angle": math.radians(phi)} if roller else {"min_curvature_radius": 0.0}
            rb = size_base_radius(law, kind, **dims, **bound)
        c = design_cam(law, kind, base_radius=rb, points=points, **dims)
    except GearleverError as exc:  # the library names the command line's flags: the bench's fields instead
        raise WorkbenchError("cam: " + re.sub(r"--([a-z]+)-?([a-z]*)", _field_name, str(exc))) from None
    L = max(rb + stroke if not angle_law else dims["pivot_distance"], 1e-9)
    shift = np.asarray(centre)
    every = max(1, points // CAM_PROFILE)
    theta, s, contact = c.theta[rows], c.s[rows], c.contact[rows]
    out = {
        "follower_kind": kind,
        "law_output": law.output,
        "units": law.units,
        "centre": list(centre),
        "frames": frames,
        "base_radius": float(rb),
        "sized": sized,
        "roller_radius": dims["roller_radius"],
        "offset": dims["offset"],
        "arm": dims["arm"],
        "pivot_distance": dims["pivot_distance"],
        "stroke": math.degrees(stroke) if angle_law else stroke,
        "cam_angle_deg": _num(np.degrees(theta)),
        "s": _num(np.degrees(s) if angle_law else s),
        "profile": _xy(c.surface[::every] + shift, L),
        "contact": _xy(contact + shift, L),
        "pressure_angle_deg": _num(np.degrees(c.pressure_angle[rows])),
        "pressure_angle_max_deg": math.degrees(c.pressure_angle_max),
        "undercut": bool(c.undercut),
        "roller_centre": None,
        "face": None,
        "pivot": None,
    }
    up = np.array([0.0, 1.0])
    if fk.contact == "roller":
        q = fk.path(s, _follower_params(dims), rb)[0]
        out["roller_centre"] = _xy(q + shift, L)
        tip = q
    else:
        beta = fk.face(s, _follower_params(dims), rb)[0]
        n = np.stack([np.cos(beta), np.sin(beta)], axis=1)
        t = np.stack([-n[:, 1], n[:, 0]], axis=1)
        fp = fk.face_position(contact, beta, _follower_params(dims))
        ref = fk.face_position(contact + t, beta, _follower_params(dims)) - fp
        t = t * np.sign(ref)[:, None]  # along the face, the way the library measures the contact's place
        foot = contact - fp[:, None] * t
        margin = 0.15 * max(c.face_width, rb)
        lo, hi = c.face_contact_min - margin, c.face_contact_max + margin
        out["face"] = [_xy(foot + lo * t + shift, L), _xy(foot + hi * t + shift, L)]
        tip = foot
    if angle_law:
        pivot = np.array([dims["pivot_distance"], 0.0])
        out["pivot"] = list(_xy((pivot + shift)[None, :], L)[0])
        out["follower"] = [_xy(np.broadcast_to(pivot, tip.shape) + shift, L), _xy(tip + shift, L)]
    else:
        out["follower"] = [_xy(tip + shift, L), _xy(tip + rb * up + shift, L)]
    how = (
        f"sized for a pressure angle of at most {phi:g} deg and no undercut"
        if sized and fk.contact == "roller"
        else ("sized for no undercut" if sized else "as given")
    )
    u = f" {law.units}" if law.units and not angle_law else ""
    out["message"] = (
        f"cam: {kind} follower, base radius {rb:.4g}{u} ({how}); pressure angle at most "
        f"{math.degrees(c.pressure_angle_max):.3g} deg; drawn as its own mechanism (the model file has no cam pair)"
    )
    from gearlever.cams import cam_toml

    report = {"pressure_angle_max_deg": math.degrees(c.pressure_angle_max), "undercut": bool(c.undercut)}
    out["cam_toml"] = cam_toml(c, law.to_dict(), report, "Written by the gearlever workbench", centre=centre)
    return out


def cam_file_params(text) -> dict:
    """The cam parameters of a CAM.toml text (law, follower, dimensions, ``centre``), checked by the library.

    The text is read by :func:`gearlever.cams.load_cam` (every refusal of the
    CAM format, named) and :func:`gearlever.cams.cam_centre`; the answer is
    what :func:`cam` takes: ``law`` (the text itself, which reads as a
    LAW.toml), ``follower``, ``base_radius`` and the follower's dimensions
    given in the file, and ``centre``.

    >>> c = cam({"example": "law_lift", "centre": [100, 0], "frames": 36})
    >>> p = cam_file_params(c["cam_toml"])
    >>> p["follower"], p["centre"], round(p["base_radius"], 3)
    ('translating-roller', [100.0, 0.0], 30.019)
    """
    import tempfile
    from pathlib import Path

    from gearlever.cams import cam_centre, load_cam

    if not isinstance(text, str) or not 0 < len(text) <= 100_000:
        raise WorkbenchError("file must be the TOML text of a CAM file ([cam] and [law], at most 100000 characters)")
    d = _toml(text, "file")
    if isinstance(d.get("law"), dict) and "samples" in d["law"]:
        raise WorkbenchError("file: the law's samples name a CSV file; the bench takes [[law.segment]] tables")
    with tempfile.TemporaryDirectory() as tmp:
        p = Path(tmp) / "cam.toml"
        p.write_text(text, encoding="utf-8")
        try:
            load_cam(p, points=360)
            centre = cam_centre(p)
        except GearleverError as exc:
            raise WorkbenchError(
                "file: " + str(exc).replace(str(p) + ": ", "").replace(str(p), "the CAM file")
            ) from None
    table = d["cam"]
    out = {"law": text, "follower": table["follower"], "centre": list(centre)}
    for key in ("base_radius", "roller_radius", "offset", "arm", "pivot_distance"):
        if key in table:
            out[key] = float(table[key])
    return out


def _field_name(m) -> str:
    return m.group(1) + ("_" + m.group(2) if m.group(2) else "")


def _follower_params(dims: dict):
    from gearlever.cams import FollowerParams

    return FollowerParams(dims["roller_radius"], dims["offset"], dims["arm"], dims["pivot_distance"])


def _pair_xy(params: dict, key: str) -> tuple:
    v = params.get(key, [0.0, 0.0])
    if (
        not isinstance(v, list)
        or len(v) != 2
        or not all(not isinstance(c, bool) and isinstance(c, (int, float)) and math.isfinite(c) for c in v)
        or not all(abs(c) <= 1e9 for c in v)
    ):
        raise WorkbenchError(f"{key} must be [x, y], two finite numbers of at most 1e9 in size, got {v!r}"[:200])
    return float(v[0]), float(v[1])


# --------------------------------------------------------------------------- examples
def examples() -> list:
    """The shipped example models that have ``[links]``: ``[{"name", "title"}]``."""
    out = []
    for name, _text, d in _shipped_examples():
        if "links" not in d:
            continue
        title = d.get("mechanism", {}).get("name") if isinstance(d.get("mechanism"), dict) else None
        out.append({"name": name, "title": str(title or name)})
    return out


def example(name: str) -> str:
    """The TOML text of the shipped example ``name`` (one of :func:`examples`)."""
    from importlib import resources

    names = [e["name"] for e in examples()]
    if name not in names:
        raise WorkbenchError(f"example: unknown example {name!r} (examples: {', '.join(names)})")
    return resources.files("gearlever.data").joinpath("examples", f"{name}.toml").read_text(encoding="utf-8")


# --------------------------------------------------------------------------- synthesis jobs
def _int(params: dict, key: str, default: int, lo: int, hi: int) -> int:
    v = params.get(key, default)
    if isinstance(v, bool) or not isinstance(v, int) or not lo <= v <= hi:
        raise WorkbenchError(f"{key} must be an integer from {lo} to {hi}, got {v!r}")
    return v


def _float(params: dict, key: str, default, lo: float, hi: float):
    v = params.get(key, default)
    if v is None:
        return None
    if isinstance(v, bool) or not isinstance(v, (int, float)) or not (math.isfinite(v) and lo <= v <= hi):
        raise WorkbenchError(f"{key} must be a number from {lo:g} to {hi:g}, got {v!r}")
    return float(v)


def _points(params: dict, key: str, lo: int, hi: int, width: int = 2) -> np.ndarray:
    v = params.get(key)
    if not isinstance(v, list) or not lo <= len(v) <= hi:
        raise WorkbenchError(f"{key} must be a list of {lo} to {hi} points, got {_kind(v)}")
    for i, p in enumerate(v):
        if (
            not isinstance(p, list)
            or len(p) != width
            or not all(not isinstance(c, bool) and isinstance(c, (int, float)) and math.isfinite(c) for c in p)
            or not all(abs(c) <= 1e9 for c in p)
        ):
            raise WorkbenchError(f"{key}[{i}] must be {width} finite numbers of at most 1e9 in size, got {p!r}")
    return np.array(v, dtype=float)


def _kind(v) -> str:
    return f"{len(v)} items" if isinstance(v, list) else type(v).__name__


def _pair(params: dict, key: str, default=None) -> tuple:
    v = params.get(key, default)
    if (
        not isinstance(v, list)
        or len(v) != 2
        or not all(not isinstance(c, bool) and isinstance(c, (int, float)) and math.isfinite(c) for c in v)
        or not all(abs(c) <= 1e6 for c in v)
        or v[0] == v[1]
    ):
        raise WorkbenchError(f"{key} must be two different finite numbers [from, to] of at most 1e6, got {v!r}")
    return float(v[0]), float(v[1])


_JOB_KEYS = {
    "path": ("target", "budget", "seed", "type"),
    "curve": ("target", "time", "seed", "budget", "max_joints", "designs"),
    "function": ("expr", "x_range", "input_range_deg", "output_range_deg", "points", "type"),
    "motion": ("poses", "fixed_pivots", "moving_pivots"),
    "law": ("law", "type", "budget", "seed"),
}


def check_job(params) -> dict:
    """A job's parameters checked before it starts: ``{"kind": ..., ...}`` with defaults filled in.

    Raises :class:`WorkbenchError` naming the field, so that a bad job is a 400
    at once, never a failed job later.

    >>> check_job({"kind": "path", "target": [[0, 0], [1, 1], [2, 0]]})["budget"]
    2000
    """
    if not isinstance(params, dict):
        raise WorkbenchError("the job must be a JSON object with a kind")
    kind = params.get("kind")
    if kind not in JOB_KINDS:
        raise WorkbenchError(f"kind must be one of {', '.join(JOB_KINDS)}, got {kind!r}")
    unknown = [k for k in params if k != "kind" and k not in _JOB_KEYS[kind]]
    if unknown:
        raise WorkbenchError(f"{unknown[0]}: not a parameter of a {kind} job ({', '.join(_JOB_KEYS[kind])})")
    out: dict = {"kind": kind}
    if kind == "path":
        from gearlever.synthesis.path import MAX_BUDGET

        out["target"] = _points(params, "target", 3, MAX_TARGET)
        out["budget"] = _int(params, "budget", 2000, 480, min(MAX_BUDGET, 200_000))
        out["seed"] = _int(params, "seed", 0, 0, 2**31 - 1)
        out["type"] = _type(params, "path", "fourbar", auto=True)
    elif kind == "curve":
        out["target"] = _points(params, "target", 3, MAX_TARGET)
        out["time"] = _float(params, "time", 20.0, 1.0, 600.0)
        out["budget"] = _int(params, "budget", 20_000, 1000, 200_000) if "budget" in params else None
        out["seed"] = _int(params, "seed", 0, 0, 2**31 - 1)
        out["max_joints"] = _int(params, "max_joints", 8, 4, 20)
        out["designs"] = _int(params, "designs", MAX_RESULTS, 1, MAX_RESULTS)
        if out["budget"] is not None:
            out["time"] = None
    elif kind == "function":
        from gearlever.synthesis.expr import parse_expression

        expr = params.get("expr")
        if not isinstance(expr, str) or not 0 < len(expr) <= 200:
            raise WorkbenchError(f"expr must be a formula in x of 1 to 200 characters, got {expr!r}")
        try:
            parse_expression(expr)
        except GearleverError as exc:
            raise WorkbenchError(f"expr: {exc}") from None
        out["expr"] = expr
        out["x_range"] = _pair(params, "x_range")
        out["input_range_deg"] = _pair(params, "input_range_deg")
        out["output_range_deg"] = _pair(params, "output_range_deg")
        out["points"] = _int(params, "points", 3, 3, 50)
        out["type"] = _type(params, "function", "fourbar")
    elif kind == "motion":
        poses = _points(params, "poses", 3, 5, width=3)
        out["poses"] = poses
        for key in ("fixed_pivots", "moving_pivots"):
            if key in params and params[key] is not None:
                out[key] = [tuple(p) for p in _points(params, key, 2, 2)]
        if len(poses) == 3 and ("fixed_pivots" in out) == ("moving_pivots" in out):
            raise WorkbenchError("poses: three poses need fixed_pivots or moving_pivots (one of them)")
        if len(poses) > 3 and ("fixed_pivots" in out or "moving_pivots" in out):
            raise WorkbenchError("fixed_pivots/moving_pivots are for three poses only")
    else:
        from gearlever.synthesis.law.driver import DEFAULT_BUDGET, MAX_BUDGET

        law = params.get("law")
        if not isinstance(law, str) or not 0 < len(law) <= 100_000:
            raise WorkbenchError("law must be the TOML text of a [law] table (at most 100000 characters)")
        out["law_obj"] = _law(law)
        out["type"] = _type(params, "law", "auto", auto=True)
        out["budget"] = _int(params, "budget", DEFAULT_BUDGET, 1, MAX_BUDGET)
        out["seed"] = _int(params, "seed", 0, 0, 2**31 - 1)
    return out


def _type(params: dict, family: str, default: str, auto: bool = False) -> str:
    """The job's ``type``: a kind of ``family`` in the one registry of synthesis kinds (or ``auto``)."""
    from gearlever.synthesis.registry import names

    known = names(family) + (("auto",) if auto else ())
    v = params.get("type", default)
    if v not in known:
        raise WorkbenchError(f"type must be one of {', '.join(known)}, got {v!r}")
    return v


def _law(text: str):
    """A :class:`~gearlever.laws.MotionLaw` from a LAW.toml text (segments only: samples name a file)."""
    import tempfile
    from pathlib import Path

    from gearlever.laws import load_law

    d = _toml(text, "law")
    if isinstance(d.get("law"), dict) and "samples" in d["law"]:
        raise WorkbenchError("law: samples name a CSV file; the bench takes [[law.segment]] tables")
    with tempfile.TemporaryDirectory() as tmp:
        p = Path(tmp) / "law.toml"
        p.write_text(text, encoding="utf-8")
        try:
            return load_law(p)
        except GearleverError as exc:
            raise WorkbenchError(str(exc).replace(str(p), "law")) from None


def _result(rank: int, score: dict, model: dict, comment: str) -> dict:
    from gearlever.mechanism.modelfile import model_toml

    return {
        "rank": rank,
        "score": _jsonable({k: float(v) if isinstance(v, np.floating) else v for k, v in score.items()}),
        "model": model_toml(model, comment),
    }


def _problem(params: dict) -> tuple:
    """``(family, kind name, args, kwargs)`` of a checked job: what the family's driver is called with.

    The kind's name is the job's ``type`` (``auto``: every kind of the family,
    the driver's choice); a motion job's kind is told by its number of poses.
    """
    family = params["kind"]
    if family == "path":
        return family, params["type"], (params["target"],), {}
    if family == "curve":
        kw = {"max_joints": params["max_joints"], "designs": params["designs"], "time_limit": params["time"]}
        return family, "topology", (params["target"],), kw
    if family == "function":
        from gearlever.synthesis.function import function_targets

        slider = params["type"] == "slider-crank"
        orange = params["output_range_deg"] if slider else np.radians(params["output_range_deg"])
        tg = function_targets(
            params["expr"], params["x_range"], np.radians(params["input_range_deg"]), orange, params["points"]
        )
        kw = {"target_at": tg.target_at, "input_range": tg.input_range}
        return family, params["type"], (tg.input_angle, tg.target), kw
    if family == "motion":
        poses = params["poses"]
        kw = {k: params.get(k) for k in ("fixed_pivots", "moving_pivots")}
        return family, f"{len(poses)}-poses", (poses[:, :2], np.radians(poses[:, 2])), kw
    return family, params["type"], (params["law_obj"],), {}


def _designs(family: str, res, params: dict) -> list:
    """``[(score, model dict, comment)]`` of a family's result, best first (what the bench lists)."""
    if family == "path":
        if not res.feasible:
            raise WorkbenchError("target: no buildable linkage passes near these points; draw them again")
        comment = f"gearlever workbench: path synthesis ({res.kind}, seed {params['seed']})"
        return [({"objective": res.objective, "kind": res.kind}, res.model(), comment)]
    if family == "curve":
        from gearlever.synthesis.curve.model import linkage_model

        if not len(res.designs):
            raise WorkbenchError(
                "target: no linkage was found within the search's time; give it more time (time) or draw again"
            )
        return [
            (
                {"distance": float(d), "material": float(mt), "joints": lk.n_joints, "links": len(lk.edges)},
                linkage_model(lk),
                f"gearlever workbench: curve synthesis, design {n} (distance {d:.6g}, material {mt:.6g})",
            )
            for n, (lk, d, mt) in enumerate(zip(res.designs, res.error, res.material), 1)
        ]
    if family == "function":
        if res.defect:
            raise WorkbenchError(f"function: refused, {res.defect}; change the ranges or the points")
        score = {"structural_error_max": res.structural_error_max, "grashof": getattr(res, "grashof", "")}
        return [(score, res.model, f"gearlever workbench: function y = {params['expr']}")]
    if family == "motion":
        good = [s for s in res.solutions if not s.defect] or list(res.solutions)
        if not good:
            raise WorkbenchError("poses: no four-bar guides the coupler through these poses")
        return [
            (
                {"residual": s.residual, "grashof": s.grashof, "defect": s.defect},
                s.model,
                f"gearlever workbench: motion synthesis ({res.method}), solution {n}",
            )
            for n, s in enumerate(good, 1)
        ]
    return [({"kind": res.kind}, res.model(), f"gearlever workbench: law synthesis ({res.kind})")]


def _driver(family: str, name: str):
    """The registered kind ``name`` of ``family`` (:mod:`gearlever.synthesis.registry`), ``(call, searched)``.

    ``auto`` is every kind of the family: the family's driver with ``kind="auto"``.
    """
    import importlib

    from gearlever.synthesis import registry

    if name == "auto":
        k = registry.kinds(family)[0]
        module, _, fn = k.entry.partition(":")
        return functools.partial(getattr(importlib.import_module(module), fn), **{k.kind_arg: "auto"}), k.searched
    k = registry.get(family, name)
    return k.synthesize, k.searched


def run_job(params: dict, progress=None, cancelled=None, scheduler: str | None = None) -> list:
    """Run a synthesis job checked by :func:`check_job`; answer its ranked designs.

    The job's family and kind are looked up in the one registry of synthesis
    kinds (:func:`gearlever.synthesis.registry.kinds`): its driver is called
    once, with the seed, budget, scheduler and progress of a searched kind,
    and its designs are wrapped as model texts.

    Parameters
    ----------
    params : dict
        From :func:`check_job`.
    progress : callable, optional
        ``progress(stage, done, total)``.
    cancelled : callable, optional
        True once the job is to stop: checked at every progress report (the
        library's searches also stop at their next generation,
        :data:`gearlever.synthesis._search.STOP`); raises :class:`Cancelled`.
    scheduler : str, optional
        Address of a dask.distributed scheduler for the searches (path, curve, law).

    Returns
    -------
    list of dict
        ``{"rank", "score", "model"}`` best first; ``model`` is the TOML text.
    """
    from gearlever.synthesis._search import STOP

    def tick(stage, done, total):
        if cancelled is not None and cancelled():
            STOP.set()
            raise Cancelled()
        if progress is not None:
            progress(str(stage), int(done), int(total))

    family = params["kind"]
    tick("start", 0, 1)
    try:
        name_, args, kw = _problem(params)[1:]
        call, searched = _driver(family, name_)
        if searched:
            kw.update(seed=params["seed"], budget=params["budget"], scheduler=scheduler, progress=tick, workers=1)
        else:
            tick("synthesis", 0, 1)
        res = call(*args, **kw)
        tick("done", 1, 1)
        designs = _designs(family, res, params)[:MAX_RESULTS]
        return [_result(n, score, model, comment) for n, (score, model, comment) in enumerate(designs, 1)]
    except GearleverError as exc:
        if isinstance(exc, WorkbenchError):
            raise
        raise WorkbenchError(f"{family}: {exc}") from None
    finally:
        if cancelled is not None and cancelled():
            STOP.set()
