/**
 * Reads an image's size from its header without decoding it, so that the
 * texture memory limit is checked before a decoder allocates anything
 * (a 1 KB PNG can claim 65535 × 65535 texels). PNG: the IHDR chunk; JPEG:
 * the first start-of-frame marker (ITU T.81 §B.2.2); WebP (EXT_texture_webp):
 * the RIFF chunks (webp-header.ts); KTX2 (KHR_texture_basisu): the header and
 * level index (ktx2-header.ts; level 0's size here).
 */
import { sanitize } from '../util/message.ts';
import { imageDecodeError } from './image-error.ts';
import { checkJpeg } from './jpeg-check.ts';
import { isKtx2, readKtx2Info } from './ktx2-header.ts';
import { readPngChunks } from './png-check.ts';
import { isWebp, readWebpInfo } from './webp-header.ts';

/** The image formats a glTF texture may hold here: PNG and JPEG (core glTF), WebP and KTX2 (extensions). */
export type TextureImageType = 'image/png' | 'image/jpeg' | 'image/webp' | 'image/ktx2';

export interface ImageInfo {
  mimeType: TextureImageType;
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

/** The format from the bytes, WebP and KTX2 included (sniffImageType is PNG and JPEG only). */
export function sniffTextureType(bytes: Uint8Array): TextureImageType | null {
  const type = sniffImageType(bytes);
  if (type !== null) return type;
  if (isWebp(bytes)) return 'image/webp';
  if (isKtx2(bytes)) return 'image/ktx2';
  return null;
}

/**
 * Size and format of a PNG, JPEG, WebP or KTX2 image; throws a clear error, prefixed
 * by `what` when given, when the header is broken.
 */
export function readImageInfo(bytes: Uint8Array, what = ''): ImageInfo {
  const fail = (message: string): never => {
    throw new Error(what === '' ? message : `${what}: ${message}`);
  };
  const type = sniffTextureType(bytes);
  if (type === 'image/webp' || type === 'image/ktx2') {
    try {
      const { width, height } = type === 'image/webp' ? readWebpInfo(bytes) : readKtx2Info(bytes);
      return { mimeType: type, width, height };
    } catch (e) {
      return fail(imageDecodeError(e).message);
    }
  }
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
  return fail(notPngOrJpeg(bytes));
}

/**
 * Checks an image's structure and its declared size against the bytes present and
 * the texel budget (png-check.ts, jpeg-check.ts), without decoding or inflating:
 * cheap, so it runs on every image before the texture store is allocated. Throws
 * FormatError('PNG' | 'JPEG', …); non-images are the caller's to rule out first.
 */
export function checkImageBytes(bytes: Uint8Array, maxTexels: number): void {
  if (sniffImageType(bytes) === 'image/png') readPngChunks(bytes, maxTexels);
  else checkJpeg(bytes, maxTexels);
}

/** Image formats glTF extensions carry that are not decoded here, by signature. */
function otherFormat(b: Uint8Array): string | null {
  const text = (from: number, to: number) => String.fromCharCode(...b.subarray(from, to));
  if (b.length >= 12 && text(0, 4) === 'RIFF' && text(8, 12) === 'WEBP') return 'WebP';
  if (b.length >= 12 && b[0] === 0xab && text(1, 7) === 'KTX 20') return 'KTX2';
  if (b.length >= 6 && (text(0, 6) === 'GIF87a' || text(0, 6) === 'GIF89a')) return 'GIF';
  if (b.length >= 12 && text(4, 8) === 'ftyp' && /^(avi[fs]|hei[cfsx]|mif1)$/.test(text(8, 12))) {
    return 'AVIF/HEIF';
  }
  return null;
}

/**
 * The format of an image that is not PNG or JPEG but honestly another one, to be
 * ignored rather than rejected: by its signature ("a WebP image"), else by a declared
 * MIME type other than PNG's or JPEG's ("image/ktx2"). Null for bytes that claim to be
 * PNG or JPEG (or nothing) and are not: those are damage.
 */
export function otherImageFormat(bytes: Uint8Array, declared: string): string | null {
  const other = otherFormat(bytes);
  if (other !== null) return `a ${other} image`;
  if (declared !== '' && declared !== 'image/png' && declared !== 'image/jpeg') {
    return sanitize(declared, 40);
  }
  return null;
}

/**
 * The message for bytes that are neither PNG nor JPEG: the format when it is one we
 * know by its signature, else the first bytes (hex and printable text), and the
 * MIME type the file declared when it claims otherwise.
 */
export function notPngOrJpeg(bytes: Uint8Array, declared = ''): string {
  const said = declared === '' ? '' : `; its mimeType says ${sanitize(declared, 40)}`;
  const other = otherFormat(bytes);
  if (other !== null) return `a ${other} image, not PNG or JPEG${said}`;
  if (bytes.length === 0) return `not a PNG or JPEG image (it is empty${said})`;
  const head = bytes.subarray(0, 8);
  const hexes = Array.from(head, (b) => b.toString(16).padStart(2, '0')).join(' ');
  const text = Array.from(head, (b) => (b >= 0x20 && b < 0x7f ? String.fromCharCode(b) : '.')).join(
    '',
  );
  return `not a PNG or JPEG image (it starts with ${hexes}${bytes.length > 8 ? ' …' : ''}, "${sanitize(text, 16, true)}"${said})`;
}
