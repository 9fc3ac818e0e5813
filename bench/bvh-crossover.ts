/**
 * Measures where a BVH starts to beat the plain loop over shapes: renders
 * random-sphere scenes of growing size both ways (single thread, same
 * seed) and reports M segments/s, each configuration in its own process so
 * one cannot warm (or pollute the type feedback of) another. The crossover
 * sets BVH_THRESHOLD in src/core/scene/compile/compile.ts.
 * Run: node scripts/run-ts.mjs bench/bvh-crossover.ts
 */
import { execFileSync } from 'node:child_process';
import { mkdirSync, writeFileSync } from 'node:fs';
import { readFileSync } from 'node:fs';
import {
  Film,
  PathTracer,
  RenderStats,
  compileScene,
  parseScene,
  type Scene,
} from '../src/core/index.ts';
import { randomSpheresScene } from '../src/core/scene/load/random-spheres.ts';

const counts = [1, 2, 4, 8, 12, 16, 24, 32, 48, 64, 128];
const size = 80;
const spp = 4;
const reps = 5;
let sink = 0;

function measure(count: number, bvh?: boolean): number {
  const scene: Scene =
    count === 0
      ? parseScene(readFileSync('scenes/cornell.json', 'utf8'))
      : randomSpheresScene(count);
  const tracer = new PathTracer(compileScene(scene, { bvh }), {
    width: size,
    height: size,
    maxBounces: 4,
    seed: 1,
    camera: scene.camera,
  });
  const rates: number[] = [];
  for (let r = 0; r < reps + 1; r++) {
    const film = new Film(size, size);
    const stats = new RenderStats();
    const t0 = performance.now();
    tracer.renderRows(film, 0, size, 0, spp, stats);
    const sec = (performance.now() - t0) / 1000;
    sink += film.sums[0];
    if (r > 0) rates.push(stats.segments / sec / 1e6); // r = 0 is the warm-up
  }
  rates.sort((a, b) => a - b);
  return rates[rates.length >> 1];
}

const [mode, countArg] = process.argv.slice(2);
if (mode === 'list' || mode === 'bvh' || mode === 'auto') {
  // Child: one measurement, printed as JSON (count 0 = the Cornell box).
  const bvh = mode === 'auto' ? undefined : mode === 'bvh';
  process.stdout.write(
    JSON.stringify({ rate: measure(Number(countArg), bvh), sink: sink > 0 }) + '\n',
  );
} else {
  const rows: { shapes: number; list: number; bvh: number }[] = [];
  const run = (m: string, count: number): number =>
    JSON.parse(
      execFileSync(
        process.execPath,
        ['scripts/run-ts.mjs', 'bench/bvh-crossover.ts', m, String(count)],
        {
          encoding: 'utf8',
        },
      ),
    ).rate;
  for (const count of counts) {
    const list = run('list', count);
    const bvh = run('bvh', count);
    rows.push({ shapes: count + 2, list, bvh });
    console.log(
      `${String(count + 2).padStart(4)} shapes  list ${list.toFixed(2)}  bvh ${bvh.toFixed(2)} M segments/s`,
    );
  }
  // The crossover: the smallest size from which the BVH wins at every larger size measured.
  let crossover: number | null = null;
  for (let i = rows.length - 1; i >= 0 && rows[i].bvh > rows[i].list; i--)
    crossover = rows[i].shapes;
  console.log(
    crossover === null
      ? 'BVH faster at none of the sizes measured'
      : `BVH faster from ${crossover} shapes`,
  );
  // The stress case of the tracer-core issue: 10,000 spheres under an area
  // light against the Cornell box, per segment, each as the compiler builds it.
  const cornell = run('auto', 0);
  const spheres10k = run('auto', 10000);
  console.log(
    `Cornell ${cornell.toFixed(2)}, 10,000 spheres ${spheres10k.toFixed(2)} M segments/s: ratio ${(cornell / spheres10k).toFixed(2)}`,
  );
  mkdirSync('bench/results', { recursive: true });
  writeFileSync(
    'bench/results/bvh-crossover.json',
    JSON.stringify(
      { date: new Date().toISOString(), size, spp, reps, rows, crossover, cornell, spheres10k },
      null,
      1,
    ),
  );
}
