/**
 * Claims and commits on a shared film, written so that a worker may die at
 * any instruction and lose nothing, count nothing twice.
 *
 * A worker may die anywhere: an uncaught error, `terminate()` (Chromium
 * lets a busy worker run on for up to two seconds and then stops it
 * wherever it is), the browser reclaiming its memory. The pool learns of a
 * death for certain only once the worker's Web Lock is released
 * (src/view/pool.ts); from then on its token counts as dead, and
 * `recoverDead` cleans up after it. Three rules make that possible:
 *
 * 1. Every write that changes who owns what is one Int32 store. A claim is
 *    recorded in the worker's slot before it is taken (the counter bumped or
 *    the reclaim entry cleared), so a death between the two leaves a claim
 *    that recovery can see is still free; a finished pass is recorded before
 *    the slot is cleared, so recovery can see it is done.
 * 2. A row commits pass p only if it holds exactly p passes (the per-row
 *    pass word), so a pass can never land twice, and the re-render of an
 *    orphaned stripe renders only the rows its dead owner had not committed.
 * 3. A commit copies its row into the journal first and then publishes the
 *    row's index; a commit cut short (the lock still held by the dead
 *    worker, the film's row half written) is finished from the journal by
 *    whoever breaks the lock.
 *
 * The claims a dead worker held go to the reclaim list, from which workers
 * take the smallest first, before any new claim. A worker waiting for a
 * stripe's previous pass swaps its own claim for a smaller reclaimed one,
 * so the smallest open claim (whose dependency is always done) is always
 * being rendered or about to be: no wait can last forever as long as one
 * worker lives. Open claims (held or reclaimed) number at most the pool's
 * workers: a new claim is taken only when the reclaim list is empty, that
 * is, when every open claim is held by a live worker, and each holds one.
 *
 * Each step function takes an optional `die(step)` called between its
 * writes: the unit tests throw from it to kill a simulated worker at every
 * point of the protocol. Production passes nothing.
 */
import { AUX_CHANNELS, type Film } from '../../src/core/index.ts';
import {
  C_CLAIM,
  C_COMMITS,
  C_DONE,
  C_GEN,
  C_JOURNAL_PASS,
  C_JOURNAL_ROW,
  C_LOCK,
  C_RECLAIMS,
  C_TARGET,
  MAX_SLOTS,
  RECLAIM_BASE,
  SLOT_BASE,
  SLOT_WORDS,
  rowPassBase,
  rowStampBase,
  stripeOrder,
} from './render-protocol.ts';

/** Test hook: called between the protocol's writes (see the header). */
export type Die = (step: number) => void;

/** Where a job's words are, and the order of its stripes. */
export class ControlLayout {
  readonly stripes: number;
  readonly height: number;
  readonly stripeRows: number;
  readonly stampBase: number;
  readonly passBase: number;
  /** Claim k of a pass renders stripe order[k] (see stripeOrder). */
  readonly order: Int32Array;

  constructor(height: number, stripeRows: number) {
    this.height = height;
    this.stripeRows = stripeRows;
    this.stripes = Math.ceil(height / stripeRows);
    this.stampBase = rowStampBase(this.stripes);
    this.passBase = rowPassBase(this.stripes, height);
    this.order = stripeOrder(this.stripes);
  }

  passOf(claim: number): number {
    return Math.floor(claim / this.stripes);
  }

  stripeOf(claim: number): number {
    return this.order[claim - this.passOf(claim) * this.stripes];
  }
}

/** Sets the words that do not start at zero: no journal entry, no reclaims, empty slots. */
export function initControl(ctrl: Int32Array): void {
  ctrl[C_JOURNAL_ROW] = -1;
  ctrl.fill(-1, RECLAIM_BASE, RECLAIM_BASE + MAX_SLOTS);
  ctrl[C_RECLAIMS] = 0;
  for (let s = 0; s < MAX_SLOTS; s++) {
    ctrl[SLOT_BASE + s * SLOT_WORDS] = 0;
    ctrl[SLOT_BASE + s * SLOT_WORDS + 1] = -1;
  }
}

/**
 * Copies row `fromRow` of `from` over row `toRow` of `to` (rows counted
 * within each film): every plane (the Float32 sums, the exact sums' limbs, and the
 * albedo and normal planes when both films have them).
 */
export function copyFilmRow(to: Film, toRow: number, from: Film, fromRow: number): void {
  const n = to.width * 4;
  const a = fromRow * n;
  const b = toRow * n;
  to.sums.set(from.sums.subarray(a, a + n), b);
  to.hi.set(from.hi.subarray(a, a + n), b);
  to.lo.set(from.lo.subarray(a, a + n), b);
  if (to.auxHi !== null && from.auxHi !== null) {
    const m = to.width * AUX_CHANNELS;
    to.auxHi.set(from.auxHi.subarray(fromRow * m, (fromRow + 1) * m), toRow * m);
    to.auxLo!.set(from.auxLo!.subarray(fromRow * m, (fromRow + 1) * m), toRow * m);
  }
}

