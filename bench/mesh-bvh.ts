/**
 * Triangle meshes in the BVH, measured: build time and resident bytes per triangle for
 * the Stanford bunny (npm package `bunny`, 3,674 triangles) and a generated mesh of
 * 1,000,000 triangles (a bumpy sphere), and tracing speed (M segments/s) of the
 * million-triangle mesh in the Cornell box against the Cornell box itself, in one
 * process, repetitions interleaved, medians reported.
 *
 *   node scripts/run-ts.mjs bench/mesh-bvh.ts [REPS] [OUT.json]
 *
 * Build time is the whole compile of the mesh scene's geometry (triangle boxes and the
 * binned SAH build), wall and process CPU (CPU time is what a shared machine disturbs
 * least). Bytes per triangle are what stays resident for tracing: positions (24 bytes
 * per vertex), indices (12 per triangle), BVH nodes (64 bytes each) and references (4).
 */
import { readFileSync, writeFileSync } from 'node:fs';
import { createRequire } from 'node:module';
import { resolve } from 'node:path';
import {
  Film,
  PathTracer,
  RenderStats,
  compileScene,
  parseScene,
  type Scene,
} from '../src/core/index.ts';
import { bunnyMesh, cornellWith, millionMesh } from './mesh-scenes.ts';

const reps = Number(process.argv[2] ?? 5);
const out = process.argv[3] ?? 'bench/results/mesh-bvh.json';
const require = createRequire(resolve('package.json'));

const median = (xs: number[]) => [...xs].sort((a, b) => a - b)[xs.length >> 1];
const cpuMs = (c: NodeJS.CpuUsage) => (c.user + c.system) / 1000;

function buildFigures(name: string, scene: Scene, triangles: number) {
  const wall: number[] = [];
  const cpu: number[] = [];
  let bytes = 0;
  let nodes = 0;
  let depth = 0;
  for (let r = 0; r < reps; r++) {
    const c0 = process.cpuUsage();
    const t0 = performance.now();
    const compiled = compileScene(scene, { bvh: true });
    wall.push(performance.now() - t0);
    cpu.push(cpuMs(process.cpuUsage(c0)));
    const bvh = compiled.bvh!;
    bytes = compiled.meshes!.byteLength + bvh.byteLength;
    nodes = bvh.nodeCount;
    depth = bvh.depth;
  }
  return {
    name,
    triangles,
    build_ms_median: +median(wall).toFixed(1),
    build_cpu_ms_median: +median(cpu).toFixed(1),
    build_ms_all: wall.map((x) => +x.toFixed(1)),
    bvh_nodes: nodes,
    bvh_depth: depth,
    bytes_per_triangle: +(bytes / triangles).toFixed(1),
  };
}

function throughput(scene: Scene) {
  const tracer = new PathTracer(compileScene(scene), {
    width: 64,
    height: 64,
    maxBounces: 6,
    seed: 1,
    camera: scene.camera,
  });
  return () => {
    const film = new Film(64, 64);
    const stats = new RenderStats();
    const c0 = process.cpuUsage();
    const t0 = performance.now();
    tracer.renderRows(film, 0, 64, 0, 4, stats);
    const s = (performance.now() - t0) / 1000;
    const cpu = cpuMs(process.cpuUsage(c0)) / 1000;
    return {
      msegs: stats.segments / s / 1e6,
      msegsCpu: stats.segments / cpu / 1e6,
      sink: film.sums[(32 * 64 + 32) * 4],
    };
  };
}

const { positions: bunnyPositions, indices: bunnyIndices } = bunnyMesh(require);
const cornell = parseScene(readFileSync('scenes/cornell.json', 'utf8'));
const big = millionMesh();
const bigTriangles = big.indices.length / 3;

const results = {
  command: 'node scripts/run-ts.mjs bench/mesh-bvh.ts ' + process.argv.slice(2).join(' '),
  node: process.version,
  reps,
  build: [
    buildFigures(
      'bunny (npm bunny)',
      cornellWith(bunnyPositions, bunnyIndices),
      bunnyIndices.length / 3,
    ),
    buildFigures('bumpy sphere', cornellWith(big.positions, big.indices), bigTriangles),
  ],
  throughput: {} as Record<string, unknown>,
};
process.stderr.write(JSON.stringify(results.build) + '\n');

const runs = {
  cornell: throughput(cornell),
  bunny: throughput(cornellWith(bunnyPositions, bunnyIndices)),
  million: throughput(cornellWith(big.positions, big.indices)),
};
const rates: Record<string, number[]> = { cornell: [], bunny: [], million: [] };
const cpuRates: Record<string, number[]> = { cornell: [], bunny: [], million: [] };
let sink = 0;
for (let r = 0; r <= reps; r++) {
  for (const [name, run] of Object.entries(runs)) {
    const { msegs, msegsCpu, sink: s } = run();
    sink += s;
    if (r > 0) {
      rates[name].push(+msegs.toFixed(4));
      cpuRates[name].push(+msegsCpu.toFixed(4));
    }
  }
}
const med = (r: Record<string, number[]>) =>
  Object.fromEntries(Object.entries(r).map(([k, v]) => [k, +median(v).toFixed(3)]));
const m = med(rates);
const mc = med(cpuRates);
results.throughput = {
  msegments_per_s_median: m,
  msegments_per_cpu_s_median: mc,
  all: rates,
  all_per_cpu_s: cpuRates,
  cornell_over_million: +(m.cornell / m.million).toFixed(2),
  cornell_over_million_cpu: +(mc.cornell / mc.million).toFixed(2),
  cornell_over_bunny_cpu: +(mc.cornell / mc.bunny).toFixed(2),
  note: '64×64, 4 spp, 6 bounces, one thread, NEE+MIS; repetitions interleaved',
  sink,
};
writeFileSync(out, JSON.stringify(results, null, 1) + '\n');
process.stdout.write(JSON.stringify(results, null, 1) + '\n');
