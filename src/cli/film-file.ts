/**
 * `.film` files on disk: the identity of a render (hashes of the scene and
 * of the settings that change its pixels), and bounded reading with one
 * clear error per problem. (Writing is output.ts's atomic OutputFile.)
 */
import { createHash } from 'node:crypto';
import { closeSync, fstatSync, openSync, readSync, statSync } from 'node:fs';
import {
  AUX_NAMES,
  FILM_FORMAT,
  FILM_FORMAT_AUX,
  FilmFileError,
  FilmHeaderError,
  MAX_HEADER_BYTES,
  checksumMismatch,
  countsProblem,
  decodeFilmFile,
  decodeFilmHeader,
  filmCountsOffset,
  tooManySamples,
  type FilmFile,
  type FilmHeader,
  type FilmSettings,
} from '../core/film/film-file.ts';
import { SCALE_BITS } from '../core/film/exact-sum.ts';
import { rangeSamples } from '../core/film/sample-ranges.ts';
import { crc32 } from '../core/io/crc32.ts';
import type { Scene } from '../core/scene/format/types.ts';
import packageJson from '../../package.json' with { type: 'json' };
import { CliError } from './errors.ts';
import { reason, showPath } from './read-bounded.ts';
import { renderSettingsOf } from '../core/scene/format/render-settings.ts';

export const RENDERER = `pathwise ${packageJson.version}`;

/** What a render's parts must share to be merged. */
export interface FilmIdentity {
  renderer: string;
  scene_sha256: string;
  settings: FilmSettings;
  key: string;
}

function sha256(text: string): string {
  return createHash('sha256').update(text).digest('hex');
}

/**
 * SHA-256 of a loaded scene: its JSON, in which every typed array (decoded meshes,
 * glTF models and their textures, environment maps) stands as its type and length, and
 * then the arrays' bytes in the order the JSON names them — the same content gives the
 * same hash, without turning millions of numbers into text.
 */
function sceneHash(value: unknown): string {
  const arrays: ArrayBufferView[] = [];
  const text = JSON.stringify(value, (_key, v: unknown) => {
    if (ArrayBuffer.isView(v)) {
      arrays.push(v);
      return { typed: v.constructor.name, bytes: v.byteLength };
    }
    return v;
  });
  const hash = createHash('sha256').update(text);
  for (const a of arrays) hash.update(new Uint8Array(a.buffer, a.byteOffset, a.byteLength));
  return hash.digest('hex');
}

/**
 * The identity of a render. The scene hash covers the loaded scene (every
 * default filled in, so formatting and key order of the file do not
 * matter) without its name and settings, which change no pixel; the
 * settings that do are hashed separately, with the renderer's version.
 */
export function filmIdentity(scene: Scene, settings: FilmSettings): FilmIdentity {
  const { name: _name, settings: _settings, ...pixels } = scene;
  const scene_sha256 = sceneHash(pixels);
  const canonical = renderSettingsOf(settings);
  const key = sha256(JSON.stringify({ renderer: RENDERER, scene_sha256, settings: canonical }));
  return { renderer: RENDERER, scene_sha256, settings: canonical, key };
}

export function makeHeader(
  identity: FilmIdentity,
  spp: number,
  ranges: [number, number][],
  stats: FilmHeader['stats'],
  /** The film carries albedo and normal: a `pathwise-film/2` header. */
  aux = false,
): FilmHeader {
  return {
    format: aux ? FILM_FORMAT_AUX : FILM_FORMAT,
    renderer: identity.renderer,
    scene_sha256: identity.scene_sha256,
    settings: identity.settings,
    key: identity.key,
    scale_bits: SCALE_BITS,
    spp,
    ranges,
    stats,
    ...(aux ? { aux: AUX_NAMES } : {}),
  };
}

const CHUNK = 1 << 20;

/**
 * The header of a `.film` file, once the whole file is known to be intact: its length
 * matches the header, its checksum matches its bytes, and its pixels' sample counts
 * agree with the header's ranges and stats. The body is streamed in 1 MiB chunks, never
 * held whole, so `merge` can refuse a damaged or inconsistent part before it compares
 * parts (a flipped bit in a header would otherwise read as "renders of different
 * scenes", and pixels holding samples outside empty ranges as "missing samples").
 */