function minReclaimIndex(ctrl: Int32Array): number {
  let at = -1;
  for (let i = RECLAIM_BASE; i < RECLAIM_BASE + MAX_SLOTS; i++) {
    const c = ctrl[i];
    if (c >= 0 && (at < 0 || c < ctrl[at])) at = i;
  }
  return at;
}

function reclaimIndexOf(ctrl: Int32Array, claim: number): number {
  for (let i = RECLAIM_BASE; i < RECLAIM_BASE + MAX_SLOTS; i++) if (ctrl[i] === claim) return i;
  return -1;
}

/** Puts `claim` in a free reclaim entry (one store). Returns false when the list is full. */
function pushReclaim(ctrl: Int32Array, claim: number): boolean {
  const at = reclaimIndexOf(ctrl, -1);
  if (at < 0) return false;
  ctrl[at] = claim;
  ctrl[C_RECLAIMS]++;
  return true;
}

function writeSlot(ctrl: Int32Array, slot: number, token: number, claim: number, gen: number) {
  const base = SLOT_BASE + slot * SLOT_WORDS;
  ctrl[base + 2] = gen;
  ctrl[base + 1] = claim;
  // The token last: until it is there, recovery of this worker ignores the record.
  ctrl[base] = token;
}

/** A quick unlocked look: is any claim waiting to be taken over? */
export function hasReclaims(ctrl: Int32Array): boolean {
  return Atomics.load(ctrl, C_RECLAIMS) > 0;
}

/**
 * Under the lock: takes the smallest reclaimed claim, else the next new one
 * below the target; -1 when there is none. Reclaimed claims are taken
 * whatever the target, since later passes of their stripes wait for them.
 */
export function takeClaim(
  ctrl: Int32Array,
  layout: ControlLayout,
  slot: number,
  token: number,
  die?: Die,
): number {
  const gen = ctrl[C_GEN];
  const at = ctrl[C_RECLAIMS] > 0 ? minReclaimIndex(ctrl) : -1;
  let claim: number;
  if (at >= 0) {
    claim = ctrl[at];
  } else {
    claim = ctrl[C_CLAIM];
    // Atomic: the main thread raises the target without the lock, after writing an
    // adaptive film's map (src/view/shared-job.ts advance), which this load makes visible.
    if (claim >= layout.stripes * Atomics.load(ctrl, C_TARGET)) return -1;
  }
  writeSlot(ctrl, slot, token, claim, gen);
  die?.(1);
  if (at >= 0) {
    ctrl[at] = -1;
    die?.(2);
    ctrl[C_RECLAIMS]--;
  } else {
    ctrl[C_CLAIM] = claim + 1;
  }
  return claim;
}

/**
 * Under the lock, for a worker waiting on its claim's previous pass: trades
 * `held` for the smallest reclaimed claim when that is smaller (it is older
 * work that others may be waiting for). Returns the claim now held. The
 * order of the three stores keeps every claim findable at every step: held
 * goes to the list first, then the record moves, then the taken entry is
 * cleared.
 */
export function swapClaim(
  ctrl: Int32Array,
  held: number,
  slot: number,
  token: number,
  die?: Die,
): number {
  const at = minReclaimIndex(ctrl);
  if (at < 0 || ctrl[at] >= held) return held;
  const claim = ctrl[at];
  if (!pushReclaim(ctrl, held)) return held;
  die?.(1);
  writeSlot(ctrl, slot, token, claim, ctrl[C_GEN]);
  die?.(2);
  ctrl[at] = -1;
  ctrl[C_RECLAIMS]--;
  return claim;
}

/**
 * Under the lock: puts `row` (a one-row film: image row y with pass `pass`
 * rendered on top of the film's) into the film if the generation still
 * holds and the row has exactly `pass` passes. Returns whether it did.
 */
export function commitRow(
  ctrl: Int32Array,
  layout: ControlLayout,
  film: Film,
  journal: Film,
  row: Film,
  y: number,
  pass: number,
  gen: number,
  die?: Die,
): boolean {
  const passWord = layout.passBase + y;
  if (ctrl[C_GEN] !== gen || ctrl[passWord] !== pass) return false;
  copyFilmRow(journal, 0, row, 0);
  die?.(1);
  ctrl[C_JOURNAL_PASS] = pass;
  ctrl[C_JOURNAL_ROW] = y;
  die?.(2);
  copyFilmRow(film, y - film.y0, row, 0);
  die?.(3);
  ctrl[passWord] = pass + 1;
  die?.(4);
  ctrl[layout.stampBase + y] = ++ctrl[C_COMMITS];
  die?.(5);
  ctrl[C_JOURNAL_ROW] = -1;
  return true;
}

