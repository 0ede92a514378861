// What the mechanism page (viewer.js) and the cam page (cam.js) share: number formatting, SVG helpers,
// plot axes, pan and zoom of the drawing with the turning drag, and the transport (frames, play, URL, keys).
const GL = (function () {
  "use strict";
  const NS = document.getElementById("view").namespaceURI;  // SVG's (no URL in the page: nothing looks online)
  const $ = (id) => document.getElementById(id);

  // a number to d significant digits (default 6), trailing zeros of the fraction dropped (never those of
  // a whole number: 1000 stays "1000"); "–" for no value
  function fmt(v, d) {
    if (v === null || v === undefined || v === "" || !isFinite(Number(v))) return "–";
    const s = Number(v).toPrecision(d || 6);
    const e = s.indexOf("e");
    let man = e < 0 ? s : s.slice(0, e);
    const ex = e < 0 ? "" : s.slice(e);
    if (man.indexOf(".") >= 0) man = man.replace(/0+$/, "").replace(/\.$/, "");
    if (/^-0*$/.test(man)) man = "0";
    return man + ex;
  }
  // text for innerHTML: model names, units and labels are the user's text
  const esc = (t) => String(t).replace(/[&<>"']/g, (c) => ({ "&": "&amp;", "<": "&lt;", ">": "&gt;", '"': "&quot;", "'": "&#39;" })[c]);

  // ------------------------------------------------------------------ svg helpers
  function el(tag, attrs, parent) {
    const e = document.createElementNS(NS, tag);
    for (const k in attrs) e.setAttribute(k, attrs[k]);
    if (parent) parent.appendChild(e);
    return e;
  }
  function show(e, on) { e.style.display = on ? "" : "none"; }
  function setLine(e, x1, y1, x2, y2) {
    e.setAttribute("x1", x1); e.setAttribute("y1", y1); e.setAttribute("x2", x2); e.setAttribute("y2", y2);
  }

  // ------------------------------------------------------------------ plot axes
  const PM = { l: 62, r: 12, t: 10, b: 30 };  // the plot's margins (px)
  function niceTicks(lo, hi, n) {
    if (!(hi > lo)) { hi = lo + 1; lo = lo - 1; }
    const raw = (hi - lo) / n, mag = Math.pow(10, Math.floor(Math.log10(raw)));
    const step = [1, 2, 2.5, 5, 10].map((m) => m * mag).find((s) => s >= raw) || raw;
    const out = [];
    for (let v = Math.ceil(lo / step) * step; v <= hi + 1e-9 * step; v += step) out.push(v);
    return out;
  }
  // an axis tick: the decimals its step needs (2.5 -> "2.5", 1000 -> "1000"); very large or small
  // values to 6 significant digits
  function tickLabel(v, step) {
    if (Math.abs(v) < 1e-9 * step) return "0";
    const a = Math.max(Math.abs(v), step);
    if (a >= 1e7 || a < 1e-4) return fmt(v, 6);
    const dec = Math.min(12, Math.max(0, Math.ceil(-Math.log10(step)) + 1));
    return fmt(Number(v.toFixed(dec)), 15);
  }
  // grid, ticks and axes of a plot W x H px whose data map to px by X and Y; the x axis named xlabel
  function drawAxes(plot, W, H, X, Y, yt, xt, xlabel) {
    yt.forEach((v) => {
      el("line", { class: "grid", x1: PM.l, x2: W - PM.r, y1: Y(v), y2: Y(v) }, plot);
      const t = el("text", { class: "ytick", x: PM.l - 4, y: Y(v) + 4, "text-anchor": "end", "data-value": v }, plot);
      t.textContent = tickLabel(v, yt.length > 1 ? yt[1] - yt[0] : Math.abs(v) || 1);
    });
    xt.forEach((v) => {
      el("line", { class: "grid", y1: PM.t, y2: H - PM.b, x1: X(v), x2: X(v) }, plot);
      const t = el("text", { class: "xtick", x: X(v), y: H - PM.b + 14, "text-anchor": "middle", "data-value": v }, plot);
      t.textContent = tickLabel(v, xt.length > 1 ? xt[1] - xt[0] : Math.abs(v) || 1);
    });
    el("line", { class: "axis", x1: PM.l, x2: W - PM.r, y1: H - PM.b, y2: H - PM.b }, plot);
    el("line", { class: "axis", x1: PM.l, x2: PM.l, y1: PM.t, y2: H - PM.b }, plot);
    const xl = el("text", { x: W - PM.r, y: H - 3, "text-anchor": "end" }, plot);
    xl.textContent = xlabel;
  }
  // the frame (of N over the plot's width) under the pointer
  function plotFrameAt(plot, N, evt) {
    const r = plot.getBoundingClientRect();
    const f = (evt.clientX - r.left - PM.l) / (r.width - PM.l - PM.r);
    return Math.min(N - 1, Math.max(0, Math.round(f * N)));
  }

  // ------------------------------------------------------------------ zoom, pan, turning drag
  // The drawing `view` (its <g id="world"> flipped so that y is up) in the state st (s, tx, ty, drag,
  // frame).  o.applyView() redraws after a change of the view; o.bbox [x0, y0, x1, y1] is what fit()
  // shows.  A pointer down on a ".grab" element when o.canTurn() starts a turning drag: the frame
  // follows the change of the pointer's angle about o.pivot() (null: no drag) since the grab (from
  // wherever it starts, the pivot included), one frame per 360/N degrees; elsewhere it pans.
  function viewControls(o) {
    const view = o.view, st = o.st, N = o.N;
    function fit() {
      const w = view.clientWidth || 800, hgt = view.clientHeight || 500;
      const [x0, y0, x1, y1] = o.bbox;
      const s = 0.94 * Math.min(w / (x1 - x0), hgt / (y1 - y0));
      st.s = s;
      st.tx = w / 2 - s * (x0 + x1) / 2;
      st.ty = hgt / 2 + s * (y0 + y1) / 2;
      o.applyView();
    }
    const toScreen = (x, y) => [st.tx + st.s * x, st.ty - st.s * y];
    function toWorld(evt) {
      const r = view.getBoundingClientRect();
      const sx = evt.clientX - r.left, sy = evt.clientY - r.top;
      return [(sx - st.tx) / st.s, (st.ty - sy) / st.s];
    }
    view.addEventListener("wheel", (evt) => {
      evt.preventDefault();
      const r = view.getBoundingClientRect();
      const sx = evt.clientX - r.left, sy = evt.clientY - r.top;
      const wx = (sx - st.tx) / st.s, wy = (st.ty - sy) / st.s;
      const f = Math.exp(-evt.deltaY * 0.0015);
      st.s *= f; st.tx = sx - st.s * wx; st.ty = sy + st.s * wy;
      o.applyView();
    }, { passive: false });
    // the pointer's angle about the pivot (null within a few pixels of it: no direction there)
    function pointerAngle(evt) {
      const [wx, wy] = toWorld(evt);
      const c = o.pivot();
      if (!c || c[0] === null || c[1] === null) return null;
      const dx = wx - c[0], dy = wy - c[1];
      return Math.hypot(dx, dy) * st.s < 6 ? null : Math.atan2(dy, dx);
    }
    view.addEventListener("pointerdown", (evt) => {
      const grab = evt.target.closest && evt.target.closest(".grab");
      view.setPointerCapture(evt.pointerId);
      if (grab && o.canTurn()) {
        st.drag = { mode: "turn", k0: st.frame, a: pointerAngle(evt), turn: 0 };
        o.setPlaying(false);
      } else {
        st.drag = { mode: "pan", x: evt.clientX, y: evt.clientY };
        view.style.cursor = "grabbing";
      }
    });
    view.addEventListener("pointermove", (evt) => {
      const d = st.drag;
      if (!d) return;
      if (d.mode === "pan") {
        st.tx += evt.clientX - d.x; st.ty += evt.clientY - d.y;
        d.x = evt.clientX; d.y = evt.clientY;
        o.applyView();
        return;
      }
      const a = pointerAngle(evt);
      if (a === null) return;
      if (d.a !== null) d.turn += Math.atan2(Math.sin(a - d.a), Math.cos(a - d.a));
      d.a = a;
      const k = d.k0 + Math.round(d.turn * N / (2 * Math.PI));
      if (((k % N) + N) % N !== st.frame) o.setFrame(k);
    });
    function endDrag(evt) {
      if (st.drag) { st.drag = null; view.style.cursor = ""; try { view.releasePointerCapture(evt.pointerId); } catch (e) { /* released */ } }
    }
    view.addEventListener("pointerup", endDrag);
    view.addEventListener("pointercancel", endDrag);
    return { fit: fit, toScreen: toScreen, toWorld: toWorld };
  }

  // ------------------------------------------------------------------ frames, play, URL, keys
  // N frames in st (frame, playing, speed, acc, last); o.render() draws the frame st.frame; playing
  // advances o.fps() frames a second (times the speed) in the direction o.dir (+1 or -1);
  // o.urlParams(u) adds the page's own parameters to the URL (?frame=k&play=1).  Drives the controls
  // play, step, step-back, speed, frame (slider) and the keys space and arrows.
  function transport(o) {
    const st = o.st, N = o.N;
    let urlTimer = null;
    function setFrame(k) {
      st.frame = ((Math.round(k) % N) + N) % N;
      o.render();
    }
    function scheduleUrl() {
      if (urlTimer) return;
      urlTimer = setTimeout(() => {
        urlTimer = null;
        try {
          const u = new URL(window.location.href);
          u.searchParams.set("frame", st.frame);
          if (st.playing) u.searchParams.set("play", "1"); else u.searchParams.delete("play");
          if (o.urlParams) o.urlParams(u);
          history.replaceState(null, "", u.toString());
        } catch (e) { /* a page opened where the URL cannot change */ }
      }, 250);
    }
    function setPlaying(on) {
      st.playing = on;
      st.last = null;
      st.acc = 0;
      $("play").textContent = on ? "❚❚ pause" : "▶ play";
      $("play").setAttribute("aria-pressed", on ? "true" : "false");
      scheduleUrl();
      if (on) requestAnimationFrame(tick);
    }
    function tick(t) {
      if (!st.playing) return;
      if (st.last !== null) {
        st.acc += Math.min(0.25, (t - st.last) / 1000) * o.fps() * st.speed;
        const n = Math.floor(st.acc);
        if (n > 0) { st.acc -= n; setFrame(st.frame + n * o.dir); }
      }
      st.last = t;
      requestAnimationFrame(tick);
    }
    $("play").addEventListener("click", () => setPlaying(!st.playing));
    $("step").addEventListener("click", () => { setPlaying(false); setFrame(st.frame + 1); });
    $("step-back").addEventListener("click", () => { setPlaying(false); setFrame(st.frame - 1); });
    $("speed").addEventListener("change", () => { st.speed = Number($("speed").value); });
    const frameInput = $("frame");
    frameInput.max = N - 1;
    frameInput.addEventListener("input", () => setFrame(Number(frameInput.value)));
    document.addEventListener("keydown", (evt) => {
      const tag = evt.target && evt.target.tagName;
      if (tag === "SELECT" || (tag === "INPUT" && evt.target.type === "text")) return;
      if (evt.key === " " || evt.code === "Space") { evt.preventDefault(); setPlaying(!st.playing); }
      else if (evt.key === "ArrowRight" || evt.key === "ArrowUp") { evt.preventDefault(); setPlaying(false); setFrame(st.frame + 1); }
      else if (evt.key === "ArrowLeft" || evt.key === "ArrowDown") { evt.preventDefault(); setPlaying(false); setFrame(st.frame - 1); }
    });
    // the frame of ?frame=k (default 0)
    function startFrame(params) {
      const f0 = Number(params.get("frame"));
      return Number.isFinite(f0) ? ((Math.floor(f0) % N) + N) % N : 0;
    }
    return { setFrame: setFrame, setPlaying: setPlaying, scheduleUrl: scheduleUrl, startFrame: startFrame };
  }

  return {
    NS: NS, $: $, fmt: fmt, esc: esc, el: el, show: show, setLine: setLine,
    PM: PM, niceTicks: niceTicks, tickLabel: tickLabel, drawAxes: drawAxes, plotFrameAt: plotFrameAt,
    viewControls: viewControls, transport: transport,
  };
})();
