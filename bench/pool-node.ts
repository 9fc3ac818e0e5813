/**
 * Thread scaling of the browser's worker pool, run in Node: the page's own
 * WorkerPool (src/view/pool.ts) and render worker (workers/browser/render-worker.ts)
 * with a film job of either mode, shared (SharedFilmJob: workers claim
 * stripe passes from the control block) or transfer (TransferFilmJob: the
 * main thread hands out passes and merges rows). Only the Worker object is
 * an adapter around worker_threads (pool-node-shim.ts): the scheduling,
 * locking and copying code is the browser's.
 *
 * For each worker count: time from creating the pool (worker start-up
 * included) to the target spp done, and the paths per second; the film is
 * checked to be bit-identical across counts.
 *
 *   node scripts/run-ts.mjs bench/pool-node.ts [--scene FILE] [--size 512] [--spp 16]
 *     [--threads 1,2,4,8,16] [--mode shared|transfer] [--worker BUNDLE] [--out FILE]
 * (--worker: a prebuilt bundle of bench/pool-node-worker.ts; built with
 * esbuild when left out.)
 */
import { createHash } from 'node:crypto';
import { existsSync, mkdirSync, mkdtempSync, readFileSync, writeFileSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import os from 'node:os';
import path from 'node:path';
import { compileScene, packScene, parseScene, DEFAULT_SAMPLER } from '../src/core/index.ts';
import { WorkerPool, type PoolClient } from '../src/view/pool.ts';
import type { FilmJob } from '../src/view/film-job.ts';
import { SharedFilmJob } from '../src/view/shared-job.ts';
import { TransferFilmJob } from '../src/view/transfer-job.ts';
import { chooseStripeRows, type JobConfig } from '../workers/browser/render-protocol.ts';
import { NodeWebWorker } from './node-web-worker.ts';

const opt: Record<string, string> = {};
for (let i = 2; i < process.argv.length; i += 2)
  opt[process.argv[i].slice(2)] = process.argv[i + 1];
const sceneFile = opt.scene ?? 'scenes/cornell.json';
const size = Number(opt.size ?? 512);
const spp = Number(opt.spp ?? 16);
const mode = (opt.mode ?? 'shared') as 'shared' | 'transfer';
const counts = (opt.threads ?? `1,2,4,8,${os.availableParallelism()}`).split(',').map(Number);

async function workerBundle(): Promise<string> {
  if (opt.worker) return path.resolve(opt.worker);
  const prebuilt = fileURLToPath(new URL('./pool-node-worker.mjs', import.meta.url));
  if (import.meta.url.endsWith('.mjs') && existsSync(prebuilt)) return prebuilt;
  const { build } = await import('esbuild');
  const out = path.join(mkdtempSync(path.join(os.tmpdir(), 'pathwise-pool-')), 'worker.mjs');
  await build({
    entryPoints: [path.resolve('bench/pool-node-worker.ts')],
    outfile: out,
    bundle: true,
    platform: 'node',
    format: 'esm',
    target: 'node20',
    logLevel: 'warning',
  });
  return out;
}

const scene = parseScene(readFileSync(sceneFile, 'utf8'));
const packed = packScene(compileScene(scene), mode === 'shared');
const file = await workerBundle();

async function run(threads: number): Promise<{ seconds: number; hash: string }> {
  const stripeRows = chooseStripeRows(size, threads);
  const job: FilmJob =
    mode === 'shared'
      ? new SharedFilmJob(size, size, stripeRows, spp)
      : new TransferFilmJob(size, size, stripeRows, spp);
  const config: JobConfig = {
    mode,
    version: 1,
    sceneId: 1,
    scene: packed,
    width: size,
    height: size,
    maxBounces: scene.settings.maxBounces,
    seed: 1,
    estimator: 'nee-mis',
    sampler: DEFAULT_SAMPLER,
    camera: scene.camera,
    stripeRows,
    aux: false,
    film: job instanceof SharedFilmJob ? job.filmBuffer : undefined,
    ctrl: job instanceof SharedFilmJob ? job.ctrlBuffer : undefined,
    journal: job instanceof SharedFilmJob ? job.journalBuffer : undefined,
  };
  job.setVersion(1);
  job.setTarget(spp);
  job.reset();
  let failure: string | null = null;
  const client: PoolClient = {
    id: 1,
    config: () => config,
    nextTask: () => job.nextTask?.(1) ?? null,
    onResult: (r) => job.onResult?.(r),
    onWorkerError: (m) => (failure = m),
    onTaskLost: (t) => job.onTaskLost?.(t),
    recover: () => job.recover?.() ?? true,
  };
  const t0 = performance.now();
  const pool = new WorkerPool(
    { workerFactory: () => new NodeWebWorker(file) as unknown as Worker },
    threads,
  );
  pool.register(client);
  pool.kick();
  while (job.passesDone() < spp && failure === null) {
    await new Promise((r) => setTimeout(r, 2));
  }
  const seconds = (performance.now() - t0) / 1000;
  pool.terminate();
  if (failure) throw new Error(`render worker: ${failure}`);
  const hash = createHash('sha256')
    .update(new Uint8Array(job.film.buffer as ArrayBuffer))
    .digest('hex')
    .slice(0, 16);
  return { seconds, hash };
}

await run(Math.min(2, Math.max(...counts))); // warm-up: file cache, CPU clocks
const points: {
  threads: number;
  seconds: number;
  mpaths_per_s: number;
  efficiency?: number;
  film_sha256: string;
}[] = [];
for (const threads of counts) {
  const { seconds, hash } = await run(threads);
  points.push({
    threads,
    seconds,
    mpaths_per_s: (size * size * spp) / seconds / 1e6,
    film_sha256: hash,
  });
  process.stderr.write(`pool (${mode}), ${threads} workers: ${seconds.toFixed(3)} s\n`);
}
const base = points.find((p) => p.threads === 1);
for (const p of points) if (base) p.efficiency = base.seconds / p.seconds / p.threads;
const identical = points.every((p) => p.film_sha256 === points[0].film_sha256);
const report = {
  schema: 'pathwise-bench-pool-node/1',
  command: `node scripts/run-ts.mjs bench/pool-node.ts ${process.argv.slice(2).join(' ')}`.trim(),
  date: new Date().toISOString(),
  cpu: os.cpus()[0]?.model,
  cores: os.availableParallelism(),
  node: process.version,
  node_options: process.execArgv,
  config: { scene: sceneFile, size, spp, mode },
  films_bit_identical: identical,
  points,
};
if (opt.out) {
  mkdirSync(path.dirname(path.resolve(opt.out)), { recursive: true });
  writeFileSync(opt.out, JSON.stringify(report, null, 2) + '\n');
}
process.stdout.write(JSON.stringify(report) + '\n');
process.exit(identical ? 0 : 1);
