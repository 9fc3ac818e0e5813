/**
 * The shared-memory claim protocol (workers/browser/shared-claims.ts) under worker
 * deaths at every point, simulated in one thread: simulated workers take
 * turns doing one step each (claim, swap, render and commit a row, finish),
 * some die in the middle of a step (inside the lock, between any two of the
 * protocol's writes, through its `die` hook) or between steps, the main
 * thread recovers them some steps later (SharedFilmJob.recover, as the pool
 * does once a death is certain), and replacements join. The film must end
 * bit-identical to an undisturbed render, every time; the counts show that
 * the hard cases (a lock held by the dead, a half-written stripe, a commit
 * cut short) really happened.
 */
import { readFileSync } from 'node:fs';
import { describe, expect, it } from 'vitest';
import {
  Film,
  PathTracer,
  RenderStats,
  compileScene,
  parseScene,
  type CompiledScene,
} from '../../../src/core/index.ts';
import { SharedFilmJob } from '../../../src/view/shared-job.ts';
import { faults, isDead, markDead, newWorkerToken } from '../../../src/view/worker-deaths.ts';
import {
  C_CONFIG,
  C_DONE,
  C_GEN,
  C_LOCK,
  MAX_SLOTS,
} from '../../../workers/browser/render-protocol.ts';
import {
  ControlLayout,
  commitRow,
  copyFilmRow,
  finishClaim,
  hasReclaims,
  swapClaim,
  takeClaim,
} from '../../../workers/browser/shared-claims.ts';
import { differingWords, mulberry32 } from '../../helpers/faults.ts';

const WIDTH = 10;
const HEIGHT = 24;
const STRIPE_ROWS = 3;
const TARGET = 5;
const SEED = 3;

const scene = parseScene(readFileSync('scenes/cornell.json', 'utf8'));
const compiled: CompiledScene = compileScene(scene);

function tracerOf(height: number): PathTracer {
  return new PathTracer(compiled, {
    width: WIDTH,
    height,
    maxBounces: 4,
    seed: SEED,
    camera: scene.camera,
  });
}

class Killed extends Error {}

/** Commits refused because the row already had the pass (a killed worker's late commit). */
let refused = 0;

/** One simulated render worker: the steps of render-worker.ts's shared loop, one per turn. */
class SimWorker {
  readonly token = newWorkerToken();
  claim = -1;
  gen = 0;
  dead = false;
  /** Recovered from while still running (premature). */
  recovered = false;
  /** A row rendered and not yet committed (-1: none). */
  pendingRow = -1;
  private readonly tracer: PathTracer;
  private readonly row = new Film(WIDTH, 1);
  private readonly stats = new RenderStats();
  constructor(
    readonly slot: number,
    private readonly job: SharedFilmJob,
    private readonly layout: ControlLayout,
  ) {
    this.tracer = tracerOf(layout.height);
  }

  private get ctrl(): Int32Array {
    return new Int32Array(this.job.ctrlBuffer);
  }

  /** Its next step would trade its claim for a reclaimed one. */
  wouldSwap(): boolean {
    const ctrl = this.ctrl;
    if (this.claim < 0 || ctrl[C_GEN] !== this.gen || !hasReclaims(ctrl)) return false;
    return ctrl[C_DONE + this.layout.stripeOf(this.claim)] < this.layout.passOf(this.claim);
  }

  private tryLock(): boolean {
    return Atomics.compareExchange(this.ctrl, C_LOCK, 0, this.token) === 0;
  }

  private unlock(): void {
    Atomics.store(this.ctrl, C_LOCK, 0);
  }

