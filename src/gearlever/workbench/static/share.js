// A share link: the model's TOML text, deflate-raw compressed and base64url encoded, in the URL fragment
// (#m=...), and the cam's CAM.toml text the same way after it (&c=...) when a cam is on the bench.
// Nothing is stored on the server; the fragment never reaches it.

function toBase64Url(bytes) {
  let bin = "";
  for (let i = 0; i < bytes.length; i += 0x8000) bin += String.fromCharCode(...bytes.subarray(i, i + 0x8000));
  return btoa(bin).replace(/\+/g, "-").replace(/\//g, "_").replace(/=+$/, "");
}

function fromBase64Url(text) {
  const b64 = text.replace(/-/g, "+").replace(/_/g, "/") + "===".slice((text.length + 3) % 4);
  const bin = atob(b64);
  const out = new Uint8Array(bin.length);
  for (let i = 0; i < bin.length; i++) out[i] = bin.charCodeAt(i);
  return out;
}

async function pipe(bytes, stream) {
  const out = new Response(new Blob([bytes]).stream().pipeThrough(stream));
  return new Uint8Array(await out.arrayBuffer());
}

export async function encodeModel(toml) {
  const packed = await pipe(new TextEncoder().encode(toml), new CompressionStream("deflate-raw"));
  return toBase64Url(packed);
}

/** At most 4 MiB of text out of a fragment (the model file's own cap). */
export async function decodeModel(fragment) {
  const packed = fromBase64Url(fragment);
  const bytes = await pipe(packed, new DecompressionStream("deflate-raw"));
  if (bytes.length > 4 * 1024 * 1024) throw new Error("the shared model is larger than 4 MiB");
  return new TextDecoder("utf-8", { fatal: true }).decode(bytes);
}

/** The share link of a model (and of its cam: the CAM.toml text, compressed the same way, as &c=...). */
export async function shareUrl(toml, cam = null) {
  const url = new URL(window.location.href);
  url.search = "";
  url.hash = `m=${await encodeModel(toml)}` + (cam ? `&c=${await encodeModel(cam)}` : "");
  return url.toString();
}

/** The model text carried by the current URL's fragment, or null. */
export async function modelFromFragment() {
  const shared = await sharedFromFragment();
  return shared ? shared.model : null;
}

/** {model, cam} carried by the current URL's fragment (cam null when the link has none), or null. */
export async function sharedFromFragment() {
  const m = /^#m=([A-Za-z0-9_-]+)(?:&c=([A-Za-z0-9_-]+))?$/.exec(window.location.hash);
  if (!m) return null;
  return { model: await decodeModel(m[1]), cam: m[2] ? await decodeModel(m[2]) : null };
}
