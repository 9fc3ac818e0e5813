/**
 * The Benchmark button: a fixed 10-second run on the Cornell box with all
 * workers, reporting segments (rays) per second, the samples per pixel
 * reached, the worker count and the browser's core count. The user's
 * scene and settings come back afterwards. It samples uniformly: an adaptive
 * pass past the pilot costs less than a uniform one, so its samples per pixel
 * would not compare with other runs'.
 */
import type { CameraDesc } from '../core/index.ts';
import type { Controller } from '../view/index.ts';
import { PRESETS } from './presets.ts';

export const BENCHMARK_SECONDS = 10;
/** Seconds traced before the measurement starts (scene compilation, JIT). */
export const BENCHMARK_WARMUP_S = 0.5;

export interface BenchmarkResult {
  mraysPerSecond: number;
  spp: number;
  workers: number;
  cores: number;
  width: number;
  height: number;
  seconds: number;
}

const sleep = (ms: number) => new Promise((r) => setTimeout(r, ms));

export async function runBenchmark(
  c: Controller,
  seconds = BENCHMARK_SECONDS,
): Promise<BenchmarkResult> {
  const before = {
    scene: c.scene as unknown,
    camera: c.scene ? c.getCamera() : (null as CameraDesc | null),
    paused: c.paused,
    target: c.stats().target,
    adaptive: c.adaptive,
  };
  c.setAdaptive(false);
  await c.setScene(PRESETS.cornell);
  // No target: the run must not stop early by converging.
  c.setTargetSpp(1 << 20);
  c.resume();
  // A short warm-up lets the workers compile the scene and the JIT settle.
  await sleep(BENCHMARK_WARMUP_S * 1000);
  const s0 = c.segmentsTraced();
  const t0 = performance.now();
  await sleep(seconds * 1000);
  const s1 = c.segmentsTraced();
  const t1 = performance.now();
  const stats = c.stats();
  const result: BenchmarkResult = {
    mraysPerSecond: (s1 - s0) / ((t1 - t0) / 1000) / 1e6,
    spp: stats.spp,
    workers: stats.workers,
    cores: navigator.hardwareConcurrency || 0,
    width: stats.width,
    height: stats.height,
    seconds: (t1 - t0) / 1000,
  };
  c.setTargetSpp(before.target);
  c.setAdaptive(before.adaptive);
  if (before.scene) {
    await c.setScene(before.scene);
    if (before.camera) c.setCamera(before.camera);
  }
  if (before.paused) c.pause();
  return result;
}
