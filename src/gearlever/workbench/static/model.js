// The page's model object: the model file as a JSON object (what POST /api/parse answers), and the edits the
// tools make to it. Nothing here computes motion: positions are the sketch the user drew.

export const EMPTY = () => ({ mechanism: { name: "mechanism", units: "mm" }, points: {}, links: {} });

export const clone = (m) => JSON.parse(JSON.stringify(m));

const TABLE_ORDER = ["mechanism", "points", "links", "sliders", "gears", "meshes", "inputs", "masses", "loads", "lengths", "poses"];

function key(k) {
  return /^[A-Za-z0-9_-]+$/.test(k) ? k : JSON.stringify(k);
}

function value(v) {
  if (typeof v === "string") return JSON.stringify(v);
  if (typeof v === "number") return Number.isFinite(v) ? String(v) : "nan";
  if (typeof v === "boolean") return v ? "true" : "false";
  if (Array.isArray(v)) return `[${v.map(value).join(", ")}]`;
  if (v && typeof v === "object") return `{ ${Object.entries(v).map(([k, x]) => `${key(k)} = ${value(x)}`).join(", ")} }`;
  return '""';
}

/** TOML text of a model object (used while the model is still incomplete and the server refuses to dump it). */
export function toToml(model) {
  const out = [];
  const names = [...TABLE_ORDER, ...Object.keys(model).filter((k) => !TABLE_ORDER.includes(k))];
  for (const t of names) {
    const v = model[t];
    if (v === undefined || v === null) continue;
    if (Array.isArray(v)) {
      for (const row of v) {
        out.push(`[[${t}]]`);
        for (const [k, x] of Object.entries(row)) out.push(`${key(k)} = ${value(x)}`);
        out.push("");
      }
    } else if (typeof v === "object") {
      out.push(`[${t}]`);
      for (const [k, x] of Object.entries(v)) out.push(`${key(k)} = ${value(x)}`);
      out.push("");
    }
  }
  return out.join("\n");
}

/** A new name PREFIX1, PREFIX2... not used by any point, link, slider or gear. */
export function freshName(model, prefix) {
  const used = new Set([
    ...Object.keys(model.points || {}), ...Object.keys(model.links || {}),
    ...Object.keys(model.gears || {}), ...(model.sliders || []).map((s) => s.name || s.link),
  ]);
  for (let i = 1; ; i++) if (!used.has(`${prefix}${i}`)) return `${prefix}${i}`;
}

export const isGround = (model, p) => (model.links?.ground || []).includes(p);

export function linksOf(model, p) {
  return Object.entries(model.links || {}).filter(([, pts]) => pts.includes(p)).map(([n]) => n);
}

export function addPoint(model, prefix, xy) {
  const name = freshName(model, prefix);
  model.points ||= {};
  model.points[name] = xy;
  return name;
}

/** A point with this exact name (a fresh one). */
export function placePoint(model, name, xy) {
  model.points ||= {};
  model.points[name] = xy;
  return name;
}

/** The next free pin name: A, B, C... then J1, J2... */
export function pinName(model) {
  const used = new Set([...Object.keys(model.points || {}), ...Object.keys(model.links || {})]);
  for (const c of "ABCDEFGHKLMNQRSTUVW") if (!used.has(c)) return c;
  return freshName(model, "J");
}

export function addGroundPivot(model, xy) {
  const name = addPoint(model, "O", xy);
  model.links ||= {};
  model.links.ground ||= [];
  model.links.ground.push(name);
  return name;
}

export function makeGround(model, p) {
  model.links ||= {};
  model.links.ground ||= [];
  if (!model.links.ground.includes(p)) model.links.ground.push(p);
}

/** A link through two joints; its name "crank" for the first link on a ground pivot, else link1... */
export function addLink(model, a, b) {
  model.links ||= {};
  const name = freshName(model, "link");
  model.links[name] = [a, b];
  return name;
}

export function growLink(model, link, p) {
  if (!model.links[link].includes(p)) model.links[link].push(p);
}

/** Drive the link (it must carry a ground pivot): it becomes the input (one per degree of freedom). */
export function setInput(model, link, dof) {
  const inputs = (model.inputs || []).filter((i) => i.link !== link);
  const keep = Math.max(0, (dof ?? 1) - 1);
  model.inputs = [...inputs.slice(0, keep), { link }];
}