  /**
   * One step; `die(step)` throws Killed to kill it inside the step. Returns
   * false when it could do nothing (the lock is busy, nothing to claim, or
   * waiting for a previous pass).
   */
  step(die?: (step: number) => void): boolean {
    const ctrl = this.ctrl;
    const layout = this.layout;
    if (this.claim < 0 || ctrl[C_GEN] !== this.gen) {
      if (!this.tryLock()) return false;
      this.gen = ctrl[C_GEN];
      this.claim = takeClaim(ctrl, layout, this.slot, this.token, die);
      this.unlock();
      return this.claim >= 0;
    }
    const pass = layout.passOf(this.claim);
    const stripe = layout.stripeOf(this.claim);
    if (ctrl[C_DONE + stripe] < pass) {
      if (!hasReclaims(ctrl) || !this.tryLock()) return false;
      const held = this.claim;
      this.claim = swapClaim(ctrl, held, this.slot, this.token, die);
      this.unlock();
      return this.claim !== held;
    }
    const film = this.job.film;
    if (this.pendingRow >= 0) {
      // Commit the row rendered in the previous step (time passed meanwhile).
      if (!this.tryLock()) return false;
      const rowFilm = new Film(WIDTH, 1, this.row.buffer, this.pendingRow);
      const journal = new Film(WIDTH, 1, this.job.journalBuffer);
      this.pendingRow = -1;
      if (!commitRow(ctrl, layout, film, journal, rowFilm, rowFilm.y0, pass, this.gen, die)) {
        refused++;
      }
      this.unlock();
      return true;
    }
    const y0 = stripe * layout.stripeRows;
    const y1 = Math.min(layout.height, y0 + layout.stripeRows);
    let y = y0;
    while (y < y1 && ctrl[layout.passBase + y] !== pass) y++;
    if (y < y1) {
      // Render one row into the private copy; it is committed next step.
      const rowFilm = new Film(WIDTH, 1, this.row.buffer, y);
      copyFilmRow(rowFilm, 0, film, y);
      this.tracer.renderRow(rowFilm, y, pass, pass + 1, this.stats);
      this.pendingRow = y;
      return true;
    }
    if (!this.tryLock()) return false;
    finishClaim(ctrl, stripe, pass, this.gen, this.slot, die);
    this.unlock();
    this.claim = -1;
    return true;
  }
}

interface RunCounts {
  deaths: number;
  deathsHoldingLock: number;
  /** Killed workers that ran on after being terminated (as Chromium lets them for up to 2 s). */
  zombieSteps: number;
  swaps: number;
  steps: number;
}

interface Shape {
  height: number;
  stripeRows: number;
  workers: number;
  /** Chance per step that the stepping worker is killed. */
  killRate: number;
  /** Recovery comes up to this many steps after the death is certain. */
  recoveryDelay: number;
  /**
   * Recovery may come while a killed worker still runs (a grace period too
   * short, as without Web Locks): its slot is not given to another worker
   * until it is really dead, but it may still commit rows of its claim.
   */
  premature?: boolean;
  /** Chance per step that a killed worker still running stops for good (default 0.1). */
  zombieKillRate?: number;
  /** Share of the steps that go to killed workers still running, while there are any (0.5). */
  zombieShare?: number;
}

/**
 * Renders TARGET passes with simulated workers, killing one now and then at
 * a random point of its step. A killed worker is replaced at once, but may
 * run on (a zombie: the rest of its claim, as a terminated worker finishes
 * its current task) before it really dies, maybe inside the lock; the main
 * thread recovers some steps after the real death (or earlier, `premature`).
 */
