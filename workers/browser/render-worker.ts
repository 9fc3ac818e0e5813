/**
 * Web Worker of the browser pool. Control calls (configure, kick, stop)
 * arrive through comlink; pixels never do.
 *
 * Shared mode: the worker claims (pass, stripe) pairs from the job's
 * control block, renders each row of the stripe into a private one-row
 * copy of the film and commits the row under the lock only if the
 * generation is unchanged — so a reset drops stale work at row granularity
 * and no stale sample lands. Pass k+1 of a stripe waits until pass k of it
 * is done, so two commits of a row never overwrite each other's samples;
 * the film's sums are exact, so the image is bit-identical to the command
 * line's. Claims and commits follow shared-claims.ts, so that the worker
 * may die anywhere: the pool then hands what it held to the others, and
 * nothing counts twice.
 *
 * Transfer mode (no SharedArrayBuffer): the main thread sends one pass of
 * one stripe with its rows of the film (and, past an adaptive film's pilot,
 * its rows of the sample map); the worker adds the pass and sends the rows
 * back.
 *
 * Several controllers may share the pool, so a worker holds one job per
 * controller and serves them in turn.
 */
import * as Comlink from 'comlink';
import {
  type CompiledScene,
  Film,
  PathTracer,
  RenderStats,
  unpackScene,
} from '../../src/core/index.ts';
import {
  C_CONFIG,
  C_CRASH,
  C_HANG,
  C_DONE,
  C_GEN,
  C_PAUSED,
  C_REJECTED,
  C_SEGMENTS,
  lock,
  unlock,
  type JobConfig,
  type RenderWorkerApi,
  type StripeResult,
  type StripeTask,
  type WorkerSetup,
} from './render-protocol.ts';
import {
  ControlLayout,
  commitRow,
  copyFilmRow,
  finishClaim,
  hasReclaims,
  swapClaim,
  takeClaim,
  type Die,
} from './shared-claims.ts';

interface Job {
  config: JobConfig;
  compiled: CompiledScene;
  tracer: PathTracer;
  film?: Film;
  ctrl?: Int32Array;
  /** One-row film the rows are rendered into before they are committed. */
  row?: Film;
  /** The job's commit journal (one row, shared). */
  journal?: Film;
  layout?: ControlLayout;
  /** Transfer mode, an adaptive film: the rates of the rows tasks brought (whole image). */
  map?: Uint8Array;
}

const jobs = new Map<number, Job>();
const stats = new RenderStats();
let running = false;
let stopping = false;
let stopped: (() => void) | undefined;
/** Slot and lock token, from the pool's init. */
let setup: WorkerSetup = { slot: 0, token: 2, lifeLock: null };
/** Test hook (crash): rows still to commit before throwing; 0 when no crash is asked for. */
let crashAfterRows = 0;
/** An uncaught error happened: the pool is replacing this worker, which renders nothing more. */
let broken = false;
/** Test hook (hang): commitRow's `die`, which spins for ever at the chosen step. */
let hangAt: Die | undefined;

function armHang(step: number): void {
  hangAt = (at) => {
    if (at !== step) return;
    for (;;) {
      // Frozen inside the commit, holding the lock, until terminated.
    }
  };
}
/** init has answered: shared-mode claims wait for it, so that a death is always noticed. */
let initialised = false;

/** Throws `error` out of the current task, so that the pool sees an `error` event. */
function die(error: unknown): void {
  broken = true;
  setTimeout(() => {
    throw error;
  });
}

/**
 * Rebuilds only what the new configuration changes: the scene arrives
 * compiled and packed (unpacked here into views, once per scene), the
 * tracer per size/seed.
 */
