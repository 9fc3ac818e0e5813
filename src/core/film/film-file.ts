/**
 * The `.film` file, format `pathwise-film/1` (docs/film-format.md): a
 * film's exact sums with what is needed to merge it with other parts of
 * the same render — the settings and scene it was rendered from, and the
 * sample ranges it holds.
 *
 *   offset 0    "pathwise-film/1\n"                     16 bytes, ASCII
 *          16   header length H                          uint32 LE
 *          20   header, JSON in ASCII (other characters as \uXXXX), H bytes;
 *               zero bytes up to a multiple of 8
 *          P    count [n]   uint32 LE   accepted samples per pixel; zero-padded to 8
 *               hi    [4n]  float64 LE  exact-sum high limbs, R G B L² per pixel
 *               lo    [4n]  float64 LE  exact-sum low limbs
 *          end−4 CRC-32 of every byte before it         uint32 LE
 *
 * Version 2 (`pathwise-film/2`, FILM_FORMAT_AUX) adds the header key `aux` and, after
 * `lo`, auxHi [6n] and auxLo [6n]: the exact sums of albedo R G B and normal X Y Z
 * (integrator/aux.ts). A film without them is written as version 1, as before.
 *
 * n = width·height, pixels row-major from the top row. The Float32 display
 * sums are not stored: they are one rounding of the exact sums (Film.resolve).
 *
 * The decoder trusts nothing: every header field is checked for type and
 * range, the file's length must be exactly what the header implies (so a
 * truncated file or a lying header is named as such before anything large
 * is allocated), the checksum must match, and every pixel's values must be
 * canonical exact sums that its sample count can reach (no NaN, no
 * fractions, nothing out of range). Each problem is one FilmFileError
 * sentence.
 */
import { crc32 } from '../io/crc32.ts';
import { JsonError, parseJson } from '../io/json.ts';
import { isValidExact } from './exact-sum.ts';
import { Film } from './film.ts';
import { ADAPTIVE_PILOT, RATE_MIN, adaptiveCount } from './adaptive.ts';
import { rangeSamples } from './sample-ranges.ts';
import {
  FILM_FORMAT,
  FILM_FORMAT_AUX,
  FilmFileError,
  FilmHeaderError,
  type FilmHeader,
  MAX_HEADER_BYTES,
  validateHeader,
} from './film-header.ts';

export {
  AUX_NAMES,
  FILM_FORMAT,
  FILM_FORMAT_AUX,
  FilmFileError,
  FilmHeaderError,
  type FilmHeader,
  type FilmSettings,
  MAX_HEADER_BYTES,
} from './film-header.ts';

const MAGIC = FILM_FORMAT + '\n';
const MAGIC_AUX = FILM_FORMAT_AUX + '\n';
const PROLOGUE = 20;

export interface FilmFile {
  header: FilmHeader;
  film: Film;
}

const align8 = (n: number) => Math.ceil(n / 8) * 8;
const LITTLE_ENDIAN = new Uint8Array(new Uint32Array([1]).buffer)[0] === 1;

/** Byte length of a whole file whose header takes `headerBytes` bytes (`aux`: version 2). */
export function filmFileLength(
  headerBytes: number,
  width: number,
  height: number,
  aux = false,
): number {
  const n = width * height;
  return align8(PROLOGUE + headerBytes) + align8(4 * n) + (aux ? 160 : 64) * n + 4;
}

/** Whether a header is of a version-2 film (one with albedo and normal). */
export function hasAux(header: FilmHeader): boolean {
  return header.format === FILM_FORMAT_AUX;
}

