// The gearlever workbench page: draw a mechanism, send it to the local server, draw the cycle it answers.
// The page never computes motion: every pose, velocity, plot value and instant centre comes from
// POST /api/solve (the whole cycle at once, so playing, scrubbing and dragging the input need no round trip).
// Model names are shown with textContent and setAttribute only; the model text is never evaluated.

import * as api from "./api.js";
import * as M from "./model.js";
import { drawPlot, el } from "./plots.js";
import { sharedFromFragment, shareUrl } from "./share.js";

const FRAMES = 360;
const POSE_PX = 36; // drawn length of a pose's direction
const HIT_PX = 8;
const $ = (sel) => document.querySelector(sel);
const $$ = (sel) => [...document.querySelectorAll(sel)];

const S = {
  ready: false,
  model: M.EMPTY(),
  toml: "",
  tool: "select",
  view: { s: 4, tx: 200, ty: 300 },
  frames: null, // the last /api/solve answer
  stale: false, // the model changed since those frames
  frame: 0,
  playing: false,
  speed: 1,
  undo: [],
  redo: [],
  selected: null, // {kind: "joint"|"link", name}
  draftLink: null, // {first: joint} or {link: name} while the link tool grows a link
  lastGear: null,
  curve: [],
  cam: null, // {centre: [x, y], law: "example:NAME" | "file:NAME", follower}: a cam placed with the cam tool
  camFrames: null, // the last /api/cam answer for S.cam
  camRevision: -1,
  camError: "",
  dof: null,
  redundant: null,
  inputs: [],
  message: "",
  error: "",
  job: null,
  file: { name: null, etag: null },
  pending: 0,
  revision: 0,
  forces: null, // the last /api/forces answer, for S.forcesRevision
  forcesRevision: -1,
  rpm: 60,
};

// ---------------------------------------------------------------- view transform

const svg = () => $("#canvas");
const toPx = (x, y) => [S.view.tx + S.view.s * x, S.view.ty - S.view.s * y];
const toModel = (px, py) => [(px - S.view.tx) / S.view.s, (S.view.ty - py) / S.view.s];

function eventPx(ev) {
  const r = svg().getBoundingClientRect();
  return [ev.clientX - r.left, ev.clientY - r.top];
}

function gridStep() {
  const raw = 40 / S.view.s;
  const p = 10 ** Math.floor(Math.log10(raw));
  for (const m of [1, 2, 5, 10]) if (m * p >= raw) return m * p;
  return 10 * p;
}

function snap([x, y]) {
  if (!$("#snap").checked) return [x, y];
  const g = gridStep() / 2;
  const r = (v) => Number((Math.round(v / g) * g).toPrecision(12));
  return [r(x), r(y)];
}

function fit() {
  const r = svg().getBoundingClientRect();
  let box = null;
  const cams = S.camFrames && S.cam ? [...S.camFrames.profile.filter(Boolean), ...S.camFrames.follower.flat().filter(Boolean)] : [];
  if (S.frames && S.frames.extent && S.frames.extent.every(Number.isFinite)) {
    box = [...S.frames.extent];
    if (cams.length) {
      // the cam turns: the circle of its profile about its pivot, and its follower
      const [cx, cy] = S.camFrames.centre;
      const R = Math.max(...S.camFrames.profile.filter(Boolean).map(([x, y]) => Math.hypot(x - cx, y - cy)));
      for (const [x, y] of [...cams, [cx - R, cy - R], [cx + R, cy + R]]) {
        box = [Math.min(box[0], x), Math.min(box[1], y), Math.max(box[2], x), Math.max(box[3], y)];
      }
    }
  } else {
    const pts = Object.values(S.model.points || {});
    pts.push(...cams);
    if (pts.length) {
      const xs = pts.map((p) => p[0]);
      const ys = pts.map((p) => p[1]);
      box = [Math.min(...xs), Math.min(...ys), Math.max(...xs), Math.max(...ys)];
    }
  }
  if (!box) {
    S.view = { s: 4, tx: r.width * 0.3, ty: r.height * 0.65 };
    return;
  }
  let [x0, y0, x1, y1] = box;
  const span = Math.max(x1 - x0, y1 - y0, 1e-9);
  if (x1 - x0 < span * 0.2) { x0 -= span * 0.1; x1 += span * 0.1; }
  if (y1 - y0 < span * 0.2) { y0 -= span * 0.1; y1 += span * 0.1; }
  const m = 40;
  const s = Math.min((r.width - 2 * m) / (x1 - x0), (r.height - 2 * m) / (y1 - y0));
  S.view.s = s > 0 && Number.isFinite(s) ? s : 4;
  S.view.tx = r.width / 2 - S.view.s * (x0 + x1) / 2;
  S.view.ty = r.height / 2 + S.view.s * (y0 + y1) / 2;
}

// ---------------------------------------------------------------- what is drawn where

/** The motion poses of the model ([[poses]]: point, angle_deg) as [x, y, angle_deg]. */
function poses() {
  return (S.model.poses || []).map((p) => [p.point[0], p.point[1], p.angle_deg]);
}

/** A pose as the model keeps it: the pointer's place to 6 significant digits (what a user would type). */
function setPose(k, [x, y, a]) {
  const tidy = (v) => Number(Number(v).toPrecision(6));
  S.model.poses[k] = { point: [tidy(x), tidy(y)], angle_deg: tidy(a) };
}

/** Frames of the cycle drawn: the mechanism's, else the cam's when a cam is alone on the bench. */
function frameCount() {
  if (S.frames && !S.stale) return S.frames.frames;
  return S.camFrames && S.camRevision === S.revision ? S.camFrames.frames : 0;
}

function poseIndex() {
  if (!S.frames || S.stale || !S.frames.frames) return null;
  return S.frame;
}

/** The drawn position of a point: the solved pose at the current frame (the last closed one when it does not
 * assemble there), else the sketch. */
function pos(name) {
  const i = poseIndex();
  if (i !== null) {
    const series = S.frames.point && S.frames.point[name];
    if (series) {
      const p = series[i] || series[lastClosed(i)];
      if (p && p[0] !== null) return p;
    }
  }
  return (S.model.points || {})[name] || null;
}

function lastClosed(i) {
  const closed = S.frames.closed || [];
  for (let k = 0; k < closed.length; k++) {
    const j = (i - k + closed.length) % closed.length;
    if (closed[j]) return j;
  }
  return 0;
}

function inputLinks() {
  return (S.model.inputs || []).map((i) => i.link).filter(Boolean);
}

function jointsAt(px, py) {
  let best = null;
  let bestD = HIT_PX;
  for (const name of Object.keys(S.model.points || {})) {
    const p = pos(name);
    if (!p) continue;
    const [qx, qy] = toPx(p[0], p[1]);
    const d = Math.hypot(qx - px, qy - py);
    if (d <= bestD) { best = name; bestD = d; }
  }
  return best;
}

function linkAt(px, py) {
  let best = null;
  let bestD = HIT_PX;
  for (const [name, pts] of Object.entries(S.model.links || {})) {
    if (name === "ground") continue;
    for (let k = 0; k < pts.length; k++) {
      for (let j = k + 1; j < pts.length; j++) {
        const a = pos(pts[k]);
        const b = pos(pts[j]);
        if (!a || !b) continue;
        const d = segDist([px, py], toPx(...a), toPx(...b));
        if (d <= bestD) { best = name; bestD = d; }
      }
    }
  }
  return best;
}

