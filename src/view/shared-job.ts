/**
 * A film on a SharedArrayBuffer that the workers write in place. The main
 * thread only changes the control block under its lock (see
 * workers/browser/render-protocol.ts) and reads the sums for display.
 *
 * Workers may die holding a claim or even the lock (workers/browser/shared-claims.ts
 * says how that is survived): `recover` hands a dead worker's claims to the
 * living and finishes its cut-short commit. The main thread never waits
 * long for the lock: if its holder does not let go within
 * LOCK_PATIENCE_MS (it may have died a moment ago, before the pool knew),
 * the job walks away from its buffers and starts on fresh ones, which is
 * always safe where it happens (a reset or a new configuration, after which
 * the old samples are not wanted); the controller then sends the workers
 * the new buffers.
 */
import { Film } from '../core/index.ts';
import {
  C_CLAIM,
  C_COMMITS,
  C_CONFIG,
  C_DONE,
  C_GEN,
  C_LOCK,
  C_PAUSED,
  C_REJECTED,
  C_SEGMENTS,
  C_TARGET,
  MAIN_TOKEN,
  controlWords,
  lock,
  unlock,
} from '../../workers/browser/render-protocol.ts';
import {
  ControlLayout,
  initControl,
  lockMain,
  recoverDead,
} from '../../workers/browser/shared-claims.ts';
import type { FilmJob } from './film-job.ts';
import { PilotGate } from './pilot-gate.ts';
import { faults, isDead } from './worker-deaths.ts';

/** How long the main thread spins for a lock before it gives the buffers up. */
const LOCK_PATIENCE_MS = 50;

interface Abandoned {
  ctrl: Int32Array;
  stripes: number;
}

export class SharedFilmJob implements FilmJob {
  film!: Film;
  readonly width: number;
  readonly height: number;
  readonly stripeRows: number;
  readonly stripes: number;
  filmBuffer!: SharedArrayBuffer;
  ctrlBuffer!: SharedArrayBuffer;
  /** One row of film: a commit's row goes here first (shared-claims.ts, rule 3). */
  journalBuffer!: SharedArrayBuffer;
  private ctrl!: Int32Array;
  private journal!: Film;
  private readonly layout: ControlLayout;
  private lastSegments = 0;
  private cleared = false;
  /** Row stamps as of the last takeDirtyRows. */
  private readonly seen: Int32Array;
  /** Control blocks given up while a worker held their lock: broken when it is known dead. */
  private abandoned: Abandoned[] = [];
  private renewed = false;

  /** The film has albedo and normal planes (for the denoiser). */
  readonly aux: boolean;
  /**
   * An adaptive film's per-pixel rates (pilot-gate.ts), which the workers read; null
   * for a uniform film. Kept when the job moves to new buffers: only this thread writes
   * it, and only between a finished pilot and the passes after it.
   */
  readonly mapBuffer: SharedArrayBuffer | null;
  private readonly gate: PilotGate;
  /** The caller's target; the control block holds the gate's cap of it. */
  private target: number;

  constructor(
    width: number,
    height: number,
    stripeRows: number,
    target: number,
    aux = false,
    adaptive = false,
  ) {
    this.width = width;
    this.aux = aux;
    this.height = height;
    this.stripeRows = stripeRows;
    this.layout = new ControlLayout(height, stripeRows);
    this.stripes = this.layout.stripes;
    this.seen = new Int32Array(height).fill(-1);
    this.allocate();
    this.mapBuffer = adaptive ? new SharedArrayBuffer(width * height) : null;
    this.gate = new PilotGate(this.mapBuffer && new Uint8Array(this.mapBuffer));
    this.target = target;
    this.ctrl[C_CONFIG] = -1;
    this.ctrl[C_TARGET] = this.gate.cap(target);
  }

  get adaptive(): boolean {
    return this.gate.adaptive;
  }

  get pilotPending(): boolean {
    return this.gate.closed;
  }