function configure(id: number, config: JobConfig): void {
  const old = jobs.get(id);
  let compiled: CompiledScene;
  if (config.scene) {
    compiled = unpackScene(config.scene);
  } else if (old && old.config.sceneId === config.sceneId) {
    compiled = old.compiled;
  } else {
    throw new Error(`job ${id}: configuration without its scene`);
  }
  const c = old?.config;
  let tracer: PathTracer;
  if (
    old &&
    old.compiled === compiled &&
    c!.width === config.width &&
    c!.height === config.height &&
    c!.seed === config.seed &&
    c!.estimator === config.estimator &&
    c!.sampler === config.sampler
  ) {
    tracer = old.tracer;
    tracer.maxBounces = config.maxBounces;
    tracer.setCamera(config.camera);
  } else {
    tracer = new PathTracer(compiled, config);
  }
  const job: Job = { config: { ...config, scene: undefined }, compiled, tracer };
  // An adaptive film: passes past the pilot follow the map (shared mode: the main thread's,
  // filled before any such pass is claimed; transfer mode: filled from the tasks).
  if (config.adaptive === true) {
    job.map =
      config.mode === 'shared'
        ? new Uint8Array(config.map!)
        : old?.map?.length === config.width * config.height
          ? old.map
          : new Uint8Array(config.width * config.height);
  }
  tracer.sampleMap = job.map ?? null;
  if (config.mode === 'shared') {
    const aux = config.aux;
    job.film =
      old?.config.film === config.film && old?.film
        ? old.film
        : new Film(config.width, config.height, config.film!, 0, 0, aux);
    job.ctrl =
      old?.config.ctrl === config.ctrl && old?.ctrl ? old.ctrl : new Int32Array(config.ctrl!);
    job.row =
      old?.row && old.row.width === config.width && (old.row.auxHi !== null) === aux
        ? old.row
        : new Film(config.width, 1, undefined, 0, 0, aux);
    job.journal =
      old?.config.journal === config.journal && old?.journal
        ? old.journal
        : new Film(config.width, 1, config.journal!, 0, 0, aux);
    job.layout =
      old?.layout &&
      old.layout.height === config.height &&
      old.layout.stripeRows === config.stripeRows
        ? old.layout
        : new ControlLayout(config.height, config.stripeRows);
  }
  jobs.set(id, job);
  kick();
}

/**
 * Yields to the event loop (so control calls get through) without
 * setTimeout's clamping. Every YIELD_TIMER_EVERY-th yield is a timer: an
 * event loop that serves a port's own messages before other ports' (Node's
 * worker_threads, behind the benchmarks' shim) would otherwise never
 * deliver the pool's calls while there is work.
 */
const yieldChannel = new MessageChannel();
const yieldWaiters: (() => void)[] = [];
yieldChannel.port1.onmessage = () => yieldWaiters.shift()?.();
const YIELD_TIMER_EVERY = 16;
let yields = 0;
function yieldToEvents(): Promise<void> {
  return new Promise((resolve) => {
    if (++yields % YIELD_TIMER_EVERY === 0) {
      setTimeout(resolve, 0);
      return;
    }
    yieldWaiters.push(resolve);
    yieldChannel.port2.postMessage(0);
  });
}

function kick(): void {
  if (running || stopping || broken || !initialised) return;
  running = true;
  void loop();
}

async function loop(): Promise<void> {
  try {
    for (;;) {
      let worked = false;
      for (const job of jobs.values()) {
        if (job.config.mode === 'shared' && renderOneStripe(job)) worked = true;
        if (stopping) break;
      }
      if (stopping || !worked) break;
      await yieldToEvents();
    }
  } catch (e) {
    // Whatever it held stays recorded in its slot: the pool replaces this
    // worker and hands its claim to the others.
    die(e);
  } finally {
    running = false;
    if (stopping) stopped?.();
  }
}

