// Scenes the speed benchmarks need beyond scenes/: a field of N
// non-overlapping spheres on a ground quad under one area light (the
// 10,000-sphere case of issue 10), and a room lit by N small emitters (the
// many-light case of issue 23). Deterministic for a given (count, seed),
// written as a plain pathwise-scene/1 file so pathwise and the native
// anchor read the very same bytes.
//
//   node bench/scenes.mjs spheres 10000 > /tmp/spheres-10k.json
//   node bench/scenes.mjs many-lights 10000 > /tmp/many-lights-10k.json
import { writeFileSync } from 'node:fs';
import { manyLights } from '../tests/helpers/many-lights-scene.mjs';

export { manyLights };

/** PCG hash (the same permutation as src/core/rng/pcg.ts), for placement only. */
function pcgHash(input) {
  const state = (Math.imul(input, 747796405) + 2891336453) | 0;
  const word = Math.imul((state >>> ((state >>> 28) + 4)) ^ state, 277803737);
  return ((word >>> 22) ^ word) >>> 0;
}

/**
 * N spheres on a jittered grid of unit cells, one per cell: radius in
 * [0.12, 0.42], centre jittered so the sphere stays inside its cell, so no
 * two spheres overlap or touch; lifted off the ground by 0–0.3.
 */
export function spheresField(count, seed = 1) {
  let state = seed >>> 0;
  const rand = () => (state = pcgHash(state + 1)) / 4294967296;
  const side = Math.ceil(Math.sqrt(count));
  const half = side / 2;
  const round = (v) => +v.toFixed(6);
  const shapes = [
    {
      type: 'quad',
      corner: [-half - 1, 0, -half - 1],
      u: [0, 0, 2 * half + 2],
      v: [2 * half + 2, 0, 0],
      material: 'ground',
    },
    {
      type: 'quad',
      corner: [-half / 3, side, -half / 3],
      u: [(2 * half) / 3, 0, 0],
      v: [0, 0, (2 * half) / 3],
      material: 'lamp',
    },
  ];
  const mats = ['red', 'white', 'metal', 'blue'];
  for (let i = 0; i < count; i++) {
    const gx = i % side;
    const gz = Math.floor(i / side);
    const r = 0.12 + 0.3 * rand();
    const slack = 0.5 - r - 0.01;
    shapes.push({
      type: 'sphere',
      center: [
        round(gx - half + 0.5 + (2 * rand() - 1) * slack),
        round(r + 0.3 * rand()),
        round(gz - half + 0.5 + (2 * rand() - 1) * slack),
      ],
      radius: round(r),
      material: mats[i % mats.length],
    });
  }
  // Lamp power grows with the field's area so the image exposure stays put.
  const e = 10;
  return {
    format: 'pathwise-scene/1',
    name: `${count} spheres under an area light`,
    camera: {
      position: [0, side * 0.6, -side * 0.6],
      target: [0, 0, side * 0.05],
      up: [0, 1, 0],
      fovY: 45,
    },
    settings: { width: 128, height: 128, maxBounces: 6, spp: 16 },
    materials: {
      ground: { type: 'diffuse', albedo: [0.6, 0.6, 0.6] },
      red: { type: 'diffuse', albedo: [0.7, 0.2, 0.15] },
      white: { type: 'diffuse', albedo: [0.75, 0.75, 0.75] },
      blue: { type: 'diffuse', albedo: [0.15, 0.25, 0.7] },
      metal: { type: 'conductor', color: [0.9, 0.8, 0.6], roughness: 0.3 },
      lamp: { type: 'diffuse', albedo: [0, 0, 0], emission: [e, e, e] },
    },
    shapes,
    environment: [0.02, 0.02, 0.03],
  };
}

/** Writes the N-sphere scene to `file` and returns the path. */
export function writeSpheresField(file, count, seed = 1) {
  writeFileSync(file, JSON.stringify(spheresField(count, seed)));
  return file;
}

if (import.meta.url === `file://${process.argv[1]}`) {
  const [kind, n] = process.argv.slice(2);
  if (kind !== 'spheres' && kind !== 'many-lights') {
    process.stderr.write('usage: node bench/scenes.mjs spheres|many-lights N > FILE\n');
    process.exit(2);
  }
  const make = kind === 'spheres' ? spheresField : manyLights;
  process.stdout.write(JSON.stringify(make(Number(n ?? 10000))) + '\n');
}
