/**
 * What the browser's main thread and its render workers share: the layout
 * of the control block that sits in shared memory next to each film, the
 * spin lock that guards it, and the messages of the control channel.
 *
 * One control block (an Int32Array on a SharedArrayBuffer) belongs to one
 * film. The main thread changes it only under the lock; workers read it
 * under the lock when they claim work and when they commit a finished row,
 * so a reset (clear the film, bump the generation) can never interleave
 * with a commit, and no sample of an old generation lands in a new image.
 */
import type { CameraDesc, PackedScene, RenderSettings } from '../../src/core/index.ts';

/** Word indices of the control block. */
export const C_LOCK = 0;
/** Bumped by every reset: a row rendered under another generation is dropped. */
export const C_GEN = 1;
/** Bumped when the job's configuration changes; a worker renders only under the version it holds. */
export const C_CONFIG = 2;
/** Next new claim: claim c is pass ⌊c / stripes⌋ of stripe order[c mod stripes]. */
export const C_CLAIM = 3;
/**
 * Target passes: the caller's, or at most the pilot's while an adaptive film's map is
 * not built (src/view/pilot-gate.ts). Past the pilot a pixel holds at most that many samples.
 */
export const C_TARGET = 4;
export const C_PAUSED = 5;
/** Rows committed so far (any generation); also the stamp of the latest row change. */
export const C_COMMITS = 6;
/** Segments traced, modulo 2^32 (read as a difference). */
export const C_SEGMENTS = 7;
export const C_REJECTED = 8;
/** Entries in the reclaim list (a hint for a quick look; the entries themselves are the truth). */
export const C_RECLAIMS = 9;
/**
 * The commit journal (see shared-claims.ts): the row whose commit is under
 * way (-1: none) and the pass that commit adds. The row's new samples sit
 * in the job's journal buffer meanwhile, so a commit cut short by a dying
 * worker can be finished by whoever breaks its lock.
 */
export const C_JOURNAL_ROW = 10;
export const C_JOURNAL_PASS = 11;
/**
 * Test hook (shared mode): when > 0, the next worker to take a claim throws
 * after committing that many rows (see render-worker.ts). Armed in shared
 * memory rather than by message, so it lands whichever worker runs next: a
 * message to one worker can miss when that worker is descheduled while the
 * others finish the render.
 */
export const C_CRASH = 12;
/**
 * Test hook (shared mode), for the same reason: when > 0, the next worker
 * to take a claim freezes for good at that step of its next row commit,
 * holding the lock, and writes −(its token) here so that the test knows
 * whom to terminate.
 */
export const C_HANG = 13;

/**
 * Workers a control block keeps records for: one slot per live worker of
 * the pool (at most 64) plus the dead ones not yet recovered.
 */
export const MAX_SLOTS = 128;
/**
 * The reclaim list: MAX_SLOTS words, each an open claim that no live worker
 * holds (its worker died) or -1. Open claims number at most the pool's
 * workers (shared-claims.ts says why), so the list cannot overflow.
 */
export const RECLAIM_BASE = 16;
/** Per slot: the token of the worker using it, the claim it holds (-1: none), and its generation. */
export const SLOT_BASE = RECLAIM_BASE + MAX_SLOTS;
export const SLOT_WORDS = 3;
/** First of `stripes` words: passes finished per stripe in the current generation. */
export const C_DONE = SLOT_BASE + MAX_SLOTS * SLOT_WORDS;

/** The main thread's lock token; a worker's is its own, ≥ 2, never reused on the page. */
export const MAIN_TOKEN = 1;

/**
 * After the stripe words, one word per image row: the C_COMMITS value of
 * the row's latest change, so the display uploads only rows that changed.
 */
export function rowStampBase(stripes: number): number {
  return C_DONE + stripes;
}

/**
 * After the stamps, one word per row: passes committed to the row in the
 * current generation. A commit adds pass p only to a row that has exactly
 * p, so no pass can count twice, whoever commits it and however often.
 */
export function rowPassBase(stripes: number, height: number): number {
  return rowStampBase(stripes) + height;
}

export function controlWords(stripes: number, height: number): number {
  return rowPassBase(stripes, height) + height;
}

/**
 * Spin lock holding the owner's token, so that a lock left held by a dead
 * worker can be recognised and broken (shared-claims.ts). Held only for a
 * claim or a row copy (microseconds), so the main thread, which may not
 * block with Atomics.wait, can afford to spin.
 */
export function lock(ctrl: Int32Array, token: number): void {
  while (Atomics.compareExchange(ctrl, C_LOCK, 0, token) !== 0) {
    // Busy wait: the holder is copying one row at most.
  }
}

export function unlock(ctrl: Int32Array): void {
  Atomics.store(ctrl, C_LOCK, 0);
}

/**
 * Rows per stripe: enough stripes for load balance (~16 per worker, as the
 * command line does), but no fewer than 4 rows, so a stripe's claim and
 * dependency check stay cheap next to its rendering.
 */
