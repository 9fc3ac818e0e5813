/**
 * Reads an image's size from its header without decoding it, so that the
 * texture memory limit is checked before a decoder allocates anything
 * (a 1 KB PNG can claim 65535 × 65535 texels). PNG: the IHDR chunk; JPEG:
 * the first start-of-frame marker (ITU T.81 §B.2.2).
 */

export interface ImageInfo {
  mimeType: 'image/png' | 'image/jpeg';
  width: number;
  height: number;
}

const PNG_SIGNATURE = [0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a];

/** The format from the bytes themselves (a file's MIME type may lie). */
export function sniffImageType(bytes: Uint8Array): 'image/png' | 'image/jpeg' | null {
  if (bytes.length >= 8 && PNG_SIGNATURE.every((b, i) => bytes[i] === b)) return 'image/png';
  if (bytes.length >= 3 && bytes[0] === 0xff && bytes[1] === 0xd8 && bytes[2] === 0xff) {
    return 'image/jpeg';
  }
  return null;
}

/**
 * Size and format of a PNG or JPEG; throws a clear error, prefixed by `what`
 * when given, when the header is broken.
 */
export function readImageInfo(bytes: Uint8Array, what = ''): ImageInfo {
  const fail = (message: string): never => {
    throw new Error(what === '' ? message : `${what}: ${message}`);
  };
  const type = sniffImageType(bytes);
  if (type === 'image/png') {
    // Signature, then the IHDR chunk: length (4), "IHDR", width, height.
    if (bytes.length < 24 || String.fromCharCode(...bytes.subarray(12, 16)) !== 'IHDR') {
      fail(`PNG without an IHDR header (truncated?)`);
    }
    const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
    return { mimeType: type, width: view.getUint32(16), height: view.getUint32(20) };
  }
  if (type === 'image/jpeg') {
    let p = 2;
    while (p + 4 <= bytes.length) {
      if (bytes[p] !== 0xff) fail(`corrupt JPEG marker at byte ${p}`);
      const marker = bytes[p + 1];
      if (marker === 0xff) {
        p++; // fill byte
        continue;
      }
      const length = (bytes[p + 2] << 8) | bytes[p + 3];
      // SOF0–SOF15 except DHT (C4), JPG (C8) and DAC (CC).
      if (
        marker >= 0xc0 &&
        marker <= 0xcf &&
        marker !== 0xc4 &&
        marker !== 0xc8 &&
        marker !== 0xcc
      ) {
        if (p + 9 > bytes.length) break;
        const height = (bytes[p + 5] << 8) | bytes[p + 6];
        const width = (bytes[p + 7] << 8) | bytes[p + 8];
        return { mimeType: type, width, height };
      }
      if (length < 2) fail(`corrupt JPEG segment length at byte ${p}`);
      p += 2 + length;
    }
    fail(`JPEG without a frame header (truncated?)`);
  }
  return fail(`not a PNG or JPEG image (unrecognised signature)`);
}
