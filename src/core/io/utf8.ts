/**
 * Strict UTF-8 (docs/scene-format.md, "Bad input"): invalid UTF-8 is an error naming its
 * position, never replaced by U+FFFD, since two different invalid names would otherwise
 * become the same key. Decoding uses the platform's TextDecoder with `fatal: true`; only
 * when it fails does a scan of our own find where (TextDecoder does not say).
 */

// TextDecoder is in Node, browsers and workers alike, but not in the ES2022 lib that
// src/core compiles against: declare the little that is used.
interface StrictDecoder {
  decode(input: Uint8Array): string;
}
declare const TextDecoder: new (
  label: string,
  options: { fatal: boolean; ignoreBOM?: boolean },
) => StrictDecoder;

export class Utf8Error extends Error {
  override name = 'Utf8Error';
  /** Byte offset of the first byte of the invalid sequence. */
  readonly offset: number;
  /** 1-based line of that byte (lines end at LF bytes). */
  readonly line: number;

  constructor(offset: number, line: number, detail: string) {
    super(`not valid UTF-8 at byte ${offset} (line ${line}): ${detail}`);
    this.offset = offset;
    this.line = line;
  }
}

let decoder: StrictDecoder | undefined;

/**
 * Decodes UTF-8 bytes; a leading byte-order mark is dropped. Throws Utf8Error naming the
 * byte offset (and line) of the first invalid sequence.
 */
export function decodeUtf8(bytes: Uint8Array): string {
  decoder ??= new TextDecoder('utf-8', { fatal: true });
  try {
    return decoder.decode(bytes);
  } catch {
    const bad = findInvalidUtf8(bytes);
    // TextDecoder and the scan implement the same rules (WHATWG Encoding, Unicode §3.9
    // table 3-7); should they ever disagree, still fail, at the end of the input.
    const offset = bad?.offset ?? bytes.length;
    let line = 1;
    for (let i = 0; i < offset; i++) if (bytes[i] === 0x0a) line++;
    throw new Utf8Error(offset, line, bad?.detail ?? 'rejected by the decoder');
  }
}

const hex = (b: number): string => '0x' + b.toString(16).padStart(2, '0');

/**
 * The first ill-formed sequence (Unicode §3.9, table 3-7: no overlong forms, no
 * surrogates, nothing above U+10FFFF), or undefined when the bytes are well-formed.
 */
export function findInvalidUtf8(bytes: Uint8Array): { offset: number; detail: string } | undefined {
  const n = bytes.length;
  let i = 0;
  while (i < n) {
    const b = bytes[i];
    if (b < 0x80) {
      i++;
      continue;
    }
    let need: number;
    let lo = 0x80;
    let hi = 0xbf;
    if (b >= 0xc2 && b <= 0xdf) need = 1;
    else if (b >= 0xe0 && b <= 0xef) {
      need = 2;
      if (b === 0xe0) lo = 0xa0; // overlong
      if (b === 0xed) hi = 0x9f; // surrogates
    } else if (b >= 0xf0 && b <= 0xf4) {
      need = 3;
      if (b === 0xf0) lo = 0x90; // overlong
      if (b === 0xf4) hi = 0x8f; // above U+10FFFF
    } else {
      const what = b < 0xc0 ? 'a continuation byte without a lead byte' : 'a byte never used';
      return { offset: i, detail: `byte ${hex(b)} is ${what} in UTF-8` };
    }
    for (let k = 1; k <= need; k++) {
      if (i + k >= n) {
        return { offset: i, detail: `the sequence starting with ${hex(b)} is cut off` };
      }
      const c = bytes[i + k];
      const min = k === 1 ? lo : 0x80;
      const max = k === 1 ? hi : 0xbf;
      if (c < min || c > max) {
        return { offset: i, detail: `the sequence starting with ${hex(b)} is broken by ${hex(c)}` };
      }
    }
    i += need + 1;
  }
  return undefined;
}

/**
 * UTF-8 length of `text` as TextEncoder would produce it (lone surrogates become U+FFFD, 3
 * bytes). Returns Infinity without counting when the length is certainly over `limit`.
 */
export function utf8Length(text: string, limit: number): number {
  if (text.length > limit) return Infinity; // every UTF-16 code unit is at least one byte
  let bytes = 0;
  for (let i = 0; i < text.length; i++) {
    const c = text.charCodeAt(i);
    if (c < 0x80) bytes += 1;
    else if (c < 0x800) bytes += 2;
    else if (c >= 0xd800 && c <= 0xdbff && isLowSurrogate(text.charCodeAt(i + 1))) {
      bytes += 4;
      i++;
    } else bytes += 3;
  }
  return bytes;
}

function isLowSurrogate(c: number): boolean {
  return c >= 0xdc00 && c <= 0xdfff;
}
