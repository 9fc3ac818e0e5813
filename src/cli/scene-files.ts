/**
 * The command line's SceneFileReader: paths relative to the scene file's folder, read
 * with a bound. The size is checked before reading when the file reports one, and the
 * read itself stops one byte past the limit, so a pipe or device (which reports no
 * size) cannot make it read without end either.
 */
import { closeSync, fstatSync, openSync, readSync } from 'node:fs';
import { isAbsolute, resolve } from 'node:path';
import type { SceneFileReader } from '../core/index.ts';

export function nodeSceneFiles(sceneDir: string): SceneFileReader {
  return {
    async read(path: string, maxBytes: number): Promise<Uint8Array> {
      const full = isAbsolute(path) ? path : resolve(sceneDir, path);
      return readBounded(full, maxBytes);
    },
  };
}

export function readBounded(path: string, maxBytes: number): Uint8Array {
  let fd: number;
  try {
    fd = openSync(path, 'r');
  } catch (e) {
    throw new Error(systemMessage(e, 'cannot open it'));
  }
  try {
    const stat = fstatSync(fd);
    if (stat.isDirectory()) throw new Error('it is a directory, not a file');
    if (stat.isFile() && stat.size > maxBytes) {
      throw new Error(`the file is ${stat.size} bytes, more than the limit of ${maxBytes}`);
    }
    // A regular file is read at its size; anything else in chunks up to the limit.
    let buffer = new Uint8Array(stat.isFile() ? stat.size : Math.min(maxBytes + 1, 1 << 20));
    let length = 0;
    for (;;) {
      if (length === buffer.length) {
        if (stat.isFile() || length > maxBytes) break;
        const bigger = new Uint8Array(Math.min(maxBytes + 1, buffer.length * 2));
        bigger.set(buffer);
        buffer = bigger;
      }
      const n = readSync(fd, buffer, length, buffer.length - length, null);
      if (n === 0) break;
      length += n;
    }
    if (length > maxBytes) {
      throw new Error(`the file is more than the limit of ${maxBytes} bytes`);
    }
    return length === buffer.length ? buffer : buffer.subarray(0, length);
  } catch (e) {
    throw new Error(systemMessage(e, 'cannot read it'));
  } finally {
    closeSync(fd);
  }
}

/** "cannot open it: no such file or directory" rather than Node's code-laden message. */
function systemMessage(e: unknown, what: string): string {
  const err = e as NodeJS.ErrnoException;
  if (err.code === 'ENOENT') return `${what}: no such file`;
  if (err.code === 'EACCES') return `${what}: permission denied`;
  if (err.code === 'EISDIR') return `${what}: it is a directory, not a file`;
  if (err.code === undefined && e instanceof Error) return e.message;
  return `${what}: ${err.code ?? ''} ${err.message ?? String(e)}`.trim();
}
