/**
 * The browser's worker pool and render worker, run in Node on real threads
 * (worker_threads behind the benchmark's Web Worker shim, as
 * bench/pool-node.ts does), with workers killed for real: Node's
 * `terminate()` stops a thread at once, wherever it is — in the middle of a
 * row, holding the lock, between the journal and the film copy. Node has no
 * Web Locks, so the pool waits its grace period before recovering (the
 * path a browser without them takes). The film must end bit-identical to
 * an undisturbed render, in shared memory and in transfer mode.
 */
import { readFileSync } from 'node:fs';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import {
  ADAPTIVE_PILOT,
  DEFAULT_SAMPLER,
  Film,
  PathTracer,
  RenderStats,
  compileScene,
  packScene,
  parseScene,
} from '../../../src/core/index.ts';
import type { FilmJob } from '../../../src/view/film-job.ts';
import { WorkerPool, type PoolClient } from '../../../src/view/pool.ts';
import { SharedFilmJob } from '../../../src/view/shared-job.ts';
import { TransferFilmJob } from '../../../src/view/transfer-job.ts';
import { faults } from '../../../src/view/worker-deaths.ts';
import {
  C_CRASH,
  C_HANG,
  C_LOCK,
  type JobConfig,
} from '../../../workers/browser/render-protocol.ts';
import { bundleWorker } from '../../helpers/bundle-worker.ts';
import { renderAdaptiveFilm } from '../../helpers/render.ts';
import { differingWords, mulberry32 } from '../../helpers/faults.ts';
import { NodeWebWorker } from '../../../bench/node-web-worker.ts';

const WIDTH = 32;
const HEIGHT = 96;
const STRIPE_ROWS = 3;
const SPP_UNIFORM = 12;
const SEED = 5;

const scene = parseScene(readFileSync('scenes/cornell.json', 'utf8'));
let workerFile = '';
let dispose = (): void => {};

beforeAll(async () => {
  ({ file: workerFile, dispose } = await bundleWorker('bench/pool-node-worker.ts', 'pool-faults'));
});

afterAll(() => dispose());

/** Passes of the adaptive renders: past the 16-pass pilot, so faults land on both sides. */
const ADAPTIVE_SPP = 24;

function reference(aux: boolean, adaptive = false, spp = SPP_UNIFORM): Film {
  const film = new Film(WIDTH, HEIGHT, undefined, 0, 0, aux);
  const tracer = new PathTracer(compileScene(scene), {
    width: WIDTH,
    height: HEIGHT,
    maxBounces: scene.settings.maxBounces,
    seed: SEED,
    camera: scene.camera,
  });
  if (adaptive) return renderAdaptiveFilm(tracer, film, ADAPTIVE_SPP);
  tracer.renderRows(film, 0, HEIGHT, 0, spp, new RenderStats());
  return film;
}

const sleepFor = (ms: number) => new Promise((r) => setTimeout(r, ms));

/**
 * Renders with `threads` workers, doing `faults` at seeded random points of
 * the render: 'kill' terminates a worker, 'crash' makes one throw in its
 * next stripe (or task), 'hang' freezes one inside a row commit and then
 * terminates it. `adaptive`: ADAPTIVE_SPP passes, adaptively; the waits here open the
 * pilot gate as the page's frame loop does.
 */
