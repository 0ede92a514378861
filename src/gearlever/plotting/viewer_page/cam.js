(function () {
  "use strict";
  const D = JSON.parse(document.getElementById("gl-data").textContent);
  const N = D.N, L = D.L, F = D.F;
  const view = document.getElementById("view");
  const NS = view.namespaceURI;
  const world = document.getElementById("world");
  const $ = (id) => document.getElementById(id);
  const DEG = 180 / Math.PI;
  const st = { frame: 0, playing: false, speed: 1, acc: 0, last: null, s: 1, tx: 0, ty: 0, drag: null };

  function fmt(v, d) {
    if (v === null || v === undefined || !isFinite(Number(v))) return "–";
    const s = Number(v).toPrecision(d || 6);
    const e = s.indexOf("e");
    let man = e < 0 ? s : s.slice(0, e);
    const ex = e < 0 ? "" : s.slice(e);
    if (man.indexOf(".") >= 0) man = man.replace(/0+$/, "").replace(/\.$/, "");
    if (/^-0*$/.test(man)) man = "0";
    return man + ex;
  }
  const esc = (t) => String(t).replace(/[&<>"']/g, (c) => ({ "&": "&amp;", "<": "&lt;", ">": "&gt;", '"': "&quot;", "'": "&#39;" })[c]);
  function el(tag, attrs, parent) {
    const e = document.createElementNS(NS, tag);
    for (const k in attrs) e.setAttribute(k, attrs[k]);
    if (parent) parent.appendChild(e);
    return e;
  }
  function show(e, on) { e.style.display = on ? "" : "none"; }
  function setLine(e, x1, y1, x2, y2) { e.setAttribute("x1", x1); e.setAttribute("y1", y1); e.setAttribute("x2", x2); e.setAttribute("y2", y2); }
  const poly = (xs, ys) => xs.map((x, i) => x + "," + ys[i]).join(" ");

  // ------------------------------------------------------------------ the drawing
  const gGround = $("ground"), gCam = $("cam"), gFol = $("follower");
  gCam.setAttribute("data-cam", D.follower);
  el("circle", { class: "base-circle", cx: 0, cy: 0, r: D.base_radius }, gCam);
  el("polygon", { class: "cam-body", "data-profile": "surface", points: poly(D.profile.x, D.profile.y) }, gCam);
  const pitchEl = D.pitch ? el("polygon", { class: "pitch", "data-pitch": "pitch", points: poly(D.pitch.x, D.pitch.y) }, gCam) : null;
  // a mark on the cam (its angle zero) and the shaft
  el("line", { class: "cam-mark", x1: 0, y1: 0, x2: 0.6 * D.base_radius, y2: 0 }, gCam);
  el("circle", { class: "hub", "data-hub": "1", fill: "#1f3b66", cx: 0, cy: 0, r: 0.06 * D.base_radius }, gCam);
  // ground: the cam's bearing, the follower's pivot or guide
  const h = 0.06 * L;
  function groundPivot(x, y) {
    el("polygon", { class: "ground-shape", points: `${x},${y} ${x - h * 0.7},${y - h} ${x + h * 0.7},${y - h}` }, gGround);
    el("line", { class: "hatch", x1: x - h, y1: y - h, x2: x + h, y2: y - h }, gGround);
    for (let i = 0; i < 5; i++) { const x0 = x - h + i * h * 0.5; el("line", { class: "hatch", x1: x0, y1: y - h, x2: x0 - h * 0.35, y2: y - h * 1.4 }, gGround); }
  }
  groundPivot(0, 0);
  if (D.pivot) groundPivot(D.pivot[0], D.pivot[1]);
  if (D.guide) {
    const g = D.guide;
    [-1, 1].forEach((sgn) => {
      const x = g.x + sgn * g.w;
      el("line", { class: "hatch", "data-guide": sgn, x1: x, y1: g.y0, x2: x, y2: g.y1 }, gGround);
      for (let i = 0; i <= 4; i++) { const y = g.y0 + (g.y1 - g.y0) * i / 4; el("line", { class: "hatch", x1: x, y1: y, x2: x + sgn * 0.4 * g.w, y2: y - 0.4 * g.w }, gGround); }
    });
  }
  const armEl = el("line", { class: "follower", "data-arm": D.motion }, gFol);
  const faceEl = F.face ? el("line", { class: "face", "data-face": D.follower }, gFol) : null;
  const rollerEl = F.rx ? el("circle", { class: "roller", "data-roller": D.follower, r: D.roller_radius }, gFol) : null;
  const normalEl = el("line", { class: "normal", "data-normal": "1" }, gFol);
  const pivotEl = D.pivot ? el("circle", { class: "pt ground-pt", cx: D.pivot[0], cy: D.pivot[1], r: 1 }, gFol) : null;
  const contactEl = el("circle", { class: "contact", "data-contact": "1", r: 1 }, gFol);

  // ------------------------------------------------------------------ view transform
  function applyView() {
    world.setAttribute("transform", `matrix(${st.s},0,0,${-st.s},${st.tx},${st.ty})`);
    contactEl.setAttribute("r", 3.5 / st.s);
    if (pivotEl) pivotEl.setAttribute("r", 4.5 / st.s);
    render();
  }
  function fit() {
    const w = view.clientWidth || 800, hgt = view.clientHeight || 500;
    const [x0, y0, x1, y1] = D.bbox;
    const s = 0.94 * Math.min(w / (x1 - x0), hgt / (y1 - y0));
    st.s = s; st.tx = w / 2 - s * (x0 + x1) / 2; st.ty = hgt / 2 + s * (y0 + y1) / 2;
    applyView();
  }
  function toWorld(evt) {
    const r = view.getBoundingClientRect();
    return [(evt.clientX - r.left - st.tx) / st.s, (st.ty - (evt.clientY - r.top)) / st.s];
  }

  // ------------------------------------------------------------------ one frame
  const outName = D.output === "angle" ? "ψ" : "s";
  function render() {
    const k = st.frame;
    gCam.setAttribute("transform", `rotate(${D.theta[k] * DEG})`);
    const a = F.arm;
    setLine(armEl, a[0][k], a[1][k], a[2][k], a[3][k]);
    if (faceEl) setLine(faceEl, F.face[0][k], F.face[1][k], F.face[2][k], F.face[3][k]);
    if (rollerEl) { rollerEl.setAttribute("cx", F.rx[k]); rollerEl.setAttribute("cy", F.ry[k]); }
    contactEl.setAttribute("cx", F.cx[k]); contactEl.setAttribute("cy", F.cy[k]);
    // the common normal at the contact (the line of the force), 0.3 L long
    let nx, ny;
    if (rollerEl) { nx = F.rx[k] - F.cx[k]; ny = F.ry[k] - F.cy[k]; }
    else { nx = -(F.face[3][k] - F.face[1][k]); ny = F.face[2][k] - F.face[0][k]; }
    const n = Math.hypot(nx, ny) || 1;
    setLine(normalEl, F.cx[k] - 0.15 * L * nx / n, F.cy[k] - 0.15 * L * ny / n, F.cx[k] + 0.3 * L * nx / n, F.cy[k] + 0.3 * L * ny / n);
    show(normalEl, $("show-normal").checked);
    if (pitchEl) show(pitchEl, $("show-pitch").checked);
    $("readout").textContent = `θ = ${(D.theta[k] * DEG).toFixed(2)}° · ${outName} = ${fmt(F.s[k])} ${D.out_units} · pressure angle = ${fmt(F.phi[k], 4)}°`;
    $("frame").value = k;
    plotCursor();
    scheduleUrl();
  }

  // ------------------------------------------------------------------ plot
  const per = D.out_units + "/rad";
  const quantities = [
    { id: "s", label: `follower ${D.output === "angle" ? "angle ψ" : "displacement s"} (${D.out_units})`, get: (k) => F.s[k] },
    { id: "phi", label: "pressure angle (deg)", get: (k) => F.phi[k] },
    { id: "v", label: `velocity (${per})`, get: (k) => F.v[k] },
    { id: "a", label: `acceleration (${per}²)`, get: (k) => F.a[k] },
  ];
  const qsel = $("quantity");
  quantities.forEach((q) => { const o = document.createElement("option"); o.value = q.id; o.textContent = q.label; qsel.appendChild(o); });
  const plot = $("plot");
  const PM = { l: 62, r: 12, t: 10, b: 30 };
  let plotState = null;
  function niceTicks(lo, hi, n) {
    if (!(hi > lo)) { hi = lo + 1; lo = lo - 1; }
    const raw = (hi - lo) / n, mag = Math.pow(10, Math.floor(Math.log10(raw)));
    const step = [1, 2, 2.5, 5, 10].map((m) => m * mag).find((s) => s >= raw) || raw;
    const out = [];
    for (let v = Math.ceil(lo / step) * step; v <= hi + 1e-9 * step; v += step) out.push(v);
    return out;
  }
  function tickLabel(v, step) {
    if (Math.abs(v) < 1e-9 * step) return "0";
    const dec = Math.min(12, Math.max(0, Math.ceil(-Math.log10(step)) + 1));
    return fmt(Number(v.toFixed(dec)), 15);
  }
  function drawPlot() {
    while (plot.firstChild) plot.removeChild(plot.firstChild);
    const q = quantities.find((x) => x.id === qsel.value);
    const W = plot.clientWidth || 800, H = plot.clientHeight || 180;
    const xs = [], ys = [];
    for (let k = 0; k < N; k++) { xs.push(D.theta[k] * DEG); ys.push(q.get(k)); }
    let lo = Math.min(...ys), hi = Math.max(...ys);
    if (hi - lo < 1e-12 * Math.max(1, Math.abs(hi))) { lo -= 1; hi += 1; }
    const pad = 0.05 * (hi - lo); lo -= pad; hi += pad;
    const X = (v) => PM.l + (W - PM.l - PM.r) * v / 360;
    const Y = (v) => PM.t + (H - PM.t - PM.b) * (hi - v) / (hi - lo);
    const yt = niceTicks(lo, hi, 4), xt = niceTicks(0, 360, 8);
    yt.forEach((v) => {
      el("line", { class: "grid", x1: PM.l, x2: W - PM.r, y1: Y(v), y2: Y(v) }, plot);
      const t = el("text", { class: "ytick", x: PM.l - 4, y: Y(v) + 4, "text-anchor": "end" }, plot);
      t.textContent = tickLabel(v, yt.length > 1 ? yt[1] - yt[0] : 1);
    });
    xt.forEach((v) => {
      el("line", { class: "grid", y1: PM.t, y2: H - PM.b, x1: X(v), x2: X(v) }, plot);
      const t = el("text", { class: "xtick", x: X(v), y: H - PM.b + 14, "text-anchor": "middle" }, plot);
      t.textContent = tickLabel(v, xt[1] - xt[0]);
    });
    el("line", { class: "axis", x1: PM.l, x2: W - PM.r, y1: H - PM.b, y2: H - PM.b }, plot);
    el("line", { class: "axis", x1: PM.l, x2: PM.l, y1: PM.t, y2: H - PM.b }, plot);
    const xl = el("text", { x: W - PM.r, y: H - 3, "text-anchor": "end" }, plot); xl.textContent = "cam angle θ (deg)";
    let d = "";
    for (let k = 0; k < N; k++) d += (k ? "L" : "M") + X(xs[k]).toFixed(1) + "," + Y(ys[k]).toFixed(1);
    d += "L" + X(360).toFixed(1) + "," + Y(ys[0]).toFixed(1);
    el("path", { class: "curve", "data-curve": q.id, d: d }, plot);
    const cursor = el("line", { class: "cursor", "data-cursor": "1", y1: PM.t, y2: H - PM.b }, plot);
    const dot = el("circle", { class: "cursor-dot", r: 3.5, fill: "#b3261e" }, plot);
    plotState = { xs, ys, X, Y, H, cursor, dot };
    plotCursor();
  }
  function plotCursor() {
    if (!plotState) return;
    const ps = plotState, k = st.frame, x = ps.X(ps.xs[k]);
    setLine(ps.cursor, x, PM.t, x, ps.H - PM.b);
    ps.dot.setAttribute("cx", x); ps.dot.setAttribute("cy", ps.Y(ps.ys[k]));
  }
  plot.addEventListener("click", (evt) => {
    const r = plot.getBoundingClientRect();
    const f = (evt.clientX - r.left - PM.l) / (r.width - PM.l - PM.r);
    setPlaying(false);
    setFrame(Math.min(N - 1, Math.max(0, Math.round(f * N))));
  });
  qsel.addEventListener("change", drawPlot);

  // ------------------------------------------------------------------ frames, play, URL
  function setFrame(k) { st.frame = ((Math.round(k) % N) + N) % N; render(); }
  let urlTimer = null;
  function scheduleUrl() {
    if (urlTimer) return;
    urlTimer = setTimeout(() => {
      urlTimer = null;
      try {
        const u = new URL(window.location.href);
        u.searchParams.set("frame", st.frame);
        if (st.playing) u.searchParams.set("play", "1"); else u.searchParams.delete("play");
        history.replaceState(null, "", u.toString());
      } catch (e) { /* a page opened where the URL cannot change */ }
    }, 250);
  }
  function setPlaying(on) {
    st.playing = on; st.last = null; st.acc = 0;
    $("play").textContent = on ? "❚❚ pause" : "▶ play";
    $("play").setAttribute("aria-pressed", on ? "true" : "false");
    scheduleUrl();
    if (on) requestAnimationFrame(tick);
  }
  function tick(t) {
    if (!st.playing) return;
    if (st.last !== null) {
      st.acc += Math.min(0.25, (t - st.last) / 1000) * (N / 6) * st.speed;  // 1x: a turn in 6 s
      const n = Math.floor(st.acc);
      if (n > 0) { st.acc -= n; setFrame(st.frame + n); }
    }
    st.last = t;
    requestAnimationFrame(tick);
  }
  $("play").addEventListener("click", () => setPlaying(!st.playing));
  $("step").addEventListener("click", () => { setPlaying(false); setFrame(st.frame + 1); });
  $("step-back").addEventListener("click", () => { setPlaying(false); setFrame(st.frame - 1); });
  $("speed").addEventListener("change", () => { st.speed = Number($("speed").value); });
  $("fit").addEventListener("click", fit);
  ["show-pitch", "show-normal"].forEach((id) => $(id).addEventListener("change", render));
  if (!D.pitch) $("show-pitch").parentNode.hidden = true;
  const frameInput = $("frame");
  frameInput.max = N - 1;
  frameInput.addEventListener("input", () => setFrame(Number(frameInput.value)));
  document.addEventListener("keydown", (evt) => {
    const tag = evt.target && evt.target.tagName;
    if (tag === "SELECT") return;
    if (evt.key === " " || evt.code === "Space") { evt.preventDefault(); setPlaying(!st.playing); }
    else if (evt.key === "ArrowRight" || evt.key === "ArrowUp") { evt.preventDefault(); setPlaying(false); setFrame(st.frame + 1); }
    else if (evt.key === "ArrowLeft" || evt.key === "ArrowDown") { evt.preventDefault(); setPlaying(false); setFrame(st.frame - 1); }
  });

  // ------------------------------------------------------------------ zoom, pan, drag the cam
  view.addEventListener("wheel", (evt) => {
    evt.preventDefault();
    const r = view.getBoundingClientRect();
    const sx = evt.clientX - r.left, sy = evt.clientY - r.top;
    const wx = (sx - st.tx) / st.s, wy = (st.ty - sy) / st.s;
    st.s *= Math.exp(-evt.deltaY * 0.0015); st.tx = sx - st.s * wx; st.ty = sy + st.s * wy;
    applyView();
  }, { passive: false });
  // the pointer's angle about the cam centre (null within a few pixels of it)
  function pointerAngle(evt) {
    const [wx, wy] = toWorld(evt);
    return Math.hypot(wx, wy) * st.s < 6 ? null : Math.atan2(wy, wx);
  }
  // dragging the cam is relative: it turns by the change of the pointer's angle about its centre
  view.addEventListener("pointerdown", (evt) => {
    const grab = evt.target.closest && evt.target.closest(".grab");
    view.setPointerCapture(evt.pointerId);
    if (grab) { st.drag = { mode: "cam", k0: st.frame, a: pointerAngle(evt), turn: 0 }; setPlaying(false); }
    else { st.drag = { mode: "pan", x: evt.clientX, y: evt.clientY }; view.style.cursor = "grabbing"; }
  });
  view.addEventListener("pointermove", (evt) => {
    const d = st.drag;
    if (!d) return;
    if (d.mode === "pan") {
      st.tx += evt.clientX - d.x; st.ty += evt.clientY - d.y; d.x = evt.clientX; d.y = evt.clientY;
      applyView();
      return;
    }
    const a = pointerAngle(evt);
    if (a === null) return;
    if (d.a !== null) d.turn += Math.atan2(Math.sin(a - d.a), Math.cos(a - d.a));
    d.a = a;
    const k = d.k0 + Math.round(d.turn * N / (2 * Math.PI));
    if (((k % N) + N) % N !== st.frame) setFrame(k);
  });
  function endDrag(evt) {
    if (st.drag) { st.drag = null; view.style.cursor = ""; try { view.releasePointerCapture(evt.pointerId); } catch (e) { /* released */ } }
  }
  view.addEventListener("pointerup", endDrag);
  view.addEventListener("pointercancel", endDrag);
  window.addEventListener("resize", () => { fit(); drawPlot(); });

  // ------------------------------------------------------------------ start
  const U = D.units === "length" ? "" : " " + D.units;
  const dims = [`base radius ${fmt(D.base_radius)}${U}`];
  if (D.roller_radius !== null) dims.push(`roller radius ${fmt(D.roller_radius)}`);
  if (D.offset !== null && D.offset !== 0) dims.push(`offset ${fmt(D.offset)}`);
  if (D.arm !== null) dims.push(`arm ${fmt(D.arm)}`);
  if (D.pivot_distance !== null) dims.push(`pivot distance ${fmt(D.pivot_distance)}`);
  $("legend").innerHTML = `${esc(D.follower)} follower: ${esc(dims.join(", "))}; stroke ${esc(fmt(D.stroke))} ${esc(D.out_units)}; ` +
    `largest pressure angle ${esc(fmt(D.pressure_angle_max, 4))}°` + (D.undercut ? ' · <span class="warn">undercut</span>' : "");
  $("note").textContent = "The cam turns counterclockwise; dashed green: the common normal at the contact (the line of the force). " +
    "Drag the cam to turn it; drag the background to pan, wheel to zoom; space plays, arrows step.";
  const params = new URLSearchParams(window.location.search);
  const f0 = Number(params.get("frame"));
  st.frame = Number.isFinite(f0) ? ((Math.floor(f0) % N) + N) % N : 0;
  fit();
  drawPlot();
  render();
  if (params.get("play") === "1") setPlaying(true);
  window.gearlever = { fmt: fmt, data: D };
  document.body.setAttribute("data-ready", "1");
})();
