/**
 * Web Worker of the browser pool. Control calls (configure, kick, stop)
 * arrive through comlink; pixels never do.
 *
 * Shared mode: the worker claims (pass, stripe) pairs from the job's
 * control block, renders each row of the stripe into a private one-row
 * copy of the film and commits the row under the lock only if the
 * generation is unchanged — so a reset drops stale work at row granularity
 * and no stale sample lands. Pass k+1 of a stripe waits until pass k of it
 * is done, so every pixel receives samples 0, 1, 2, … in order and the
 * image is bit-identical to the command line's.
 *
 * Transfer mode (no SharedArrayBuffer): the main thread sends one pass of
 * one stripe with its rows of the film; the worker adds the pass and sends
 * the rows back.
 *
 * Several controllers may share the pool, so a worker holds one job per
 * controller and serves them in turn.
 */
import * as Comlink from 'comlink';
import { Film, PathTracer, RenderStats, unpackScene } from '../src/core/index.ts';
import type { CompiledScene } from '../src/core/index.ts';
import {
  C_CLAIM,
  C_COMMITS,
  C_CONFIG,
  C_DONE,
  C_GEN,
  C_PAUSED,
  C_REJECTED,
  C_SEGMENTS,
  C_TARGET,
  lock,
  rowStampBase,
  stripeOrder,
  unlock,
  type JobConfig,
  type RenderWorkerApi,
  type StripeResult,
  type StripeTask,
} from './render-protocol.ts';

interface Job {
  config: JobConfig;
  compiled: CompiledScene;
  tracer: PathTracer;
  film?: Film;
  ctrl?: Int32Array;
  /** One-row film the rows are rendered into before they are committed. */
  row?: Film;
  /** Claim k of a pass renders stripe order[k] (see stripeOrder). */
  order?: Int32Array;
}

const jobs = new Map<number, Job>();
const stats = new RenderStats();
let running = false;
let stopping = false;
let stopped: (() => void) | undefined;

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
    tracer = new PathTracer(compiled, {
      width: config.width,
      height: config.height,
      maxBounces: config.maxBounces,
      seed: config.seed,
      estimator: config.estimator,
      sampler: config.sampler,
      camera: config.camera,
    });
  }
  const job: Job = { config: { ...config, scene: undefined }, compiled, tracer };
  if (config.mode === 'shared') {
    job.film =
      old?.config.film === config.film && old?.film
        ? old.film
        : new Film(config.width, config.height, config.film!);
    job.ctrl =
      old?.config.ctrl === config.ctrl && old?.ctrl ? old.ctrl : new Int32Array(config.ctrl!);
    job.row = old?.row && old.row.width === config.width ? old.row : new Film(config.width, 1);
    const stripes = Math.ceil(config.height / config.stripeRows);
    job.order = old?.order?.length === stripes ? old.order : stripeOrder(stripes);
  }
  jobs.set(id, job);
  kick();
}

/** Yields to the event loop (so control calls get through) without setTimeout's clamping. */
const yieldChannel = new MessageChannel();
const yieldWaiters: (() => void)[] = [];
yieldChannel.port1.onmessage = () => yieldWaiters.shift()?.();
function yieldToEvents(): Promise<void> {
  return new Promise((resolve) => {
    yieldWaiters.push(resolve);
    yieldChannel.port2.postMessage(0);
  });
}

function kick(): void {
  if (running || stopping) return;
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
  } finally {
    running = false;
    if (stopping) stopped?.();
  }
}

/** Claims and renders one pass of one stripe. Returns false when there was nothing to claim. */
function renderOneStripe(job: Job): boolean {
  const ctrl = job.ctrl!;
  const { width, height, stripeRows, version } = job.config;
  const stripes = Math.ceil(height / stripeRows);
  lock(ctrl);
  if (
    ctrl[C_CONFIG] !== version ||
    ctrl[C_PAUSED] !== 0 ||
    ctrl[C_CLAIM] >= stripes * ctrl[C_TARGET]
  ) {
    unlock(ctrl);
    return false;
  }
  const claim = ctrl[C_CLAIM]++;
  const gen = ctrl[C_GEN];
  unlock(ctrl);
  const pass = Math.floor(claim / stripes);
  const stripe = job.order![claim - pass * stripes];

  // Pass `pass` of this stripe may start only once pass − 1 is committed.
  // Claims are taken in order, so the worker holding that pass is already
  // rendering it; the wait is short and rare when stripes outnumber workers.
  for (;;) {
    const done = Atomics.load(ctrl, C_DONE + stripe);
    if (done === pass) break;
    if (Atomics.load(ctrl, C_GEN) !== gen) return true;
    Atomics.wait(ctrl, C_DONE + stripe, done, 2);
  }

  const film = job.film!;
  const row = job.row!;
  const y0 = stripe * stripeRows;
  const y1 = Math.min(height, y0 + stripeRows);
  const n = width * 4;
  const stamps = rowStampBase(stripes);
  for (let y = y0; y < y1; y++) {
    if (Atomics.load(ctrl, C_GEN) !== gen) return true;
    const rowFilm = new Film(width, 1, row.buffer, y);
    rowFilm.sums.set(film.sums.subarray(y * n, y * n + n));
    rowFilm.extra.set(film.extra.subarray(y * n, y * n + n));
    const segments = stats.segments;
    const rejected = stats.rejected;
    job.tracer.renderRow(rowFilm, y, pass, pass + 1, stats);
    lock(ctrl);
    if (ctrl[C_GEN] === gen) {
      film.sums.set(rowFilm.sums, y * n);
      film.extra.set(rowFilm.extra, y * n);
      ctrl[stamps + y] = ++ctrl[C_COMMITS];
    }
    ctrl[C_SEGMENTS] = (ctrl[C_SEGMENTS] + (stats.segments - segments)) | 0;
    ctrl[C_REJECTED] += stats.rejected - rejected;
    unlock(ctrl);
  }
  lock(ctrl);
  if (ctrl[C_GEN] === gen) ctrl[C_DONE + stripe]++;
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
    const film = new Film(job.config.width, task.rows, task.buffer, task.y0);
    job.tracer.renderRows(film, task.y0, task.y0 + task.rows, task.pass, task.pass + 1, stats);
    rendered = true;
  }
  const result: StripeResult = {
    ...task,
    type: 'result',
    segments: stats.segments - segments,
    rejected: stats.rejected - rejected,
    rendered,
  };
  port.postMessage(result, [task.buffer]);
}

const api: RenderWorkerApi = {
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
      if (e.data.type === 'task') renderTask(e.data, port);
    };
  },
};

Comlink.expose(api);
