/**
 * The main thread's side of one film being rendered: where its samples
 * are, how many passes are done, and how to reset it. Two kinds: the
 * shared job (workers write the film in place, coordinated through the
 * control block) and the transfer job (the main thread hands out stripe
 * passes and merges the rows that come back).
 */
import type { CameraDesc, Film } from '../core/index.ts';
import type { StripeResult, StripeTask } from '../../workers/browser/render-protocol.ts';

export interface FilmJob {
  readonly film: Film;
  readonly width: number;
  readonly height: number;
  readonly stripeRows: number;
  /** The film has first-hit albedo and normal planes (Film's aux), for the denoiser. */
  readonly aux: boolean;
  /** Adaptive sampling (pilot-gate.ts): passes past the pilot follow a per-pixel map. */
  readonly adaptive: boolean;
  /** Approximate bytes held for this film (sums, exact sums, control). */
  readonly memoryBytes: number;
  /** Clears the film and drops all work in flight. */
  reset(): void;
  /** Marks the job as rendered under configuration `version` (-1: not at all). */
  setVersion(version: number): void;
  setTarget(spp: number): void;
  setPaused(paused: boolean): void;
  /**
   * Adaptive films: once every stripe holds the pilot, builds the sample map and lets
   * the workers past it (pilot-gate.ts). True when it did: the workers need waking.
   */
  advance(): boolean;
  /** An adaptive film whose map is not built yet (its pilot is under way). */
  readonly pilotPending: boolean;
  /**
   * Passes finished by every stripe: the image's samples per pixel (past an adaptive
   * film's pilot, the most any pixel holds).
   */
  passesDone(): number;
  /**
   * Mean samples per pixel after passesDone() passes: the same for a uniform film, fewer
   * past an adaptive film's pilot.
   */
  meanSamples(): number;
  /** Passes finished, averaged over stripes (fractional; for the progress bar). */
  progress(): number;
  /** True once after each reset: the whole film went back to zero. */
  takeCleared(): boolean;
  /**
   * Rows whose samples changed since the previous call, as flat
   * [y0, y1, y0, y1, …] half-open spans (empty when nothing changed).
   */
  takeDirtyRows(): number[];
  /** Segments traced since the previous call. */
  takeSegments(): number;
  rejected(): number;
  /** Work handed out and not yet back (stripes in hand, tasks out): samples may still arrive. */
  busy(): boolean;
  /** Transfer mode only. */
  nextTask?(job: number): StripeTask | null;
  onResult?(result: StripeResult): void;
  /** Transfer mode: the worker holding `task` died; the stripe goes out again. */
  onTaskLost?(task: StripeTask): void;
  /**
   * Shared mode: workers the pool knows to be dead left claims, maybe a
   * lock: hand them on. False when the lock stayed busy (try again soon).
   */
  recover?(): boolean;
  /** Shared mode: true once after the job moved to new buffers (send a new configuration). */
  takeRenewed?(): boolean;
}

/**
 * A full film as it is at one moment, for measurements off the hot path
 * (Controller.filmSnapshot): live views of its sums, not copies.
 */
export interface FilmSnapshot {
  version: number;
  width: number;
  height: number;
  sums: Float32Array;
  /** The film's exact sums (film/exact-sum.ts); index 4p + 3 holds pixel p's Σ luminance². */
  hi: Float64Array;
  lo: Float64Array;
  spp: number;
  seconds: number;
  camera: CameraDesc;
  bounces: number;
  seed: number;
}
