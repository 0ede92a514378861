// The bench's HTTP client: every call carries the token as a Bearer header; errors become ApiError.
// The token arrives once as ?token= in the page URL; it is kept in sessionStorage and removed from the
// address bar (the fragment, which may carry a shared model, stays).

const KEY = "gearlever-workbench-token";

export class ApiError extends Error {
  constructor(status, message, line, body) {
    super(message);
    this.status = status;
    this.line = line ?? null;
    this.body = body ?? null;
  }
}

function takeToken() {
  const url = new URL(window.location.href);
  const fromUrl = url.searchParams.get("token");
  if (fromUrl) {
    try { sessionStorage.setItem(KEY, fromUrl); } catch { /* storage off: keep it in memory */ }
    url.searchParams.delete("token");
    window.history.replaceState(null, "", url.pathname + url.search + url.hash);
    return fromUrl;
  }
  try { return sessionStorage.getItem(KEY) || ""; } catch { return ""; }
}

export const token = takeToken();

function headers(extra) {
  const h = { Authorization: `Bearer ${token}`, ...extra };
  return h;
}

async function errorOf(resp) {
  let body = null;
  try { body = await resp.json(); } catch { /* not JSON */ }
  const msg = body && typeof body.error === "string" ? body.error : `${resp.status} ${resp.statusText}`;
  return new ApiError(resp.status, msg, body ? body.line : null, body);
}

export async function get(path) {
  const resp = await fetch(path, { headers: headers(), cache: "no-store" });
  if (!resp.ok) throw await errorOf(resp);
  return resp.json();
}

export async function post(path, body) {
  const resp = await fetch(path, {
    method: "POST", headers: headers({ "Content-Type": "application/json" }), body: JSON.stringify(body),
  });
  if (!resp.ok) throw await errorOf(resp);
  return resp.json();
}

/** A POST answering a file: {blob, filename}. */
export async function postFile(path, body) {
  const resp = await fetch(path, {
    method: "POST", headers: headers({ "Content-Type": "application/json" }), body: JSON.stringify(body),
  });
  if (!resp.ok) throw await errorOf(resp);
  const cd = resp.headers.get("Content-Disposition") || "";
  const m = /filename\*?=(?:UTF-8'')?"?([^";]+)"?/i.exec(cd);
  return { blob: await resp.blob(), filename: m ? decodeURIComponent(m[1]) : null };
}

/** GET a workspace file: {model, etag}. */
export async function getFile(name) {
  const resp = await fetch(`/api/files/${encodeURIComponent(name)}`, { headers: headers(), cache: "no-store" });
  if (!resp.ok) throw await errorOf(resp);
  const body = await resp.json();
  return { model: body.model, etag: resp.headers.get("ETag") };
}

/** PUT a workspace file (If-Match when an ETag is known): the new ETag. */
export async function putFile(name, model, etag) {
  const h = headers({ "Content-Type": "application/json" });
  if (etag) h["If-Match"] = etag;
  const resp = await fetch(`/api/files/${encodeURIComponent(name)}`, {
    method: "PUT", headers: h, body: JSON.stringify({ model }),
  });
  if (!resp.ok) throw await errorOf(resp);
  return resp.headers.get("ETag");
}

export async function del(path) {
  const resp = await fetch(path, { method: "DELETE", headers: headers() });
  if (!resp.ok) throw await errorOf(resp);
  return resp.json();
}

/** Read a server-sent event stream with the Bearer header; onEvent(JSON) per event; resolves at its end. */
export async function events(path, onEvent, signal) {
  const resp = await fetch(path, { headers: headers({ Accept: "text/event-stream" }), signal, cache: "no-store" });
  if (!resp.ok) throw await errorOf(resp);
  const reader = resp.body.pipeThrough(new TextDecoderStream()).getReader();
  let buffer = "";
  for (;;) {
    const { value, done } = await reader.read();
    if (done) break;
    buffer += value;
    let cut;
    while ((cut = buffer.search(/\r?\n\r?\n/)) >= 0) {
      const block = buffer.slice(0, cut);
      buffer = buffer.slice(cut).replace(/^\r?\n\r?\n/, "");
      const data = block.split(/\r?\n/).filter((l) => l.startsWith("data:")).map((l) => l.slice(5).trimStart()).join("\n");
      if (data) {
        try { onEvent(JSON.parse(data)); } catch { /* a malformed event is skipped */ }
      }
    }
  }
}
