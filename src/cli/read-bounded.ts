/**
 * Reading an input file with a bound on the bytes read, whatever the source: a regular
 * file, a pipe, /dev/stdin, /dev/zero or /dev/urandom. A size reported by stat() cannot be
 * trusted for this (it is 0 for pipes and devices), so the bytes are read in chunks and
 * counted, and reading stops as soon as the count passes the limit: memory stays below
 * limit + one chunk. A regular file that stat() says is too large is rejected before any
 * byte is read, with its exact size.
 */
import { fstat, read } from 'node:fs';
import { open, type FileHandle } from 'node:fs/promises';
import { promisify } from 'node:util';
import { sanitize } from '../core/util/message.ts';
import { CliError } from './errors.ts';

const CHUNK = 1 << 20;

/** The input is larger than the limit. */
export class ReadLimitError extends CliError {
  override name = 'ReadLimitError';
  /** Size in bytes: exact when `exact`, else what was read before stopping (limit + 1). */
  readonly size: number;
  readonly exact: boolean;
  readonly limit: number;

  constructor(path: string, limit: number, size: number, exact: boolean) {
    super(
      `${showPath(path)} is larger than the limit of ${limit} bytes: ` +
        (exact ? `it has ${size} bytes` : `reading stopped after ${size} bytes`),
    );
    this.size = size;
    this.exact = exact;
    this.limit = limit;
  }
}

/** A path as messages show it: escaped, so that a hostile name cannot break the line. */
export function showPath(path: string): string {
  return sanitize(path, 240);
}

const REASONS: Record<string, string> = {
  ENOENT: 'no such file or directory',
  EISDIR: 'it is a directory',
  EACCES: 'permission denied',
  EPERM: 'operation not permitted',
  ENOTDIR: 'a component of the path is not a directory',
  ELOOP: 'too many levels of symbolic links',
  ENXIO: 'no such device (a socket or a FIFO without a writer?)',
  ENAMETOOLONG: 'the name is too long',
  EIO: 'input/output error',
  ENOSPC: 'no space left on device',
  EDQUOT: 'disk quota exceeded',
  EROFS: 'read-only file system',
  EEXIST: 'the file already exists',
};

/** A short reason for a failed file operation, without Node's raw (unsanitized) path. */
export function reason(e: unknown): string {
  const code = (e as NodeJS.ErrnoException)?.code;
  if (code !== undefined && REASONS[code] !== undefined) return REASONS[code];
  if (code !== undefined) return sanitize(code);
  return sanitize(e instanceof Error ? e.message : String(e), 200);
}

/** Descriptor 0 with the two FileHandle methods used here (it is not closed after). */
class StdinHandle {
  stat() {
    return promisify(fstat)(0);
  }
  async read(buffer: Uint8Array, offset: number, length: number, position: null) {
    const { bytesRead } = await promisify(read)(0, buffer, offset, length, position);
    return { bytesRead };
  }
  async close(): Promise<void> {}
}

const sleep = (ms: number) => new Promise<void>((resolve) => setTimeout(resolve, ms));

/**
 * Reads all of `path`, at most `limit` bytes. Throws ReadLimitError past the limit and
 * CliError (`cannot read PATH: reason`) when the file cannot be opened or read.
 */
export async function readBounded(path: string, limit: number): Promise<Uint8Array> {
  let handle: FileHandle | StdinHandle;
  try {
    // Standard input is read from descriptor 0 itself: opening /dev/stdin anew fails when
    // it is a socket (ENXIO), as it is for a child spawned by Node.
    handle = path === '-' || path === '/dev/stdin' ? new StdinHandle() : await open(path, 'r');
  } catch (e) {
    throw new CliError(`cannot read ${showPath(path)}: ${reason(e)}`);
  }
  try {
    const info = await handle.stat();
    if (info.isDirectory()) throw new CliError(`cannot read ${showPath(path)}: it is a directory`);
    if (info.isFile() && info.size > limit) throw new ReadLimitError(path, limit, info.size, true);
    const buffer = new Uint8Array(Math.min(CHUNK, limit + 1));
    const chunks: Uint8Array[] = [];
    let total = 0;
    for (;;) {
      const want = Math.min(buffer.length, limit + 1 - total);
      let n: number;
      try {
        n = (await handle.read(buffer, 0, want, null)).bytesRead;
      } catch (e) {
        // A non-blocking descriptor (some inherited stdin) has no data yet: wait for it.
        if ((e as NodeJS.ErrnoException).code === 'EAGAIN') {
          await sleep(5);
          continue;
        }
        throw new CliError(`cannot read ${showPath(path)}: ${reason(e)}`);
      }
      if (n === 0) break;
      chunks.push(buffer.slice(0, n));
      total += n;
      if (total > limit) throw new ReadLimitError(path, limit, total, false);
    }
    const out = new Uint8Array(total);
    let at = 0;
    for (const chunk of chunks) {
      out.set(chunk, at);
      at += chunk.length;
    }
    return out;
  } finally {
    await handle.close().catch(() => undefined);
  }
}
