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

/** Decodes a colour PFM (either endianness) into top-to-bottom RGB floats. */
export function decodePfm(bytes: Uint8Array): PfmImage {
  // The header is three whitespace-separated tokens after "PF".
  let pos = 0;
  const tokens: string[] = [];
  while (tokens.length < 4 && pos < bytes.length) {
    while (pos < bytes.length && /\s/.test(String.fromCharCode(bytes[pos]))) pos++;
    let tok = '';
    while (pos < bytes.length && !/\s/.test(String.fromCharCode(bytes[pos]))) {
      tok += String.fromCharCode(bytes[pos++]);
    }
    tokens.push(tok);
  }
  pos++; // the single whitespace byte that ends the header
  const [magic, ws, hs, ss] = tokens;
  if (magic !== 'PF') throw new Error(`not a colour PFM (magic ${JSON.stringify(magic)})`);
  const width = Number(ws);
  const height = Number(hs);
  const scale = Number(ss);
  if (!(
    Number.isInteger(width) &&
    Number.isInteger(height) &&
    width > 0 &&
    height > 0 &&
    scale !== 0
  )) {
    throw new Error(`bad PFM header: ${tokens.join(' ')}`);
  }
  const need = width * height * 12;
  if (bytes.length - pos < need)
    throw new Error(`PFM truncated: ${bytes.length - pos} of ${need} data bytes`);
  const little = scale < 0;
  const view = new DataView(bytes.buffer, bytes.byteOffset + pos, need);
  const rgb = new Float32Array(width * height * 3);
  let k = 0;
  for (let y = height - 1; y >= 0; y--) {
    for (let i = y * width * 3, end = i + width * 3; i < end; i++) {
      rgb[i] = view.getFloat32(k, little);
      k += 4;
    }
  }
  return { width, height, rgb };
}
