/**
 * `.film` files on disk: the identity of a render (hashes of the scene and
 * of the settings that change its pixels), bounded reading with one clear
 * error per problem, and atomic writing (write a temporary file, flush it,
 * rename it over the target: a crash leaves the old file or the new one,
 * never a torn one).
 */
import { createHash } from 'node:crypto';
import {
  closeSync,
  fstatSync,
  fsyncSync,
  openSync,
  readSync,
  renameSync,
  rmSync,
  writeSync,
} from 'node:fs';
import {
  FILM_FORMAT,
  FilmFileError,
  MAX_HEADER_BYTES,
  SCALE_BITS,
  decodeFilmFile,
  decodeFilmHeader,
  type FilmFile,
  type FilmHeader,
  type FilmSettings,
  type Scene,
} from '../core/index.ts';
import packageJson from '../../package.json' with { type: 'json' };
import { UsageError } from './args.ts';

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
 * The identity of a render. The scene hash covers the loaded scene (every
 * default filled in, so formatting and key order of the file do not
 * matter) without its name and settings, which change no pixel; the
 * settings that do are hashed separately, with the renderer's version.
 */
export function filmIdentity(scene: Scene, settings: FilmSettings): FilmIdentity {
  const { name: _name, settings: _settings, ...pixels } = scene;
  const scene_sha256 = sha256(JSON.stringify(pixels));
  const canonical: FilmSettings = {
    width: settings.width,
    height: settings.height,
    maxBounces: settings.maxBounces,
    seed: settings.seed,
    sampler: settings.sampler,
    estimator: settings.estimator,
  };
  const key = sha256(JSON.stringify({ renderer: RENDERER, scene_sha256, settings: canonical }));
  return { renderer: RENDERER, scene_sha256, settings: canonical, key };
}

export function makeHeader(
  identity: FilmIdentity,
  spp: number,
  ranges: [number, number][],
  stats: FilmHeader['stats'],
): FilmHeader {
  return {
    format: FILM_FORMAT,
    renderer: identity.renderer,
    scene_sha256: identity.scene_sha256,
    settings: identity.settings,
    key: identity.key,
    scale_bits: SCALE_BITS,
    spp,
    ranges,
    stats,
  };
}

/** Reads and checks only the header of a `.film` file (and that the file's length matches it). */
export function readFilmHeader(path: string): FilmHeader {
  return withFile(path, (fd, total) => {
    const prefix = Buffer.alloc(Math.min(total, 20 + MAX_HEADER_BYTES));
    readFully(fd, prefix, 0);
    return decodeFilmHeader(prefix, total).header;
  });
}

/**
 * Reads and checks a `.film` file. The header is read and checked first,
 * so the file's length is known to match it before the rest is read:
 * nothing large is allocated on a lying header. Errors are UsageErrors
 * (exit status 2) that start with the path.
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

function withFile<T>(path: string, body: (fd: number, total: number) => T): T {
  let fd: number;
  try {
    fd = openSync(path, 'r');
  } catch (e) {
    throw new UsageError(`cannot read ${path}: ${errorText(e)}`);
  }
  try {
    const total = fstatSync(fd).size;
    return body(fd, total);
  } catch (e) {
    if (e instanceof FilmFileError) throw new UsageError(`${path}: ${e.message}`);
    if (e instanceof RangeError) throw new UsageError(`${path}: ${e.message}`);
    if ((e as NodeJS.ErrnoException).code)
      throw new UsageError(`cannot read ${path}: ${errorText(e)}`);
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

/**
 * Writes `bytes` to `path` atomically: into `path.tmp` first, flushed to
 * disk, then renamed over `path`.
 */
export function writeFileAtomic(path: string, bytes: Uint8Array): void {
  const tmp = `${path}.tmp`;
  let fd: number | undefined;
  try {
    fd = openSync(tmp, 'w');
    let at = 0;
    while (at < bytes.length) at += writeSync(fd, bytes, at, bytes.length - at);
    fsyncSync(fd);
    closeSync(fd);
    fd = undefined;
    renameSync(tmp, path);
  } catch (e) {
    if (fd !== undefined) closeSync(fd);
    rmSync(tmp, { force: true });
    throw new UsageError(`cannot write ${path}: ${errorText(e)}`);
  }
}

/** An fs error's code and reason ("ENOENT: no such file or directory"), without the path it repeats. */
function errorText(e: unknown): string {
  const err = e as NodeJS.ErrnoException;
  if (err.code && err.syscall) {
    const reason = err.message.split(', ')[0];
    return reason.startsWith(err.code) ? reason : `${err.code}: ${reason}`;
  }
  return err.message ?? String(e);
}
