(function () {
  "use strict";
  const D = JSON.parse(document.getElementById("gl-data").textContent);
  const N = D.N, M = D.M, L = D.L;
  const view = document.getElementById("view");
  const world = document.getElementById("world");
  const labelsG = document.getElementById("labels");
  const { NS, $, fmt, esc, el, show, setLine, PM } = GL;  // common.js
  const COLORS = ["#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b", "#e377c2", "#17becf", "#bcbd22"];
  const DEG = 180 / Math.PI;

  // ------------------------------------------------------------------ state
  const st = {
    frame: 0, grid: D.grid ? D.grid.default : 0, playing: false, speed: 1, acc: 0, last: null,
    s: 1, tx: 0, ty: 0, drag: null, pathsOn: {},
  };

  // ------------------------------------------------------------------ data access
  function at(series, k) {
    if (series === undefined || series === null) return null;
    const sl = series[st.grid];
    if (sl === null || typeof sl === "number") return sl;
    return sl[k];
  }
  const S = D.S;
  const closedAt = (k) => D.closed.charAt(st.grid * N + k) === "1";
  const P = (name, k) => [at(S.x[name], k), at(S.y[name], k)];
  // one oscillation of a rocking first input (D.osc: its value and direction per frame), else one turn
  const inputAngle = (k) => (D.osc ? D.osc.q[k] : D.inputs[0].start + 2 * Math.PI * k / N);
  function rotOf(link, k) { return link === "ground" ? 0 : at(S.phi[link], k); }

  // units
  const U = D.units;
  const rated = D.rated;
  const velUnit = rated ? U + "/s" : U + "/rad";
  const accUnit = rated ? U + "/s²" : U + "/rad²";
  const wUnit = rated ? "rad/s" : "rad/rad";
  const alUnit = rated ? "rad/s²" : "rad/rad²";

  const linkColor = {};
  D.links.forEach((lk, i) => { linkColor[lk.name] = COLORS[i % COLORS.length]; });
  const inputLink = D.inputs[0].link;
  const pivotName = (() => {
    const lk = D.links.find((l) => l.name === inputLink);
    return lk ? lk.points[0] : null;
  })();

  // ------------------------------------------------------------------ build the drawing
  const gPaths = $("paths"), gGround = $("ground"), gLinks = $("links"), gArrows = $("arrows");
  const gPoints = $("points"), gCentres = $("centres"), gKennedy = $("kennedy");
  gArrows.setAttribute("data-vscale", D.vscale);
  gArrows.setAttribute("data-ascale", D.ascale);
  const h = 0.06 * L;  // ground symbol size (model units)

  // ground: a triangle and hatching under each ground pivot, hatching along ground guides
  const groundJoints = D.ground_points.filter((p) => D.joints.indexOf(p) >= 0);
  groundJoints.forEach((p) => {
    const [x, y] = P(p, 0);
    if (x === null) return;
    el("polygon", { class: "ground-shape", points: `${x},${y} ${x - h * 0.7},${y - h} ${x + h * 0.7},${y - h}` }, gGround);
    el("line", { class: "hatch", x1: x - h, y1: y - h, x2: x + h, y2: y - h }, gGround);
    for (let i = 0; i < 5; i++) {
      const x0 = x - h + i * h * 0.5;
      el("line", { class: "hatch", x1: x0, y1: y - h, x2: x0 - h * 0.35, y2: y - h * 1.4 }, gGround);
    }
  });
  D.sliders.filter((s) => s.on === "ground").forEach((s) => {
    // the guide is fixed: through the sketch position of the slider point
    const k0 = firstClosed();
    if (k0 < 0) return;
    const [px, py] = P(s.point, k0);
    const s0 = at(S.s[s.name], k0);
    const ox = px - s0 * s.dir[0], oy = py - s0 * s.dir[1];
    const nx = -s.dir[1], ny = s.dir[0];
    const off = 0.045 * L;
    const a = [ox + s.smin * s.dir[0] - off * nx, oy + s.smin * s.dir[1] - off * ny];
    const b = [ox + s.smax * s.dir[0] - off * nx, oy + s.smax * s.dir[1] - off * ny];
    el("line", { class: "hatch", x1: a[0], y1: a[1], x2: b[0], y2: b[1] }, gGround);
    const len = s.smax - s.smin, n = Math.max(2, Math.round(len / (0.04 * L)));
    for (let i = 0; i <= n; i++) {
      const t = s.smin + len * i / n;
      const cx = ox + t * s.dir[0] - off * nx, cy = oy + t * s.dir[1] - off * ny;
      el("line", { class: "hatch", x1: cx, y1: cy, x2: cx - 0.03 * L * (nx + s.dir[0]), y2: cy - 0.03 * L * (ny + s.dir[1]) }, gGround);
    }
    el("line", { class: "guide", x1: ox + s.smin * s.dir[0], y1: oy + s.smin * s.dir[1], x2: ox + s.smax * s.dir[0], y2: oy + s.smax * s.dir[1] }, gGround);
  });
  // gears of the ground (a fixed sun, a ring gear): drawn once, they do not move
  D.gears.filter((gr) => gr.link === "ground" && gr.r !== null).forEach((gr) => {
    const [cx, cy] = P(gr.centre, 0);
    if (cx === null || cy === null) return;
    el("circle", { class: "gear ground-gear" + (gr.internal ? " internal" : ""), "data-gear": gr.name, cx: cx, cy: cy, r: gr.r }, gGround);
    if (gr.internal) el("circle", { class: "ring-back", cx: cx, cy: cy, r: gr.r + 0.05 * L }, gGround);
  });
  function firstClosed() { for (let k = 0; k < N; k++) if (closedAt(k)) return k; return -1; }

  // moving links: one group each, holding its body, slider blocks, moving guides and gears
  const linkEls = {};
  D.links.forEach((lk) => {
    const g = el("g", { class: "link" + (lk.name === inputLink ? " input grab" : ""), "data-link": lk.name }, gLinks);
    const color = linkColor[lk.name];
    const parts = { g: g, body: null, blocks: [], guides: [], gears: [], hub: null };
    D.sliders.filter((s) => s.on === lk.name).forEach((s) => {
      parts.guides.push({ s: s, e: el("line", { class: "guide" }, g) });
    });
    if (lk.points.length >= 3) parts.body = el("polygon", { class: "link-body", stroke: color, fill: color }, g);
    else if (lk.points.length === 2) parts.body = el("line", { class: "link-body", stroke: color }, g);
    D.gears.filter((gr) => gr.link === lk.name && gr.r !== null).forEach((gr) => {
      parts.gears.push({
        gr: gr,
        c: el("circle", { class: "gear" + (gr.internal ? " internal" : ""), "data-gear": gr.name, stroke: color, r: gr.r }, g),
        m: el("line", { class: "gear-mark", stroke: color }, g),
      });
    });
    D.sliders.filter((s) => s.link === lk.name).forEach((s) => {
      parts.blocks.push({ s: s, e: el("polygon", { class: "block", fill: color }, g) });
    });
    if (lk.points.length === 1 && !parts.blocks.length && !parts.gears.length) {
      parts.hub = el("circle", { class: "hub", fill: color, r: 0.04 * L }, g);
    }
    linkEls[lk.name] = parts;
  });
  // the input: a dashed ring about its pivot
  let inputMark = null;
  let inputHit = null;
  if (pivotName) {
    inputMark = el("circle", { class: "input-mark", r: 0.16 * L }, gLinks);
    inputHit = el("circle", { class: "input-hit grab", "data-input-ring": D.inputs[0].label, r: 0.16 * L }, gLinks);
  }

  // paths of the moving points
  const movingPoints = D.points.filter((p) => D.ground_points.indexOf(p) < 0);
  const pathEls = {};
  movingPoints.forEach((p) => {
    pathEls[p] = el("path", { class: "path", "data-path": p }, gPaths);
    st.pathsOn[p] = true;
    const lab = document.createElement("label");
    lab.style.display = "block";
    const cb = document.createElement("input");
    cb.type = "checkbox"; cb.checked = true; cb.dataset.pathChoice = p;
    cb.addEventListener("change", () => { st.pathsOn[p] = cb.checked; applyToggles(); });
    lab.appendChild(cb); lab.appendChild(document.createTextNode(" " + p));
    $("path-points").appendChild(lab);
  });
  function buildPaths() {
    movingPoints.forEach((p) => {
      let d = "", pen = false;
      for (let k = 0; k < N; k++) {
        const [x, y] = P(p, k);
        if (x === null || y === null || !closedAt(k)) { pen = false; continue; }
        d += (pen ? "L" : "M") + x + "," + y;
        pen = true;
      }
      if (d && closedAt(0) && closedAt(N - 1)) { const [x, y] = P(p, 0); d += "L" + x + "," + y; }
      pathEls[p].setAttribute("d", d);
    });
  }

  // arrows
  const velEls = {}, accEls = {};
  movingPoints.forEach((p) => {
    velEls[p] = el("line", { class: "vel", "data-vel": p, "marker-end": "url(#head-vel)" }, gArrows);
    accEls[p] = el("line", { class: "acc", "data-acc": p, "marker-end": "url(#head-acc)" }, gArrows);
  });

  // points (every model point) and their labels
  const pointEls = {}, pointLabels = {};
  D.points.forEach((p) => {
    const isGround = D.ground_points.indexOf(p) >= 0;
    const c = el("circle", { class: "pt" + (isGround ? " ground-pt" : ""), "data-point": p, r: 1 }, gPoints);
    if (p === pivotName || (linkOf(p) === inputLink && !isGround)) c.classList.add("grab");
    pointEls[p] = c;
    pointLabels[p] = el("text", { class: "pt-label" }, labelsG);
    pointLabels[p].textContent = p;
  });
  function linkOf(p) { const lk = D.links.find((l) => l.points.indexOf(p) >= 0); return lk ? lk.name : null; }
  const linkLabels = {};
  D.links.forEach((lk) => {
    linkLabels[lk.name] = el("text", { class: "link-label", fill: linkColor[lk.name] }, labelsG);
    linkLabels[lk.name].textContent = lk.name;
    linkLabels[lk.name].style.fill = linkColor[lk.name];
  });
  const gearLabels = D.gears.filter((g) => g.r !== null).map((g) => {
    const t = el("text", { class: "gear-label" }, labelsG);
    t.textContent = `${g.name}: z = ${g.teeth}${g.internal ? " (internal)" : ""}`;
    return { g: g, t: t };
  });

  // instant centres (one-input models)
  const icEls = {}, icLabels = {};
  const IC = D.ic;
  const linkNo = {};
  if (IC) {
    IC.links.forEach((n, i) => { linkNo[n] = i + 1; });
    IC.pairs.forEach((pair) => {
      icEls[pair] = el("circle", { class: "ic", "data-ic": pair, r: 1 }, gCentres);
      const [a, b] = pair.split("/");
      const t = el("text", { class: "ic-label" }, labelsG);
      t.textContent = `${linkNo[a]}${linkNo[b]}`;
      icLabels[pair] = t;
    });
    const sel = $("kennedy-triple");
    const n = IC.links.length;
    for (let i = 0; i < n; i++) for (let j = i + 1; j < n; j++) for (let k = j + 1; k < n; k++) {
      const o = document.createElement("option");
      o.value = [i, j, k].join(",");
      o.textContent = `${i + 1}${j + 1}-${i + 1}${k + 1}-${j + 1}${k + 1} (${IC.links[i]}, ${IC.links[j]}, ${IC.links[k]})`;
      sel.appendChild(o);
    }
    const all = document.createElement("option");
    all.value = "all"; all.textContent = "all triples";
    sel.appendChild(all);
  } else {
    $("centres-label").hidden = true;
    $("kennedy-label").hidden = true;
  }
  const kennedyEls = [];

  // ------------------------------------------------------------------ view transform
  function applyView() {
    world.setAttribute("transform", `matrix(${st.s},0,0,${-st.s},${st.tx},${st.ty})`);
    const r = 4.5 / st.s;
    D.points.forEach((p) => pointEls[p].setAttribute("r", r));
    for (const pair in icEls) icEls[pair].setAttribute("r", 3.5 / st.s);
    render();
  }
  // zoom, pan, and dragging the input: it turns by the change of the pointer's angle about its pivot
  const { fit, toScreen } = GL.viewControls({
    view: view, st: st, N: N, bbox: D.bbox, applyView: applyView,
    canTurn: () => Boolean(inputLink && pivotName), pivot: () => (pivotName ? P(pivotName, st.frame) : null),
    setFrame: (k) => setFrame(k), setPlaying: (on) => setPlaying(on),
  });
  // frames, play (1x: real time at the given speed, else a turn in 6 s), URL (with ?grid=)
  const { setFrame, setPlaying, scheduleUrl, startFrame } = GL.transport({
    st: st, N: N, render: () => render(), fps: () => (D.period ? N / D.period : N / 6), dir: Math.sign(D.inputs[0].rate || 1),
    urlParams: (u) => { if (D.grid) u.searchParams.set("grid", st.grid); else u.searchParams.delete("grid"); },
  });
  // labels are queued by render() and laid out together: each at the first of a ring of places about its
  // anchor that stays inside the drawing and overlaps no label placed before it (nor a point), in order
  // of priority (points, links, gears, centres); coincident anchors therefore fan out instead of stacking
  let queue = [];
  function placeText(t, x, y, dx, dy, rank) {
    if (x === null || y === null || !isFinite(x) || !isFinite(y)) { show(t, false); return; }
    const [X, Y] = toScreen(x, y);
    queue.push({ t: t, X: X, Y: Y, dx: dx, dy: dy, rank: rank || 0 });
  }
  const boxCache = new Map();
  function textBox(t) {
    // the label's box relative to its (x, y), measured once per label and text-anchor
    const key = t.getAttribute("text-anchor") || "start";
    let c = boxCache.get(t);
    if (c && c.key === key) return c;
    t.setAttribute("x", 0); t.setAttribute("y", 0);
    const b = t.getBBox();
    c = { key: key, x: b.x - 1, y: b.y - 1, w: b.width + 2, h: b.height + 2 };
    boxCache.set(t, c);
    return c;
  }
  const RING = (() => {
    const out = [];
    [10, 18, 28, 40, 54].forEach((r) => {
      for (let i = 0; i < 12; i++) { const a = -Math.PI / 4 + i * Math.PI / 6; out.push([r * Math.cos(a), -r * Math.sin(a)]); }
    });
    return out;
  })();
  function layoutLabels(points) {
    const W = view.clientWidth || 800, H = view.clientHeight || 500;
    // boxes placed so far (labels weigh 10, point circles 1) in a grid of 48 px cells: a place is
    // checked against its neighbours only, so that a model with hundreds of names still animates
    const CELL = 48, cells = new Map();
    const cellsOf = (b, f) => {
      const i1 = Math.floor((b.x + b.w) / CELL), j1 = Math.floor((b.y + b.h) / CELL);
      for (let i = Math.floor(b.x / CELL); i <= i1; i++) for (let j = Math.floor(b.y / CELL); j <= j1; j++) f(i * 65536 + j);
    };
    const add = (b) => cellsOf(b, (c) => { const a = cells.get(c); if (a) a.push(b); else cells.set(c, [b]); });
    const overlap = (a, b) => Math.max(0, Math.min(a.x + a.w, b.x + b.w) - Math.max(a.x, b.x)) * Math.max(0, Math.min(a.y + a.h, b.y + b.h) - Math.max(a.y, b.y));
    const cost = (b, limit) => {  // the weighted overlap with the boxes near b, summed up to limit
      let c = 0;
      const i0 = Math.floor(b.x / CELL), i1 = Math.floor((b.x + b.w) / CELL);
      const j0 = Math.floor(b.y / CELL), j1 = Math.floor((b.y + b.h) / CELL);
      for (let i = i0; i <= i1; i++) for (let j = j0; j <= j1; j++) {
        const a = cells.get(i * 65536 + j);
        if (!a) continue;
        for (let n = 0; n < a.length; n++) { c += a[n].wt * overlap(b, a[n]); if (c >= limit) return c; }
      }
      return c;
    };
    const inside = (b) => b.x >= 1 && b.y >= 1 && b.x + b.w <= W - 1 && b.y + b.h <= H - 1;
    points.forEach(([X, Y]) => { if (X >= -5 && X <= W + 5 && Y >= -5 && Y <= H + 5) add({ x: X - 5, y: Y - 5, w: 10, h: 10, wt: 1 }); });
    queue.sort((a, b) => a.rank - b.rank);
    // with many names the search stays near the anchor (the first ring), so that playing stays smooth
    const tries = queue.length > 60 ? 12 : RING.length;
    queue.forEach((q) => {
      // an anchor out of the drawing (panned or zoomed away, a far centre): no label pinned to the edge
      if (!(q.X >= 0 && q.X <= W && q.Y >= 0 && q.Y <= H)) { show(q.t, false); return; }
      show(q.t, true);
      const rel = textBox(q.t);
      let best = null, bestCost = Infinity;
      for (let n = -1; n < tries; n++) {
        let dx = q.dx, dy = q.dy;
        if (n >= 0) {
          // a ring place: the box's nearest corner at (u, v) from the anchor
          const [u, v] = RING[n];
          dx = (u >= 0 ? u : u - rel.w) - rel.x; dy = (v >= 0 ? v : v - rel.h) - rel.y;
        }
        const b = { x: q.X + dx + rel.x, y: q.Y + dy + rel.y, w: rel.w, h: rel.h, wt: 10 };
        if (!inside(b)) continue;
        const c = cost(b, bestCost);
        if (c < bestCost) { bestCost = c; best = [dx, dy, b]; }
        if (c === 0) break;
      }
      if (!best) {  // no place inside: clamp the preferred one into the drawing
        const b = { x: q.X + q.dx + rel.x, y: q.Y + q.dy + rel.y, w: rel.w, h: rel.h, wt: 10 };
        const nx = Math.min(Math.max(b.x, 1), Math.max(1, W - 1 - b.w)), ny = Math.min(Math.max(b.y, 1), Math.max(1, H - 1 - b.h));
        best = [q.dx + nx - b.x, q.dy + ny - b.y, { x: nx, y: ny, w: b.w, h: b.h, wt: 10 }];
      }
      q.t.setAttribute("x", (q.X + best[0]).toFixed(1));
      q.t.setAttribute("y", (q.Y + best[1]).toFixed(1));
      add(best[2]);
    });
    queue = [];
  }

  // ------------------------------------------------------------------ render one frame
  function render() {
    const k = st.frame;
    const ok = closedAt(k);
    const names = $("show-labels").checked;
    // points
    D.points.forEach((p) => {
      const [x, y] = P(p, k);
      const c = pointEls[p];
      if (ok && x !== null && y !== null) {
        c.setAttribute("cx", x); c.setAttribute("cy", y); show(c, true);
        if (names) placeText(pointLabels[p], x, y, 6, -6, 0); else show(pointLabels[p], false);
      } else { show(c, false); show(pointLabels[p], false); }
    });
    // links
    D.links.forEach((lk) => {
      const parts = linkEls[lk.name];
      show(parts.g, ok);
      if (!ok) { show(linkLabels[lk.name], false); return; }
      const xy = lk.points.map((p) => P(p, k));
      if (parts.body) {
        if (xy.length === 2) setLine(parts.body, xy[0][0], xy[0][1], xy[1][0], xy[1][1]);
        else parts.body.setAttribute("points", xy.map((q) => q[0] + "," + q[1]).join(" "));
      }
      if (parts.hub) { parts.hub.setAttribute("cx", xy[0][0]); parts.hub.setAttribute("cy", xy[0][1]); }
      parts.gears.forEach((G) => {
        const [cx, cy] = P(G.gr.centre, k);
        const th = rotOf(lk.name, k);
        G.c.setAttribute("cx", cx); G.c.setAttribute("cy", cy);
        setLine(G.m, cx, cy, cx + G.gr.r * Math.cos(th), cy + G.gr.r * Math.sin(th));
      });
      parts.blocks.forEach((B) => {
        const s = B.s, th = rotOf(s.on, k);
        const ux = Math.cos(th) * s.dir[0] - Math.sin(th) * s.dir[1], uy = Math.sin(th) * s.dir[0] + Math.cos(th) * s.dir[1];
        const [px, py] = P(s.point, k);
        const a = 0.07 * L, b = 0.04 * L;
        const c = [[a, b], [-a, b], [-a, -b], [a, -b]].map(([u, v]) => (px + u * ux - v * uy) + "," + (py + u * uy + v * ux));
        B.e.setAttribute("points", c.join(" "));
      });
      parts.guides.forEach((Gd) => {
        const s = Gd.s, th = rotOf(s.on, k);
        const ux = Math.cos(th) * s.dir[0] - Math.sin(th) * s.dir[1], uy = Math.sin(th) * s.dir[0] + Math.cos(th) * s.dir[1];
        const [px, py] = P(s.point, k);
        const sv = at(S.s[s.name], k);
        const ox = px - sv * ux, oy = py - sv * uy;
        setLine(Gd.e, ox + s.smin * ux, oy + s.smin * uy, ox + s.smax * ux, oy + s.smax * uy);
      });
      if (names) {
        const [cx, cy, anchor] = labelAnchor(lk, parts, xy, k);
        linkLabels[lk.name].setAttribute("text-anchor", anchor || "start");
        placeText(linkLabels[lk.name], cx, cy, anchor ? -4 : 8, anchor ? -4 : 16, 1);
      } else show(linkLabels[lk.name], false);
    });
    if (inputMark) {
      const [x, y] = P(pivotName, k);
      [inputMark, inputHit].forEach((e) => {
        if (ok && x !== null) { e.setAttribute("cx", x); e.setAttribute("cy", y); show(e, true); } else show(e, false);
      });
    }
    gearLabels.forEach(({ g, t }) => {
      const [x, y] = P(g.centre, k);
      if (ok && names) placeText(t, x + g.r * 0.5, y - g.r * 0.866, 4, 14, 2); else show(t, false);
    });
    // arrows: one scale for every point and frame
    const vOn = $("show-velocity").checked, aOn = $("show-acceleration").checked;
    movingPoints.forEach((p) => {
      const [x, y] = P(p, k);
      const vx = at(S.vx[p], k), vy = at(S.vy[p], k), ax = at(S.ax[p], k), ay = at(S.ay[p], k);
      const good = ok && x !== null;
      const tiny = 1e-4 * L;  // an arrow shorter than this is only its head: hide it
      if (vOn && good && vx !== null && D.vscale * Math.hypot(vx, vy) > tiny) { setLine(velEls[p], x, y, x + D.vscale * vx, y + D.vscale * vy); show(velEls[p], true); } else show(velEls[p], false);
      if (aOn && good && ax !== null && D.ascale * Math.hypot(ax, ay) > tiny) { setLine(accEls[p], x, y, x + D.ascale * ax, y + D.ascale * ay); show(accEls[p], true); } else show(accEls[p], false);
    });
    // instant centres
    const icOn = IC && $("show-centres").checked;
    if (IC) {
      IC.pairs.forEach((pair) => {
        const x = IC.x[pair][0], y = IC.y[pair][0];
        const cx = x === null || typeof x === "number" ? x : x[k], cy = y === null || typeof y === "number" ? y : y[k];
        const e = icEls[pair];
        if (ok && cx !== null && cy !== null) { e.setAttribute("cx", cx); e.setAttribute("cy", cy); show(e, true); }
        else show(e, false);
        if (icOn && ok && cx !== null && cy !== null) placeText(icLabels[pair], cx, cy, 5, 14, 3); else show(icLabels[pair], false);
      });
      gCentres.style.display = icOn ? "" : "none";
      drawKennedy();
    }
    const dots = [];
    if (ok) D.points.forEach((p) => { const [x, y] = P(p, k); if (x !== null && y !== null) dots.push(toScreen(x, y)); });
    layoutLabels(dots);
    readout();
    plotCursor();
    scheduleUrl();
  }

  // where a link's name goes: the centroid of a real polygon, else the middle of its first bar,
  // else (one point) beside its gear rim or its block
  function labelAnchor(lk, parts, xy, k) {
    if (xy.length >= 3) {
      let area = 0, per = 0;
      for (let i = 0; i < xy.length; i++) {
        const a = xy[i], b = xy[(i + 1) % xy.length];
        area += a[0] * b[1] - b[0] * a[1];
        per += Math.hypot(b[0] - a[0], b[1] - a[1]);
      }
      if (Math.abs(area) / 2 > 0.02 * per * per / 9) {
        let cx = 0, cy = 0;
        xy.forEach((q) => { cx += q[0]; cy += q[1]; });
        return [cx / xy.length, cy / xy.length];
      }
    }
    if (xy.length >= 2) return [(xy[0][0] + xy[1][0]) / 2, (xy[0][1] + xy[1][1]) / 2];
    if (parts.gears.length) {
      const r = parts.gears[0].gr.r;
      return [xy[0][0] - 0.75 * r, xy[0][1] + 0.75 * r, "end"];
    }
    return [xy[0][0] + 0.05 * L, xy[0][1] - 0.05 * L];
  }

  function icAt(pair, k) {
    const x = IC.x[pair][0], y = IC.y[pair][0];
    const cx = x === null || typeof x === "number" ? x : x[k], cy = y === null || typeof y === "number" ? y : y[k];
    if (cx !== null && cy !== null) return { p: [cx, cy] };
    const inf = (IC.inf[pair] || []).find((r) => r[0] === k);
    return inf ? { d: [inf[1], inf[2]] } : null;
  }
  function drawKennedy() {
    kennedyEls.forEach((e) => e.remove());
    kennedyEls.length = 0;
    if (!$("show-kennedy").checked || !closedAt(st.frame)) return;
    const v = $("kennedy-triple").value;
    const n = IC.links.length;
    const triples = [];
    if (v === "all") { for (let i = 0; i < n; i++) for (let j = i + 1; j < n; j++) for (let k = j + 1; k < n; k++) triples.push([i, j, k]); }
    else if (v) triples.push(v.split(",").map(Number));
    const big = 50 * L;
    triples.forEach(([i, j, k]) => {
      const nm = (a, b) => IC.links[a] + "/" + IC.links[b];
      const cs = [icAt(nm(i, j), st.frame), icAt(nm(i, k), st.frame), icAt(nm(j, k), st.frame)].filter((c) => c);
      const fin = cs.filter((c) => c.p), dirs = cs.filter((c) => c.d);
      let a = null, d = null;
      if (fin.length >= 2) {
        // the line through the two farthest apart finite centres
        let best = -1;
        for (let u = 0; u < fin.length; u++) for (let w = u + 1; w < fin.length; w++) {
          const dd = Math.hypot(fin[w].p[0] - fin[u].p[0], fin[w].p[1] - fin[u].p[1]);
          if (dd > best) { best = dd; a = fin[u].p; d = [(fin[w].p[0] - a[0]) / dd, (fin[w].p[1] - a[1]) / dd]; }
        }
        if (!(best > 0)) return;
      } else if (fin.length === 1 && dirs.length) { a = fin[0].p; d = dirs[0].d; }
      else return;
      const e = el("line", { class: "kennedy" }, gKennedy);
      setLine(e, a[0] - big * d[0], a[1] - big * d[1], a[0] + big * d[0], a[1] + big * d[1]);
      kennedyEls.push(e);
    });
  }

  // ------------------------------------------------------------------ readout, legend
  function readout() {
    const k = st.frame;
    const th = inputAngle(k) * DEG;
    const inp = D.inputs[0];
    let html = `${esc(inp.label)}: θ = ${th.toFixed(2)}°`;
    if (D.osc) html += ` (${D.osc.dir[k] > 0 ? "up" : "down"}, rocks ${(D.osc.lower * DEG).toFixed(3)}° to ${(D.osc.upper * DEG).toFixed(3)}°)`;
    if (D.period) html += ` · t = ${(D.period * k / N).toFixed(4)} s`;
    html += ` · frame ${k}/${N}`;
    D.inputs.slice(1).forEach((p, i) => {
      let v = p.start;
      if (D.grid && i === 0) v = D.grid.values[st.grid];
      html += p.kind === "link" ? ` · ${esc(p.label)} = ${(v * DEG).toFixed(2)}°` : ` · ${esc(p.label)} = ${fmt(v)} ${esc(U)}`;
    });
    if (!closedAt(k)) html += ' · <span class="warn">not assembled</span>';
    $("readout").innerHTML = html;
    $("frame").value = k;
  }
  function legend() {
    const parts = [];
    if (pivotName) parts.push(`<span class="ring"></span>input: ${esc(D.inputs[0].label)} (thick, drag it)`);
    if ($("show-velocity").checked && D.vscale > 0)
      parts.push(`<span class="key" style="border-color:#0b6e4f"></span>velocity: 1 ${esc(U)} of arrow = ${fmt(1 / D.vscale, 4)} ${esc(velUnit)}`);
    if ($("show-acceleration").checked && D.ascale > 0)
      parts.push(`<span class="key" style="border-color:#a23b72"></span>acceleration: 1 ${esc(U)} of arrow = ${fmt(1 / D.ascale, 4)} ${esc(accUnit)}`);
    if (IC && $("show-centres").checked)
      parts.push("instant centres ij: " + IC.links.map((n, i) => `${i + 1} ${esc(n)}`).join(", "));
    $("legend").innerHTML = parts.join("<br>");
  }
  function applyToggles() {
    const pathsOn = $("show-paths").checked;
    movingPoints.forEach((p) => show(pathEls[p], pathsOn && st.pathsOn[p]));
    legend();
    render();
  }

  // ------------------------------------------------------------------ plots
  const quantities = [];
  D.links.forEach((lk) => {
    quantities.push({ id: "phi:" + lk.name, label: `angle of ${lk.name} (deg)`, get: (k) => { const v = at(S.phi[lk.name], k); return v === null ? null : (v + lk.angle0) * DEG; } });
    quantities.push({ id: "w:" + lk.name, label: `ω of ${lk.name} (${wUnit})`, get: (k) => at(S.w[lk.name], k) });
    quantities.push({ id: "al:" + lk.name, label: `α of ${lk.name} (${alUnit})`, get: (k) => at(S.al[lk.name], k) });
  });
  movingPoints.forEach((p) => {
    const mag = (a, b) => (k) => { const x = at(a, k), y = at(b, k); return x === null || y === null ? null : Math.hypot(x, y); };
    quantities.push({ id: "x:" + p, label: `x of ${p} (${U})`, get: (k) => at(S.x[p], k) });
    quantities.push({ id: "y:" + p, label: `y of ${p} (${U})`, get: (k) => at(S.y[p], k) });
    quantities.push({ id: "v:" + p, label: `|v| of ${p} (${velUnit})`, get: mag(S.vx[p], S.vy[p]) });
    quantities.push({ id: "vx:" + p, label: `vx of ${p} (${velUnit})`, get: (k) => at(S.vx[p], k) });
    quantities.push({ id: "vy:" + p, label: `vy of ${p} (${velUnit})`, get: (k) => at(S.vy[p], k) });
    quantities.push({ id: "a:" + p, label: `|a| of ${p} (${accUnit})`, get: mag(S.ax[p], S.ay[p]) });
    quantities.push({ id: "ax:" + p, label: `ax of ${p} (${accUnit})`, get: (k) => at(S.ax[p], k) });
    quantities.push({ id: "ay:" + p, label: `ay of ${p} (${accUnit})`, get: (k) => at(S.ay[p], k) });
  });
  D.sliders.forEach((s) => {
    quantities.push({ id: "s:" + s.name, label: `s of slider ${s.name} (${U})`, get: (k) => at(S.s[s.name], k) });
    quantities.push({ id: "sv:" + s.name, label: `v of slider ${s.name} (${velUnit})`, get: (k) => at(S.sv[s.name], k) });
    quantities.push({ id: "sa:" + s.name, label: `a of slider ${s.name} (${accUnit})`, get: (k) => at(S.sa[s.name], k) });
  });
  const qsel = $("quantity");
  quantities.forEach((q) => { const o = document.createElement("option"); o.value = q.id; o.textContent = q.label; qsel.appendChild(o); });
  // default: the traced point P of a synthesized linkage, else the angle of the last link (the output, usually)
  if (D.sliders.length) qsel.value = "s:" + D.sliders[D.sliders.length - 1].name;
  else if (movingPoints.includes("P")) qsel.value = "y:P";
  else if (D.links.length) qsel.value = "phi:" + D.links[D.links.length - 1].name;
  const plot = $("plot");
  let plotState = null;
  function drawPlot() {
    while (plot.firstChild) plot.removeChild(plot.firstChild);
    const q = quantities.find((x) => x.id === qsel.value);
    if (!q) return;
    const W = plot.clientWidth || 800, H = plot.clientHeight || 180;
    const xs = [], ys = [];
    for (let k = 0; k < N; k++) { xs.push(inputAngle(k) * DEG); ys.push(closedAt(k) ? q.get(k) : null); }
    const fin = ys.filter((v) => v !== null && isFinite(v));
    let lo = fin.length ? Math.min(...fin) : 0, hi = fin.length ? Math.max(...fin) : 1;
    if (hi - lo < 1e-12 * Math.max(1, Math.abs(hi))) { lo -= 1; hi += 1; }
    const pad = 0.05 * (hi - lo); lo -= pad; hi += pad;
    const x0 = xs[0], x1 = xs[0] + 360;
    const X = (v) => PM.l + (W - PM.l - PM.r) * (v - x0) / (x1 - x0);
    const Y = (v) => PM.t + (H - PM.t - PM.b) * (hi - v) / (hi - lo);
    GL.drawAxes(plot, W, H, X, Y, GL.niceTicks(lo, hi, 4), GL.niceTicks(x0, x1, 8), `input ${D.inputs[0].label} θ (deg)`);
    let d = "", pen = false;
    for (let k = 0; k < N; k++) {
      if (ys[k] === null || !isFinite(ys[k])) { pen = false; continue; }
      d += (pen ? "L" : "M") + X(xs[k]).toFixed(1) + "," + Y(ys[k]).toFixed(1); pen = true;
    }
    el("path", { class: "curve", d: d }, plot);
    const cursor = el("line", { class: "cursor", y1: PM.t, y2: H - PM.b }, plot);
    const hover = el("line", { class: "hover", y1: PM.t, y2: H - PM.b }, plot);
    const htext = el("text", { class: "hover-text", y: PM.t + 12 }, plot);
    show(hover, false); show(htext, false);
    plotState = { q, xs, ys, X, Y, W, cursor, hover, htext };
    plotCursor();
  }
  function plotCursor() {
    if (!plotState) return;
    const x = plotState.X(plotState.xs[st.frame]);
    setLine(plotState.cursor, x, PM.t, x, (plot.clientHeight || 180) - PM.b);
  }
  const plotFrameAt = (evt) => GL.plotFrameAt(plot, N, evt);
  plot.addEventListener("mousemove", (evt) => {
    if (!plotState) return;
    const k = plotFrameAt(evt), ps = plotState;
    const x = ps.X(ps.xs[k]);
    setLine(ps.hover, x, PM.t, x, (plot.clientHeight || 180) - PM.b); show(ps.hover, true);
    ps.htext.textContent = `θ = ${ps.xs[k].toFixed(2)}°: ${fmt(ps.ys[k])}`;
    const right = x > ps.W * 0.6;
    ps.htext.setAttribute("x", right ? x - 6 : x + 6);
    ps.htext.setAttribute("text-anchor", right ? "end" : "start");
    show(ps.htext, true);
  });
  plot.addEventListener("mouseleave", () => { if (plotState) { show(plotState.hover, false); show(plotState.htext, false); } });
  plot.addEventListener("click", (evt) => setFrame(plotFrameAt(evt)));
  qsel.addEventListener("change", drawPlot);

  // ------------------------------------------------------------------ controls
  $("fit").addEventListener("click", fit);
  // narrow windows: the check boxes are a menu under the "show" button
  $("options-button").addEventListener("click", (evt) => {
    evt.stopPropagation();
    const open = $("toolbar").classList.toggle("open");
    $("options-button").setAttribute("aria-expanded", open ? "true" : "false");
  });
  document.addEventListener("click", (evt) => {
    if ($("toolbar").classList.contains("open") && !$("options").contains(evt.target)) {
      $("toolbar").classList.remove("open");
      $("options-button").setAttribute("aria-expanded", "false");
    }
  });
  if (D.grid) {
    $("grid-group").hidden = false;
    const g = $("grid");
    g.max = D.grid.values.length - 1;
    g.value = st.grid;
    $("grid-label").textContent = D.inputs[1].label;
    g.addEventListener("input", () => { st.grid = Number(g.value); buildPaths(); drawPlot(); render(); });
  }
  ["show-velocity", "show-acceleration", "show-paths", "show-centres", "show-labels", "show-kennedy"].forEach((id) => $(id).addEventListener("change", applyToggles));
  $("kennedy-triple").addEventListener("change", () => { if (!$("show-kennedy").checked) $("show-kennedy").checked = true; applyToggles(); });
  window.addEventListener("resize", () => { fit(); drawPlot(); });

  // ------------------------------------------------------------------ export
  function download(name, text, type) {
    const blob = new Blob([text], { type: type });
    const a = document.createElement("a");
    a.href = URL.createObjectURL(blob);
    a.download = name;
    document.body.appendChild(a);
    a.click();
    setTimeout(() => { URL.revokeObjectURL(a.href); a.remove(); }, 1000);
  }
  const base = D.name.replace(/[^A-Za-z0-9_-]+/g, "_");
  $("export-svg").addEventListener("click", () => {
    const clone = view.cloneNode(true);
    clone.setAttribute("width", view.clientWidth);
    clone.setAttribute("height", view.clientHeight);
    const style = document.createElementNS(NS, "style");
    style.textContent = Array.from(document.styleSheets).map((s) => Array.from(s.cssRules).map((r) => r.cssText).join("\n")).join("\n");
    clone.insertBefore(style, clone.firstChild);
    download(`${base}_frame${st.frame}.svg`, new XMLSerializer().serializeToString(clone), "image/svg+xml");
  });
  // the whole cycle shown (every frame, at the chosen value of the second input) as CSV: one row per
  // frame, columns named as `gearlever mechanism analyze` names them; a cell is empty where there is no
  // value (the frame does not assemble, a centre at infinity)
  function cycleCsv() {
    const u = rated ? { v: "_s", a: "_s2", w: "rad_s", al: "rad_s2" }
      : { v: "_per_" + D.inputs[0].label, a: "_per_" + D.inputs[0].label + "_sq", w: "per_" + D.inputs[0].label, al: "per_" + D.inputs[0].label + "_sq" };
    const cols = [];
    const col = (name, get) => cols.push({ name: name, get: get });
    col("frame", (k) => k);
    col(`input_${D.inputs[0].label}_deg`, (k) => inputAngle(k) * DEG);
    if (D.period) col("time_s", (k) => D.period * k / N);
    D.inputs.slice(1).forEach((p, i) => {
      const v = D.grid && i === 0 ? D.grid.values[st.grid] : p.start;
      col(p.kind === "link" ? `input_${p.label}_deg` : `input_${p.label}_${U}`, () => (p.kind === "link" ? v * DEG : v));
    });
    col("closed", (k) => (closedAt(k) ? 1 : 0));
    const ifClosed = (f) => (k) => (closedAt(k) ? f(k) : null);
    D.links.forEach((lk) => {
      col(`${lk.name}_angle_deg`, ifClosed((k) => { const v = at(S.phi[lk.name], k); return v === null ? null : (v + lk.angle0) * DEG; }));
      col(`omega_${lk.name}_${u.w}`, ifClosed((k) => at(S.w[lk.name], k)));
      col(`alpha_${lk.name}_${u.al}`, ifClosed((k) => at(S.al[lk.name], k)));
    });
    D.sliders.forEach((sl) => {
      col(`${sl.name}_s_${U}`, ifClosed((k) => at(S.s[sl.name], k)));
      col(`v_${sl.name}_${U}${u.v}`, ifClosed((k) => at(S.sv[sl.name], k)));
      col(`a_${sl.name}_${U}${u.a}`, ifClosed((k) => at(S.sa[sl.name], k)));
    });
    D.points.forEach((p) => {
      col(`${p}_x_${U}`, ifClosed((k) => at(S.x[p], k)));
      col(`${p}_y_${U}`, ifClosed((k) => at(S.y[p], k)));
      col(`v_${p}_x_${U}${u.v}`, ifClosed((k) => at(S.vx[p], k)));
      col(`v_${p}_y_${U}${u.v}`, ifClosed((k) => at(S.vy[p], k)));
      col(`a_${p}_x_${U}${u.a}`, ifClosed((k) => at(S.ax[p], k)));
      col(`a_${p}_y_${U}${u.a}`, ifClosed((k) => at(S.ay[p], k)));
    });
    if (IC) IC.pairs.forEach((pair) => {
      col(`ic_${pair}_x_${U}`, ifClosed((k) => { const c = icAt(pair, k); return c && c.p ? c.p[0] : null; }));
      col(`ic_${pair}_y_${U}`, ifClosed((k) => { const c = icAt(pair, k); return c && c.p ? c.p[1] : null; }));
    });
    const cell = (v) => {
      if (v === null || v === undefined) return "";
      if (typeof v === "number") return isFinite(v) ? String(Number(v.toPrecision(9))) : "";
      const t = String(v);
      return /[",\r\n]/.test(t) ? '"' + t.replace(/"/g, '""') + '"' : t;
    };
    const lines = [cols.map((c) => cell(c.name)).join(",")];
    for (let k = 0; k < N; k++) lines.push(cols.map((c) => cell(c.get(k))).join(","));
    return lines.join("\n") + "\n";
  }
  $("export-csv").addEventListener("click", () => download(`${base}${D.grid ? "_" + st.grid : ""}_cycle.csv`, cycleCsv(), "text/csv"));

  // ------------------------------------------------------------------ start
  const note = [];
  if (D.grid) note.push(`Two or more inputs: the first (${D.inputs[0].label}) turns over the frames; the slider "${D.inputs[1].label}" chooses one of ${D.grid.values.length} precomputed values of the second` + (D.inputs.length > 2 ? "; further inputs stay at their start values." : "."));
  note.push(rated ? `Velocities and accelerations at ${D.inputs.map((p) => p.label + " " + fmt(p.rate * (p.kind === "link" ? 30 / Math.PI : 60), 6) + (p.kind === "link" ? " rpm" : " " + U + "/min")).join(", ")}, constant speed.` : `Velocities and accelerations are analogues per radian of ${D.inputs[0].label} (no --rpm given).`);
  if (D.centres_capped) note.push(`Instant centres are shown for models of at most ${D.centres_max} bodies.`);
  note.push("Drag the input link, its gear or its dashed ring to turn it; drag the background to pan, wheel to zoom; space plays, arrows step.");
  $("note").textContent = note.join(" ");
  buildPaths();
  const params = new URLSearchParams(window.location.search);
  if (D.grid && params.has("grid")) { const g = Number(params.get("grid")); if (g >= 0 && g < M) { st.grid = Math.floor(g); $("grid").value = st.grid; buildPaths(); } }
  st.frame = startFrame(params);
  legend();
  fit();
  applyToggles();
  drawPlot();
  if (params.get("play") === "1") setPlaying(true);
  // for tests and scripts: the number formatter of the axes, the hover and the legend, and the CSV text
  window.gearlever = { fmt: fmt, tickLabel: GL.tickLabel, cycleCsv: cycleCsv };
  document.body.setAttribute("data-ready", "1");
})();