function segDist(p, a, b) {
  const [dx, dy] = [b[0] - a[0], b[1] - a[1]];
  const L2 = dx * dx + dy * dy;
  const t = L2 ? Math.max(0, Math.min(1, ((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / L2)) : 0;
  return Math.hypot(p[0] - a[0] - t * dx, p[1] - a[1] - t * dy);
}

// ---------------------------------------------------------------- drawing

function clear(g) {
  while (g.firstChild) g.removeChild(g.firstChild);
  return g;
}

function ensureDefs() {
  if ($("#canvas defs")) return;
  const defs = el("defs");
  svg().insertBefore(defs, svg().firstChild);
  for (const [id, color] of [["arrow-v", "#2e7d32"], ["arrow-a", "#b3261e"], ["arrow-f", "#5e35b1"], ["arrow-p", "#00695c"], ["arrow-l", "#e65100"]]) {
    const m = el("marker", { id, viewBox: "0 0 10 10", refX: 9, refY: 5, markerWidth: 7, markerHeight: 7, orient: "auto-start-reverse" }, defs);
    el("path", { d: "M0,0 L10,5 L0,10 z", fill: color }, m);
  }
}

function drawGrid() {
  const g = clear($("#grid"));
  const r = svg().getBoundingClientRect();
  const step = gridStep();
  const [x0, y1] = toModel(0, 0);
  const [x1, y0] = toModel(r.width, r.height);
  const n = (x1 - x0) / step + (y1 - y0) / step;
  if (!(n < 400)) return;
  for (let x = Math.ceil(x0 / step) * step; x <= x1; x += step) {
    const [px] = toPx(x, 0);
    el("line", { x1: px, y1: 0, x2: px, y2: r.height, class: Math.abs(x) < step / 2 ? "axis" : "gridline" }, g);
  }
  for (let y = Math.ceil(y0 / step) * step; y <= y1; y += step) {
    const [, py] = toPx(0, y);
    el("line", { x1: 0, y1: py, x2: r.width, y2: py, class: Math.abs(y) < step / 2 ? "axis" : "gridline" }, g);
  }
}

const PALETTE = ["#1f5fa8", "#c77700", "#2e7d32", "#8e44ad", "#00838f", "#6d4c41", "#ad1457", "#455a64"];

function render() {
  ensureDefs();
  drawGrid();
  const model = S.model;
  const i = poseIndex();
  const links = clear($("#layer-links"));
  const joints = clear($("#layer-joints"));
  const labels = clear($("#layer-labels"));
  const paths = clear($("#layer-paths"));
  const arrows = clear($("#layer-arrows"));
  const centres = clear($("#layer-centres"));
  const curve = clear($("#layer-curve"));
  const inputs = inputLinks();
  const broken = i !== null && S.frames.closed && !S.frames.closed[i];
  svg().classList.toggle("broken", !!broken);

  // point paths over the whole cycle
  if (S.frames && !S.stale && $("#show-paths").checked) {
    const ground = new Set(model.links?.ground || []);
    for (const [name, series] of Object.entries(S.frames.point || {})) {
      if (ground.has(name)) continue;
      let d = "";
      let pen = false;
      for (const p of series) {
        if (!p || p[0] === null) { pen = false; continue; }
        const [x, y] = toPx(p[0], p[1]);
        d += `${pen ? "L" : "M"}${x.toFixed(1)},${y.toFixed(1)}`;
        pen = true;
      }
      if (d) el("path", { d, class: "path", "data-path": name }, paths);
    }
  }
  // the target curve drawn with the curve tool
  if (S.curve.length > 1) {
    el("polyline", { points: S.curve.map((p) => toPx(...p).map((v) => v.toFixed(1)).join(",")).join(" "), class: "target-curve" }, curve);
  }
  // motion poses: the coupler point and the coupler's direction
  poses().forEach(([x, y, a], k) => {
    const [px, py] = toPx(x, y);
    const r = (a * Math.PI) / 180;
    const grp = el("g", { class: "pose", "data-pose": k }, curve);
    el("line", { x1: px, y1: py, x2: px + POSE_PX * Math.cos(r), y2: py - POSE_PX * Math.sin(r), class: "pose-dir", "marker-end": "url(#arrow-p)" }, grp);
    el("circle", { cx: px, cy: py, r: 5, class: "pose-at" }, grp);
    const t = el("text", { x: px - 14, y: py - 8, class: "pose-label" }, grp);
    t.textContent = String(k + 1);
  });
  // ground hatching between ground pivots
  const groundPts = (model.links?.ground || []).map(pos).filter(Boolean);
  if (groundPts.length > 1) {
    el("polyline", { points: groundPts.map((p) => toPx(...p).join(",")).join(" "), class: "ground-line" }, links);
  }
  // gears (pitch circles from the server when solved, else from the teeth)
  const module = Number(model.mechanism?.module) || 1;
  for (const [gname, g] of Object.entries(model.gears || {})) {
    const c = pos(g.centre);
    if (!c) continue;
    const served = S.frames && !S.stale && (S.frames.gears || []).find((x) => x.name === gname);
    const radius = served ? served.radius : (module * g.teeth) / 2;
    const [cx, cy] = toPx(...c);
    const grp = el("g", { class: "gear-g", "data-gear": gname }, links);
    el("circle", { cx, cy, r: Math.max(2, radius * S.view.s), class: g.internal ? "gear internal" : "gear" }, grp);
    const ang = (i !== null && S.frames.angle_deg && S.frames.angle_deg[g.link]) ? S.frames.angle_deg[g.link][i] - S.frames.angle_deg[g.link][0] : 0;
    const a = ((ang || 0) * Math.PI) / 180;
    el("line", { x1: cx, y1: cy, x2: cx + radius * S.view.s * Math.cos(a), y2: cy - radius * S.view.s * Math.sin(a), class: "gear-mark" }, grp);
  }
  // the cam and its follower (their own mechanism, from POST /api/cam)
  if (S.cam && S.camFrames && S.camRevision === S.revision) drawCam(links, S.frame % S.camFrames.frames);
  // links
  let k = 0;
  for (const [name, pts] of Object.entries(model.links || {})) {
    if (name === "ground") continue;
    const color = PALETTE[k++ % PALETTE.length];
    const xy = pts.map(pos).filter(Boolean).map((p) => toPx(...p));
    const cls = ["link"];
    if (inputs.includes(name)) cls.push("input");
    if (S.selected?.kind === "link" && S.selected.name === name) cls.push("selected");
    if (S.draftLink?.link === name) cls.push("draft");
    const grp = el("g", { class: cls.join(" "), "data-link": name }, links);
    if (xy.length === 2) {
      el("line", { x1: xy[0][0], y1: xy[0][1], x2: xy[1][0], y2: xy[1][1], class: "link-body", stroke: color }, grp);
    } else if (xy.length > 2) {
      el("polygon", { points: xy.map((p) => p.join(",")).join(" "), class: "link-body", stroke: color, fill: color }, grp);
    } else if (xy.length === 1) {
      el("rect", { x: xy[0][0] - 12, y: xy[0][1] - 8, width: 24, height: 16, class: "block", fill: color }, grp);
    }
  }
  // sliders: the guide through the sliding point
  for (const s of model.sliders || []) {
    const p = pos(s.point);
    if (!p || !s.direction) continue;
    const [ux, uy] = s.direction;
    const n = Math.hypot(ux, uy) || 1;
    const L = 2000;
    const sk = model.points[s.point];
    const a = toPx(sk[0] - (ux / n) * L, sk[1] - (uy / n) * L);
    const b = toPx(sk[0] + (ux / n) * L, sk[1] + (uy / n) * L);
    if (s.on === "ground") el("line", { x1: a[0], y1: a[1], x2: b[0], y2: b[1], class: "guide", "data-slider": s.name || s.link }, links);
  }
  // joints
  const ground = new Set(model.links?.ground || []);
  const carriers = {};
  for (const [l, pts] of Object.entries(model.links || {})) for (const p of pts) (carriers[p] ||= []).push(l);
  for (const name of Object.keys(model.points || {})) {
    const p = pos(name);
    if (!p) continue;
    const [x, y] = toPx(...p);
    const cls = ["joint"];
    const n = (carriers[name] || []).length;
    if (ground.has(name)) cls.push("ground");
    else if (n === 1) cls.push("poi");
    else if (n === 0) cls.push("free");
    if (S.selected?.kind === "joint" && S.selected.name === name) cls.push("selected");
    if (S.draftLink?.first === name) cls.push("draft");
    const grp = el("g", { class: cls.join(" "), "data-joint": name }, joints);
    if (ground.has(name)) {
      el("path", { d: `M${x},${y} l-9,13 h18 z`, class: "ground-mark" }, grp);
      for (let h = -9; h <= 9; h += 4.5) el("line", { x1: x + h, y1: y + 13, x2: x + h - 4, y2: y + 18, class: "hatch" }, grp);
    }
    el("circle", { cx: x, cy: y, r: n === 1 && !ground.has(name) ? 3.5 : 5, class: "joint-dot" }, grp);
    const t = el("text", { x: x + 8, y: y - 8, class: "label" }, labels);
    t.textContent = name;
  }
  // velocity and acceleration arrows at the current frame
  if (i !== null) {
    for (const [kind, key, box] of [["velocity", "arrow-v", "#show-velocity"], ["acceleration", "arrow-a", "#show-acceleration"]]) {
      if (!$(box).checked || !S.frames[kind]) continue;
      const scale = arrowScale(kind);
      for (const [name, series] of Object.entries(S.frames[kind])) {
        const v = series[i];
        const p = pos(name);
        if (!v || v[0] === null || !p || ground.has(name)) continue;
        const [x, y] = toPx(...p);
        const [dx, dy] = [v[0] * scale, -v[1] * scale];
        if (Math.hypot(dx, dy) < 2) continue;
        el("line", { x1: x, y1: y, x2: x + dx, y2: y + dy, class: `arrow ${kind}`, "marker-end": `url(#${key})`, "data-arrow": `${kind}:${name}` }, arrows);
      }
    }
    if ($("#show-centres").checked && S.frames.centres) {
      for (const [key, series] of Object.entries(S.frames.centres)) {
        const c = series[i];
        if (!c || c[0] === null || !Number.isFinite(c[0])) continue;
        const [x, y] = toPx(...c);
        if (Math.abs(x) > 1e5 || Math.abs(y) > 1e5) continue;
        const g = el("g", { class: "centre", "data-centre": key }, centres);
        el("circle", { cx: x, cy: y, r: 3.5 }, g);
        const t = el("text", { x: x + 5, y: y + 12 }, g);
        t.textContent = key;
      }
    }
    if ($("#show-kennedy").checked && S.frames.kennedy) drawKennedy(centres, i);
    if ($("#show-forces").checked) drawForces(arrows, i);
    else $("#torque").textContent = "";
    drawLoads(arrows, labels);
  }
  $("#empty").hidden = Object.keys(model.points || {}).length > 0 || !!S.cam || poses().length > 0;
  updatePlayUi();
}

/** Kennedy's lines at frame i: the line through the three instant centres of each chosen triple of bodies
 * (the server answers the centres and the triples; a centre at infinity gives the line's direction). */
function drawKennedy(layer, i) {
  const f = S.frames;
  if (!f.closed[i]) return;
  const choice = $("#kennedy-triple").value;
  const triples = choice === "all" || choice === "" ? f.kennedy : [f.kennedy[Number(choice)]].filter(Boolean);
  const r = svg().getBoundingClientRect();
  const big = 4 * (r.width + r.height) / S.view.s;
  for (const keys of triples) {
    const fin = [];
    let dir = null;
    for (const key of keys) {
      const c = f.centres[key]?.[i];
      if (c && c[0] !== null) fin.push(c);
      else if (!dir) dir = centreDirection(key, i);
    }
    let a = null;
    let d = null;
    if (fin.length >= 2) {
      let best = -1;
      for (let u = 0; u < fin.length; u++) for (let w = u + 1; w < fin.length; w++) {
        const dd = Math.hypot(fin[w][0] - fin[u][0], fin[w][1] - fin[u][1]);
        if (dd > best) { best = dd; a = fin[u]; d = [(fin[w][0] - a[0]) / dd, (fin[w][1] - a[1]) / dd]; }
      }
      if (!(best > 0)) continue;
    } else if (fin.length === 1 && dir) { a = fin[0]; d = dir; }
    else continue;
    const [x1, y1] = toPx(a[0] - big * d[0], a[1] - big * d[1]);
    const [x2, y2] = toPx(a[0] + big * d[0], a[1] + big * d[1]);
    el("line", { x1, y1, x2, y2, class: "kennedy", "data-kennedy": keys.join(" ") }, layer);
  }
}

/** A unit as a user writes it: the CSV column's "N_mm" is shown "N·mm". */
const unitText = (u) => String(u || "").replace(/_/g, "·");

/** The arrows' scale (px per force unit): the largest pin reaction of the cycle and the largest load are 70 px. */
function forceScale() {
  const F = S.forces && S.forcesRevision === S.revision && !S.forces.error && $("#show-forces").checked ? S.forces : null;
  let max = 0;
  if (F) for (const series of Object.values(F.pin)) for (const v of series) if (v && v[0] !== null) max = Math.max(max, Math.hypot(v[0], v[1]));
  for (const l of S.model.loads || []) if (Array.isArray(l.force)) max = Math.max(max, Math.hypot(l.force[0], l.force[1]));
  return max > 0 ? 70 / max : 0;
}

/** Where a load's point is drawn now: a named point where it is solved, or a sketch location carried rigidly by
 * the load's link (moved with the link's first two points). */
function loadAt(load) {
  if (typeof load.point === "string") return pos(load.point);
  if (!Array.isArray(load.point)) return null;
  const [a, b] = S.model.links?.[load.link] || [];
  const [A0, B0, A, B] = [S.model.points[a], S.model.points[b], pos(a), pos(b)];
  if (!A0 || !A) return load.point;
  if (!B0 || !B) return [A[0] + load.point[0] - A0[0], A[1] + load.point[1] - A0[1]];
  const t = Math.atan2(B[1] - A[1], B[0] - A[0]) - Math.atan2(B0[1] - A0[1], B0[0] - A0[0]);
  const [dx, dy] = [load.point[0] - A0[0], load.point[1] - A0[1]];
  return [A[0] + Math.cos(t) * dx - Math.sin(t) * dy, A[1] + Math.sin(t) * dx + Math.cos(t) * dy];
}

/** The model's loads: each force an arrow ending at its point, on the pin forces' scale, labelled with its size
 * and unit (the forces' unit when the server answered them, else N, the model file's). */
function drawLoads(layer, labels) {
  const scale = forceScale();
  const unit = unitText(S.forces?.units?.force || "N");
  (S.model.loads || []).forEach((l, k) => {
    if (!Array.isArray(l.force)) return;
    const p = loadAt(l);
    const size = Math.hypot(l.force[0], l.force[1]);
    if (!p || !(size > 0) || !(scale > 0)) return;
    const [x, y] = toPx(...p);
    const [dx, dy] = [l.force[0] * scale, -l.force[1] * scale];
    el("line", { x1: x - dx, y1: y - dy, x2: x, y2: y, class: "arrow load", "marker-end": "url(#arrow-l)", "data-load": k }, layer);
    const t = el("text", { x: x - dx / 2 + 6, y: y - dy / 2, class: "load-label", "data-load-label": k }, labels);
    t.textContent = `${Number(size.toPrecision(4))} ${unit}`;
  });
}

/** Pin reactions at frame i as arrows at their pins (the force on the pin's second link), scaled so that the
 * largest of the cycle is 70 px (the loads on the same scale); the input torque in the play bar. Both from
 * POST /api/forces. */
function drawForces(layer, i) {
  const F = S.forces;
  const out = $("#torque");
  if (!F || S.forcesRevision !== S.revision) { out.textContent = ""; return; }
  if (F.error) { out.textContent = `forces: ${F.error}`; return; }
  const scale = forceScale();

  for (const [key, series] of Object.entries(F.pin)) {
    const v = series[i];
    const p = pos(key.split(":")[0]);
    if (!v || v[0] === null || !p) continue;
    const [x, y] = toPx(...p);
    const [dx, dy] = [v[0] * scale, -v[1] * scale];
    if (Math.hypot(dx, dy) < 2) continue;
    el("line", { x1: x, y1: y, x2: x + dx, y2: y + dy, class: "arrow force", "marker-end": "url(#arrow-f)", "data-force": key }, layer);
  }
  out.textContent = Object.entries(F.torque).map(([n, t]) => `T ${n} ${t[i] === null ? "–" : Number(t[i].toPrecision(4))} ${unitText(F.units.torque)}`).join(" · ");
}

/** The cam at frame i: its profile turned about its pivot by the cam's angle, the follower where the server
 * places it (roller, face, stem, arm), all from POST /api/cam. */
function drawCam(layer, i) {
  const C = S.camFrames;
  const [cx, cy] = C.centre;
  const a = (C.cam_angle_deg[i] * Math.PI) / 180;
  const [c, s] = [Math.cos(a), Math.sin(a)];
  const turn = ([x, y]) => toPx(cx + c * (x - cx) - s * (y - cy), cy + s * (x - cx) + c * (y - cy));
  const px = (p) => toPx(p[0], p[1]);
  const grp = el("g", { class: "cam", "data-cam": C.follower_kind }, layer);
  el("polygon", { points: C.profile.filter(Boolean).map((p) => turn(p).map((v) => v.toFixed(1)).join(",")).join(" "), class: "cam-profile" }, grp);
  const [hx, hy] = px([cx, cy]);
  const [mx, my] = turn([cx + 0.6 * C.base_radius, cy]);
  el("line", { x1: hx, y1: hy, x2: mx, y2: my, class: "cam-mark" }, grp);
  const pivots = [[hx, hy], ...(C.pivot ? [px(C.pivot)] : [])];
  for (const [x, y] of pivots) {
    el("path", { d: `M${x},${y} l-9,13 h18 z`, class: "ground-mark" }, grp);
    el("circle", { cx: x, cy: y, r: 4, class: "cam-hub" }, grp);
  }
  const f = el("g", { class: "follower", "data-follower": C.follower_kind }, layer);
  const [p0, p1] = [C.follower[0][i], C.follower[1][i]];
  if (p0 && p1) {
    const [a0, b0] = [px(p0), px(p1)];
    el("line", { x1: a0[0], y1: a0[1], x2: b0[0], y2: b0[1], class: "follower-body" }, f);
  }
  if (C.face && C.face[0][i] && C.face[1][i]) {
    const [a0, b0] = [px(C.face[0][i]), px(C.face[1][i])];
    el("line", { x1: a0[0], y1: a0[1], x2: b0[0], y2: b0[1], class: "follower-face" }, f);
  }
  if (C.roller_centre && C.roller_centre[i]) {
    const [x, y] = px(C.roller_centre[i]);
    el("circle", { cx: x, cy: y, r: Math.max(2, C.roller_radius * S.view.s), class: "follower-roller" }, f);
  }
}

/** The cam's law as the server takes it: a shipped example by name, or a workspace file's text. */
async function camLaw(spec) {
  if (spec.file) return { file: spec.file }; // a saved cam (CAM.toml): its law, follower and dimensions
  if (spec.lawText) return { law: spec.lawText };
  if (spec.law.startsWith("example:")) return { example: spec.law.slice("example:".length) };
  return { law: (await api.getFile(spec.law.slice("file:".length))).model };
}

/** Ask the server for the cam of S.cam (law, follower, pivot): sized and solved over one turn by the library;
 * kept for the revision it was asked for. */
async function syncCam() {
  if (!S.cam) { S.camFrames = null; S.camError = ""; S.camRevision = S.revision; return; }
  if (S.camRevision === S.revision) return;
  const revision = S.revision;
  const spec = S.cam;
  try {
    const body = { ...(await camLaw(spec)), centre: spec.centre };
    const turns = spec.on && S.frames && !S.stale ? S.frames.angle_deg?.[spec.on] : null;
    if (turns) {
      // rigid on its link: the cam's angle at each frame is the link's turn from the first frame (the sketch)
      let last = 0;
      body.angles_deg = turns.map((a) => (a === null ? last : (last = a - turns[0])));
    } else body.frames = FRAMES;
    if (spec.follower) body.follower = spec.follower;
    const answer = await api.post("/api/cam", body);
    if (revision !== S.revision) return;
    S.camFrames = answer;
    S.camError = "";
  } catch (e) {
    if (revision !== S.revision) return;
    S.camFrames = null;
    S.camError = e.message;
  }
  S.camRevision = revision;
  render();
  setStatus();
}

/** The link a cam on the ground pivot `joint` is rigid on (an input first), or null. */
function camCarrier(joint, model = S.model) {
  const onGround = joint && M.isGround(model, joint);
  const carriers = onGround ? Object.keys(model.links).filter((l) => l !== "ground" && model.links[l].includes(joint)) : [];
  const inputs = inputLinks();
  return carriers.find((l) => inputs.includes(l)) || carriers[0] || null;
}

/** The cam file saved beside a model file: NAME.toml (or NAME.links.json) -> NAME.cam.toml. */
function camFileOf(name) {
  return `${name.replace(/(\.cam)?(\.toml|\.links\.json)$/, "")}.cam.toml`;
}

/** The cam of a CAM.toml text, as the bench keeps it: its pivot (the file's [cam] centre) and follower read by the
 * server (the library's reader), the text itself sent back to draw it (exact dimensions); rigid on the link whose
 * ground pivot it sits on in `model`. */
async function camFromFile(text, model) {
  const c = await api.post("/api/cam", { file: text, frames: FRAMES });
  const joint = Object.keys(model.points || {}).find((j) => M.isGround(model, j)
    && Math.abs(model.points[j][0] - c.centre[0]) < 1e-9 && Math.abs(model.points[j][1] - c.centre[1]) < 1e-9);
  return { centre: c.centre, law: "cam", file: text, follower: c.follower_kind, on: joint ? camCarrier(joint, model) : null };
}

/** The cam tool's click: a cam on a ground pivot at xy, of the law and follower chosen beside the tool (one undo step). */
function placeCam(xy, joint) {
  const law = $("#cam-law").value;
  if (!law) { notify("choose the cam's law first (the list beside the cam tool)"); return Promise.resolve(); }
  // on a ground pivot of a moving link (an input first) the cam is rigid on that link and turns with it
  const on = camCarrier(joint);
  const before = snapshot();
  S.cam = { centre: xy, law, follower: $("#cam-follower").value || null, on };
  pushUndo(before);
  return changed();
}

/** A new law or follower chosen while a cam is on the bench: the cam is made again (one undo step). */
function camChoice() {
  if (!S.cam) return;
  const before = snapshot();
  const law = $("#cam-law").value;
  const next = { ...S.cam, law: law || S.cam.law, follower: $("#cam-follower").value || null };
  if (next.file) { next.lawText = law ? undefined : next.file; delete next.file; } // a saved cam's law, new follower
  if (law) delete next.lawText;
  S.cam = next;
  pushUndo(before);
  changed();
}

/** The law list beside the cam tool: the shipped laws and the workspace's files, asked again each time the cam
 * tool is chosen (a law saved since the page opened is listed); the choice is kept when it is still listed. */
let lawsAsked = null;
async function loadLaws() {
  const sel = $("#cam-law");
  const asked = (lawsAsked = Symbol("laws"));
  const [laws, listing] = await Promise.all([api.get("/api/laws"), api.get("/api/files")]);
  if (asked !== lawsAsked) return; // a newer refresh is under way
  const kept = sel.value;
  for (const g of [...sel.querySelectorAll("optgroup")]) g.remove();
  const add = (group, value, text) => {
    const o = document.createElement("option");
    o.value = value;
    o.textContent = text;
    group.appendChild(o);
  };
  const shipped = document.createElement("optgroup");
  shipped.label = "shipped laws";
  for (const e of laws.examples) add(shipped, `example:${e.name}`, `${e.name} (${e.output})`);
  sel.appendChild(shipped);
  const files = listing.files.filter((f) => f.name.endsWith(".toml"));
  if (files.length) {
    const ws = document.createElement("optgroup");
    ws.label = "workspace";
    for (const f of files) add(ws, `file:${f.name}`, f.name);
    sel.appendChild(ws);
  }
  sel.value = [...sel.options].some((o) => o.value === kept) ? kept : "";
}

let forcing = null;
/** Ask the server for the forces of the current model (masses, loads and gravity of the model, the input at
 * S.rpm); the answer is kept for the revision it was asked for. */
async function syncForces() {
  if (!$("#show-forces").checked || !S.frames || S.stale || S.forcesRevision === S.revision) return;
  const revision = S.revision;
  const input = S.frames.inputs[0];
  if (forcing === revision) return;
  forcing = revision;
  try {
    // the first input turns at S.rpm, the others are held (rpm 0), as in the cycle drawn
    const rpm = Object.fromEntries(S.frames.inputs.map((n) => [n, n === input ? S.rpm : 0]));
    const F = await api.post("/api/forces", { model: S.toml, frames: S.frames.frames, rpm });
    if (revision !== S.revision) return;
    S.forces = F;
  } catch (e) {
    if (revision !== S.revision) return;
    S.forces = { error: e.message };
  } finally {
    if (forcing === revision) forcing = null;
  }
  S.forcesRevision = revision;
  render();
  drawPlots();
}

const dirCache = new Map();
function centreDirection(key, i) {
  const rows = S.frames.centre_direction?.[key];
  if (!rows) return null;
  if (!dirCache.has(key)) dirCache.set(key, new Map(rows.map(([k, ux, uy]) => [k, [ux, uy]])));
  return dirCache.get(key).get(i) || null;
}

function fillKennedy() {
  const sel = $("#kennedy-triple");
  const triples = S.frames && !S.stale ? S.frames.kennedy || [] : [];
  const text = triples.map((t) => [...new Set(t.flatMap((k) => k.split("/")))].join(", "));
  const want = ["all", ...text.map((_, k) => String(k))];
  if ([...sel.options].map((o) => o.value).join("\n") === want.join("\n")) return;
  const old = sel.value;
  clear(sel);
  const all = document.createElement("option");
  all.value = "all";
  all.textContent = "all triples";
  sel.appendChild(all);
  text.forEach((t, k) => {
    const o = document.createElement("option");
    o.value = String(k);
    o.textContent = t;
    sel.appendChild(o);
  });
  sel.value = want.includes(old) ? old : "all";
}

const scaleCache = new Map();
function arrowScale(kind) {
  if (scaleCache.has(kind)) return scaleCache.get(kind);
  let max = 0;
  for (const series of Object.values(S.frames[kind] || {})) {
    for (const v of series) if (v && v[0] !== null) max = Math.max(max, Math.hypot(v[0], v[1]));
  }
  const s = max > 0 ? 70 / max : 0;
  scaleCache.set(kind, s);
  return s;
}

// ---------------------------------------------------------------- status, play bar, plots

function setStatus() {
  const parts = [];
  if (!Object.keys(S.model.points || {}).length) {
    if (!S.cam) parts.push("Empty bench: pick an example, or place two ground pivots (G) to start.");
  }
  else if (!M.solvable(S.model)) {
    if (!S.model.links?.ground?.length) parts.push("Place a ground pivot (G).");
    else if (Object.keys(S.model.links).length < 2) parts.push("Join joints into links (L): click them one after another, Enter ends.");
    else parts.push("Choose the input (I): click a link pivoted on the ground.");
  } else {
    if (S.dof !== null) parts.push(`dof ${S.dof}`);
    if (S.redundant !== null) parts.push(`redundant ${S.redundant}`);
    if (S.frames && !S.stale) {
      const closed = (S.frames.closed || []).filter(Boolean).length;
      parts.push(`assembles ${closed}/${S.frames.frames}`);
    }
  }
  if (S.cam) {
    const served = S.camFrames && S.camRevision === S.revision ? S.camFrames.message : "";
    const note = S.camError ? `cam: ${S.camError}` : (served && S.cam.on ? `${served}; it turns with ${S.cam.on}` : served);
    if (note) parts.push(note);
  }
  const status = $("#status");
  const msg = S.error || S.message;
  status.textContent = parts.join(" · ") + (msg ? ` · ${msg}` : "");
  status.classList.toggle("warn", !!msg);
}

function updatePlayUi() {
  const n = frameCount();
  const scrub = $("#scrub");
  scrub.max = String(Math.max(0, n - 1));
  if (Number(scrub.value) !== S.frame) scrub.value = String(S.frame);
  const inp = S.frames && !S.stale && S.frames.input_deg ? S.frames.input_deg[S.frame] : null;
  const kind = S.frames?.input_kind?.[S.inputs[0]];
  const camDeg = !inp && n && S.camFrames ? S.camFrames.cam_angle_deg[S.frame % S.camFrames.frames] : null;
  $("#angle").textContent = inp === null || inp === undefined
    ? (camDeg === null || camDeg === undefined ? "" : `cam ${camDeg.toFixed(1)}°`)
    : `${S.inputs[0] || "input"} ${inp.toFixed(1)}${kind === "slider" ? "" : "°"}`;
  const label = S.playing ? "pause" : "play";
  $("#play").textContent = S.playing ? "❚❚" : "▶";
  $('[data-action="play"]').textContent = label;
  for (const p of plotMarks) p?.setMark(n ? S.frame : null);
}

let plotMarks = [];
function drawPlots() {
  const f = S.frames && !S.stale ? S.frames : null;
  const linkSel = $("#plot-link");
  const pointSel = $("#plot-point");
  const links = f ? Object.keys(f.angle_deg || {}) : [];
  const points = f ? Object.keys(f.point || {}).filter((p) => !(S.model.links?.ground || []).includes(p)) : [];
  refill(linkSel, links, links.find((l) => !inputLinks().includes(l)));
  refill(pointSel, points, points[points.length - 1]);
  const xs = f ? f.input_deg : [];
  const ln = linkSel.value;
  const pn = pointSel.value;
  plotMarks = [
    drawPlot($("#plot-angle"), xs, f && ln ? linkSeries(f, ln, $("#plot-quantity").value) : [],
      { title: ln ? `link ${ln}` : "link", cursor: f ? S.frame : null }),
    drawPlot($("#plot-point-xy"), xs, f && pn ? [
      { label: `${pn} x`, ys: f.point[pn].map((p) => (p ? p[0] : null)) },
      { label: `${pn} y`, ys: f.point[pn].map((p) => (p ? p[1] : null)) },
    ] : [], { title: pn ? `point ${pn}` : "point", cursor: f ? S.frame : null }),
  ];
}

/** A link's angle (deg), angular velocity or acceleration (per unit input rate, as the server answers them). */
function linkSeries(f, ln, q) {
  if (q === "omega" && f.omega?.[ln]) return [{ label: `${ln} ω (rad/s per input rad/s)`, ys: f.omega[ln] }];
  if (q === "alpha" && f.alpha?.[ln]) return [{ label: `${ln} α (rad/s² per (input rad/s)²)`, ys: f.alpha[ln] }];
  if (q === "torque") {
    const F = S.forces && S.forcesRevision === S.revision && !S.forces.error ? S.forces : null;
    return F ? Object.entries(F.torque).map(([n, ys]) => ({ label: `input ${n} torque (${unitText(F.units.torque)}) at ${S.rpm} rpm`, ys })) : [];
  }
  return [{ label: `${ln} angle (deg)`, ys: f.angle_deg[ln] }];
}

function refill(select, names, preferred) {
  const old = select.value;
  if ([...select.options].map((o) => o.value).join("\n") !== names.join("\n")) {
    while (select.firstChild) select.removeChild(select.firstChild);
    for (const n of names) {
      const o = document.createElement("option");
      o.value = n;
      o.textContent = n;
      select.appendChild(o);
    }
  }
  select.value = names.includes(old) ? old : (preferred ?? names[0] ?? "");
}

// ---------------------------------------------------------------- model changes, undo, sync with the server

/** The undoable state: the model and the cam beside it (the model file has no cam pair). */
function snapshot() {
  return JSON.stringify({ model: S.model, cam: S.cam });
}

function restore(text) {
  const snap = JSON.parse(text);
  S.model = snap.model;
  S.cam = snap.cam;
}

function pushUndo(before) {
  if (before === snapshot()) return;
  S.undo.push(before);
  if (S.undo.length > 500) S.undo.shift();
  S.redo = [];
}

/** One edit of the model: one undo step, redrawn at once, synced with the server. */
function edit(fn) {
  const before = snapshot();
  fn(S.model);
  pushUndo(before);
  return changed();
}

function changed(opts = {}) {
  S.stale = true;
  S.revision++;
  scaleCache.clear();
  render();
  renderProps();
  setStatus();
  // a cam on a link turns with it: asked for once the link's angles of this revision are solved (finishSync)
  const cam = S.cam?.on && M.solvable(S.model) ? null : syncCam();
  return requestSync(opts).then(() => cam);
}

let syncing = null;
let again = null;
/** Dump and solve the current model; one request at a time, the newest model wins (dragging stays smooth). */
function requestSync(opts = {}) {
  if (syncing) {
    again = again || { opts, waiters: [] };
    again.opts = { ...again.opts, ...opts };
    return new Promise((resolve) => again.waiters.push(resolve));
  }
  S.pending++;
  syncing = doSync(opts).finally(() => {
    S.pending--;
    syncing = null;
    if (again) {
      const next = again;
      again = null;
      requestSync(next.opts).then(() => next.waiters.forEach((w) => w()));
    }
  });
  return syncing;
}

async function doSync({ fromText = false, text = null } = {}) {
  const revision = S.revision;
  let toml = text;
  if (toml === null && M.solvable(S.model)) {
    // an edit: the server writes the model's TOML and solves it in one round trip
    try {
      const f = await api.post("/api/solve", solveBody(S.model));
      if (revision !== S.revision) return; // a newer edit is on its way
      S.toml = f.toml;
      setTomlText(f.toml);
      takeFrames(f);
    } catch (e) {
      if (revision !== S.revision) return;
      S.error = e.message;
      S.stale = true;
      S.toml = M.toToml(S.model); // the page's own writing of the model: what is drawn is what is saved
      setTomlText(S.toml);
    }
    finishSync();
    return;
  }
  if (toml === null) {
    // an incomplete drawing (no ground, link or input yet) is not a model the server writes: written here
    toml = M.toToml(S.model);
    if (M.solvable(S.model)) {
      try {
        toml = (await api.post("/api/dump", { model: S.model })).model;
      } catch (e) {
        if (revision !== S.revision) return;
        S.error = e.message;
        S.frames = null; S.stale = false;
        setTomlText(toml);
        finishSync();
        return;
      }
    }
  }
  S.toml = toml;
  if (!fromText) setTomlText(toml);
  if (!M.solvable(S.model)) {
    S.frames = null; S.stale = false; S.dof = null; S.redundant = null; S.message = ""; S.error = "";
    S.inputs = inputLinks();
    finishSync();
    return;
  }
  try {
    const f = await api.post("/api/solve", solveBody(toml));
    if (revision !== S.revision) return; // a newer edit is on its way
    takeFrames(f);
  } catch (e) {
    if (revision !== S.revision) return;
    S.error = e.message;
    S.stale = true;
  }
  finishSync();
}

/** The body of a solve: instant centres are asked for (up to the server's cap of bodies) while they or
 * Kennedy's lines are shown; otherwise the server answers them for small models only. */
function solveBody(model) {
  const body = { model, frames: FRAMES };
  if ($("#show-centres").checked || $("#show-kennedy").checked) body.centres = true;
  return body;
}

/** A check box of centres or Kennedy's lines turned on for a model whose centres were not answered: solve again. */
function needCentres() {
  render();
  if (($("#show-centres").checked || $("#show-kennedy").checked) && S.frames && !S.stale && !S.frames.centres
    && (S.frames.inputs || []).length === 1) {
    changed({ text: S.toml, fromText: true });
  }
}

function takeFrames(f) {
  S.frames = f;
  S.stale = false;
  S.dof = f.dof; S.redundant = f.redundant; S.inputs = f.inputs || []; S.message = f.message || ""; S.error = "";
  if (S.frame >= f.frames) S.frame = 0;
  scaleCache.clear();
  dirCache.clear();
}

function finishSync() {
  if (S.cam?.on) syncCam();
  fillKennedy();
  render();
  drawPlots();
  renderProps();
  setStatus();
  syncForces();
}

function undo() {
  if (!S.undo.length) return Promise.resolve();
  S.redo.push(snapshot());
  restore(S.undo.pop());
  S.selected = null;
  return changed();
}

function redo() {
  if (!S.redo.length) return Promise.resolve();
  S.undo.push(snapshot());
  restore(S.redo.pop());
  S.selected = null;
  return changed();
}

/** Replace the model by a TOML text (one undo step); resolves once it is solved. */
async function load(text, { fitView = true, cam } = {}) {
  const parsed = await api.post("/api/parse", { model: text });
  const before = snapshot();
  S.model = parsed.model;
  if (cam !== undefined) S.cam = cam; // a file opened with its cam (or without one): the same undo step
  pushUndo(before);
  S.selected = null; S.draftLink = null; S.frame = 0;
  clearTomlError();
  const done = changed({ text });
  await done;
  if (fitView) { fit(); render(); }
  return text;
}

// ---------------------------------------------------------------- the TOML pane

function setTomlText(text) {
  const ta = $("#toml");
  if (document.activeElement === ta) return; // never overwrite what the user is typing
  ta.value = text;
  clearTomlError();
}

function clearTomlError() {
  $("#toml-error").hidden = true;
  $("#toml").removeAttribute("aria-invalid");
}

let typingTimer = null;
function onTomlInput() {
  clearTimeout(typingTimer);
  typingTimer = setTimeout(async () => {
    const text = $("#toml").value;
    try {
      const parsed = await api.post("/api/parse", { model: text });
      if ($("#toml").value !== text) return;
      const before = snapshot();
      S.model = parsed.model;
      pushUndo(before);
      clearTomlError();
      changed({ fromText: true, text });
    } catch (e) {
      const box = $("#toml-error");
      box.hidden = false;
      box.textContent = e.line ? `line ${e.line}: ${e.message}` : e.message;
      box.dataset.line = e.line ?? "";
      $("#toml").setAttribute("aria-invalid", "true");
      if (e.line) markLine(e.line);
    }
  }, 350);
}

function markLine(line) {
  const ta = $("#toml");
  const lines = ta.value.split("\n");
  let start = 0;
  for (let k = 0; k < line - 1 && k < lines.length; k++) start += lines[k].length + 1;
  const end = start + (lines[line - 1] || "").length;
  if (document.activeElement !== ta) ta.setSelectionRange(start, end);
}

// ---------------------------------------------------------------- pointer interaction

let gesture = null;
const pointers = new Map();

function onPointerDown(ev) {
  if (ev.button !== undefined && ev.button > 1) return;
  svg().setPointerCapture(ev.pointerId);
  pointers.set(ev.pointerId, eventPx(ev));
  if (pointers.size === 2) { // pinch zoom
    const [a, b] = [...pointers.values()];
    gesture = { kind: "pinch", d: Math.hypot(a[0] - b[0], a[1] - b[1]), view: { ...S.view }, mid: [(a[0] + b[0]) / 2, (a[1] + b[1]) / 2] };
    return;
  }
  const [px, py] = eventPx(ev);
  const joint = jointsAt(px, py);
  const link = joint ? null : linkAt(px, py);
  gesture = { kind: "click", start: [px, py], joint, link, moved: false, before: snapshot(), button: ev.button };
  if (ev.button === 1) { gesture.kind = "pan"; gesture.view = { ...S.view }; return; }
  if (S.tool === "select") {
    if (joint) { gesture.kind = "drag"; stop(); S.selected = { kind: "joint", name: joint }; S.stale = true; render(); renderProps(); }
    else if (!link) { gesture.kind = "pan"; gesture.view = { ...S.view }; }
  } else if (S.tool === "curve") {
    gesture.kind = "curve";
    S.curve = [toModel(px, py)];
  } else if (S.tool === "pose") {
    const hit = poseAt(px, py);
    if (hit) Object.assign(gesture, hit);
    else if (poses().length >= 5) { gesture.kind = "none"; notify("five poses at most: drag one, or clear them in the synthesis panel"); }
    else {
      (S.model.poses ||= []).push(null);
      setPose(S.model.poses.length - 1, [...toModel(px, py), 0]);
      Object.assign(gesture, { kind: "pose-turn", index: S.model.poses.length - 1, added: true });
      render();
    }
  } else if (S.tool === "input") {
    const inLink = joint && inputLinks().find((l) => S.model.links[l].includes(joint) && !M.isGround(S.model, joint));
    if (inLink && S.frames && !S.stale) { gesture.kind = "turn"; gesture.joint = joint; stop(); }
  }
}

/** The pose under the pixel: its point (drag moves it) or the tip of its direction (drag turns it). */
function poseAt(px, py) {
  const all = poses();
  for (let k = all.length - 1; k >= 0; k--) {
    const [x, y, a] = all[k];
    const [qx, qy] = toPx(x, y);
    const r = (a * Math.PI) / 180;
    if (Math.hypot(qx + POSE_PX * Math.cos(r) - px, qy - POSE_PX * Math.sin(r) - py) <= HIT_PX) return { kind: "pose-turn", index: k };
    if (Math.hypot(qx - px, qy - py) <= HIT_PX) return { kind: "pose-move", index: k };
  }
  return null;
}

function onPointerMove(ev) {
  if (!pointers.has(ev.pointerId) || !gesture) return;
  pointers.set(ev.pointerId, eventPx(ev));
  const [px, py] = eventPx(ev);
  if (gesture.kind === "pinch" && pointers.size === 2) {
    const [a, b] = [...pointers.values()];
    const f = Math.hypot(a[0] - b[0], a[1] - b[1]) / (gesture.d || 1);
    zoomAbout(gesture.mid, f, gesture.view);
    return;
  }
  if (gesture.start && Math.hypot(px - gesture.start[0], py - gesture.start[1]) > 4) gesture.moved = true;
  if (gesture.kind === "drag" && gesture.moved) {
    S.model.points[gesture.joint] = snap(toModel(px, py));
    changed();
  } else if (gesture.kind === "pan") {
    S.view.tx = gesture.view.tx + px - gesture.start[0];
    S.view.ty = gesture.view.ty + py - gesture.start[1];
    render();
  } else if (gesture.kind === "curve") {
    const p = toModel(px, py);
    const last = S.curve[S.curve.length - 1];
    if (Math.hypot(p[0] - last[0], p[1] - last[1]) * S.view.s >= 2) S.curve.push(p);
    render();
  } else if (gesture.kind === "turn") {
    turnInputTo(gesture.joint, toModel(px, py));
  } else if (gesture.kind === "pose-move" && gesture.moved) {
    const [x, y] = snap(toModel(px, py));
    setPose(gesture.index, [x, y, poses()[gesture.index][2]]);
    render();
  } else if (gesture.kind === "pose-turn" && gesture.moved) {
    const [x, y] = poses()[gesture.index];
    const [mx, my] = toModel(px, py);
    setPose(gesture.index, [x, y, Number(((Math.atan2(my - y, mx - x) * 180) / Math.PI).toFixed(2))]);
    render();
  }
}

function onPointerUp(ev) {
  pointers.delete(ev.pointerId);
  if (!gesture) return;
  const g = gesture;
  if (g.kind === "pinch") { if (pointers.size === 0) gesture = null; return; }
  gesture = null;
  const [px, py] = eventPx(ev);
  if (g.kind === "drag") {
    if (g.moved) { pushUndo(g.before); changed(); }
    else { renderProps(); S.stale = false; render(); }
    return;
  }
  if (g.kind === "curve") {
    if (S.curve.length < 3) S.curve = [];
    S.curveClosed = true;
    render();
    notify(S.curve.length ? `curve of ${S.curve.length} points drawn: synthesize from it` : "");
    return;
  }
  if (g.kind === "pose-move" || g.kind === "pose-turn" || g.kind === "none") {
    const all = poses();
    const p = all[g.index];
    if (p) {
      S.selected = { kind: "pose", index: g.index };
      renderProps();
      // a pose added, moved or turned is one undo step, saved with the model ([[poses]])
      if (g.moved || g.added) { pushUndo(g.before); changed(); }
      notify(`pose ${g.index + 1} of ${all.length}: (${Number(p[0].toPrecision(5))}, ${Number(p[1].toPrecision(5))}) at ${p[2]}°`);
    }
    return;
  }
  if (g.kind === "pan" || g.kind === "turn") {
    if (g.kind === "pan" && !g.moved && S.tool === "select") { S.selected = null; renderProps(); render(); }
    return;
  }
  if (g.moved) return;
  click(px, py, g.joint, g.link);
}

function click(px, py, joint, link) {
  const xy = snap(toModel(px, py));
  switch (S.tool) {
    case "cam":
      placeCam(joint ? [...S.model.points[joint]] : xy, joint);
      break;
    case "select":
      S.selected = link ? { kind: "link", name: link } : null;
      renderProps(); render();
      break;
    case "ground":
      if (joint) edit((m) => M.makeGround(m, joint));
      else edit((m) => { S.selected = { kind: "joint", name: M.addGroundPivot(m, xy) }; });
      break;
    case "pin":
      if (joint) { S.selected = { kind: "joint", name: joint }; renderProps(); render(); }
      else edit((m) => { S.selected = { kind: "joint", name: M.placePoint(m, M.pinName(m), xy) }; });
      break;
    case "point":
      if (joint) { S.selected = { kind: "joint", name: joint }; renderProps(); render(); }
      else edit((m) => {
        const p = M.addPoint(m, "P", xy);
        if (link) M.growLink(m, link, p);
        S.selected = { kind: "joint", name: p };
      });
      break;
    case "link": {
      const before = snapshot();
      let p = joint;
      if (!p) p = M.placePoint(S.model, M.pinName(S.model), xy);
      if (!S.draftLink) S.draftLink = { first: p };
      else if (S.draftLink.first && S.draftLink.first !== p) S.draftLink = { link: M.addLink(S.model, S.draftLink.first, p) };
      else if (S.draftLink.link) M.growLink(S.model, S.draftLink.link, p);
      pushUndo(before);
      changed();
      break;
    }
    case "input": {
      const l = link || (joint && M.linksOf(S.model, joint).find((n) => n !== "ground"));
      if (!l) { notify("click a link pivoted on the ground"); break; }
      if (!S.model.links[l].some((p) => M.isGround(S.model, p))) { notify(`${l} is not pivoted on the ground`); break; }
      edit((m) => M.setInput(m, l, S.dof && S.dof > 1 ? S.dof : 1));
      break;
    }
    case "slider":
      if (!joint) { notify("click a joint to slide it on a guide"); break; }
      edit((m) => M.addSlider(m, joint));
      break;
    case "gear": {
      if (!joint) { notify("click a joint: the gear's centre"); break; }
      const prev = S.lastGear;
      let made = null;
      edit((m) => {
        made = M.addGear(m, joint);
        if (made && prev && m.gears[prev] && m.gears[prev].link !== m.gears[made].link) M.addMesh(m, prev, made);
      });
      S.lastGear = made;
      break;
    }
    default:
      break;
  }
}

/** Drag an input: show the frame where the dragged joint points from its pivot towards the pointer. */
function turnInputTo(joint, [x, y]) {
  const link = inputLinks().find((l) => S.model.links[l].includes(joint));
  const pivot = S.model.links[link].find((p) => M.isGround(S.model, p));
  const c = pos(pivot);
  const want = Math.atan2(y - c[1], x - c[0]);
  const series = S.frames.point[joint];
  const piv = S.frames.point[pivot];
  let best = S.frame;
  let bestD = Infinity;
  series.forEach((p, k) => {
    if (!p || p[0] === null || !S.frames.closed[k]) return;
    const q = piv ? piv[k] : c;
    const a = Math.atan2(p[1] - q[1], p[0] - q[0]);
    const d = Math.abs(Math.atan2(Math.sin(a - want), Math.cos(a - want)));
    if (d < bestD) { bestD = d; best = k; }
  });
  S.frame = best;
  render();
}

function zoomAbout([px, py], f, base = S.view) {
  const s = Math.min(1e6, Math.max(1e-4, base.s * f));
  const [mx, my] = [(px - base.tx) / base.s, (base.ty - py) / base.s];
  S.view = { s, tx: px - s * mx, ty: py + s * my };
  render();
}

function onWheel(ev) {
  ev.preventDefault();
  zoomAbout(eventPx(ev), Math.exp(-ev.deltaY * 0.0015));
}

// ---------------------------------------------------------------- play

let last = 0;
function tick(t) {
  if (!S.playing) return;
  const n = frameCount();
  if (n) {
    const dt = last ? Math.min(0.1, (t - last) / 1000) : 0;
    S.frameF = ((S.frameF ?? S.frame) + dt * S.speed * (n / 4)) % n;
    S.frame = Math.floor(S.frameF);
    render();
  }
  last = t;
  requestAnimationFrame(tick);
}

function play() {
  if (S.playing) { stop(); return; }
  if (!frameCount()) { notify("nothing to play yet: the model needs an input"); return; }
  S.playing = true;
  S.frameF = S.frame;
  last = 0;
  requestAnimationFrame(tick);
  updatePlayUi();
}

function stop() {
  S.playing = false;
  updatePlayUi();
}

// ---------------------------------------------------------------- side panel

function field(parent, label, value, onChange, { type = "number", step = "any", attrs = {} } = {}) {
  const wrap = document.createElement("label");
  wrap.className = "field";
  const span = document.createElement("span");
  span.textContent = label;
  const input = document.createElement("input");
  input.type = type;
  if (type === "number") input.step = step;
  input.value = value ?? "";
  for (const [k, v] of Object.entries(attrs)) input.setAttribute(k, v);
  input.addEventListener("change", () => onChange(type === "number" ? Number(input.value) : input.value, input));
  wrap.append(span, input);
  parent.appendChild(wrap);
  return input;
}

function button(parent, label, onClick, attrs = {}) {
  const b = document.createElement("button");
  b.type = "button";
  b.textContent = label;
  for (const [k, v] of Object.entries(attrs)) b.setAttribute(k, v);
  b.addEventListener("click", onClick);
  parent.appendChild(b);
  return b;
}

const NAME_RE = /^[\p{L}_][\p{L}\p{N}_.-]{0,63}$/u;

function renderProps() {
  const box = $("#props");
  clear(box);
  const m = S.model;
  const sel = S.selected;
  if (sel?.kind === "pose" && m.poses?.[sel.index]) {
    const h = document.createElement("h3");
    h.textContent = `pose ${sel.index + 1} (motion synthesis)`;
    box.appendChild(h);
    const [x, y, a] = poses()[sel.index];
    const put = (v, k) => Number.isFinite(v) && edit(() => { const p = poses()[sel.index]; p[k] = v; setPose(sel.index, p); });
    field(box, "x", x, (v) => put(v, 0), { attrs: { "data-field": "pose-x" } });
    field(box, "y", y, (v) => put(v, 1), { attrs: { "data-field": "pose-y" } });
    field(box, "angle (deg)", a, (v) => put(v, 2), { attrs: { "data-field": "pose-angle" } });
    button(box, "delete pose", () => { edit((mm) => M.deletePose(mm, sel.index)); S.selected = null; renderProps(); }, { "data-action-pose": "delete" });
    return;
  }
  if (sel?.kind === "joint" && m.points?.[sel.name]) {
    const h = document.createElement("h3");
    h.textContent = `joint ${sel.name}`;
    box.appendChild(h);
    field(box, "name", sel.name, (v, input) => {
      if (!NAME_RE.test(v) || v in m.points) { input.value = sel.name; notify(`"${v}" is not a free name`); return; }
      edit((mm) => M.renamePoint(mm, sel.name, v)); S.selected = { kind: "joint", name: v };
    }, { type: "text", attrs: { "data-field": "name" } });
    field(box, "x", m.points[sel.name][0], (v) => Number.isFinite(v) && edit((mm) => { mm.points[sel.name][0] = v; }), { attrs: { "data-field": "x" } });
    field(box, "y", m.points[sel.name][1], (v) => Number.isFinite(v) && edit((mm) => { mm.points[sel.name][1] = v; }), { attrs: { "data-field": "y" } });
    const on = document.createElement("p");
    on.textContent = `on: ${M.linksOf(m, sel.name).join(", ") || "no link yet"}`;
    box.appendChild(on);
    const carrier = M.linksOf(m, sel.name).find((l) => l !== "ground");
    if (carrier && !M.isGround(m, sel.name)) {
      const fload = (m.loads || []).find((l) => l.point === sel.name && l.force);
      const setForce = (axis) => (v) => Number.isFinite(v) && edit((mm) => {
        const old = (mm.loads || []).find((l) => l.point === sel.name && l.force);
        const f = old ? [...old.force] : [0, 0];
        f[axis] = v;
        mm.loads = (mm.loads || []).filter((l) => !(l.point === sel.name && l.force));
        if (f[0] !== 0 || f[1] !== 0) mm.loads.push({ link: old?.link ?? carrier, point: sel.name, force: f });
        if (!mm.loads.length) delete mm.loads;
      });
      field(box, "load Fx", fload ? fload.force[0] : 0, setForce(0), { attrs: { "data-field": "load-fx" } });
      field(box, "load Fy", fload ? fload.force[1] : 0, setForce(1), { attrs: { "data-field": "load-fy" } });
    }
    const row = document.createElement("div");
    row.className = "row";
    if (!M.isGround(m, sel.name)) button(row, "make ground", () => edit((mm) => M.makeGround(mm, sel.name)));
    button(row, "delete", () => { edit((mm) => M.deletePoint(mm, sel.name)); S.selected = null; renderProps(); });
    box.appendChild(row);
    return;
  }
  if (sel?.kind === "link" && m.links?.[sel.name]) {
    const pts = m.links[sel.name];
    const h = document.createElement("h3");
    h.textContent = `link ${sel.name}`;
    box.appendChild(h);
    field(box, "name", sel.name, (v, input) => {
      if (!NAME_RE.test(v) || v in m.links || v === "ground") { input.value = sel.name; notify(`"${v}" is not a free name`); return; }
      edit((mm) => M.renameLink(mm, sel.name, v)); S.selected = { kind: "link", name: v };
    }, { type: "text", attrs: { "data-field": "name" } });
    const p = document.createElement("p");
    p.textContent = `points: ${pts.join(", ")}`;
    box.appendChild(p);
    for (let k = 1; k < pts.length; k++) {
      const [a, b] = [m.points[pts[0]], m.points[pts[k]]];
      const len = Math.hypot(b[0] - a[0], b[1] - a[1]);
      field(box, `${pts[0]}–${pts[k]}`, Number(len.toPrecision(6)), (v) => {
        if (!(v > 0)) return;
        edit((mm) => { // move the far point along the line (or the near one when the far one is fixed)
          const [fix, mov] = M.isGround(mm, pts[k]) ? [pts[k], pts[0]] : [pts[0], pts[k]];
          const [f, q] = [mm.points[fix], mm.points[mov]];
          const d = Math.hypot(q[0] - f[0], q[1] - f[1]) || 1;
          mm.points[mov] = [f[0] + ((q[0] - f[0]) * v) / d, f[1] + ((q[1] - f[1]) * v) / d];
        });
      }, { attrs: { "data-field": `length-${k}` } });
    }
    const mass = (m.masses || {})[sel.name] || {};
    field(box, "mass (kg)", mass.mass ?? 0, (v) => v >= 0 && edit((mm) => {
      mm.masses ||= {};
      mm.masses[sel.name] = { ...(mm.masses[sel.name] || {}), mass: v, centre: mm.masses[sel.name]?.centre ?? pts[0] };
    }), { attrs: { "data-field": "mass" } });
    field(box, "inertia", mass.inertia ?? 0, (v) => v >= 0 && edit((mm) => {
      mm.masses ||= {};
      mm.masses[sel.name] = { mass: 0, centre: pts[0], ...(mm.masses[sel.name] || {}), inertia: v };
    }), { attrs: { "data-field": "inertia" } });
    const tload = (m.loads || []).find((l) => l.link === sel.name && l.torque !== undefined && l.force === undefined);
    field(box, "load torque", tload?.torque ?? 0, (v) => Number.isFinite(v) && edit((mm) => {
      mm.loads = (mm.loads || []).filter((l) => !(l.link === sel.name && l.torque !== undefined && l.force === undefined));
      if (v !== 0) mm.loads.push({ link: sel.name, torque: v });
      if (!mm.loads.length) delete mm.loads;
    }), { attrs: { "data-field": "load-torque" } });
    for (const [gname, g] of Object.entries(m.gears || {})) {
      if (g.link !== sel.name) continue;
      field(box, `${gname} teeth`, g.teeth, (v) => Number.isInteger(v) && v >= 1 && edit((mm) => { mm.gears[gname].teeth = v; }), { step: "1", attrs: { "data-field": `teeth-${gname}` } });
    }
    const row = document.createElement("div");
    row.className = "row";
    if (pts.some((q) => M.isGround(m, q)) && !inputLinks().includes(sel.name)) button(row, "make input", () => edit((mm) => M.setInput(mm, sel.name, S.dof || 1)));
    button(row, "delete", () => { edit((mm) => M.deleteLink(mm, sel.name)); S.selected = null; renderProps(); });
    box.appendChild(row);
    return;
  }
  // nothing selected: the mechanism
  const h = document.createElement("h3");
  h.textContent = "mechanism";
  box.appendChild(h);
  field(box, "name", m.mechanism?.name ?? "", (v) => edit((mm) => { mm.mechanism = { ...(mm.mechanism || {}), name: v }; }), { type: "text", attrs: { "data-field": "mechanism-name" } });
  field(box, "units", m.mechanism?.units ?? "", (v) => edit((mm) => { mm.mechanism = { ...(mm.mechanism || {}), units: v }; }), { type: "text", attrs: { "data-field": "units" } });
  field(box, "input speed (rpm), for forces", S.rpm, (v, input) => {
    if (!(v > 0 && v <= 1e6)) { input.value = S.rpm; notify("the input speed is a number of rev/min above 0"); return; }
    S.rpm = v;
    S.forcesRevision = -1;
    syncForces();
  }, { attrs: { "data-field": "rpm" } });
  branchControls(box);
  const list = document.createElement("p");
  list.className = "muted";
  list.textContent = Object.keys(m.links || {}).length
    ? `links: ${Object.keys(m.links).join(", ")}. Click a joint or link to edit it.`
    : "Nothing drawn yet.";
  box.appendChild(list);
}

/** The assembly branch of each dyad the server lists: the side of its joint; a change moves the sketch there
 * (POST /api/branch answers the model re-placed on the other branch) and re-solves, as one undo step. */
function branchControls(box) {
  const list = S.frames && !S.stale ? S.frames.branches || [] : [];
  if (!list.length) return;
  const h = document.createElement("h4");
  h.textContent = "assembly branch";
  box.appendChild(h);
  for (const b of list) {
    const wrap = document.createElement("label");
    wrap.className = "field";
    const span = document.createElement("span");
    span.textContent = `${b.joint} (${b.links.join(", ")})`;
    const sel = document.createElement("select");
    sel.dataset.branch = b.joint;
    const sides = b.kind === "RRR"
      ? [["1", `left of ${b.about[0]}→${b.about[1]}`], ["-1", `right of ${b.about[0]}→${b.about[1]}`]]
      : [["1", "ahead on the guide"], ["-1", "behind on the guide"]];
    for (const [v, text] of sides) {
      const o = document.createElement("option");
      o.value = v;
      o.textContent = text;
      sel.appendChild(o);
    }
    sel.value = String(b.sigma);
    sel.addEventListener("change", () => setBranch(b.joint).catch((e) => { notify(`branch: ${e.message}`); renderProps(); }));
    wrap.append(span, sel);
    box.appendChild(wrap);
  }
}

async function setBranch(joint) {
  stop();
  const { model } = await api.post("/api/branch", { model: S.toml, joint });
  await load(model, { fitView: false });
  notify(`${joint} on its other assembly branch (undo takes it back)`);
}

// ---------------------------------------------------------------- notes, tools, dialogs

let noteTimer = null;
function notify(text) {
  const status = $("#status");
  if (!text) { setStatus(); return; }
  status.textContent = text;
  status.classList.remove("warn");
  clearTimeout(noteTimer);
  noteTimer = setTimeout(setStatus, 4000);
}

function setTool(tool) {
  if (S.draftLink && tool !== "link") endLink();
  S.tool = tool;
  S.lastGear = null;
  for (const b of $$("[data-tool]")) b.setAttribute("aria-pressed", String(b.dataset.tool === tool));
  svg().dataset.tool = tool;
  document.body.classList.remove("tools-open");
  if (tool === "cam") loadLaws().catch((e) => notify(`laws: ${e.message}`));
}

function endLink() {
  S.draftLink = null;
  render();
}

function download(blob, filename) {
  const url = URL.createObjectURL(blob);
  const a = document.createElement("a");
  a.href = url;
  a.download = filename;
  document.body.appendChild(a);
  a.click();
  a.remove();
  setTimeout(() => URL.revokeObjectURL(url), 5000);
}

async function exportAs(format) {
  const note = $("#export-note");
  note.textContent = `exporting ${format}…`;
  try {
    const body = { model: S.toml, frames: FRAMES };
    // the CAD drawings are of one pose: the frame shown
    if ((format === "dxf" || format === "svg-outline") && S.frames && !S.stale && S.frames.inputs_deg) {
      const k = S.frames.closed[S.frame] ? S.frame : lastClosed(S.frame);
      body.inputs = Object.fromEntries(Object.entries(S.frames.inputs_deg).map(([n, v]) => [n, v[k]]));
    }
    // the cam on the bench: its profile on a layer of its own, turned as in the frame shown
    if ((format === "dxf" || format === "svg-outline") && S.cam && S.camFrames && S.camRevision === S.revision) {
      body.cam = S.camFrames.cam_toml;
      body.cam_angle_deg = S.camFrames.cam_angle_deg[S.frame % S.camFrames.frames];
    }
    const { blob, filename } = await api.postFile(`/api/export/${format}`, body);
    const base = (S.file.name || S.model.mechanism?.name || "mechanism").replace(/\.toml$/, "").replace(/[^\p{L}\p{N}_.-]+/gu, "_");
    download(blob, filename || `${base}.${format}`);
    note.textContent = `${format}: ${blob.size} bytes`;
    return blob.size;
  } catch (e) {
    note.textContent = `${format}: ${e.message}`;
    throw e;
  }
}

async function openShare() {
  if (S.cam && S.camRevision !== S.revision) await syncCam();
  const link = await shareUrl(S.toml, S.cam ? S.camFrames?.cam_toml : null);
  $("#share-link").value = link;
  window.history.replaceState(null, "", new URL(link).hash);
  try { await navigator.clipboard.writeText(link); notify("share link copied"); } catch { notify("share link in the export panel"); }
  return link;
}

// files
async function listFiles() {
  const ul = clear($("#file-list"));
  try {
    const { files } = await api.get("/api/files");
    if (!files.length) { const li = document.createElement("li"); li.textContent = "no model in the workspace yet"; ul.appendChild(li); }
    for (const f of files) {
      const li = document.createElement("li");
      button(li, f.name, () => openFile(f.name), { "data-file": f.name });
      const meta = document.createElement("span");
      meta.className = "muted";
      meta.textContent = ` ${f.size} bytes`;
      li.appendChild(meta);
      ul.appendChild(li);
    }
  } catch (e) {
    const li = document.createElement("li");
    li.textContent = e.message;
    ul.appendChild(li);
  }
}

async function openFile(name) {
  if (name.endsWith(".cam.toml")) return openCam(name);
  const { model, etag } = await api.getFile(name);
  // the cam saved beside the model comes back with it (a model without one: no cam)
  let cam = null;
  let camEtag = null;
  try {
    const { files } = await api.get("/api/files");
    if (files.some((f) => f.name === camFileOf(name))) {
      const got = await api.getFile(camFileOf(name));
      cam = await camFromFile(got.model, (await api.post("/api/parse", { model })).model);
      camEtag = got.etag;
    }
  } catch (e) {
    notify(`${camFileOf(name)}: ${e.message}`);
  }
  await load(model, { cam });
  if (cam) { await syncCam(); fit(); render(); } // the view takes in the cam too
  S.file = { name, etag, camEtag };
  $("#file-name").value = name;
  $("#dlg-files").close();
  notify(`opened ${name}`);
}

/** A CAM.toml opened alone: an empty bench with the cam at its pivot (one undo step). */
async function openCam(name) {
  const { model } = await api.getFile(name);
  const cam = await camFromFile(model, M.EMPTY());
  stop();
  const before = snapshot();
  S.model = M.EMPTY();
  S.cam = cam;
  pushUndo(before);
  S.selected = null; S.draftLink = null; S.frame = 0;
  await changed();
  fit();
  render();
  S.file = { name: null, etag: null, camEtag: null };
  $("#dlg-files").close();
  notify(`opened the cam ${name}`);
}

/** Save the bench's cam as the CAM.toml beside the model file `name` (If-Match: the cam file's ETag when it was
 * opened or saved with this model); the new ETag, or null after a conflict (shown). */
async function saveCam(name, force = null) {
  const file = camFileOf(name);
  if (S.camRevision !== S.revision) await syncCam();
  if (!S.camFrames?.cam_toml) throw new Error(`the cam is not drawn (${S.camError || "not solved"}): ${file} not written`);
  try {
    S.file.camEtag = await api.putFile(file, S.camFrames.cam_toml, force || S.file.camEtag);
    return S.file.camEtag;
  } catch (e) {
    if (e.status === 412 || e.status === 428) {
      showConflict(file, e.status, { overwrite: (tag) => saveCam(name, tag), mine: name });
      if (!$("#dlg-files").open) $("#dlg-files").showModal();
      return null;
    }
    throw e;
  }
}

async function saveFile(name, { force = false } = {}) {
  name = name || S.file.name || "design.toml";
  if (name.endsWith(".cam.toml")) {
    notify(`${name}: a .cam.toml name is the cam's; save the bench as a model (.toml), its cam goes beside it`);
    return null;
  }
  const etag = S.file.name === name ? S.file.etag : null;
  $("#file-conflict").hidden = true;
  try {
    const newTag = await api.putFile(name, S.toml, force ? force : etag);
    const camEtag = S.file.name === name ? S.file.camEtag : null;
    S.file = { name, etag: newTag, camEtag };
    if (S.cam && (await saveCam(name)) === null) return null;
    // a cam file left beside a model saved without a cam would bring a cam back when it is opened: say so
    const stray = !S.cam && (await api.get("/api/files")).files.some((f) => f.name === camFileOf(name));
    notify(S.cam ? `saved ${name} and its cam ${camFileOf(name)}`
      : (stray ? `saved ${name}; ${camFileOf(name)} beside it is left as it was (it opens with ${name})` : `saved ${name}`));
    listFiles();
    return name;
  } catch (e) {
    if (e.status === 412 || e.status === 428) {
      showConflict(name, e.status);
      if (!$("#dlg-files").open) $("#dlg-files").showModal();
      return null;
    }
    notify(`not saved: ${e.message}`);
    throw e;
  }
}

function showConflict(name, status, { overwrite = null, mine = null } = {}) {
  $("#file-conflict").hidden = false;
  $("#file-conflict-text").textContent = status === 412
    ? `${name} changed in the workspace since you opened it: nothing was written. Keep which?`
    : `${name} already exists in the workspace: nothing was written. Keep which?`;
  $("#conflict-overwrite").onclick = async () => {
    const { etag } = await api.getFile(name);
    await (overwrite ? overwrite(etag) : saveFile(name, { force: etag }));
  };
  $("#conflict-copy").onclick = async () => {
    const { files } = await api.get("/api/files");
    const names = new Set(files.map((f) => f.name));
    const stem = (mine || name).replace(/\.toml$/, ""); // a cam's conflict: the bench saved as a new model
    let k = 2;
    while (names.has(`${stem}-${k}.toml`)) k++;
    S.file = { name: null, etag: null };
    await saveFile(`${stem}-${k}.toml`);
  };
  $("#conflict-theirs").onclick = () => openFile(mine || name);
}

// synthesis
function synthParams(kind) {
  const box = clear($("#synth-params"));
  const note = document.createElement("p");
  note.className = "muted";
  if (kind === "curve" || kind === "path") {
    note.textContent = S.curve.length
      ? `target: the drawn curve (${S.curve.length} points)`
      : "draw the target first: curve tool (C), press, drag and release on the canvas";
    box.appendChild(note);
    const file = document.createElement("label");
    file.className = "field";
    const span = document.createElement("span");
    span.textContent = "or import the target (CSV: x, y a row)";
    const input = document.createElement("input");
    input.type = "file";
    input.id = "synth-csv";
    input.accept = ".csv,.txt,text/csv,text/plain";
    input.addEventListener("change", () => importTarget(input.files[0]).then(() => synthParams(kind), (e) => { note.textContent = e.message; }));
    file.append(span, input);
    box.appendChild(file);
    if (kind === "curve") field(box, "time (s)", 20, () => {}, { attrs: { id: "synth-time" } });
    else field(box, "budget", 3000, () => {}, { step: "1", attrs: { id: "synth-budget" } });
    field(box, "seed", 1, () => {}, { step: "1", attrs: { id: "synth-seed" } });
  } else if (kind === "function") {
    field(box, "y = f(x)", "log10(x)", () => {}, { type: "text", attrs: { id: "synth-expr" } });
    field(box, "x range", "1, 2", () => {}, { type: "text", attrs: { id: "synth-xrange" } });
    field(box, "input range (deg)", "45, 105", () => {}, { type: "text", attrs: { id: "synth-in" } });
    field(box, "output range (deg)", "135, 225", () => {}, { type: "text", attrs: { id: "synth-out" } });
    field(box, "precision points", 3, () => {}, { step: "1", attrs: { id: "synth-points" } });
  } else if (kind === "motion") {
    note.textContent = "three to five poses, one a line: x, y, angle (deg); or place them on the canvas with the pose tool "
      + "(M: press at the coupler point, drag along the coupler; drag a pose's point or tip to move or turn it). "
      + "With three poses the moving pivots are taken on the first pose's line, a quarter of the poses' spread either side.";
    box.appendChild(note);
    const ta = document.createElement("textarea");
    ta.id = "synth-poses";
    ta.rows = 5;
    ta.value = poses().length ? poses().map((p) => p.map((v) => Number(v.toPrecision(8))).join(", ")).join("\n") : "0, 0, 0\n20, 10, 30\n40, 10, 60";
    box.appendChild(ta);
    const row = document.createElement("div");
    row.className = "row";
    button(row, "clear poses", () => { edit((m) => { delete m.poses; }); synthParams(kind); }, { id: "synth-clear-poses" });
    box.appendChild(row);
  } else if (kind === "law") {
    note.textContent = "the [law] table of a cam law file";
    box.appendChild(note);
    const ta = document.createElement("textarea");
    ta.id = "synth-law";
    ta.rows = 6;
    box.appendChild(ta);
  }
}

const nums = (text) => String(text).split(/[\s,;]+/).filter(Boolean).map(Number);

function jobBody(kind, opts = {}) {
  const val = (id, fallback) => ($(id) ? $(id).value : fallback);
  S.placement = null;
  if (kind === "curve" || kind === "path") {
    const target = opts.target || S.curve;
    if (!target || target.length < 3) throw new Error("draw the target curve first (curve tool)");
    // The topology search scores designs as the linkage synthesis challenge does (material, the links'
    // total length, under 10): the drawn curve is sent moved to the origin and scaled to an RMS radius of
    // 0.191 (the challenge suite's), and the designs are placed back on the drawing by the inverse similarity (see placeResult).
    let pts = target;
    if (kind === "curve") {
      const n = target.length;
      const c = [target.reduce((a, p) => a + p[0], 0) / n, target.reduce((a, p) => a + p[1], 0) / n];
      const rms = Math.sqrt(target.reduce((a, p) => a + (p[0] - c[0]) ** 2 + (p[1] - c[1]) ** 2, 0) / n) || 1;
      const k = rms / 0.191;
      pts = target.map(([x, y]) => [(x - c[0]) / k, (y - c[1]) / k]);
      S.placement = { c, k };
    }
    const body = { kind, target: pts.map(([x, y]) => [Number(x.toPrecision(8)), Number(y.toPrecision(8))]) };
    if (kind === "curve") body.time = Number(opts.time ?? val("#synth-time", 20));
    else body.budget = Number(opts.budget ?? val("#synth-budget", 3000));
    body.seed = Number(opts.seed ?? val("#synth-seed", 1));
    return body;
  }
  if (kind === "function") {
    return {
      kind,
      expr: opts.expr ?? val("#synth-expr", "log10(x)"),
      x_range: opts.x_range ?? nums(val("#synth-xrange", "1,2")),
      input_range_deg: opts.input_range_deg ?? nums(val("#synth-in", "45,105")),
      output_range_deg: opts.output_range_deg ?? nums(val("#synth-out", "135,225")),
      points: Number(opts.points ?? val("#synth-points", 3)),
    };
  }
  if (kind === "motion") {
    const typed = $("#synth-poses") ? val("#synth-poses", "").split("\n").filter((l) => l.trim()).map(nums) : [];
    const placed = poses();
    const chosen = opts.poses ?? (placed.length >= 3 && !$("#dlg-synth").open ? placed : (typed.length ? typed : placed));
    const body = { kind, poses: chosen.map((p) => p.map((v) => Number(Number(v).toPrecision(10)))) };
    if (body.poses.length === 3) body.moving_pivots = opts.moving_pivots ?? movingPivots(body.poses);
    return body;
  }
  if (kind === "law") return { kind, law: opts.law ?? val("#synth-law", ""), type: opts.type ?? "auto" };
  throw new Error(`unknown synthesis kind ${kind}`);
}

/** Three poses need two moving pivots: on the first pose's coupler line, a quarter of the poses' spread either side. */
function movingPivots(poses) {
  const xs = poses.map((p) => p[0]);
  const ys = poses.map((p) => p[1]);
  const spread = Math.max(Math.max(...xs) - Math.min(...xs), Math.max(...ys) - Math.min(...ys)) || 1;
  const [x, y, a] = poses[0];
  const [c, s] = [Math.cos((a * Math.PI) / 180), Math.sin((a * Math.PI) / 180)];
  const d = spread / 4;
  return [[x - d * c, y - d * s], [x + d * c, y + d * s]].map((p) => p.map((v) => Number(v.toPrecision(10))));
}

/** A CSV of target points (x, y a row; rows that are not two numbers, such as a header, are skipped) read in the
 * page: it becomes the target curve, as if drawn. Nothing is sent until a synthesis runs. */
async function importTarget(file) {
  if (!file) return;
  if (file.size > 1_000_000) throw new Error(`${file.name}: ${file.size} bytes, more than the cap of 1000000`);
  const text = await file.text();
  const pts = [];
  for (const line of text.split(/\r?\n/)) {
    const cells = line.split(/[,;\t ]+/).filter(Boolean);
    if (cells.length < 2) continue;
    const [x, y] = [Number(cells[0]), Number(cells[1])];
    if (Number.isFinite(x) && Number.isFinite(y)) pts.push([x, y]);
  }
  if (pts.length < 3) throw new Error(`${file.name}: ${pts.length} rows of two numbers, a target needs 3 or more`);
  if (pts.length > 2000) throw new Error(`${file.name}: ${pts.length} points, more than the cap of 2000`);
  S.curve = pts;
  render();
  notify(`target of ${pts.length} points imported from ${file.name}`);
}

let jobAbort = null;
/** Run a synthesis job to its end with progress; the answer of GET /api/jobs/{id} at the end. */
async function runJob(body) {
  const placement = S.placement;
  const { id } = await api.post("/api/jobs", body);
  S.job = { id, state: "running", kind: body.kind };
  $("#synth-cancel").disabled = false;
  $("#synth-run").disabled = true;
  clear($("#synth-results"));
  const progress = (ev) => {
    const p = ev.progress || {};
    S.job.progress = p; // the state changes only once the results are listed
    $("#synth-stage").textContent = `${ev.state || ""} ${p.stage || ""} ${p.done ?? ""}${p.total ? `/${p.total}` : ""}`;
    if (p.total) { $("#synth-progress").max = p.total; $("#synth-progress").value = p.done || 0; }
  };
  jobAbort = new AbortController();
  try {
    await api.events(`/api/jobs/${encodeURIComponent(id)}/events`, progress, jobAbort.signal);
  } catch { /* the stream ended or was cut: poll below */ }
  let answer = await api.get(`/api/jobs/${encodeURIComponent(id)}`);
  while (answer.state === "running") {
    await new Promise((r) => setTimeout(r, 400));
    answer = await api.get(`/api/jobs/${encodeURIComponent(id)}`);
    progress(answer);
  }
  progress(answer);
  S.job = { id, state: answer.state, kind: body.kind };
  $("#synth-cancel").disabled = true;
  $("#synth-run").disabled = false;
  listResults(answer, placement);
  answer.placement = placement;
  return answer;
}

function listResults(answer, placement) {
  const ol = clear($("#synth-results"));
  if (answer.state !== "done") {
    const li = document.createElement("li");
    li.textContent = answer.state === "failed" ? `failed: ${answer.error || "?"}` : answer.state;
    ol.appendChild(li);
    return;
  }
  if (!(answer.results || []).length) {
    const li = document.createElement("li");
    li.textContent = "no design found: give the search more time, or draw the curve again";
    ol.appendChild(li);
  }
  for (const r of answer.results || []) {
    const li = document.createElement("li");
    const score = Object.entries(r.score || {}).map(([k, v]) => `${k} ${typeof v === "number" ? Number(v.toPrecision(4)) : v}`).join(", ");
    const span = document.createElement("span");
    span.textContent = `#${r.rank} ${score} `;
    li.appendChild(span);
    button(li, "insert", async () => {
      try {
        await load(await placeResult(r.model, placement));
        notify(`result #${r.rank} inserted (undo takes it out)`);
      } catch (e) { notify(e.message); }
    }, { "data-result": r.rank });
    ol.appendChild(li);
  }
}

/** A design of the curve search placed where the target was drawn: the sketch moved and scaled back. */
async function placeResult(text, pl) {
  if (!pl) return text;
  const { model } = await api.post("/api/parse", { model: text });
  for (const [name, [x, y]] of Object.entries(model.points || {})) {
    model.points[name] = [Number((pl.c[0] + x * pl.k).toPrecision(10)), Number((pl.c[1] + y * pl.k).toPrecision(10))];
  }
  for (const key of Object.keys(model.lengths || {})) model.lengths[key] *= pl.k;
  return (await api.post("/api/dump", { model })).model;
}

async function cancelJob() {
  if (!S.job) return;
  try { await api.del(`/api/jobs/${encodeURIComponent(S.job.id)}`); } catch (e) { notify(e.message); }
  if (jobAbort) jobAbort.abort();
}

async function synthesize(opts = {}) {
  const kind = opts.kind || $("#synth-kind").value;
  const answer = await runJob(jobBody(kind, opts));
  if (answer.state !== "done" || !(answer.results || []).length) {
    throw new Error(`synthesis ${answer.state}: ${answer.error || "no result"}`);
  }
  const best = await placeResult(answer.results[0].model, answer.placement);
  await load(best);
  return best;
}

// ---------------------------------------------------------------- keyboard

const SHORTCUTS = [
  ["V", "select and drag", () => setTool("select")],
  ["G", "ground pivot", () => setTool("ground")],
  ["P", "pin joint", () => setTool("pin")],
  ["L", "link (Enter or Esc ends it)", () => setTool("link")],
  ["S", "slider", () => setTool("slider")],
  ["E", "gear", () => setTool("gear")],
  ["O", "point of interest", () => setTool("point")],
  ["I", "input", () => setTool("input")],
  ["C", "curve (freehand target)", () => setTool("curve")],
  ["M", "motion pose (press at the point, drag along the coupler)", () => setTool("pose")],
  ["K", "cam and follower (the law and follower chosen beside the tool)", () => setTool("cam")],
  ["Space", "play / pause", () => play()],
  ["← →", "previous / next frame", null],
  ["Ctrl+Z", "undo", () => undo()],
  ["Ctrl+Shift+Z, Ctrl+Y", "redo", () => redo()],
  ["Ctrl+S", "save into the workspace", null],
  ["Delete", "delete the selected joint, link or pose", null],
  ["F", "fit the drawing", null],
  ["N", "new empty bench", null],
  ["?", "this help", null],
];

function onKey(ev) {
  const tag = document.activeElement?.tagName;
  const typing = tag === "TEXTAREA" || tag === "INPUT" || tag === "SELECT";
  const ctrl = ev.ctrlKey || ev.metaKey;
  if (ctrl && ev.key.toLowerCase() === "s") { ev.preventDefault(); save(); return; }
  if (typing) return;
  if (ctrl && ev.key.toLowerCase() === "z") { ev.preventDefault(); (ev.shiftKey ? redo : undo)(); return; }
  if (ctrl && ev.key.toLowerCase() === "y") { ev.preventDefault(); redo(); return; }
  if (ctrl || ev.altKey) return;
  if (ev.key === "Escape" || ev.key === "Enter") { if (S.draftLink) { endLink(); ev.preventDefault(); } return; }
  if (ev.key === " ") { ev.preventDefault(); play(); return; }
  if (ev.key === "ArrowRight" || ev.key === "ArrowLeft") {
    const n = frameCount();
    if (n) { S.frame = (S.frame + (ev.key === "ArrowRight" ? 1 : n - 1)) % n; render(); }
    return;
  }
  if (ev.key === "Delete" || ev.key === "Backspace") {
    const sel = S.selected;
    if (sel?.kind === "pose") edit((m) => M.deletePose(m, sel.index));
    else if (sel?.kind === "joint") edit((m) => M.deletePoint(m, sel.name));
    else if (sel?.kind === "link") edit((m) => M.deleteLink(m, sel.name));
    S.selected = null;
    renderProps();
    return;
  }
  const k = ev.key.toLowerCase();
  if (k === "f") { fit(); render(); return; }
  if (k === "n") { newBench(); return; }
  if (ev.key === "?") { $("#dlg-help").showModal(); return; }
  const tool = { v: "select", g: "ground", p: "pin", l: "link", s: "slider", e: "gear", o: "point", i: "input", c: "curve", m: "pose", k: "cam" }[k];
  if (tool) setTool(tool);
}

function newBench() {
  stop();
  edit((m) => { for (const key of Object.keys(m)) delete m[key]; Object.assign(m, M.EMPTY()); S.cam = null; });
  S.curve = [];
  S.selected = null;
  S.file = { name: null, etag: null };
  fit();
  render();
}

async function save() {
  if (S.file.name) return saveFile(S.file.name);
  $("#dlg-files").showModal();
  listFiles();
  return null;
}

// ---------------------------------------------------------------- start

function buildHelp() {
  const tb = $("#shortcuts tbody");
  for (const [keys, what] of SHORTCUTS) {
    const tr = document.createElement("tr");
    const a = document.createElement("td");
    const kbd = document.createElement("kbd");
    kbd.textContent = keys;
    a.appendChild(kbd);
    const b = document.createElement("td");
    b.textContent = what;
    tr.append(a, b);
    tb.appendChild(tr);
  }
}

async function loadExamples() {
  try {
    const { examples } = await api.get("/api/examples");
    const sel = $("#examples");
    for (const e of examples) {
      const o = document.createElement("option");
      o.value = e.name;
      o.textContent = e.title ? `${e.name}: ${e.title}` : e.name;
      sel.appendChild(o);
    }
  } catch (e) {
    notify(`examples: ${e.message}`);
  }
}

async function openExample(name) {
  if (!name) return;
  const { model } = await api.get(`/api/examples/${encodeURIComponent(name)}`);
  S.file = { name: null, etag: null };
  await load(model);
  $("#examples").value = "";
}

function wire() {
  const c = svg();
  c.addEventListener("pointerdown", onPointerDown);
  c.addEventListener("pointermove", onPointerMove);
  c.addEventListener("pointerup", onPointerUp);
  c.addEventListener("pointercancel", (ev) => { pointers.delete(ev.pointerId); gesture = null; });
  c.addEventListener("wheel", onWheel, { passive: false });
  c.addEventListener("contextmenu", (ev) => ev.preventDefault());
  document.addEventListener("keydown", onKey);
  for (const b of $$("[data-tool]")) b.addEventListener("click", () => setTool(b.dataset.tool));
  const actions = {
    new: newBench,
    play,
    undo,
    redo,
    save,
    export: () => { $("#dlg-export").showModal(); openShare().catch((e) => notify(e.message)); },
    synthesize: () => { synthParams($("#synth-kind").value); $("#dlg-synth").showModal(); },
    share: () => { $("#dlg-export").showModal(); openShare().catch((e) => notify(e.message)); },
    files: () => { $("#dlg-files").showModal(); listFiles(); },
    help: () => $("#dlg-help").showModal(),
  };
  for (const b of $$("[data-action]")) b.addEventListener("click", () => actions[b.dataset.action]());
  $("#play").addEventListener("click", play);
  $("#scrub").addEventListener("input", () => { stop(); S.frame = Number($("#scrub").value); render(); });
  $("#speed").addEventListener("change", () => { S.speed = Number($("#speed").value); });
  $("#fit").addEventListener("click", () => { fit(); render(); });
  for (const id of ["#show-velocity", "#show-acceleration", "#show-paths", "#kennedy-triple"]) $(id).addEventListener("change", render);
  for (const id of ["#show-centres", "#show-kennedy"]) $(id).addEventListener("change", needCentres);
  $("#show-forces").addEventListener("change", () => { render(); syncForces(); });
  $("#plot-link").addEventListener("change", drawPlots);
  $("#plot-point").addEventListener("change", drawPlots);
  $("#plot-quantity").addEventListener("change", drawPlots);
  $("#toml").addEventListener("input", onTomlInput);
  $("#examples").addEventListener("change", () => openExample($("#examples").value).catch((e) => notify(e.message)));
  $("#fold").addEventListener("click", () => {
    const open = document.body.classList.toggle("tools-open");
    $("#fold").setAttribute("aria-expanded", String(open));
  });
  for (const b of $$("[data-export]")) b.addEventListener("click", () => exportAs(b.dataset.export).catch(() => {}));
  $("#file-save").addEventListener("click", () => saveFile($("#file-name").value.trim()).catch(() => {}));
  $("#synth-kind").addEventListener("change", () => synthParams($("#synth-kind").value));
  $("#synth-run").addEventListener("click", () => {
    let body;
    try { body = jobBody($("#synth-kind").value); } catch (e) { $("#synth-stage").textContent = e.message; return; }
    runJob(body).catch((e) => { $("#synth-stage").textContent = e.message; $("#synth-run").disabled = false; });
  });
  $("#synth-cancel").addEventListener("click", cancelJob);
  $("#cam-law").addEventListener("change", camChoice);
  $("#cam-follower").addEventListener("change", camChoice);
  window.addEventListener("resize", () => { render(); drawPlots(); });
  window.addEventListener("hashchange", () => fromFragment());
}

async function fromFragment() {
  let shared = null;
  try { shared = await sharedFromFragment(); } catch (e) { notify(`share link: ${e.message}`); return false; }
  if (shared === null) return false;
  try {
    const cam = shared.cam ? await camFromFile(shared.cam, (await api.post("/api/parse", { model: shared.model })).model) : null;
    await load(shared.model, { cam });
    if (cam) { await syncCam(); fit(); render(); }
    notify(shared.cam ? "opened from the share link, with its cam" : "opened from the share link");
    return true;
  } catch (e) { notify(`share link: ${e.message}`); return false; }
}

window.workbench = {
  load: (text) => load(text),
  model: () => S.toml,
  state: () => ({
    ready: S.ready, dof: S.dof, inputs: [...S.inputs], frames: S.frames && !S.stale ? S.frames.frames : 0,
    message: S.error || S.message, job: S.job ? { ...S.job } : null,
    pending: S.pending > 0 || !!again, revision: S.revision, frame: S.frame, playing: S.playing,
    tool: S.tool, undo: S.undo.length, redo: S.redo.length, curve: S.curve.length, file: { ...S.file },
    forces: S.forcesRevision === S.revision && S.forces ? (S.forces.error || "ready") : null,
  }),
  frames: () => (S.frames && !S.stale ? S.frames : null),
  forces: () => (S.forcesRevision === S.revision ? S.forces : null),
  toScreen: (x, y) => { const r = svg().getBoundingClientRect(); const [px, py] = toPx(x, y); return [r.left + px, r.top + py]; },
  synthesize,
  undo: () => undo(),
  redo: () => redo(),
  // for tests and scripts
  play: () => { if (!S.playing) play(); }, pause: stop, setFrame: (i) => { S.frame = i; render(); },
  setTool, fit: () => { fit(); render(); }, save: (name) => saveFile(name), open: openFile,
  share: openShare, export: exportAs, curve: () => S.curve.map((p) => [...p]), poses: () => poses(), cam: () => (S.camRevision === S.revision ? S.camFrames : null), view: () => ({ ...S.view }), branch: (joint) => setBranch(joint),
};

async function start() {
  buildHelp();
  wire();
  setTool("select");
  fit();
  render();
  renderProps();
  setStatus();
  drawPlots();
  await loadExamples();
  await loadLaws().catch((e) => notify(`laws: ${e.message}`));
  const opened = await fromFragment();
  const name = new URL(window.location.href).searchParams.get("open");
  if (name && !opened) {
    try { await openFile(name); } catch (e) { notify(`open ${name}: ${e.message}`); }
  }
  S.ready = true;
  setStatus();
}

start().catch((e) => { S.ready = true; notify(e.message); });
