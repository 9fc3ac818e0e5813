/**
 * The mesh scenes of the speed benchmarks (bench/mesh-bvh.ts, bench/inproc.ts): the
 * Cornell box's walls and light with one mesh in place of its two boxes, the mesh being
 * the Stanford bunny (npm package `bunny`, 3,674 triangles, at the box's scale as in
 * scenes/cornell-bunny.json) or a generated bumpy sphere of 1,000,000 triangles.
 */
import { readFileSync } from 'node:fs';
import { createRequire } from 'node:module';
import { resolve } from 'node:path';
import { parseScene, validateScene, type Scene } from '../src/core/index.ts';

/** A sphere of nu × nv quads (2·nu·nv triangles) with a bumpy radius. */
export function bumpySphere(
  nu: number,
  nv: number,
  radius: number,
  center: number[],
): { positions: Float64Array; indices: Uint32Array } {
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

/** The 1,000,000-triangle bumpy sphere of bench/mesh-bvh.ts. */
export function millionMesh(): { positions: Float64Array; indices: Uint32Array } {
  return bumpySphere(1000, 500, 150, [278, 160, 280]);
}

/** The Stanford bunny at the Cornell box's scale (as in scenes/cornell-bunny.json). */
export function bunnyMesh(require: (id: string) => unknown): {
  positions: Float64Array;
  indices: Uint32Array;
} {
  const bunny = require('bunny') as { positions: number[][]; cells: number[][] };
  const positions = Float64Array.from(bunny.positions.flat());
  const indices = Uint32Array.from(bunny.cells.flat());
  for (let i = 0; i < positions.length; i += 3) {
    positions[i] = 278 + 25 * positions[i];
    positions[i + 1] = 0.08 + 25 * positions[i + 1];
    positions[i + 2] = 290 + 25 * positions[i + 2];
  }
  return { positions, indices };
}

/** The Cornell box's walls and light (scenes/cornell.json) with one mesh in place of its two boxes. */
export function cornellWith(positions: Float64Array, indices: Uint32Array): Scene {
  const json = JSON.parse(readFileSync('scenes/cornell.json', 'utf8'));
  const scene = validateScene({
    ...json,
    shapes: [
      ...json.shapes.slice(0, 6),
      { type: 'mesh', material: 'white', positions: [0, 0, 0, 1, 0, 0, 0, 1, 0] },
    ],
  });
  const mesh = scene.shapes[6];
  if (mesh.type === 'mesh') mesh.data = { positions, indices, normals: null, skipped: 0 };
  return scene;
}

/**
 * The scene a benchmark names on its command line: `@million` or `@bunny` (the Cornell
 * box with that mesh, above), else a scene file.
 */
export function loadBenchScene(name: string): Scene {
  if (name === '@million') {
    const m = millionMesh();
    return cornellWith(m.positions, m.indices);
  }
  if (name === '@bunny') {
    const m = bunnyMesh(createRequire(resolve('package.json')));
    return cornellWith(m.positions, m.indices);
  }
  return parseScene(readFileSync(name, 'utf8'));
}