  /** New, zeroed buffers (a RangeError when the memory is not there). */
  private allocate(): void {
    const filmBuffer = new SharedArrayBuffer(Film.byteLength(this.width, this.height, this.aux));
    const ctrlBuffer = new SharedArrayBuffer(controlWords(this.stripes, this.height) * 4);
    const journalBuffer = new SharedArrayBuffer(Film.byteLength(this.width, 1, this.aux));
    // Written once here, before a worker reads it (as the command line does, src/cli/render.ts):
    // a page first read by a worker maps the zero page, and its first write then interrupts
    // every core running the page's threads (a TLB shootdown).
    new Uint8Array(filmBuffer).fill(0);
    this.filmBuffer = filmBuffer;
    this.ctrlBuffer = ctrlBuffer;
    this.journalBuffer = journalBuffer;
    this.film = new Film(this.width, this.height, filmBuffer, 0, 0, this.aux);
    this.journal = new Film(this.width, 1, journalBuffer, 0, 0, this.aux);
    this.ctrl = new Int32Array(ctrlBuffer);
    initControl(this.ctrl);
  }

  get memoryBytes(): number {
    return (
      this.filmBuffer.byteLength +
      this.ctrlBuffer.byteLength +
      this.journalBuffer.byteLength +
      (this.mapBuffer?.byteLength ?? 0)
    );
  }

  /** Takes the lock for the main thread; see the header for what happens when it cannot. */
  private acquire(): void {
    const broken = faults.locksBroken;
    if (lockMain(this.ctrl, MAIN_TOKEN, isDead, LOCK_PATIENCE_MS, faults)) {
      // A broken lock: its dead holder's claims and cut-short commit first.
      if (faults.locksBroken > broken) this.repair();
      return;
    }
    try {
      this.renew();
    } catch {
      // No memory for new buffers: all that is left is to wait for the holder.
      lock(this.ctrl, MAIN_TOKEN);
      return;
    }
    lock(this.ctrl, MAIN_TOKEN);
  }

  /**
   * Moves to fresh buffers, keeping the counters that the controller reads
   * as differences. Workers still on the old block drop their work at the
   * next look (a new generation, no configuration) once its lock is free.
   */
  private renew(): void {
    const old = this.ctrl;
    const carried = [C_GEN, C_CONFIG, C_TARGET, C_PAUSED, C_COMMITS, C_SEGMENTS, C_REJECTED].map(
      (w) => [w, Atomics.load(old, w)],
    );
    this.allocate();
    for (const [w, v] of carried) this.ctrl[w] = v;
    // The new film is empty: an adaptive one starts a new pilot.
    this.gate.close();
    this.ctrl[C_TARGET] = this.gate.cap(this.target);
    this.ctrl[C_GEN]++;
    Atomics.add(old, C_GEN, 1);
    Atomics.store(old, C_CONFIG, -1);
    for (let s = 0; s < this.stripes; s++) Atomics.notify(old, C_DONE + s);
    this.abandoned.push({ ctrl: old, stripes: this.stripes });
    this.seen.fill(-1);
    this.renewed = true;
    faults.renewals++;
  }

  /** True once after the job moved to new buffers: the workers need them (a new configuration). */
  takeRenewed(): boolean {
    const r = this.renewed;
    this.renewed = false;
    return r;
  }

  reset(): void {
    this.acquire();
    // Under the lock no worker is committing a row; once the generation is
    // bumped, rows rendered before this point fail their commit check.
    this.film.clear();
    this.clearProgress();
    unlock(this.ctrl);
    // The display blanks the whole image once (takeCleared) instead of
    // tone mapping every row of zeros; rows committed from now on carry
    // new stamps and are drawn over the blank.
    this.cleared = true;
    // Workers waiting for a stripe's previous pass look at the generation again.
    this.notifyAll();
  }

  private notifyAll(): void {
    for (let s = 0; s < this.stripes; s++) Atomics.notify(this.ctrl, C_DONE + s);
  }