export function chooseStripeRows(height: number, workers: number): number {
  return Math.max(1, Math.min(4, height), Math.floor(height / (Math.max(1, workers) * 16)));
}

/**
 * The order in which every pass visits its stripes: claim k of a pass takes
 * stripe order[k]. Bit-reversed (the van der Corput sequence in base 2,
 * skipping indices past the end), so the first claims of a pass lie evenly
 * spread over the frame and each later claim halves the gaps: the pass
 * fills the image coarse to fine instead of top to bottom. Only which rows
 * a claim covers changes; every pixel still receives samples 0, 1, 2, … in
 * order (pass k + 1 of a stripe waits for pass k), so the sums stay
 * bit-identical to the command line's.
 */
export function stripeOrder(stripes: number): Int32Array {
  const order = new Int32Array(stripes);
  let bits = 0;
  while (1 << bits < stripes) bits++;
  let n = 0;
  for (let i = 0; n < stripes; i++) {
    let r = 0;
    for (let b = 0; b < bits; b++) r |= ((i >> b) & 1) << (bits - 1 - b);
    if (r < stripes) order[n++] = r;
  }
  return order;
}

export type JobMode = 'shared' | 'transfer';

/** Everything a worker needs to render one controller's image. */
export interface JobConfig extends RenderSettings {
  mode: JobMode;
  /** Equals the control block's C_CONFIG word (shared) or tags tasks (transfer). */
  version: number;
  /**
   * The scene, compiled once on the main thread and packed (a
   * SharedArrayBuffer when the page is isolated, else a buffer copied to
   * each worker). It travels only when `sceneId` changed since this worker
   * last saw the job.
   */
  sceneId: number;
  scene?: PackedScene;
  camera: CameraDesc;
  stripeRows: number;
  /**
   * The film carries first-hit albedo and normal planes (integrator/aux.ts), for the
   * denoiser: every film the worker makes for this job (shared film, row, journal,
   * transferred windows) has them.
   */
  aux: boolean;
  /** Shared mode: the film's buffer and its control block. */
  film?: SharedArrayBuffer;
  ctrl?: SharedArrayBuffer;
  /** Shared mode: one row of film, where a commit puts its row first (see C_JOURNAL_ROW). */
  journal?: SharedArrayBuffer;
  /**
   * Shared mode, an adaptive film (`adaptive`): the per-pixel rates, width·height bytes,
   * which the main thread fills before any pass past the pilot may be claimed
   * (src/view/pilot-gate.ts). Transfer mode ships each stripe's rows with its task.
   */
  map?: SharedArrayBuffer;
}

/** What a worker learns from the pool before anything else. */
export interface WorkerSetup {
  /** Its record in every control block (shared mode). */
  slot: number;
  /** Its lock token (≥ 2, unique on the page). */
  token: number;
  /**
   * Name of a Web Lock (navigator.locks) the worker holds for its whole
   * life; the pool asks for it too and is granted it once the worker is
   * really gone, however it died. Null where the page has no Web Locks.
   */
  lifeLock: string | null;
}

/** Transfer mode: one pass of one stripe, its rows of the film shipped both ways. */
export interface StripeTask {
  type: 'task';
  job: number;
  version: number;
  gen: number;
  stripe: number;
  pass: number;
  y0: number;
  rows: number;
  /** Film window (every plane of rows [y0, y0+rows)); transferred. */
  buffer: ArrayBuffer;
  /** An adaptive film past its pilot: the rates of rows [y0, y0+rows) (src/view/pilot-gate.ts). */
  map?: Uint8Array;
}

export interface StripeResult extends Omit<StripeTask, 'type'> {
  type: 'result';
  segments: number;
  rejected: number;
  /** False when the worker no longer had the job's configuration: nothing was added. */
  rendered: boolean;
}

/** The comlink API a render worker exposes. */
export interface RenderWorkerApi {
  /**
   * Answers once the worker holds its life lock (true; false without Web
   * Locks): from then on its death is noticed however it happens.
   */
  init(setup: WorkerSetup): Promise<boolean>;
  configure(job: number, config: JobConfig): void;
  removeJob(job: number): void;
  /** Shared mode: look for work now (after a reset, resume or new target). */
  kick(): void;
  /** Finishes the stripe in hand and stops; the worker can then be terminated safely. */
  stop(): Promise<void>;
  /** Transfer mode: the port that carries StripeTask/StripeResult messages. */
  setTaskPort(port: MessagePort): void;
  /**
   * Test hook (the pool's crashWorker): throw an uncaught error in the
   * middle of the next stripe, after `rows` of its rows are committed (in
   * transfer mode: instead of answering the next task).
   */
  crash(rows: number): void;
  /**
   * Test hook (the pool's hangWorker): stop dead, for good, at point `step`
   * of the next row commit (shared-claims.ts commitRow), holding the lock,
   * as a worker frozen by the system would; the test then terminates it,
   * which Chromium completes two seconds later, wherever it stands.
   */
  hang(step: number): void;
}