function runWithDeaths(seed: number, shape: Shape) {
  const random = mulberry32(seed);
  const { height, stripeRows } = shape;
  const layout = new ControlLayout(height, stripeRows);
  const job = new SharedFilmJob(WIDTH, height, stripeRows, TARGET);
  job.setVersion(1);
  job.reset();
  const free = Array.from({ length: MAX_SLOTS }, (_, i) => i).reverse();
  const live: SimWorker[] = [];
  const zombies: SimWorker[] = [];
  /** Workers whose recovery is due at step `at`; `dead`: really dead (else a zombie, premature). */
  const pending: { worker: SimWorker; at: number }[] = [];
  const counts: RunCounts = { deaths: 0, deathsHoldingLock: 0, zombieSteps: 0, swaps: 0, steps: 0 };
  for (let i = 0; i < shape.workers; i++) live.push(new SimWorker(free.pop()!, job, layout));
  const ctrl = () => new Int32Array(job.ctrlBuffer);
  let idle = 0;
  const dieAt = (point: number) => (step: number) => {
    if (step === point) throw new Killed();
  };
  const reallyDies = (w: SimWorker) => {
    w.dead = true;
    counts.deaths++;
    if (Atomics.load(ctrl(), C_LOCK) === w.token) counts.deathsHoldingLock++;
    zombies.splice(zombies.indexOf(w), 1);
    if (!shape.premature || !pending.some((p) => p.worker === w)) {
      pending.push({
        worker: w,
        at: counts.steps + Math.floor(random() * (shape.recoveryDelay + 1)),
      });
    }
  };
  while (job.passesDone() < TARGET) {
    counts.steps++;
    if (counts.steps > 400_000) throw new Error('no progress: the render is stuck');
    // Recover deaths whose time has come (the pool's bury → recover).
    for (let i = pending.length - 1; i >= 0; i--) {
      const { worker, at } = pending[i];
      if (at > counts.steps) continue;
      markDead(worker.token);
      // Another dead worker, not yet known dead, may hold the lock: recover
      // would wait its patience out and say false, and the pool try again
      // shortly. So does this, without the wait (tested once below).
      const holder = Atomics.load(ctrl(), C_LOCK);
      if ((holder !== 0 && !isDead(holder)) || !job.recover()) {
        pending[i].at = counts.steps + 5;
        continue;
      }
      pending.splice(i, 1);
      if (worker.dead) free.push(worker.slot);
      else worker.recovered = true;
    }
    const pickZombie = zombies.length > 0 && random() < (shape.zombieShare ?? 0.5);
    const pool = pickZombie ? zombies : live;
    const w = pool[Math.floor(random() * pool.length)];
    const zombie = zombies.includes(w);
    // Deaths in a swap are rare by chance and matter: made likelier.
    const rate = zombie ? (shape.zombieKillRate ?? 0.1) : w.wouldSwap() ? 0.3 : shape.killRate;
    const kill = random() < rate;
    const point = Math.floor(random() * 7) - 1;
    let died = false;
    let worked = false;
    try {
      if (zombie && w.claim < 0) {
        // A terminated worker stops at its task's end: it takes no new claim.
        died = true;
      } else {
        const before = w.claim;
        worked = w.step(kill ? dieAt(point) : undefined);
        if (zombie) counts.zombieSteps++;
        if (before >= 0 && w.claim >= 0 && w.claim !== before) counts.swaps++;
        if (kill && point < 0) died = true;
      }
    } catch (e) {
      if (!(e instanceof Killed)) throw e;
      died = true;
    }
    idle = worked ? 0 : idle + 1;
    if (died && zombie) {
      reallyDies(w);
    } else if (died || (kill && !zombie)) {
      // Terminated: replaced at once. Really dead now (it was inside a step,
      // or stopped between steps), or a zombie that runs on for a while.
      live.splice(live.indexOf(w), 1);
      zombies.push(w);
      live.push(new SimWorker(free.pop()!, job, layout));
      if (shape.premature && random() < 0.5) {
        pending.push({
          worker: w,
          at: counts.steps + Math.floor(random() * (shape.recoveryDelay + 1)),
        });
      }
      if (died || random() < 0.5) reallyDies(w);
    }
    // Every live worker stuck (e.g. on a dead worker's lock) only until recovery.
    if (idle > 10_000 && pending.length === 0 && zombies.length === 0) {
      throw new Error('live workers are stuck');
    }
  }
  return { job, counts };
}

function differingWordsIn(job: SharedFilmJob, height: number): number {
  return differingWords(job.film, reference(height));
}

const references = new Map<number, Film>();
function reference(height: number): Film {
  let film = references.get(height);
  if (!film) {
    film = new Film(WIDTH, height);
    tracerOf(height).renderRows(film, 0, height, 0, TARGET, new RenderStats());
    references.set(height, film);
  }
  return film;
}

function faultDelta(before: typeof faults) {
  return {
    reclaimed: faults.reclaimed - before.reclaimed,
    partial: faults.partial - before.partial,
    repairs: faults.journalRepairs - before.journalRepairs,
    broken: faults.locksBroken - before.locksBroken,
  };
}