  /**
   * Under the lock: a new generation with nothing claimed, reclaimed, done
   * or committed (row stamps stay: they only ever grow), and an adaptive
   * film's gate closed until its new pilot is done.
   */
  private clearProgress(): void {
    const ctrl = this.ctrl;
    this.gate.close();
    ctrl[C_TARGET] = this.gate.cap(this.target);
    ctrl[C_CLAIM] = 0;
    initControl(ctrl);
    ctrl.fill(0, C_DONE, C_DONE + this.stripes);
    ctrl.fill(0, this.layout.passBase, this.layout.passBase + this.height);
    ctrl[C_GEN]++;
  }

  setVersion(version: number): void {
    this.acquire();
    this.ctrl[C_CONFIG] = version;
    // A new generation too: a stripe in hand under the old configuration
    // stops at its next row instead of finishing (a film being switched
    // away from, e.g. for the drag preview, must free the workers at once).
    this.ctrl[C_GEN]++;
    unlock(this.ctrl);
    this.notifyAll();
  }

  setTarget(spp: number): void {
    this.target = spp;
    Atomics.store(this.ctrl, C_TARGET, this.gate.cap(spp));
  }

  advance(): boolean {
    if (!this.gate.tryOpen(this.film, this.passesDone())) return false;
    // The map's writes come before this atomic store, and a worker takes a claim past
    // the pilot only after an atomic load of the new target (takeClaim): the load
    // synchronises with the store, so the worker sees the whole map.
    Atomics.store(this.ctrl, C_TARGET, this.target);
    return true;
  }

  setPaused(paused: boolean): void {
    Atomics.store(this.ctrl, C_PAUSED, paused ? 1 : 0);
  }

  /**
   * After the pool learnt of dead workers (isDead): their claims go back to
   * the others, a commit one of them cut short is finished, and locks they
   * held are broken, here and on given-up blocks. Returns false when a live
   * holder kept the lock too long; the pool tries again shortly.
   */
  recover(): boolean {
    this.abandoned = this.abandoned.filter((a) => {
      const holder = Atomics.load(a.ctrl, C_LOCK);
      if (holder !== 0 && isDead(holder)) {
        // Nothing on it is wanted; breaking the lock only frees live workers spinning on it.
        if (Atomics.compareExchange(a.ctrl, C_LOCK, holder, 0) === holder) {
          faults.locksBroken++;
        }
        for (let s = 0; s < a.stripes; s++) Atomics.notify(a.ctrl, C_DONE + s);
        return false;
      }
      return holder !== 0;
    });
    if (!lockMain(this.ctrl, MAIN_TOKEN, isDead, LOCK_PATIENCE_MS, faults)) return false;
    this.repair();
    unlock(this.ctrl);
    this.notifyAll();
    return true;
  }

  /** Under the lock: recoverDead, for this block. */
  private repair(): void {
    const ok = recoverDead(this.ctrl, this.layout, this.film, this.journal, isDead, faults);
    if (!ok) {
      // More open claims than the list holds, which its bound rules out:
      // start the image over rather than lose a claim.
      this.film.clear();
      this.clearProgress();
      this.cleared = true;
    }
  }

  passesDone(): number {
    let min = Infinity;
    for (let s = 0; s < this.stripes; s++) min = Math.min(min, Atomics.load(this.ctrl, C_DONE + s));
    return min === Infinity ? 0 : min;
  }

  meanSamples(): number {
    return this.gate.meanSamples(this.passesDone());
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
    const base = this.layout.stampBase;
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
    // and the controller resets (zeroing both counts) whenever it does. A
    // dead worker's claim stays open (reclaimed) until another finishes it.
    let done = 0;
    for (let s = 0; s < this.stripes; s++) done += Atomics.load(this.ctrl, C_DONE + s);
    return Atomics.load(this.ctrl, C_CLAIM) > done;
  }
}
