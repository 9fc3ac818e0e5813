/**
 * Writing an output file safely: checked before the work starts, written atomically.
 *
 * `prepareOutput` runs before rendering, so that a missing directory, a directory in the
 * way, a device (`/dev/full`) or a read-only place is a one-line error (exit status 2)
 * at once, not a crash at the end of a long render. It creates the temporary file in the
 * directory of the output (same file system, so the final rename is atomic); `commit`
 * writes the bytes there, flushes them and renames the file into place, so readers see
 * the old file or the new one, never half of one. On any failure the temporary file is
 * removed.
 */
import { lstat, open, realpath, rename, stat, unlink, type FileHandle } from 'node:fs/promises';
import { basename, dirname, join, resolve } from 'node:path';
import { randomBytes } from 'node:crypto';
import { CliError } from './errors.ts';
import { temps } from './host.ts';
import { reason, showPath } from './read-bounded.ts';

export class OutputFile {
  private handle: FileHandle | null;
  private done = false;
  /** The temporary file's slot in the registry the main thread cleans up from. */
  private readonly slot: number;

  private constructor(
    /** The path as the user gave it (for messages). */
    readonly path: string,
    /** Where the file will be: the path, resolved through a symbolic link to a file. */
    readonly target: string,
    /** The temporary file beside the target. */
    readonly temp: string,
    handle: FileHandle,
    slot: number,
  ) {
    this.handle = handle;
    this.slot = slot;
  }

  /** Writes `bytes` to the temporary file, flushes it, and renames it onto the target. */
  async commit(bytes: Uint8Array): Promise<void> {
    const handle = this.handle;
    if (handle === null || this.done) throw new Error('output already committed or discarded');
    try {
      let at = 0;
      while (at < bytes.length) {
        const { bytesWritten } = await handle.write(bytes, at, bytes.length - at);
        at += bytesWritten;
      }
      await handle.sync();
      await handle.close();
      this.handle = null;
      await rename(this.temp, this.target);
      this.done = true;
      temps.release(this.slot);
    } catch (e) {
      await this.discard();
      throw new CliError(`cannot write ${showPath(this.path)}: ${reason(e)}`);
    }
  }

  /** Removes the temporary file (after a failure, or when the work was abandoned). */
  async discard(): Promise<void> {
    if (this.done) return;
    this.done = true;
    const handle = this.handle;
    this.handle = null;
    await handle?.close().catch(() => undefined);
    await unlink(this.temp).catch(() => undefined);
    temps.release(this.slot);
  }

  /**
   * Checks that `path` can be written and creates its temporary file. Throws CliError
   * (`cannot write PATH: reason`) when the directory is missing, the path is a directory
   * or not a regular file (a device, a FIFO), or the directory is not writable.
   */
  static async prepare(path: string): Promise<OutputFile> {
    const fail = (why: string): never => {
      throw new CliError(`cannot write ${showPath(path)}: ${why}`);
    };
    let target = resolve(path);
    const existing = await stat(target).catch((e: NodeJS.ErrnoException) =>
      e.code === 'ENOENT' ? null : fail(reason(e)),
    );
    if (existing !== null) {
      if (existing.isDirectory()) fail('it is a directory');
      // Renaming over a device would replace the device node; writing into one (/dev/full)
      // cannot be atomic. Only regular files are replaced.
      if (!existing.isFile()) fail(`it is ${kind(existing)}, not a regular file`);
      // Replace the file a symbolic link points to, not the link.
      if ((await lstat(target)).isSymbolicLink()) target = await realpath(target);
    }
    const dir = dirname(target);
    const dirInfo = await stat(dir).catch((e: NodeJS.ErrnoException) =>
      fail(
        e.code === 'ENOENT'
          ? `the directory ${showPath(dir)} does not exist`
          : `${showPath(dir)}: ${reason(e)}`,
      ),
    );
    if (!dirInfo.isDirectory()) fail(`${showPath(dir)} is not a directory`);
    const temp = join(
      dir,
      `.${basename(target)}.${process.pid}-${randomBytes(4).toString('hex')}.tmp`,
    );
    // Recorded before it exists: a signal from here on removes it (temp-registry.ts).
    const slot = temps.creating(temp);
    let handle: FileHandle;
    try {
      handle = await open(temp, 'wx');
      temps.created(slot);
    } catch (e) {
      temps.release(slot);
      return fail(`cannot create a file in ${showPath(dir)}: ${reason(e)}`);
    }
    return new OutputFile(path, target, temp, handle, slot);
  }
}

function kind(info: Awaited<ReturnType<typeof stat>>): string {
  if (info.isCharacterDevice()) return 'a character device';
  if (info.isBlockDevice()) return 'a block device';
  if (info.isFIFO()) return 'a FIFO';
  if (info.isSocket()) return 'a socket';
  return 'a special file';
}