/** Claims and renders one pass of one stripe. Returns false when there was nothing to claim. */
function renderOneStripe(job: Job): boolean {
  const ctrl = job.ctrl!;
  const layout = job.layout!;
  const { width, version } = job.config;
  const { slot, token } = setup;
  lock(ctrl, token);
  if (ctrl[C_CONFIG] !== version || ctrl[C_PAUSED] !== 0) {
    unlock(ctrl);
    return false;
  }
  let claim = takeClaim(ctrl, layout, slot, token);
  const gen = ctrl[C_GEN];
  unlock(ctrl);
  if (claim < 0) return false;
  // Test hook: a crash armed in shared memory falls to whoever claims next.
  const armed = Atomics.exchange(ctrl, C_CRASH, 0);
  if (armed > 0) crashAfterRows = armed;
  const hangStep = Atomics.load(ctrl, C_HANG);
  if (hangStep > 0 && Atomics.compareExchange(ctrl, C_HANG, hangStep, -token) === hangStep) {
    armHang(hangStep);
  }

  // Pass `pass` of this stripe may start only once pass − 1 is committed.
  // Claims are taken in order, so the worker holding that pass is already
  // rendering it; the wait is short and rare when stripes outnumber workers.
  // If that worker died, its claim is in the reclaim list: take it over.
  let pass: number;
  let stripe: number;
  for (;;) {
    pass = layout.passOf(claim);
    stripe = layout.stripeOf(claim);
    const done = Atomics.load(ctrl, C_DONE + stripe);
    if (done >= pass) break;
    if (Atomics.load(ctrl, C_GEN) !== gen) return true;
    if (hasReclaims(ctrl)) {
      lock(ctrl, token);
      const held = claim;
      if (ctrl[C_GEN] === gen) claim = swapClaim(ctrl, claim, slot, token);
      unlock(ctrl);
      if (claim !== held) continue;
    }
    Atomics.wait(ctrl, C_DONE + stripe, done, 2);
  }

  const film = job.film!;
  const journal = job.journal!;
  const row = job.row!;
  const y0 = stripe * layout.stripeRows;
  const y1 = Math.min(layout.height, y0 + layout.stripeRows);
  for (let y = y0; y < y1; y++) {
    if (Atomics.load(ctrl, C_GEN) !== gen) return true;
    // Committed already by a worker that held this claim and died.
    if (Atomics.load(ctrl, layout.passBase + y) !== pass) continue;
    const rowFilm = new Film(width, 1, row.buffer, y, 0, row.auxHi !== null);
    copyFilmRow(rowFilm, 0, film, y);
    const segments = stats.segments;
    const rejected = stats.rejected;
    job.tracer.renderRows(rowFilm, y, y + 1, pass, pass + 1, stats);
    lock(ctrl, token);
    commitRow(ctrl, layout, film, journal, rowFilm, y, pass, gen, hangAt);
    ctrl[C_SEGMENTS] = (ctrl[C_SEGMENTS] + (stats.segments - segments)) | 0;
    ctrl[C_REJECTED] += stats.rejected - rejected;
    unlock(ctrl);
    if (crashAfterRows > 0 && --crashAfterRows === 0) {
      throw new Error('render worker crashed (test hook)');
    }
  }
  lock(ctrl, token);
  finishClaim(ctrl, stripe, pass, gen, slot);
  unlock(ctrl);
  Atomics.notify(ctrl, C_DONE + stripe);
  return true;
}

/** Transfer mode: adds one pass to the shipped rows and ships them back. */
function renderTask(task: StripeTask, port: MessagePort): void {
  const job = jobs.get(task.job);
  const segments = stats.segments;
  const rejected = stats.rejected;
  let rendered = false;
  if (job && job.config.version === task.version) {
    if (task.map) job.map!.set(task.map, task.y0 * job.config.width);
    const film = new Film(job.config.width, task.rows, task.buffer, task.y0, 0, job.config.aux);
    job.tracer.renderRows(film, task.y0, task.y0 + task.rows, task.pass, task.pass + 1, stats);
    rendered = true;
  }
  const result: StripeResult = {
    ...task,
    // The map rows came for the render; they need not travel back.
    map: undefined,
    type: 'result',
    segments: stats.segments - segments,
    rejected: stats.rejected - rejected,
    rendered,
  };
  port.postMessage(result, [task.buffer]);
}

const api: RenderWorkerApi = {
  async init(given: WorkerSetup): Promise<boolean> {
    setup = given;
    const locks = typeof navigator !== 'undefined' ? navigator.locks : undefined;
    let held = false;
    if (given.lifeLock && locks) {
      // Held until the worker is gone: the pool's request for the same lock
      // is granted then, whether it was terminated, crashed or killed.
      held = await new Promise<boolean>((resolve) => {
        locks
          .request(given.lifeLock!, () => {
            resolve(true);
            return new Promise<never>(() => {});
          })
          .catch(() => resolve(false));
      });
    }
    initialised = true;
    kick();
    return held;
  },
  configure,
  removeJob(id: number) {
    jobs.delete(id);
  },
  kick,
  stop() {
    stopping = true;
    if (!running) return Promise.resolve();
    return new Promise<void>((resolve) => (stopped = resolve));
  },
  setTaskPort(port: MessagePort) {
    port.onmessage = (e: MessageEvent<StripeTask>) => {
      if (e.data.type !== 'task' || broken) return;
      if (crashAfterRows > 0) {
        crashAfterRows = 0;
        die(new Error('render worker crashed (test hook)'));
        return;
      }
      renderTask(e.data, port);
    };
  },
  crash(rows: number) {
    crashAfterRows = Math.max(1, Math.floor(rows));
  },
  hang(step: number) {
    armHang(step);
  },
};

Comlink.expose(api);
