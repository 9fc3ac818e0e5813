/**
 * Many-light sampling at equal time (issue 23, goal 1): the room lit by N small
 * emitters (bench/scenes.mjs `manyLights`), rendered in this process on one thread
 * with next-event estimation choosing its light by the light BVH
 * (src/core/lights/light-bvh.ts) and, as before it, by power alone (`lightSampler:
 * 'power'`). Each render adds 1-spp passes until --seconds have passed; its relMSE
 * against the reference (mean over pixels and channels of (x − ref)² / (ref² + 0.01),
 * as bench/denoise-time.ts) is then measured. Rounds alternate which sampler goes
 * first and use fresh seeds; the table gives each round and the median ratio of
 * relMSE (power / BVH), measured in this one run.
 *
 *   npm run build:cli   (not needed: this runs the TypeScript core directly)
 *   node scripts/run-ts.mjs bench/many-lights.ts --reference REF.pfm
 *        [--count 10000] [--seconds 20] [--rounds 3] [--width 128] [--height 96] [--bounces B]
 *
 * REF.pfm: the scene rendered long; bench/results/many-lights/reference.pfm (its README
 * says how it was made and checked against Mitsuba 3). Not a test.
 */
import { readFileSync } from 'node:fs';
import {
  Film,
  PathTracer,
  RenderStats,
  compileScene,
  decodePfm,
  parseScene,
} from '../src/core/index.ts';
import type { LightSamplerKind } from '../src/core/index.ts';
import { manyLights } from './scenes.mjs';
import { relMse } from './lib.mjs';

const args = process.argv.slice(2);
const flag = (name: string, dflt: string): string => {
  const i = args.indexOf(`--${name}`);
  return i >= 0 ? args[i + 1]! : dflt;
};
const count = Number(flag('count', '10000'));
const seconds = Number(flag('seconds', '20'));
const rounds = Number(flag('rounds', '3'));
const width = Number(flag('width', '128'));
const height = Number(flag('height', '96'));
const refFile = flag('reference', '');
const bouncesFlag = flag('bounces', '');
if (refFile === '') throw new Error('--reference REF.pfm is required');
const ref = decodePfm(readFileSync(refFile));
if (ref.width !== width || ref.height !== height) {
  throw new Error(`reference is ${ref.width}×${ref.height}, not ${width}×${height}`);
}

const scene = parseScene(JSON.stringify(manyLights(count)));
if (bouncesFlag !== '') scene.settings.maxBounces = Number(bouncesFlag);
const t0 = performance.now();
const compiled = compileScene(scene);
const compileMs = performance.now() - t0;
const t1 = performance.now();
const lightBvh = compiled.lightBvh();
const buildMs = performance.now() - t1;
if (lightBvh === null) throw new Error('the scene has no light BVH');

interface Run {
  sampler: LightSamplerKind;
  spp: number;
  seconds: number;
  error: number;
}

function render(sampler: LightSamplerKind, seed: number): Run {
  const start = performance.now();
  const tracer = new PathTracer(compiled, {
    width,
    height,
    maxBounces: scene.settings.maxBounces,
    seed,
    camera: scene.camera,
    lightSampler: sampler,
  });
  const film = new Film(width, height);
  const stats = new RenderStats();
  let spp = 0;
  while (performance.now() - start < seconds * 1000) {
    tracer.renderRows(film, 0, height, spp, spp + 1, stats);
    spp++;
  }
  const elapsed = (performance.now() - start) / 1000;
  film.resolve();
  return { sampler, spp, seconds: elapsed, error: relMse(film.mean(), ref.rgb) };
}

// Warm-up: both samplers' code paths compiled before the clock matters.
for (const s of ['bvh', 'power'] as const) {
  const tracer = new PathTracer(compiled, {
    width: 16,
    height: 12,
    maxBounces: scene.settings.maxBounces,
    seed: 1,
    camera: scene.camera,
    lightSampler: s,
  });
  const film = new Film(16, 12);
  for (let k = 0; k < 8; k++) tracer.renderRows(film, 0, 12, k, k + 1, new RenderStats());
}

const rows: string[] = [];
const ratios: number[] = [];
for (let round = 0; round < rounds; round++) {
  const order: LightSamplerKind[] = round % 2 === 0 ? ['power', 'bvh'] : ['bvh', 'power'];
  const runs = {} as Record<LightSamplerKind, Run>;
  for (const s of order) runs[s] = render(s, 1000 + round);
  const ratio = runs.power.error / runs.bvh.error;
  ratios.push(ratio);
  rows.push(
    `| ${round + 1} | ${runs.power.spp} | ${runs.power.error.toExponential(2)} | ` +
      `${runs.bvh.spp} | ${runs.bvh.error.toExponential(2)} | ${ratio.toFixed(1)}× |`,
  );
}
ratios.sort((a, b) => a - b);
process.stdout.write(
  `${count} emitters, ${width}×${height}, ${seconds} s per render, 1 thread; ` +
    `scene compile ${compileMs.toFixed(0)} ms, light BVH build ${buildMs.toFixed(0)} ms ` +
    `(${lightBvh.count} emitters, depth ${lightBvh.depth})\n\n` +
    `| round | power: spp | power: relMSE | BVH: spp | BVH: relMSE | relMSE power / BVH |\n` +
    `|---|---|---|---|---|---|\n` +
    rows.join('\n') +
    `\n\nmedian ratio ${ratios[Math.floor(ratios.length / 2)]!.toFixed(1)}×\n`,
);
