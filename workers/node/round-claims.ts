/**
 * The command line's rounds (src/cli/render.ts) with worker threads that
 * may die anywhere — an uncaught error, running out of memory, a kill —
 * and the render going on bit-identical.
 *
 * A round adds samples [s0, s1) to every stripe. The film's sums are exact
 * (core/film/exact-sum.ts), so which thread renders a stripe, and when,
 * changes no bit; what must never happen is a stripe counted twice or half.
 * So a stripe is never rendered in place: the worker copies its rows into
 * its own journal (a shared buffer per worker slot), renders the round's
 * samples on top there, writes the stripe's counters, publishes the
 * journal (one store: the stripe's index in the slot's word), copies the
 * rows back into the film and marks the stripe done (one store). Each
 * step is recoverable once the thread is gone (Node's `exit` event says so
 * for certain): a stripe claimed and not published is freed and rendered
 * again from the film's untouched rows; a published one is finished from
 * the journal, whatever part of the copy back had happened.
 *
 * Claims are single compare-and-swaps on the stripe's state word (free →
 * the claiming slot + 1), so a stripe's owner is always known. A stripe's
 * counters (paths, segments, rejected samples) are the same whichever
 * thread renders it, so the round's counters are summed from the stripes,
 * and a render with deaths reports what an undisturbed one does.
 */
import { Film } from '../../src/core/film/film.ts';
import type { PathTracer } from '../../src/core/integrator/path-tracer.ts';
import { RenderStats } from '../../src/core/integrator/render-stats.ts';

/** Stripe state: free, or claimed by slot k (k + 1), or done this round. */
export const STRIPE_FREE = 0;
export const STRIPE_DONE = -1;

/** Test hook: called between the steps (see the header); throwing from it kills the thread there. */
export type Die = (step: number) => void;

/** What the main thread and every worker share for the rounds. */
export interface RoundMemory {
  /** [0]: next stripe to try (a hint; reset per round). */
  counter: Int32Array;
  /** Per stripe: STRIPE_FREE, slot + 1, or STRIPE_DONE. */
  state: Int32Array;
  /** Per stripe: paths, segments, rejected samples of its latest render. */
  stripeStats: Float64Array;
  /** Per slot: the stripe whose journal is published (-1: none). */
  published: Int32Array;
}

export function roundMemory(stripes: number, slots: number): RoundMemory {
  const memory: RoundMemory = {
    counter: new Int32Array(new SharedArrayBuffer(4)),
    state: new Int32Array(new SharedArrayBuffer(4 * stripes)),
    stripeStats: new Float64Array(new SharedArrayBuffer(24 * stripes)),
    published: new Int32Array(new SharedArrayBuffer(4 * slots)),
  };
  memory.published.fill(-1);
  return memory;
}

/** The buffers of a RoundMemory, to send to a worker. */
export function roundBuffers(m: RoundMemory): SharedArrayBuffer[] {
  return [m.counter, m.state, m.stripeStats, m.published].map((a) => a.buffer as SharedArrayBuffer);
}

export function roundMemoryFrom([
  counter,
  state,
  stats,
  published,
]: SharedArrayBuffer[]): RoundMemory {
  return {
    counter: new Int32Array(counter),
    state: new Int32Array(state),
    stripeStats: new Float64Array(stats),
    published: new Int32Array(published),
  };
}

/** Main thread, before a round: every stripe free. */
export function startRound(m: RoundMemory): void {
  Atomics.store(m.counter, 0, 0);
  for (let s = 0; s < m.state.length; s++) Atomics.store(m.state, s, STRIPE_FREE);
}

