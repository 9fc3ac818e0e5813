/**
 * The temporary files a command has in the making, in shared memory, so that the
 * process's main thread can remove them when a signal arrives however busy the command
 * is. The command runs in a worker thread (command.ts); the main thread (main.ts) only
 * waits for it and for SIGINT / SIGTERM, so its handler runs within milliseconds at every
 * stage, whatever the command is doing: reading a FIFO, parsing, building a BVH, encoding.
 *
 * A slot's state word: FREE; RESERVED while the command writes the path; CREATING from
 * just before the file is opened until the open has settled; CREATED while the file may
 * exist. The main thread removes the files of CREATING and CREATED slots, waiting a
 * little for a CREATING one to settle, so no file created in that window is left behind.
 */
import { unlinkSync } from 'node:fs';

const SLOTS = 16;
/** Bytes of a path (UTF-8); Linux's PATH_MAX is 4096. */
const PATH_BYTES = 8192;
const FREE = 0;
const RESERVED = 1;
const CREATING = 2;
const CREATED = 3;
/** Longest wait (ms) for a file being created to settle before it is removed. */
const SETTLE_MS = 300;

export class TempRegistry {
  readonly buffer: SharedArrayBuffer;
  private readonly state: Int32Array;
  private readonly length: Int32Array;
  private readonly bytes: Uint8Array;

  constructor(buffer = new SharedArrayBuffer(SLOTS * 8 + SLOTS * PATH_BYTES)) {
    this.buffer = buffer;
    this.state = new Int32Array(buffer, 0, SLOTS);
    this.length = new Int32Array(buffer, SLOTS * 4, SLOTS);
    this.bytes = new Uint8Array(buffer, SLOTS * 8);
  }

  /**
   * Records `path` as about to be created; returns its slot, or -1 when it cannot be
   * recorded (a path longer than any file system takes, or every slot in use).
   */
  creating(path: string): number {
    const encoded = new TextEncoder().encode(path);
    if (encoded.length > PATH_BYTES) return -1;
    for (let k = 0; k < SLOTS; k++) {
      if (Atomics.compareExchange(this.state, k, FREE, RESERVED) !== FREE) continue;
      this.bytes.set(encoded, k * PATH_BYTES);
      this.length[k] = encoded.length;
      Atomics.store(this.state, k, CREATING);
      return k;
    }
    return -1;
  }

  /** The creation of slot k's file has settled: it may exist. */
  created(k: number): void {
    if (k < 0) return;
    Atomics.store(this.state, k, CREATED);
    Atomics.notify(this.state, k);
  }

  /** Slot k's file was renamed into place or removed: nothing to clean up. */
  release(k: number): void {
    if (k < 0) return;
    Atomics.store(this.state, k, FREE);
    Atomics.notify(this.state, k);
  }

  /** Removes every file that may exist (the signal handler's work); synchronous. */
  removeAll(): void {
    for (let k = 0; k < SLOTS; k++) {
      if (Atomics.load(this.state, k) === CREATING) {
        Atomics.wait(this.state, k, CREATING, SETTLE_MS);
      }
      const s = Atomics.load(this.state, k);
      if (s !== CREATING && s !== CREATED) continue;
      const path = new TextDecoder().decode(
        this.bytes.slice(k * PATH_BYTES, k * PATH_BYTES + this.length[k]),
      );
      try {
        unlinkSync(path);
      } catch {
        // never created, or already renamed or removed
      }
      Atomics.store(this.state, k, FREE);
    }
  }
}