export function encodeFilmFile(header: FilmHeader, film: Film): Uint8Array {
  const { width, height } = header.settings;
  if (film.width !== width || film.rows !== height) {
    throw new RangeError(`film is ${film.width}×${film.rows}, header says ${width}×${height}`);
  }
  const aux = hasAux(header);
  if (aux !== (film.auxHi !== null)) {
    throw new RangeError(
      aux
        ? 'header is pathwise-film/2 but the film has no aux planes'
        : 'film has aux planes: its header must be pathwise-film/2',
    );
  }
  const json = asciiBytes(
    JSON.stringify(header).replace(
      /[^\x20-\x7e]/g,
      (ch) => '\\u' + ch.charCodeAt(0).toString(16).padStart(4, '0'),
    ),
  );
  const n = width * height;
  const total = filmFileLength(json.length, width, height, aux);
  const out = new Uint8Array(total);
  const view = new DataView(out.buffer);
  out.set(aux ? MAGIC_AUX_BYTES : MAGIC_BYTES, 0);
  view.setUint32(16, json.length, true);
  out.set(json, PROLOGUE);
  let at = align8(PROLOGUE + json.length);
  const sums = film.sums;
  for (let p = 0; p < n; p++) view.setUint32(at + 4 * p, sums[p * 4 + 3], true);
  at += align8(4 * n);
  for (const plane of filmPlanes(film)) {
    if (LITTLE_ENDIAN) {
      out.set(new Uint8Array(plane.buffer, plane.byteOffset, plane.byteLength), at);
    } else {
      for (let k = 0; k < plane.length; k++) view.setFloat64(at + 8 * k, plane[k], true);
    }
    at += 8 * plane.length;
  }
  view.setUint32(at, crc32(out.subarray(0, at)), true);
  return out;
}

/**
 * Reads and checks the magic and the header from the first bytes of a
 * file (at least PROLOGUE + H of them; the caller may read the rest only
 * once it knows how long the file must be). `total` is the whole file's
 * length, to name truncation precisely.
 */
export function decodeFilmHeader(
  prefix: Uint8Array,
  total: number,
): { header: FilmHeader; byteLength: number } {
  const present = prefix.subarray(0, Math.min(total, MAGIC_BYTES.length));
  // A prefix of either magic (a file cut inside it is named as truncated below).
  const v2 = !startsWith(MAGIC_BYTES, present) && startsWith(MAGIC_AUX_BYTES, present);
  if (!v2 && !startsWith(MAGIC_BYTES, present)) {
    throw new FilmFileError(
      `not a .film file: it does not start with "${FILM_FORMAT}" or "${FILM_FORMAT_AUX}"`,
    );
  }
  if (total < PROLOGUE) {
    throw new FilmFileError(`truncated: ${total} bytes, not even the ${PROLOGUE}-byte prologue`);
  }
  const view = new DataView(prefix.buffer, prefix.byteOffset, prefix.byteLength);
  const h = view.getUint32(16, true);
  if (h === 0 || h > MAX_HEADER_BYTES) {
    throw new FilmFileError(`header length ${h} is outside [1, ${MAX_HEADER_BYTES}]`);
  }
  if (total < PROLOGUE + h) {
    throw new FilmFileError(
      `truncated: ${total} bytes, but the header alone needs ${PROLOGUE + h}`,
    );
  }
  if (prefix.length < PROLOGUE + h) {
    throw new RangeError(`decodeFilmHeader needs the first ${PROLOGUE + h} bytes`);
  }
  const header = parseHeader(prefix.subarray(PROLOGUE, PROLOGUE + h), v2);
  const byteLength = filmFileLength(h, header.settings.width, header.settings.height, v2);
  if (total < byteLength) {
    throw new FilmFileError(
      `truncated: ${total} bytes, but a ${header.settings.width}×${header.settings.height} film needs ${byteLength}`,
    );
  }
  if (total > byteLength) {
    throw new FilmFileError(
      `${total} bytes, more than the ${byteLength} that its ${header.settings.width}×${header.settings.height} header describes`,
    );
  }
  // What the header alone can tell once its size is known right: a pixel traces one path
  // per sample of the ranges, so the paths are pixels × samples (within the bounds of
  // adaptive sampling), and no more were rejected than traced. (Whether the pixels'
  // counts agree needs the body.)
  const { paths, rejected } = header.stats;
  const n = header.settings.width * header.settings.height;
  const samples = rangeSamples(header.ranges);
  const [least, most] = pathBounds(header);
  if (paths < least || paths > most || rejected > paths) {
    // Empty ranges with paths traced: samples no range accounts for (issue 27, item 5).
    throw new FilmHeaderError(
      samples === 0
        ? `stats do not add up: ${paths} paths and ${rejected} rejected, but its ranges are empty (inconsistent)`
        : `stats do not add up: ${paths} paths and ${rejected} rejected for ${n} pixels × ${samples} samples of its ranges (inconsistent)`,
    );
  }
  return { header, byteLength };
}

/**
 * The header's bytes, parsed and checked: a FilmFileError when they are not JSON (or
 * repeat a key), a FilmHeaderError when the JSON says something impossible.
 */