/** Under the lock: pass `pass` of `stripe` is complete; the slot holds nothing any more. */
export function finishClaim(
  ctrl: Int32Array,
  stripe: number,
  pass: number,
  gen: number,
  slot: number,
  die?: Die,
): void {
  if (ctrl[C_GEN] === gen && ctrl[C_DONE + stripe] <= pass) ctrl[C_DONE + stripe] = pass + 1;
  die?.(1);
  ctrl[SLOT_BASE + slot * SLOT_WORDS + 1] = -1;
}

/** What recoveries did, summed over calls. */
export interface RecoveryReport {
  /** Claims of dead workers put back for the living to render. */
  reclaimed: number;
  /** Of those, stripes whose dead owner had committed some rows of the pass but not all. */
  partial: number;
  /** Rows those owners had committed, kept as they were (not rendered again). */
  rowsKept: number;
  /** Commits cut short (the dead worker held the lock) finished from the journal. */
  journalRepairs: number;
  /** Locks found held by a dead worker and broken. */
  locksBroken: number;
}

export function emptyReport(): RecoveryReport {
  return { reclaimed: 0, partial: 0, rowsKept: 0, journalRepairs: 0, locksBroken: 0 };
}

/**
 * Main thread: takes the lock. A holder known dead can never release it,
 * so its lock is broken (counted in `report`; recoverDead must follow at
 * once, under the same lock). A live holder copies one row at most, but a
 * worker thread may be descheduled on a busy machine, and a holder may
 * have died a moment ago without the pool knowing yet: after `patienceMs`
 * this gives up and returns false rather than freeze the page.
 */
export function lockMain(
  ctrl: Int32Array,
  token: number,
  isDead: (token: number) => boolean,
  patienceMs: number,
  report: RecoveryReport,
): boolean {
  let start = -1;
  for (let spins = 0; ; spins++) {
    const holder = Atomics.compareExchange(ctrl, C_LOCK, 0, token);
    if (holder === 0) return true;
    if (isDead(holder)) {
      if (Atomics.compareExchange(ctrl, C_LOCK, holder, token) === holder) {
        report.locksBroken++;
        return true;
      }
      continue;
    }
    if ((spins & 1023) === 1023) {
      const now = performance.now();
      if (start < 0) start = now;
      else if (now - start > patienceMs) return false;
    }
  }
}

/**
 * Under the lock: cleans up after dead workers. Finishes a commit the
 * journal shows was under way (only a dead holder of the lock can leave
 * one), and puts every claim a dead worker held and had not finished back
 * in the reclaim list. Returns false when the list was full, which the
 * bound in the header rules out; the caller then resets the film.
 */
export function recoverDead(
  ctrl: Int32Array,
  layout: ControlLayout,
  film: Film,
  journal: Film,
  isDead: (token: number) => boolean,
  report: RecoveryReport,
): boolean {
  const y = ctrl[C_JOURNAL_ROW];
  if (y >= 0) {
    const pass = ctrl[C_JOURNAL_PASS];
    const passWord = layout.passBase + y;
    if (ctrl[passWord] === pass) {
      copyFilmRow(film, y - film.y0, journal, 0);
      ctrl[passWord] = pass + 1;
    }
    ctrl[layout.stampBase + y] = ++ctrl[C_COMMITS];
    ctrl[C_JOURNAL_ROW] = -1;
    report.journalRepairs++;
  }
  let ok = true;
  const gen = ctrl[C_GEN];
  for (let s = 0; s < MAX_SLOTS; s++) {
    const base = SLOT_BASE + s * SLOT_WORDS;
    const token = ctrl[base];
    if (token === 0 || !isDead(token)) continue;
    const claim = ctrl[base + 1];
    if (claim >= 0 && ctrl[base + 2] === gen && isOpen(ctrl, layout, claim)) {
      if (pushReclaim(ctrl, claim)) {
        report.reclaimed++;
        const pass = layout.passOf(claim);
        const y0 = layout.stripeOf(claim) * layout.stripeRows;
        const y1 = Math.min(layout.height, y0 + layout.stripeRows);
        let kept = 0;
        for (let r = y0; r < y1; r++) if (ctrl[layout.passBase + r] > pass) kept++;
        report.rowsKept += kept;
        if (kept > 0) report.partial++;
      } else {
        ok = false;
      }
    }
    ctrl[base + 1] = -1;
    ctrl[base] = 0;
  }
  // The count is a hint that a death between an entry and its count can skew.
  let n = 0;
  for (let i = RECLAIM_BASE; i < RECLAIM_BASE + MAX_SLOTS; i++) if (ctrl[i] >= 0) n++;
  ctrl[C_RECLAIMS] = n;
  return ok;
}

/** A claim taken in this generation, in nobody's hands now that its worker is dead, not done. */
function isOpen(ctrl: Int32Array, layout: ControlLayout, claim: number): boolean {
  if (claim >= ctrl[C_CLAIM] || reclaimIndexOf(ctrl, claim) >= 0) return false;
  return ctrl[C_DONE + layout.stripeOf(claim)] <= layout.passOf(claim);
}