export function readFilmHeader(path: string): FilmHeader {
  return withFile(path, (fd, total) => {
    const prefix = Buffer.alloc(Math.min(total, 20 + MAX_HEADER_BYTES));
    readFully(fd, prefix, 0);
    let decoded: { header: FilmHeader; byteLength: number };
    try {
      decoded = decodeFilmHeader(prefix, total);
    } catch (e) {
      // A header that says something wrong may have been changed after it was written:
      // if the checksum of the file as it stands does not match, say that instead.
      if (e instanceof FilmHeaderError && total >= 24) {
        const { stored, computed } = checksums(fd, total);
        if (stored !== computed) throw checksumMismatch(stored, computed);
      }
      throw e;
    }
    const { header, byteLength } = decoded;
    const { width, height } = header.settings;
    const n = width * height;
    const samples = rangeSamples(header.ranges);
    // Counts start 8-aligned and chunks are 4-aligned: no count straddles two chunks.
    const countsAt = filmCountsOffset(prefix.readUInt32LE(16));
    const countsEnd = countsAt + 4 * n;
    const chunk = Buffer.alloc(Math.min(CHUNK, byteLength));
    let crc = 0;
    let accepted = 0;
    let first: Error | null = null;
    for (let at = 0; at < byteLength - 4;) {
      const want = Math.min(chunk.length, byteLength - 4 - at);
      readRange(fd, chunk, want, at);
      crc = crc32(chunk.subarray(0, want), crc);
      for (let o = Math.max(at, countsAt); o < Math.min(at + want, countsEnd); o += 4) {
        const count = chunk.readUInt32LE(o - at);
        accepted += count;
        if (count > samples && first === null) {
          first = tooManySamples((o - countsAt) / 4, width, count, samples);
        }
      }
      at += want;
    }
    readRange(fd, chunk, 4, byteLength - 4);
    const stored = chunk.readUInt32LE(0);
    // Damage first: a changed byte explains any inconsistency after it.
    if (stored !== crc) throw checksumMismatch(stored, crc);
    if (first !== null) throw first;
    const problem = countsProblem(header, accepted);
    if (problem !== null) throw problem;
    return header;
  });
}

/** The CRC-32 stored in the last 4 of `total` bytes, and the one of the bytes before. */
function checksums(fd: number, total: number): { stored: number; computed: number } {
  const chunk = Buffer.alloc(Math.min(CHUNK, total));
  let computed = 0;
  for (let at = 0; at < total - 4;) {
    const want = Math.min(chunk.length, total - 4 - at);
    readRange(fd, chunk, want, at);
    computed = crc32(chunk.subarray(0, want), computed);
    at += want;
  }
  readRange(fd, chunk, 4, total - 4);
  return { stored: chunk.readUInt32LE(0), computed };
}

/** Reads `length` bytes at `position` into the start of `into`. */
function readRange(fd: number, into: Buffer, length: number, position: number): void {
  let got = 0;
  while (got < length) {
    const n = readSync(fd, into, got, length - got, position + got);
    if (n === 0) {
      throw new FilmFileError(
        `truncated while reading: ${position + got} of ${position + length} bytes`,
      );
    }
    got += n;
  }
}

/**
 * Reads and checks a `.film` file. The header is read and checked first,
 * so the file's length is known to match it before the rest is read:
 * nothing large is allocated on a lying header. (So a `.film` must be a
 * regular file, not a pipe.) Errors are CliErrors (exit status 2) that
 * name the file.
 */
export function readFilmFile(path: string): FilmFile {
  return withFile(path, (fd, total) => {
    const prefix = Buffer.alloc(Math.min(total, 20 + MAX_HEADER_BYTES));
    readFully(fd, prefix, 0);
    const { byteLength } = decodeFilmHeader(prefix, total);
    const bytes = Buffer.alloc(byteLength);
    prefix.copy(bytes, 0, 0, prefix.length);
    readFully(fd, bytes, prefix.length);
    return decodeFilmFile(bytes);
  });
}

/** Runs `body`, naming the file in a FilmFileError. */
function named<T>(path: string, body: () => T): T {
  try {
    return body();
  } catch (e) {
    if (e instanceof FilmFileError) throw new CliError(`${showPath(path)}: ${e.message}`);
    throw e;
  }
}

function withFile<T>(path: string, body: (fd: number, total: number) => T): T {
  let fd: number;
  try {
    // Not opened if not a regular file: opening a FIFO would wait for a writer.
    const info = statSync(path);
    if (!info.isFile() && !info.isDirectory()) {
      throw new CliError(
        `cannot read ${showPath(path)}: not a regular file (a .film's length is checked against its header)`,
      );
    }
    fd = openSync(path, 'r');
  } catch (e) {
    if (e instanceof CliError) throw e;
    throw new CliError(`cannot read ${showPath(path)}: ${reason(e)}`);
  }
  try {
    const info = fstatSync(fd);
    if (info.isDirectory()) throw new CliError(`cannot read ${showPath(path)}: it is a directory`);
    if (!info.isFile()) {
      throw new CliError(
        `cannot read ${showPath(path)}: not a regular file (a .film's length is checked against its header)`,
      );
    }
    return named(path, () => body(fd, info.size));
  } catch (e) {
    if (e instanceof CliError) throw e;
    if (e instanceof RangeError) throw new CliError(`${showPath(path)}: ${e.message}`);
    if ((e as NodeJS.ErrnoException).code) {
      throw new CliError(`cannot read ${showPath(path)}: ${reason(e)}`);
    }
    throw e;
  } finally {
    closeSync(fd);
  }
}

function readFully(fd: number, into: Buffer, from: number): void {
  let at = from;
  while (at < into.length) {
    const n = readSync(fd, into, at, into.length - at, at);
    if (n === 0) throw new FilmFileError(`truncated while reading: ${at} of ${into.length} bytes`);
    at += n;
  }
}
