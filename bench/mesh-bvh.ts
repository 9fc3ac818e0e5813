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
  validateScene,
  type Scene,
} from '../src/core/index.ts';

const reps = Number(process.argv[2] ?? 5);
const out = process.argv[3] ?? 'bench/results/mesh-bvh.json';
const require = createRequire(resolve('package.json'));
const bunny = require('bunny') as { positions: number[][]; cells: number[][] };

/** A sphere of nu × nv quads (2·nu·nv triangles) with a bumpy radius. */
function bumpySphere(nu: number, nv: number, radius: number, center: number[]) {
  const positions = new Float64Array(nu * (nv + 1) * 3);
  let k = 0;
  for (let j = 0; j <= nv; j++) {
    const theta = (Math.PI * j) / nv;
    for (let i = 0; i < nu; i++) {
      const phi = (2 * Math.PI * i) / nu;
      const bump =
        1 + 0.04 * Math.sin(7 * phi) * Math.sin(5 * theta) + 0.01 * Math.sin(40 * phi + 3 * theta);
      const r = radius * bump;
      positions[k++] = center[0] + r * Math.sin(theta) * Math.cos(phi);
      positions[k++] = center[1] + r * Math.cos(theta);
      positions[k++] = center[2] + r * Math.sin(theta) * Math.sin(phi);
    }
  }
  const indices = new Uint32Array(nu * nv * 6);
  k = 0;
  for (let j = 0; j < nv; j++) {
    for (let i = 0; i < nu; i++) {
      const a = j * nu + i;
      const b = j * nu + ((i + 1) % nu);
      const c = (j + 1) * nu + ((i + 1) % nu);
      const d = (j + 1) * nu + i;
      indices.set([a, c, b, a, d, c], k);
      k += 6;
    }
  }
  return { positions, indices };
}

const cornell = parseScene(readFileSync('scenes/cornell.json', 'utf8'));

/** The Cornell box's walls and light with one mesh in place of its two boxes. */
function cornellWith(positions: Float64Array, indices: Uint32Array): Scene {
  const scene = validateScene({
    ...JSON.parse(readFileSync('scenes/cornell.json', 'utf8')),
    shapes: [
      ...JSON.parse(readFileSync('scenes/cornell.json', 'utf8')).shapes.slice(0, 6),
      { type: 'mesh', material: 'white', positions: [0, 0, 0, 1, 0, 0, 0, 1, 0] },
    ],
  });
  const mesh = scene.shapes[6];
  if (mesh.type === 'mesh') mesh.data = { positions, indices, normals: null, skipped: 0 };
  return scene;
}

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

const bunnyPositions = Float64Array.from(bunny.positions.flat());
const bunnyIndices = Uint32Array.from(bunny.cells.flat());
// Bunny at the Cornell box's scale (as in scenes/cornell-bunny.json).
for (let i = 0; i < bunnyPositions.length; i += 3) {
  bunnyPositions[i] = 278 + 25 * bunnyPositions[i];
  bunnyPositions[i + 1] = 0.08 + 25 * bunnyPositions[i + 1];
  bunnyPositions[i + 2] = 290 + 25 * bunnyPositions[i + 2];
}
const big = bumpySphere(1000, 500, 150, [278, 160, 280]);
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