function parseHeader(bytes: Uint8Array, v2: boolean): FilmHeader {
  const value = parseHeaderText(bytes);
  try {
    return validateHeader(value, v2);
  } catch (e) {
    if (e instanceof FilmFileError && !(e instanceof FilmHeaderError)) {
      throw new FilmHeaderError(e.message.slice(FILM_FORMAT.length + 2));
    }
    throw e;
  }
}

function parseHeaderText(bytes: Uint8Array): unknown {
  const text = asciiText(bytes);
  if (text === null) throw new FilmFileError('header is not ASCII JSON');
  let value: unknown;
  try {
    // The strict parser (io/json.ts): JSON.parse keeps the last of a key given twice, so
    // `"seed": 1, …, "seed": 2` would read as one seed though the writer wrote two.
    value = parseJson(text);
  } catch (e) {
    if (e instanceof JsonError && e.kind === 'duplicate') {
      throw new FilmFileError(
        `header: key ${e.path} given twice, at line ${e.line}, byte ${PROLOGUE + e.offset}`,
      );
    }
    throw new FilmFileError(`header is not valid JSON: ${(e as Error).message}`);
  }
  return value;
}

/** The bytes of an ASCII string (the core has no TextEncoder: no DOM lib). */
function asciiBytes(text: string): Uint8Array {
  const out = new Uint8Array(text.length);
  for (let i = 0; i < text.length; i++) out[i] = text.charCodeAt(i);
  return out;
}

/** The text of ASCII bytes, or null if one is not ASCII. */
function asciiText(bytes: Uint8Array): string | null {
  let s = '';
  for (let i = 0; i < bytes.length; i += 8192) {
    const chunk = bytes.subarray(i, i + 8192);
    for (const b of chunk)
      if (b > 0x7e || (b < 0x20 && b !== 0x0a && b !== 0x09 && b !== 0x0d)) return null;
    s += String.fromCharCode(...chunk);
  }
  return s;
}

const MAGIC_BYTES = asciiBytes(MAGIC);
const MAGIC_AUX_BYTES = asciiBytes(MAGIC_AUX);

/** The planes a file stores after the counts, in order. */
function filmPlanes(film: Film): Float64Array[] {
  return film.auxHi !== null ? [film.hi, film.lo, film.auxHi, film.auxLo!] : [film.hi, film.lo];
}

function startsWith(bytes: Uint8Array, prefix: string | Uint8Array): boolean {
  const p = typeof prefix === 'string' ? asciiBytes(prefix) : prefix;
  if (bytes.length < p.length) return false;
  for (let i = 0; i < p.length; i++) if (bytes[i] !== p[i]) return false;
  return true;
}

