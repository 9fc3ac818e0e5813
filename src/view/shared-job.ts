/**
 * A film on a SharedArrayBuffer that the workers write in place. The main
 * thread only changes the control block under its lock (see
 * workers/render-protocol.ts) and reads the sums for display.
 */
import { Film } from '../core/index.ts';
import {
  C_CLAIM,
  C_CONFIG,
  C_DONE,
  C_GEN,
  C_PAUSED,
  C_REJECTED,
  C_SEGMENTS,
  C_TARGET,
  controlWords,
  lock,
  rowStampBase,
  unlock,
} from '../../workers/render-protocol.ts';
import type { FilmJob } from './film-job.ts';

export class SharedFilmJob implements FilmJob {
  readonly film: Film;
  readonly width: number;
  readonly height: number;
  readonly stripeRows: number;
  readonly stripes: number;
  readonly filmBuffer: SharedArrayBuffer;
  readonly ctrlBuffer: SharedArrayBuffer;
  private readonly ctrl: Int32Array;
  private lastSegments = 0;
  private cleared = false;
  /** Row stamps as of the last takeDirtyRows. */
  private readonly seen: Int32Array;

  constructor(width: number, height: number, stripeRows: number, target: number) {
    this.width = width;
    this.height = height;
    this.stripeRows = stripeRows;
    this.stripes = Math.ceil(height / stripeRows);
    this.filmBuffer = new SharedArrayBuffer(Film.byteLength(width, height));
    this.ctrlBuffer = new SharedArrayBuffer(controlWords(this.stripes, height) * 4);
    this.seen = new Int32Array(height).fill(-1);
    this.film = new Film(width, height, this.filmBuffer);
    this.ctrl = new Int32Array(this.ctrlBuffer);
    this.ctrl[C_CONFIG] = -1;
    this.ctrl[C_TARGET] = target;
  }

  get memoryBytes(): number {
    return this.filmBuffer.byteLength + this.ctrlBuffer.byteLength;
  }

  reset(): void {
    const ctrl = this.ctrl;
    lock(ctrl);
    // Under the lock no worker is committing a row; once the generation is
    // bumped, rows rendered before this point fail their commit check.
    this.film.clear();
    ctrl[C_CLAIM] = 0;
    ctrl.fill(0, C_DONE, C_DONE + this.stripes);
    ctrl[C_GEN]++;
    unlock(ctrl);
    // The display blanks the whole image once (takeCleared) instead of
    // tone mapping every row of zeros; rows committed from now on carry
    // new stamps and are drawn over the blank.
    this.cleared = true;
    // Workers waiting for a stripe's previous pass look at the generation again.
    for (let s = 0; s < this.stripes; s++) Atomics.notify(ctrl, C_DONE + s);
  }

  setVersion(version: number): void {
    const ctrl = this.ctrl;
    lock(ctrl);
    ctrl[C_CONFIG] = version;
    // A new generation too: a stripe in hand under the old configuration
    // stops at its next row instead of finishing (a film being switched
    // away from, e.g. for the drag preview, must free the workers at once).
    ctrl[C_GEN]++;
    unlock(ctrl);
    for (let s = 0; s < this.stripes; s++) Atomics.notify(ctrl, C_DONE + s);
  }

  setTarget(spp: number): void {
    Atomics.store(this.ctrl, C_TARGET, spp);
  }

  setPaused(paused: boolean): void {
    Atomics.store(this.ctrl, C_PAUSED, paused ? 1 : 0);
  }

  passesDone(): number {
    let min = Infinity;
    for (let s = 0; s < this.stripes; s++) min = Math.min(min, Atomics.load(this.ctrl, C_DONE + s));
    return min === Infinity ? 0 : min;
  }

  progress(): number {
    let sum = 0;
    for (let s = 0; s < this.stripes; s++) sum += Atomics.load(this.ctrl, C_DONE + s);
    return sum / this.stripes;
  }

  takeCleared(): boolean {
    const c = this.cleared;
    this.cleared = false;
    return c;
  }

  takeDirtyRows(): number[] {
    const spans: number[] = [];
    const base = rowStampBase(this.stripes);
    let start = -1;
    for (let y = 0; y < this.height; y++) {
      const stamp = Atomics.load(this.ctrl, base + y);
      const dirty = stamp !== this.seen[y];
      this.seen[y] = stamp;
      if (dirty && start < 0) start = y;
      if (!dirty && start >= 0) {
        spans.push(start, y);
        start = -1;
      }
    }
    if (start >= 0) spans.push(start, this.height);
    return spans;
  }

  takeSegments(): number {
    const now = Atomics.load(this.ctrl, C_SEGMENTS);
    // The counter wraps at 2^32; the difference modulo 2^32 is exact.
    const delta = (now - this.lastSegments) >>> 0;
    this.lastSegments = now;
    return delta;
  }

  rejected(): number {
    return Atomics.load(this.ctrl, C_REJECTED);
  }

  busy(): boolean {
    // Every claim ends in a finished pass unless the generation moves on,
    // and the controller resets (zeroing both counts) whenever it does.
    let done = 0;
    for (let s = 0; s < this.stripes; s++) done += Atomics.load(this.ctrl, C_DONE + s);
    return Atomics.load(this.ctrl, C_CLAIM) > done;
  }
}
