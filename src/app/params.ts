/**
 * URL parameters of the demo: the first scene, fixed sizes and seeds for
 * tests and benchmarks, and switches that force the fallback paths, e.g.
 * `?scene=spheres`, `?width=64&height=64&seed=1&spp=8`, `?shared=off`,
 * `?display=canvas2d` (or `webgl2`, even on a software renderer), `?workers=2`,
 * `?bench=2` (a 2-second benchmark), `?scale=1&dpr=3` (a fixed render scale;
 * devicePixelRatio counted up to 3 instead of 2), `?denoise=1` (the Denoise switch on),
 * `?restdraw=0` (draw every frame while the view rests; bench/browser-demo.mjs compares),
 * `?adaptive=0` (every pixel in every pass; adaptive sampling is on by default).
 */
import type { PathTracerOptions } from '../view/index.ts';
import { PRESETS, type PresetName } from './presets.ts';

export interface DemoParams {
  preset: PresetName;
  options: PathTracerOptions;
  /** A `scene` parameter that names no preset (the Cornell box is shown instead). */
  unknownScene: string | null;
  /** Length of the benchmark in seconds (`bench`; default BENCHMARK_SECONDS). */
  benchmarkSeconds: number | undefined;
}

function positiveInt(value: string | null): number | undefined {
  if (value === null) return undefined;
  const n = Number(value);
  return Number.isInteger(n) && n > 0 ? n : undefined;
}

function nonNegativeInt(value: string | null): number | undefined {
  if (value === null) return undefined;
  const n = Number(value);
  return Number.isInteger(n) && n >= 0 ? n : undefined;
}

function displayParam(value: string | null): PathTracerOptions['display'] {
  return value === 'canvas2d' || value === 'webgl2' ? value : 'auto';
}

export function readParams(search: string): DemoParams {
  const q = new URLSearchParams(search);
  const name = q.get('scene') ?? 'cornell';
  const known = Object.hasOwn(PRESETS, name);
  const preset: PresetName = known ? (name as PresetName) : 'cornell';
  const scale = Number(q.get('scale'));
  const dpr = Number(q.get('dpr'));
  const options: PathTracerOptions = {
    width: positiveInt(q.get('width')),
    height: positiveInt(q.get('height')),
    seed: nonNegativeInt(q.get('seed')),
    spp: positiveInt(q.get('spp')),
    bounces: nonNegativeInt(q.get('bounces')),
    workers: positiveInt(q.get('workers')),
    renderScale: scale > 0 ? scale : undefined,
    maxPixelRatio: dpr > 0 ? dpr : undefined,
    display: displayParam(q.get('display')),
    shared: q.get('shared') === 'off' ? 'off' : 'auto',
    denoise: q.get('denoise') === '1',
    adaptive: q.get('adaptive') !== '0',
    restDrawMs: nonNegativeInt(q.get('restdraw')),
  };
  return {
    preset,
    options,
    unknownScene: known ? null : name,
    benchmarkSeconds: positiveInt(q.get('bench')),
  };
}