/** Decodes a whole `.film` file. Throws FilmFileError naming the first problem. */
export function decodeFilmFile(bytes: Uint8Array): FilmFile {
  const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
  let decoded: { header: FilmHeader; byteLength: number };
  try {
    decoded = decodeFilmHeader(bytes, bytes.length);
  } catch (e) {
    // A header that says something wrong in a file whose checksum fails was damaged
    // after it was written: that is the problem to name.
    if (e instanceof FilmHeaderError && bytes.length >= PROLOGUE + 4) {
      const stored = view.getUint32(bytes.length - 4, true);
      const actual = crc32(bytes.subarray(0, bytes.length - 4));
      if (stored !== actual) throw checksumMismatch(stored, actual);
    }
    throw e;
  }
  const { header, byteLength } = decoded;
  const stored = view.getUint32(byteLength - 4, true);
  const actual = crc32(bytes.subarray(0, byteLength - 4));
  if (stored !== actual) throw checksumMismatch(stored, actual);
  const { width, height } = header.settings;
  const n = width * height;
  const aux = hasAux(header);
  const film = new Film(width, height, undefined, 0, 0, aux);
  let at = filmCountsOffset(view.getUint32(16, true));
  const counts = new Uint32Array(n);
  for (let p = 0; p < n; p++) counts[p] = view.getUint32(at + 4 * p, true);
  at += align8(4 * n);
  for (const plane of filmPlanes(film)) {
    if (LITTLE_ENDIAN) {
      new Uint8Array(plane.buffer, plane.byteOffset, plane.byteLength).set(
        bytes.subarray(at, at + plane.byteLength),
      );
    } else {
      for (let k = 0; k < plane.length; k++) plane[k] = view.getFloat64(at + 8 * k, true);
    }
    at += plane.byteLength;
  }
  const samples = rangeSamples(header.ranges);
  const sums = film.sums;
  const hi = film.hi;
  const lo = film.lo;
  let accepted = 0;
  for (let p = 0; p < n; p++) {
    const count = counts[p];
    const where = () => `pixel (${p % width}, ${Math.floor(p / width)})`;
    if (count > samples) throw tooManySamples(p, width, count, samples);
    for (let c = 0; c < 4; c++) {
      const i = p * 4 + c;
      if (!isValidExact(hi[i], lo[i], count)) {
        throw new FilmFileError(
          `${where()} channel ${'RGBL'[c]}: invalid exact sum (${hi[i]}, ${lo[i]}) for ${count} samples`,
        );
      }
      hi[i] += 0; // −0 → +0, the canonical zero
      lo[i] += 0;
    }
    if (aux) {
      const ah = film.auxHi!;
      const al = film.auxLo!;
      for (let c = 0; c < 6; c++) {
        const i = p * 6 + c;
        if (!isValidExact(ah[i], al[i], count)) {
          throw new FilmFileError(
            `${where()} ${c < 3 ? 'albedo' : 'normal'} channel ${'RGBXYZ'[c]}: invalid exact sum (${ah[i]}, ${al[i]}) for ${count} samples`,
          );
        }
        ah[i] += 0;
        al[i] += 0;
      }
    }
    sums[p * 4 + 3] = count;
    accepted += count;
  }
  const statsProblem = countsProblem(header, accepted);
  if (statsProblem !== null) throw statsProblem;
  film.resolve();
  return { header, film };
}

/** Where the per-pixel sample counts begin, in a file whose header takes `headerBytes`. */
export function filmCountsOffset(headerBytes: number): number {
  return align8(PROLOGUE + headerBytes);
}

/** The stored CRC-32 differs from the bytes': the file changed after it was written. */
export function checksumMismatch(stored: number, computed: number): FilmFileError {
  return new FilmFileError(
    `checksum mismatch (stored ${hex8(stored)}, computed ${hex8(computed)}): the file is corrupt (damaged since it was written)`,
  );
}

/** Pixel `p` holds more samples than the header's ranges: the file contradicts itself. */
export function tooManySamples(
  p: number,
  width: number,
  count: number,
  samples: number,
): FilmFileError {
  const where = `pixel (${p % width}, ${Math.floor(p / width)})`;
  return new FilmFileError(
    samples === 0
      ? `inconsistent: ${where} has ${count} samples, but the header's ranges are empty`
      : `${where} has ${count} samples, more than the ${samples} of its ranges (inconsistent)`,
  );
}

/**
 * The fewest and most paths a film's ranges account for: pixels × samples, or for an
 * adaptive render (film/adaptive.ts) from every pixel at the lowest rate to every
 * pixel at the full rate.
 */
export function pathBounds(header: FilmHeader): [number, number] {
  const n = header.settings.width * header.settings.height;
  const samples = rangeSamples(header.ranges);
  if (header.settings.adaptive !== true) return [n * samples, n * samples];
  let least = 0;
  for (const [a, b] of header.ranges) {
    least +=
      adaptiveCount(b, ADAPTIVE_PILOT, RATE_MIN) - adaptiveCount(a, ADAPTIVE_PILOT, RATE_MIN);
  }
  return [n * least, n * samples];
}

/**
 * Whether the samples the pixels hold (`accepted`, their sum) and the header's stats
 * agree: every path of every pixel of every sample of the ranges was traced, and was
 * either accepted or rejected. null when they do.
 */
export function countsProblem(header: FilmHeader, accepted: number): FilmFileError | null {
  const n = header.settings.width * header.settings.height;
  const samples = rangeSamples(header.ranges);
  const { paths, rejected } = header.stats;
  const [least, most] = pathBounds(header);
  if (paths < least || paths > most || accepted + rejected !== paths) {
    return new FilmFileError(
      `stats do not add up: ${paths} paths and ${rejected} rejected for ${n} pixels × ${samples} samples with ${accepted} accepted (inconsistent)`,
    );
  }
  return null;
}

function hex8(v: number): string {
  return v.toString(16).padStart(8, '0');
}
