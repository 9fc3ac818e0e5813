/**
 * Many-light sampling at equal time (issue 23, goal 1): the room lit by N small
 * emitters (bench/scenes.mjs `manyLights`), or any scene file (--scene), rendered in
 * this process on one thread with next-event estimation choosing its lights three
 * ways (`lightSampler`): by the light BVH with splitting (the default, up to
 * LIGHT_SPLIT lights per vertex), by the light BVH one light at a time, and by power
 * alone. Each render adds 1-spp passes until --seconds have passed; its relMSE against
 * the reference (mean over pixels and channels of (x − ref)² / (ref² + 0.01), as
 * bench/denoise-time.ts) is then measured. Rounds rotate which sampler goes first and
 * use fresh seeds; the table gives each round and the median ratios of relMSE,
 * measured in this one run.
 *
 *   node scripts/run-ts.mjs bench/many-lights.ts --reference REF.pfm
 *        [--count 10000 | --scene FILE.json] [--seconds 20] [--rounds 3] [--bounces B]
 *
 * The image size is the reference's. REF.pfm for the hall: bench/results/many-lights/
 * reference.pfm (its README says how it was made and checked against Mitsuba 3). Not a
 * test.
 */
import { readFileSync } from 'node:fs';
import { dirname, resolve } from 'node:path';
import {
  Film,
  PathTracer,
  RenderStats,
  compileScene,
  decodePfm,
  parseScene,
} from '../src/core/index.ts';
import type { LightSamplerKind } from '../src/core/index.ts';
import { nodeSceneFiles } from '../src/cli/scene-files.ts';
import { resolveSceneFiles } from '../src/core/loading.ts';
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
const sceneFile = flag('scene', '');
const refFile = flag('reference', '');
const bouncesFlag = flag('bounces', '');
if (refFile === '') throw new Error('--reference REF.pfm is required');
const ref = decodePfm(readFileSync(refFile));
const { width, height } = ref;

const scene =
  sceneFile === ''
    ? parseScene(JSON.stringify(manyLights(count)))
    : await resolveSceneFiles(
        parseScene(readFileSync(sceneFile, 'utf8')),
        nodeSceneFiles(dirname(resolve(sceneFile))),
      );
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

const SAMPLERS: LightSamplerKind[] = ['split', 'bvh', 'power'];

// Warm-up: every sampler's code path compiled before the clock matters.
for (const s of SAMPLERS) {
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

const median = (v: number[]): number => v.slice().sort((a, b) => a - b)[v.length >> 1]!;
const rows: string[] = [];
const vsPower: number[] = [];
const vsBvh: number[] = [];
for (let round = 0; round < rounds; round++) {
  // Rotate the order, so that no sampler always runs first (or last) in a round.
  const order = SAMPLERS.map((_, k) => SAMPLERS[(k + round) % SAMPLERS.length]!);
  const runs = {} as Record<LightSamplerKind, Run>;
  for (const s of order) runs[s] = render(s, 1000 + round);
  vsPower.push(runs.power.error / runs.split.error);
  vsBvh.push(runs.bvh.error / runs.split.error);
  rows.push(
    `| ${round + 1} | ` +
      SAMPLERS.map((s) => `${runs[s].spp} | ${runs[s].error.toExponential(2)}`).join(' | ') +
      ` | ${vsPower[round]!.toFixed(1)}× | ${vsBvh[round]!.toFixed(1)}× |`,
  );
}
const what = sceneFile === '' ? `${count} emitters` : sceneFile;
process.stdout.write(
  `${what}, ${width}×${height}, ${seconds} s per render, 1 thread; ` +
    `scene compile ${compileMs.toFixed(0)} ms, light BVH build ${buildMs.toFixed(0)} ms ` +
    `(${lightBvh.count} emitters, depth ${lightBvh.depth})\n\n` +
    `| round | split: spp | split: relMSE | BVH: spp | BVH: relMSE | power: spp | power: relMSE | ` +
    `relMSE power / split | relMSE BVH / split |\n` +
    `|---|---|---|---|---|---|---|---|---|\n` +
    rows.join('\n') +
    `\n\nmedian ratios: power / split ${median(vsPower).toFixed(1)}×, ` +
    `BVH / split ${median(vsBvh).toFixed(1)}×\n`,
);