export function addSlider(model, p) {
  const block = freshName(model, "block");
  model.links[block] = [p];
  model.sliders ||= [];
  model.sliders.push({ name: block, link: block, on: "ground", point: p, direction: [1.0, 0.0] });
  return block;
}

export function addGear(model, p, teeth = 20) {
  const carriers = linksOf(model, p);
  const link = carriers.find((l) => l !== "ground") || carriers[0];
  if (!link) return null;
  model.gears ||= {};
  const name = freshName(model, "gear");
  model.gears[name] = { link, centre: p, teeth };
  return name;
}

export function addMesh(model, a, b) {
  model.meshes ||= [];
  model.meshes.push({ gears: [a, b] });
}

function renameIn(list, from, to) {
  return list.map((x) => (x === from ? to : x));
}

export function renamePoint(model, from, to) {
  model.points = Object.fromEntries(Object.entries(model.points).map(([k, v]) => [k === from ? to : k, v]));
  for (const l of Object.keys(model.links || {})) model.links[l] = renameIn(model.links[l], from, to);
  for (const s of model.sliders || []) if (s.point === from) s.point = to;
  for (const g of Object.values(model.gears || {})) if (g.centre === from) g.centre = to;
  for (const m of Object.values(model.masses || {})) if (m.centre === from) m.centre = to;
  for (const l of model.loads || []) if (l.point === from) l.point = to;
}

export function renameLink(model, from, to) {
  model.links = Object.fromEntries(Object.entries(model.links).map(([k, v]) => [k === from ? to : k, v]));
  for (const i of model.inputs || []) if (i.link === from) i.link = to;
  for (const s of model.sliders || []) { if (s.link === from) s.link = to; if (s.on === from) s.on = to; }
  for (const g of Object.values(model.gears || {})) if (g.link === from) g.link = to;
  for (const m of model.meshes || []) if (m.carrier === from) m.carrier = to;
  if (model.masses && from in model.masses) {
    model.masses = Object.fromEntries(Object.entries(model.masses).map(([k, v]) => [k === from ? to : k, v]));
  }
  for (const l of model.loads || []) if (l.link === from) l.link = to;
}

export function deleteLink(model, name) {
  if (name === "ground") return;
  delete model.links[name];
  if (model.inputs) model.inputs = model.inputs.filter((i) => i.link !== name);
  if (model.sliders) model.sliders = model.sliders.filter((s) => s.link !== name && s.on !== name);
  if (model.gears) for (const [g, v] of Object.entries(model.gears)) if (v.link === name) delete model.gears[g];
  if (model.meshes) model.meshes = model.meshes.filter((m) => m.gears.every((g) => g in (model.gears || {})) && m.carrier !== name);
  if (model.masses) delete model.masses[name];
  if (model.loads) model.loads = model.loads.filter((l) => l.link !== name);
  tidy(model);
}

export function deletePoint(model, name) {
  delete model.points[name];
  for (const [l, pts] of Object.entries(model.links || {})) {
    model.links[l] = pts.filter((p) => p !== name);
    if (model.links[l].length === 0 && l !== "ground") deleteLink(model, l);
  }
  if (model.sliders) model.sliders = model.sliders.filter((s) => s.point !== name);
  if (model.gears) for (const [g, v] of Object.entries(model.gears)) if (v.centre === name) delete model.gears[g];
  if (model.meshes) model.meshes = model.meshes.filter((m) => m.gears.every((g) => g in (model.gears || {})));
  if (model.loads) model.loads = model.loads.filter((l) => l.point !== name);
  tidy(model);
}

/** Delete the motion pose at index k of [[poses]]. */
export function deletePose(model, k) {
  if (model.poses) model.poses.splice(k, 1);
  tidy(model);
}

function tidy(model) {
  for (const t of ["inputs", "sliders", "meshes", "loads", "poses"]) if (Array.isArray(model[t]) && model[t].length === 0) delete model[t];
  for (const t of ["gears", "masses"]) if (model[t] && Object.keys(model[t]).length === 0) delete model[t];
}

/** Enough for the engine: a ground, a moving link and an input. */
export function solvable(model) {
  return !!(model.links && model.links.ground && model.links.ground.length && model.inputs && model.inputs.length
    && Object.keys(model.links).length >= 2);
}
