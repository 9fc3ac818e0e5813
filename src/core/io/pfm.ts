/**
 * Portable Float Map, the standard layout: header "PF\n{w} {h}\n-1.0\n"
 * (negative scale = little-endian), then float32 RGB rows from the bottom
 * of the image to the top.
 */

/** Encodes an RGB float image (row 0 at the top) as PFM bytes. */
export function encodePfm(width: number, height: number, rgb: Float32Array): Uint8Array {
  if (rgb.length !== width * height * 3) {
    throw new RangeError(`PFM data has ${rgb.length} floats, expected ${width * height * 3}`);
  }
  // ASCII header; TextEncoder is not part of the core's ES2022 lib.
  const header = Uint8Array.from(`PF\n${width} ${height}\n-1.0\n`, (c) => c.charCodeAt(0));
  const out = new Uint8Array(header.length + rgb.length * 4);
  out.set(header, 0);
  const view = new DataView(out.buffer, header.length);
  let k = 0;
  for (let y = height - 1; y >= 0; y--) {
    for (let i = y * width * 3, end = i + width * 3; i < end; i++) {
      view.setFloat32(k, rgb[i], true);
      k += 4;
    }
  }
  return out;
}

export interface PfmImage {
  width: number;
  height: number;
  /** RGB, row 0 at the top. */
  rgb: Float32Array;
}

export interface PfmLimits {
  maxWidth: number;
  maxHeight: number;
}

/**
 * Decodes a PFM (colour "PF" or greyscale "Pf", either endianness; the magnitude of the
 * scale is ignored, its sign gives the byte order) into top-to-bottom RGB floats. The
 * size is checked against `limits` and against the bytes present before anything is
 * allocated; problems are thrown as Errors with one-line messages.
 */
export function decodePfm(bytes: Uint8Array, limits?: PfmLimits): PfmImage {
  // The header is three whitespace-separated tokens after the magic, each short.
  let pos = 0;
  const tokens: string[] = [];
  const space = (c: number) => c === 0x20 || c === 0x0a || c === 0x0d || c === 0x09;
  while (tokens.length < 4 && pos < bytes.length) {
    while (pos < bytes.length && space(bytes[pos])) pos++;
    let tok = '';
    while (pos < bytes.length && !space(bytes[pos])) {
      if (tok.length < 32) tok += String.fromCharCode(bytes[pos]);
      pos++;
    }
    tokens.push(tok);
  }
  pos++; // the single whitespace byte that ends the header
  const [magic, ws, hs, ss] = tokens;
  if (magic !== 'PF' && magic !== 'Pf') {
    throw new Error(`not a PFM file (magic ${JSON.stringify(magic ?? '')}, expected "PF" or "Pf")`);
  }
  const channels = magic === 'PF' ? 3 : 1;
  const width = Number(ws);
  const height = Number(hs);
  const scale = Number(ss);
  if (!(
    /^\d+$/.test(ws ?? '') &&
    /^\d+$/.test(hs ?? '') &&
    width > 0 &&
    height > 0 &&
    Number.isFinite(scale) &&
    scale !== 0
  )) {
    throw new Error(`bad PFM header: ${JSON.stringify(tokens.join(' ').slice(0, 80))}`);
  }
  if (limits !== undefined && (width > limits.maxWidth || height > limits.maxHeight)) {
    throw new Error(
      `the image is ${width} × ${height}, more than the limit of ${limits.maxWidth} × ${limits.maxHeight}`,
    );
  }
  const need = width * height * channels * 4;
  if (bytes.length - pos < need) {
    throw new Error(
      `PFM truncated: the header declares ${width} × ${height}, which needs ${need} data bytes, ` +
        `but ${Math.max(0, bytes.length - pos)} follow it`,
    );
  }
  const little = scale < 0;
  const view = new DataView(bytes.buffer, bytes.byteOffset + pos, need);
  const rgb = new Float32Array(width * height * 3);
  let k = 0;
  for (let y = height - 1; y >= 0; y--) {
    for (let i = y * width * 3, end = i + width * 3; i < end; i += 3) {
      if (channels === 3) {
        rgb[i] = view.getFloat32(k, little);
        rgb[i + 1] = view.getFloat32(k + 4, little);
        rgb[i + 2] = view.getFloat32(k + 8, little);
        k += 12;
      } else {
        rgb[i] = rgb[i + 1] = rgb[i + 2] = view.getFloat32(k, little);
        k += 4;
      }
    }
  }
  return { width, height, rgb };
}
