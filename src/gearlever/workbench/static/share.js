// A share link: the model's TOML text, deflate-raw compressed and base64url encoded, in the URL fragment
// (#m=...). Nothing is stored on the server; the fragment never reaches it.

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

export async function shareUrl(toml) {
  const url = new URL(window.location.href);
  url.search = "";
  url.hash = `m=${await encodeModel(toml)}`;
  return url.toString();
}

/** The model text carried by the current URL's fragment, or null. */
export async function modelFromFragment() {
  const m = /^#m=([A-Za-z0-9_-]+)$/.exec(window.location.hash);
  return m ? decodeModel(m[1]) : null;
}