/** Takes a free stripe for `slot`: first from the counter, then any freed by a death; -1 when none. */
export function claimStripe(m: RoundMemory, slot: number): number {
  const stripes = m.state.length;
  for (;;) {
    const s = Atomics.add(m.counter, 0, 1);
    if (s >= stripes) break;
    if (Atomics.compareExchange(m.state, s, STRIPE_FREE, slot + 1) === STRIPE_FREE) return s;
  }
  for (let s = 0; s < stripes; s++) {
    if (Atomics.compareExchange(m.state, s, STRIPE_FREE, slot + 1) === STRIPE_FREE) return s;
  }
  return -1;
}

/** Rows [y0, y1) of stripe `s`. */
export function stripeRows(s: number, stripeRowCount: number, height: number): [number, number] {
  const y0 = s * stripeRowCount;
  return [y0, Math.min(height, y0 + stripeRowCount)];
}

/**
 * Adds samples [s0, s1) to stripe `s` (claimed by `slot`) through the
 * slot's journal, as the header says. `stats` receives the stripe's counters.
 */
export function renderStripeRound(
  m: RoundMemory,
  slot: number,
  tracer: PathTracer,
  film: Film,
  journalBuffer: SharedArrayBuffer,
  stripeRowCount: number,
  s: number,
  s0: number,
  s1: number,
  stats: RenderStats,
  die?: Die,
): void {
  const [y0, y1] = stripeRows(s, stripeRowCount, film.rows);
  const journal = new Film(film.width, y1 - y0, journalBuffer, y0, 0, film.auxHi !== null);
  journal.copyRowsFrom(film);
  const paths = stats.paths;
  const segments = stats.segments;
  const rejected = stats.rejected;
  tracer.renderRows(journal, y0, y1, s0, s1, stats);
  m.stripeStats[3 * s] = stats.paths - paths;
  m.stripeStats[3 * s + 1] = stats.segments - segments;
  m.stripeStats[3 * s + 2] = stats.rejected - rejected;
  die?.(1);
  Atomics.store(m.published, slot, s);
  die?.(2);
  film.copyRowsFrom(journal);
  die?.(3);
  Atomics.store(m.state, s, STRIPE_DONE);
  die?.(4);
  Atomics.store(m.published, slot, -1);
}

/** What recovering from dead workers did, summed over calls. */
export interface RoundRecovery {
  /** Stripes a dead worker had claimed and not published: rendered again by the others. */
  freed: number;
  /** Stripes a dead worker had published: finished from its journal. */
  finished: number;
}

/**
 * Main thread, once the worker of `slot` is certainly gone: finishes its
 * published stripe from the journal and frees any stripe it still claims.
 */
export function recoverSlot(
  m: RoundMemory,
  slot: number,
  film: Film,
  journalBuffer: SharedArrayBuffer,
  stripeRowCount: number,
  report: RoundRecovery,
): void {
  const s = Atomics.load(m.published, slot);
  if (s >= 0 && Atomics.load(m.state, s) === slot + 1) {
    const [y0, y1] = stripeRows(s, stripeRowCount, film.rows);
    film.copyRowsFrom(new Film(film.width, y1 - y0, journalBuffer, y0, 0, film.auxHi !== null));
    Atomics.store(m.state, s, STRIPE_DONE);
    report.finished++;
  }
  Atomics.store(m.published, slot, -1);
  for (let i = 0; i < m.state.length; i++) {
    if (Atomics.compareExchange(m.state, i, slot + 1, STRIPE_FREE) === slot + 1) report.freed++;
  }
}

/** Stripes done this round. */
export function stripesDone(m: RoundMemory): number {
  let n = 0;
  for (let s = 0; s < m.state.length; s++) if (Atomics.load(m.state, s) === STRIPE_DONE) n++;
  return n;
}

/** Adds the round's counters (every stripe's) to `stats`. */
export function addRoundStats(m: RoundMemory, stats: RenderStats): void {
  for (let s = 0; s < m.state.length; s++) {
    stats.paths += m.stripeStats[3 * s];
    stats.segments += m.stripeStats[3 * s + 1];
    stats.rejected += m.stripeStats[3 * s + 2];
  }
}
