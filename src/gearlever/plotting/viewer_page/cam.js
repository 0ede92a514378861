(function () {
  "use strict";
  const D = JSON.parse(document.getElementById("gl-data").textContent);
  const N = D.N, L = D.L, F = D.F;
  const view = document.getElementById("view");
  const world = document.getElementById("world");
  const { $, fmt, esc, el, show, setLine, PM } = GL;  // common.js
  const DEG = 180 / Math.PI;
  const st = { frame: 0, playing: false, speed: 1, acc: 0, last: null, s: 1, tx: 0, ty: 0, drag: null };
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
  // zoom, pan, and dragging the cam: it turns by the change of the pointer's angle about its centre
  const { fit } = GL.viewControls({
    view: view, st: st, N: N, bbox: D.bbox, applyView: applyView,
    canTurn: () => true, pivot: () => [0, 0], setFrame: (k) => setFrame(k), setPlaying: (on) => setPlaying(on),
  });
  // frames, play (1x: a turn in 6 s), URL
  const { setFrame, setPlaying, scheduleUrl, startFrame } = GL.transport({ st: st, N: N, render: () => render(), fps: () => N / 6, dir: 1 });

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
  let plotState = null;
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
    GL.drawAxes(plot, W, H, X, Y, GL.niceTicks(lo, hi, 4), GL.niceTicks(0, 360, 8), "cam angle θ (deg)");
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
  plot.addEventListener("click", (evt) => { setPlaying(false); setFrame(GL.plotFrameAt(plot, N, evt)); });
  qsel.addEventListener("change", drawPlot);

  // ------------------------------------------------------------------ controls
  $("fit").addEventListener("click", fit);
  ["show-pitch", "show-normal"].forEach((id) => $(id).addEventListener("change", render));
  if (!D.pitch) $("show-pitch").parentNode.hidden = true;
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
  st.frame = startFrame(params);
  fit();
  drawPlot();
  render();
  if (params.get("play") === "1") setPlaying(true);
  window.gearlever = { fmt: fmt, data: D };
  document.body.setAttribute("data-ready", "1");
})();