async function renderWithFaults(
  mode: 'shared' | 'transfer',
  kinds: ('kill' | 'crash' | 'hang')[],
  seed: number,
  aux = false,
  adaptive = false,
): Promise<{ film: Film; errors: string[] }> {
  const random = mulberry32(seed);
  const SPP = adaptive ? ADAPTIVE_SPP : SPP_UNIFORM;
  const job: FilmJob =
    mode === 'shared'
      ? new SharedFilmJob(WIDTH, HEIGHT, STRIPE_ROWS, SPP, aux, adaptive)
      : new TransferFilmJob(WIDTH, HEIGHT, STRIPE_ROWS, SPP, aux, adaptive);
  const shared = job instanceof SharedFilmJob ? job : null;
  const config = (): JobConfig => ({
    mode,
    version: 1,
    sceneId: 1,
    scene: packScene(compileScene(scene), mode === 'shared'),
    width: WIDTH,
    height: HEIGHT,
    maxBounces: scene.settings.maxBounces,
    seed: SEED,
    estimator: 'nee-mis',
    sampler: DEFAULT_SAMPLER,
    camera: scene.camera,
    stripeRows: STRIPE_ROWS,
    aux,
    adaptive,
    map: shared?.mapBuffer ?? undefined,
    film: shared?.filmBuffer,
    ctrl: shared?.ctrlBuffer,
    journal: shared?.journalBuffer,
  });
  const current = config();
  job.setVersion(1);
  job.setTarget(SPP);
  job.reset();
  const errors: string[] = [];
  const client: PoolClient = {
    id: 1,
    config: () => current,
    nextTask: () => job.nextTask?.(1) ?? null,
    onResult: (r) => job.onResult?.(r),
    onWorkerError: (m) => errors.push(m),
    onTaskLost: (t) => job.onTaskLost?.(t),
    recover: () => job.recover?.() ?? true,
  };
  const pool = new WorkerPool(
    { workerFactory: () => new NodeWebWorker(workerFile) as unknown as Worker },
    2,
  );
  // Each wait first lets an adaptive render past its pilot once every stripe holds it.
  const sleep = (ms: number) => {
    if (job.advance()) pool.kick();
    return sleepFor(ms);
  };
  pool.register(client);
  // The render is held two passes past the next fault's point (never past
  // SPP), so that a fast machine cannot finish before every fault has landed;
  // raising the target keeps the samples. Workers start at the first hold.
  let target = 0;
  // While a fault waits for its worker to reach a stripe or a commit, the
  // hold moves on a pass at a time if the render has caught up with it.
  const extend = () => {
    if (job.passesDone() >= target && target < SPP) {
      target++;
      job.setTarget(target);
      pool.kick();
    }
  };
  try {
    for (let i = 0; i < kinds.length; i++) {
      // An adaptive render's last fault lands past the pilot gate, whatever the draws.
      const at =
        adaptive && i === kinds.length - 1
          ? ADAPTIVE_PILOT + 1 + 2 * random()
          : ((i + 0.5 + 0.5 * random()) / (kinds.length + 1)) * SPP;
      target = Math.max(target, Math.min(SPP, Math.ceil(at) + 2));
      job.setTarget(target);
      pool.kick();
      while (job.progress() < at) await sleep(1 + 3 * random());
      const index = Math.floor(random() * 4);
      const kind = kinds[i];
      if (kind === 'kill') {
        while (!pool.killWorker(index)) await sleep(2);
      } else if (kind === 'crash') {
        const crashed = faults.crashed;
        if (shared) {
          // Armed in shared memory: whichever worker claims next crashes one
          // row into that stripe. (A message to one worker could miss: on a
          // loaded machine the other can finish the render while it sleeps.)
          Atomics.store(new Int32Array(shared.ctrlBuffer), C_CRASH, 1);
        } else {
          while (!pool.crashWorker(index, 1)) await sleep(2);
        }
        // It crashes in its next stripe (or task): wait for it.
        while (faults.crashed === crashed && job.passesDone() < SPP) {
          extend();
          await sleep(2);
        }
      } else {
        // Armed in shared memory too: whichever worker claims next freezes
        // at that step of its next row commit and leaves −(its token) in
        // C_HANG, then holds the lock for good (a live holder keeps it for
        // microseconds).
        const ctrl = new Int32Array(shared!.ctrlBuffer);
        Atomics.store(ctrl, C_HANG, 1 + Math.floor(random() * 5));
        const until = Date.now() + 30_000;
        let token = 0;
        while (Date.now() < until) {
          token = -Atomics.load(ctrl, C_HANG);
          if (token > 0 && Atomics.load(ctrl, C_LOCK) === token) break;
          extend();
          await sleep(2);
        }
        expect(token).toBeGreaterThan(0);
        expect(Atomics.load(ctrl, C_LOCK)).toBe(token);
        Atomics.store(ctrl, C_HANG, 0);
        pool.killWorker(0, token);
      }
    }
    job.setTarget(SPP);
    pool.kick();
    const deadline = Date.now() + 90_000;
    while ((job.passesDone() < SPP || job.busy()) && errors.length === 0) {
      if (Date.now() > deadline) throw new Error(`stuck at ${job.progress()} passes`);
      await sleep(5);
    }
  } finally {
    pool.terminate();
  }
  return { film: job.film, errors };
}