describe('shared claims survive workers dying anywhere', () => {
  it('an undisturbed simulated render equals the sequential render bit for bit', () => {
    const shape = {
      height: HEIGHT,
      stripeRows: STRIPE_ROWS,
      workers: 3,
      killRate: 0,
      recoveryDelay: 0,
    };
    const { job, counts } = runWithDeaths(1, shape);
    expect(counts.deaths).toBe(0);
    expect(differingWordsIn(job, HEIGHT)).toBe(0);
  });

  for (const [name, shape, seeds] of [
    [
      'thin stripes',
      { height: HEIGHT, stripeRows: STRIPE_ROWS, workers: 4, killRate: 0.02, recoveryDelay: 30 },
      40,
    ],
    [
      'few stripes, many waiting workers',
      { height: 16, stripeRows: 8, workers: 5, killRate: 0.03, recoveryDelay: 60 },
      40,
    ],
  ] as [string, Shape, number][]) {
    it(`with deaths at every step of the protocol the film stays bit-identical (${name}, ${seeds} seeds)`, () => {
      const before = { ...faults };
      const total = { deaths: 0, holding: 0, zombieSteps: 0, swaps: 0 };
      for (let seed = 1; seed <= seeds; seed++) {
        const { job, counts } = runWithDeaths(seed, {
          ...shape,
          workers: 1 + (seed % shape.workers),
        });
        expect(differingWordsIn(job, shape.height), `seed ${seed}`).toBe(0);
        expect(job.passesDone()).toBe(TARGET);
        total.deaths += counts.deaths;
        total.holding += counts.deathsHoldingLock;
        total.zombieSteps += counts.zombieSteps;
        total.swaps += counts.swaps;
      }
      const d = faultDelta(before);
      console.log(
        `shared-claims simulation (${name}): ${total.deaths} deaths (${total.holding} holding the lock, ` +
          `${total.zombieSteps} steps run by killed workers before they died), ${d.reclaimed} claims reclaimed ` +
          `(${d.partial} half-written stripes), ${total.swaps} swaps, ${d.repairs} commits finished from the journal, ` +
          `${d.broken} locks broken`,
      );
      // The hard cases must really have been exercised.
      expect(total.deaths).toBeGreaterThan(100);
      expect(total.holding).toBeGreaterThan(10);
      expect(total.zombieSteps).toBeGreaterThan(20);
      expect(d.partial).toBeGreaterThan(5);
      expect(d.repairs).toBeGreaterThan(3);
      expect(d.broken).toBeGreaterThanOrEqual(total.holding);
      if (shape.stripeRows >= 8) expect(total.swaps).toBeGreaterThan(50);
    });
  }

  it('recovery that comes while the killed worker still runs counts no pass twice (40 seeds)', () => {
    const shape: Shape = {
      height: 16,
      stripeRows: 4,
      workers: 3,
      killRate: 0.03,
      recoveryDelay: 10,
      premature: true,
      zombieKillRate: 0.05,
      // Slow: their late commits come after the stripe moved on.
      zombieShare: 0.02,
    };
    let zombieSteps = 0;
    const refusedBefore = refused;
    for (let seed = 1; seed <= 40; seed++) {
      const { job, counts } = runWithDeaths(seed, shape);
      expect(differingWordsIn(job, shape.height), `seed ${seed}`).toBe(0);
      zombieSteps += counts.zombieSteps;
    }
    expect(zombieSteps).toBeGreaterThan(50);
    // Late commits of killed workers really came, and were refused.
    expect(refused - refusedBefore).toBeGreaterThan(10);
  });

  it('the main thread neither hangs on a lock whose holder died unnoticed nor breaks a live one', () => {
    const layout = new ControlLayout(HEIGHT, STRIPE_ROWS);
    const job = new SharedFilmJob(WIDTH, HEIGHT, STRIPE_ROWS, TARGET);
    job.setVersion(1);
    job.reset();
    const w = new SimWorker(0, job, layout);
    // Dies inside a commit, holding the lock; the pool does not know yet.
    w.step();
    w.step();
    expect(() =>
      w.step((step) => {
        if (step === 3) throw new Killed();
      }),
    ).toThrow(Killed);
    const ctrl = new Int32Array(job.ctrlBuffer);
    expect(Atomics.load(ctrl, C_LOCK)).toBe(w.token);
    // Recovery gives up after its patience, leaving the lock alone.
    expect(job.recover()).toBe(false);
    expect(Atomics.load(ctrl, C_LOCK)).toBe(w.token);
    // A reset cannot wait either: the job moves to new buffers.
    job.reset();
    expect(job.takeRenewed()).toBe(true);
    expect(Atomics.load(new Int32Array(job.ctrlBuffer), C_LOCK)).toBe(0);
    // The old block's lock is broken once the death is known, freeing any
    // live worker spinning on it; the old block says it is no longer in use.
    markDead(w.token);
    expect(job.recover()).toBe(true);
    expect(Atomics.load(ctrl, C_LOCK)).toBe(0);
    expect(Atomics.load(ctrl, C_CONFIG)).toBe(-1);
    // And the render on the new buffers is exact.
    const live = [new SimWorker(1, job, layout), new SimWorker(2, job, layout)];
    for (let i = 0; job.passesDone() < TARGET; i++) {
      live[i % 2].step();
      if (i > 100_000) throw new Error('stuck');
    }
    expect(differingWordsIn(job, HEIGHT)).toBe(0);
  });
});
