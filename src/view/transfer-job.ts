/**
 * The fallback without SharedArrayBuffer: the film lives on the main
 * thread, and each task ships one stripe's rows (every plane of the film) to
 * a worker, which adds one pass and ships them back. A stripe is out at
 * most once at a time (its rows come back whole and replace the film's),
 * and the film's sums are exact, so the image is the same, bit for bit,
 * as the shared path's.
 */
import { ADAPTIVE_PILOT, Film } from '../core/index.ts';
import {
  stripeOrder,
  type StripeResult,
  type StripeTask,
} from '../../workers/browser/render-protocol.ts';
import type { FilmJob } from './film-job.ts';
import { PilotGate } from './pilot-gate.ts';

export class TransferFilmJob implements FilmJob {
  readonly film: Film;
  readonly width: number;
  readonly height: number;
  readonly stripeRows: number;
  readonly stripes: number;
  private gen = 0;
  private version = -1;
  /** The caller's target; stripes are handed out up to the gate's cap of it. */
  private target: number;
  private readonly gate: PilotGate;
  private paused = false;
  private done: Int32Array;
  private inFlight: Uint8Array;
  /** Stripes in the order a pass visits them (spread over the frame, see stripeOrder). */
  private readonly order: Int32Array;
  /** Stripes ready for their next pass, in the order they will be handed out. */
  private queue: number[] = [];
  /** Rows changed since the last takeDirtyRows, as [y0, y1) spans. */
  private dirty: number[] = [];
  private cleared = false;
  private segments = 0;
  private rejectedCount = 0;

  /** The film has albedo and normal planes (for the denoiser). */
  readonly aux: boolean;

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
    this.stripes = Math.ceil(height / stripeRows);
    this.film = new Film(width, height, undefined, 0, 0, aux);
    this.target = target;
    this.gate = new PilotGate(adaptive ? new Uint8Array(width * height) : null);
    this.done = new Int32Array(this.stripes);
    this.inFlight = new Uint8Array(this.stripes);
    this.order = stripeOrder(this.stripes);
    this.requeue();
  }

  get adaptive(): boolean {
    return this.gate.adaptive;
  }

  get pilotPending(): boolean {
    return this.gate.closed;
  }

  get memoryBytes(): number {
    return this.film.buffer.byteLength + (this.gate.map?.byteLength ?? 0);
  }

  /** Passes stripes may be taken to now (the caller's target, capped at a closed gate). */
  private limit(): number {
    return this.gate.cap(this.target);
  }

  private requeue(): void {
    this.queue = [];
    const limit = this.limit();
    for (const s of this.order) {
      if (!this.inFlight[s] && this.done[s] < limit) this.queue.push(s);
    }
  }

  advance(): boolean {
    // No stripe is out once all hold the pilot: the capped target handed out no more.
    if (!this.gate.tryOpen(this.film, this.passesDone())) return false;
    this.requeue();
    return true;
  }

  reset(): void {
    this.gen++;
    this.gate.close();
    this.film.clear();
    this.done = new Int32Array(this.stripes);
    // Tasks of the old generation still out are dropped when they return.
    this.inFlight = new Uint8Array(this.stripes);
    this.requeue();
    this.dirty = [];
    this.cleared = true;
  }

  setVersion(version: number): void {
    this.version = version;
  }

  setTarget(spp: number): void {
    this.target = spp;
    this.requeue();
  }

  setPaused(paused: boolean): void {
    this.paused = paused;
  }

  passesDone(): number {
    let min = Infinity;
    for (let s = 0; s < this.stripes; s++) min = Math.min(min, this.done[s]);
    return min === Infinity ? 0 : min;
  }

  meanSamples(): number {
    return this.gate.meanSamples(this.passesDone());
  }

  progress(): number {
    let sum = 0;
    for (let s = 0; s < this.stripes; s++) sum += this.done[s];
    return sum / this.stripes;
  }

  takeCleared(): boolean {
    const c = this.cleared;
    this.cleared = false;
    return c;
  }

  takeDirtyRows(): number[] {
    const d = this.dirty;
    this.dirty = [];
    return d;
  }

  takeSegments(): number {
    const s = this.segments;
    this.segments = 0;
    return s;
  }

  rejected(): number {
    return this.rejectedCount;
  }

  busy(): boolean {
    return this.inFlight.includes(1);
  }

  nextTask(job: number): StripeTask | null {
    if (this.paused || this.version < 0) return null;
    const stripe = this.queue.shift();
    if (stripe === undefined) return null;
    const y0 = stripe * this.stripeRows;
    const rows = Math.min(this.height, y0 + this.stripeRows) - y0;
    const buffer = new ArrayBuffer(Film.byteLength(this.width, rows, this.aux));
    const window = new Film(this.width, rows, buffer, y0, 0, this.aux);
    window.copyRowsFrom(this.film);
    this.inFlight[stripe] = 1;
    const pass = this.done[stripe];
    const map = this.gate.map;
    return {
      type: 'task',
      job,
      version: this.version,
      gen: this.gen,
      stripe,
      pass,
      y0,
      rows,
      buffer,
      // Past the pilot, the stripe's rows of the map travel with it.
      map:
        map !== null && pass >= ADAPTIVE_PILOT
          ? map.slice(y0 * this.width, (y0 + rows) * this.width)
          : undefined,
    };
  }

  /**
   * A task's worker died before answering: its rows never left this
   * film (they travelled as a copy), so the stripe simply goes out again.
   */
  onTaskLost(task: StripeTask): void {
    if (task.gen !== this.gen) return;
    const s = task.stripe;
    this.inFlight[s] = 0;
    if (this.done[s] < this.limit()) this.queue.unshift(s);
  }

  onResult(result: StripeResult): void {
    this.segments += result.segments;
    this.rejectedCount += result.rejected;
    if (result.gen !== this.gen) return;
    const s = result.stripe;
    this.inFlight[s] = 0;
    if (result.rendered) {
      const window = new Film(this.width, result.rows, result.buffer, result.y0, 0, this.aux);
      this.film.copyRowsFrom(window);
      this.done[s]++;
      // Collapsed when frames stop (a hidden tab) so the list stays small.
      if (this.dirty.length > 2 * this.stripes) this.dirty = [0, this.height];
      else this.dirty.push(result.y0, result.y0 + result.rows);
    }
    // The last stripe of the pilot opens the gate (the queue is then refilled).
    if (this.gate.closed && this.advance()) return;
    if (this.done[s] < this.limit()) {
      // A stripe that was not rendered goes first again, to keep pass order tight.
      if (result.rendered) this.queue.push(s);
      else this.queue.unshift(s);
    }
  }
}