describe('the browser pool with workers killed on real threads (Node)', () => {
  const expected = reference(false);
  // The shared test's film carries the denoiser's albedo and normal planes: a commit's
  // journal and every repair must move them with the radiance.
  const expectedAux = reference(true);

  it('shared memory (with albedo and normal planes): kills, crashes and frozen lock holders, the film stays bit-identical', async () => {
    const before = { ...faults };
    const { film, errors } = await renderWithFaults(
      'shared',
      ['kill', 'hang', 'crash', 'kill', 'kill', 'hang', 'crash', 'kill'],
      3,
      true,
    );
    expect(film.auxHi).not.toBeNull();
    expect(errors).toEqual([]);
    expect(differingWords(film, expectedAux)).toBe(0);
    const d = {
      killed: faults.killed - before.killed,
      crashed: faults.crashed - before.crashed,
      reclaimed: faults.reclaimed - before.reclaimed,
      locksBroken: faults.locksBroken - before.locksBroken,
      journalRepairs: faults.journalRepairs - before.journalRepairs,
      partial: faults.partial - before.partial,
    };
    console.log(`browser pool in Node, shared: ${JSON.stringify(d)}`);
    expect(d.killed).toBe(6);
    expect(d.crashed).toBe(2);
    // Node stops a thread at once. A crash comes one row into a stripe, so
    // each crash leaves a half-written stripe behind; a kill leaves one only
    // if it lands while the worker holds a claim (most do: 6-8 of 8 here).
    expect(d.reclaimed).toBeGreaterThanOrEqual(d.crashed);
    expect(d.partial).toBeGreaterThanOrEqual(d.crashed);
    // The two frozen ones died holding the lock, inside a commit; a kill
    // that lands during a commit breaks one more (seen in 1 of 3 idle runs).
    expect(d.locksBroken).toBeGreaterThanOrEqual(2);
  });

  it('transfer mode: kills and crashes, the film stays bit-identical', async () => {
    const before = { ...faults };
    const { film, errors } = await renderWithFaults(
      'transfer',
      ['kill', 'crash', 'kill', 'crash', 'kill'],
      4,
    );
    expect(errors).toEqual([]);
    expect(differingWords(film, expected)).toBe(0);
    expect(faults.tasksResent - before.tasksResent).toBeGreaterThanOrEqual(2);
  });

  const expectedAdaptive = reference(false, true);
  it('adaptive sampling, faults before and after the pilot gate: bit-identical to the adaptive render (shared memory and transfer mode)', async () => {
    // The map is not all ones: the adaptive film is not the uniform one of as many passes.
    expect(differingWords(expectedAdaptive, reference(false, false, ADAPTIVE_SPP))).toBeGreaterThan(
      0,
    );
    const shared = await renderWithFaults(
      'shared',
      ['kill', 'crash', 'kill', 'hang'],
      7,
      false,
      true,
    );
    expect(shared.errors).toEqual([]);
    expect(differingWords(shared.film, expectedAdaptive)).toBe(0);
    const transfer = await renderWithFaults('transfer', ['kill', 'crash', 'kill'], 8, false, true);
    expect(transfer.errors).toEqual([]);
    expect(differingWords(transfer.film, expectedAdaptive)).toBe(0);
  });

  it('transfer mode with albedo and normal planes: the windows carry them, bit-identical', async () => {
    const { film, errors } = await renderWithFaults('transfer', ['kill'], 6, true);
    expect(errors).toEqual([]);
    expect(film.auxHi).not.toBeNull();
    expect(differingWords(film, expectedAux)).toBe(0);
  });
});
