// Small SVG line plots against the input, with a hover readout and a cursor at the current frame.

const NS = "http://www.w3.org/2000/svg";
const COLORS = ["#1f5fa8", "#b3261e", "#2e7d32", "#8e44ad"];

export function el(name, attrs = {}, parent = null) {
  const e = document.createElementNS(NS, name);
  for (const [k, v] of Object.entries(attrs)) e.setAttribute(k, String(v));
  if (parent) parent.appendChild(e);
  return e;
}

function nice(lo, hi) {
  if (!(hi > lo)) { hi = lo + 1; lo -= 1; }
  const pad = (hi - lo) * 0.06;
  return [lo - pad, hi + pad];
}

function fmt(v) {
  if (v === null || !Number.isFinite(v)) return "–";
  const a = Math.abs(v);
  return a !== 0 && (a >= 1e5 || a < 1e-3) ? v.toExponential(3) : v.toPrecision(4).replace(/\.?0+$/, "");
}

/**
 * Draw series [{label, ys}] against xs in svg; title names the quantity; cursor is the frame to mark.
 * Hover shows the values at the nearest frame as text (textContent: labels are model names).
 */
export function drawPlot(svg, xs, series, { title = "", xlabel = "input (deg)", cursor = null } = {}) {
  while (svg.firstChild) svg.removeChild(svg.firstChild);
  const W = svg.clientWidth || 300;
  const H = svg.clientHeight || 140;
  svg.setAttribute("viewBox", `0 0 ${W} ${H}`);
  const L = 46, R = 14, T = 30, B = 22;
  el("rect", { x: 0, y: 0, width: W, height: H, class: "plot-bg" }, svg);
  const t = el("text", { x: L, y: 12, class: "plot-title" }, svg);
  t.textContent = title;
  if (!xs || !xs.length || !series.length) {
    const e = el("text", { x: W / 2, y: H / 2, class: "plot-empty", "text-anchor": "middle" }, svg);
    e.textContent = "no data";
    return;
  }
  const finite = series.flatMap((s) => s.ys.filter((v) => v !== null && Number.isFinite(v)));
  const [ylo, yhi] = nice(Math.min(...finite), Math.max(...finite));
  const xfin = xs.filter((v) => v !== null && Number.isFinite(v));
  const [xlo, xhi] = [Math.min(...xfin), Math.max(...xfin)];
  const sx = (x) => L + ((x - xlo) / (xhi - xlo || 1)) * (W - L - R);
  const sy = (y) => T + (1 - (y - ylo) / (yhi - ylo)) * (H - T - B);
  el("line", { x1: L, y1: H - B, x2: W - R, y2: H - B, class: "plot-axis" }, svg);
  el("line", { x1: L, y1: T, x2: L, y2: H - B, class: "plot-axis" }, svg);
  for (const y of [ylo, (ylo + yhi) / 2, yhi]) {
    const lbl = el("text", { x: L - 4, y: sy(y) + 4, class: "plot-tick", "text-anchor": "end" }, svg);
    lbl.textContent = fmt(y);
  }
  for (const [x, anchor] of [[xlo, "start"], [(xlo + xhi) / 2, "middle"], [xhi, "end"]]) {
    const lbl = el("text", { x: sx(x), y: H - 6, class: "plot-tick", "text-anchor": anchor }, svg);
    lbl.textContent = fmt(x);
  }
  t.textContent = `${title} against ${xlabel}`;
  series.forEach((s, k) => {
    let d = "";
    let pen = false;
    s.ys.forEach((y, i) => {
      if (y === null || !Number.isFinite(y) || xs[i] === null) { pen = false; return; }
      d += `${pen ? "L" : "M"}${sx(xs[i]).toFixed(1)},${sy(y).toFixed(1)}`;
      pen = true;
    });
    el("path", { d, class: "plot-line", stroke: COLORS[k % COLORS.length] }, svg);
    const key = el("text", { x: L + 4 + k * 120, y: 24, class: "plot-key", fill: COLORS[k % COLORS.length] }, svg);
    key.textContent = s.label;
  });
  const mark = el("line", { x1: 0, y1: T, x2: 0, y2: H - B, class: "plot-cursor" }, svg);
  const setMark = (i) => {
    if (i === null || xs[i] === null) { mark.setAttribute("visibility", "hidden"); return; }
    mark.setAttribute("visibility", "visible");
    mark.setAttribute("x1", sx(xs[i])); mark.setAttribute("x2", sx(xs[i]));
  };
  setMark(cursor);
  const readout = el("text", { x: W - R, y: H - B - 5, class: "plot-readout", "text-anchor": "end" }, svg);
  const hover = el("line", { x1: 0, y1: T, x2: 0, y2: H - B, class: "plot-hover", visibility: "hidden" }, svg);
  const hit = el("rect", { x: L, y: T, width: W - L - R, height: H - T - B, class: "plot-hit" }, svg);
  hit.addEventListener("pointermove", (ev) => {
    const r = svg.getBoundingClientRect();
    const x = xlo + ((ev.clientX - r.left) * (W / r.width) - L) / (W - L - R) * (xhi - xlo);
    let best = 0;
    xs.forEach((v, i) => { if (v !== null && Math.abs(v - x) < Math.abs(xs[best] - x)) best = i; });
    hover.setAttribute("visibility", "visible");
    hover.setAttribute("x1", sx(xs[best])); hover.setAttribute("x2", sx(xs[best]));
    readout.textContent = `${fmt(xs[best])}: ` + series.map((s) => `${s.label} ${fmt(s.ys[best])}`).join(", ");
    svg.dataset.hover = String(best);
  });
  hit.addEventListener("pointerleave", () => { hover.setAttribute("visibility", "hidden"); readout.textContent = ""; });
  return { setMark };
}
