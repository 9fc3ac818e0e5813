/**
 * MikkTSpace through the core's own WebAssembly loader
 * (src/core/gltf/mikktspace-wasm.ts) gives exactly what the `mikktspace`
 * package's own Node build gives, on a random mesh; both refuse an empty one.
 */
import { createRequire } from 'node:module';
import { describe, expect, it } from 'vitest';
import { nodeTangentGenerator } from '../../../src/cli/gltf-node.ts';
import { type TangentGenerator, weldCorners } from '../../../src/core/gltf/tangents.ts';
import { hashToUnit, sampleKey } from '../../../src/core/rng/pcg.ts';

describe('MikkTSpace loader', () => {
  it('matches the package build bit for bit', async () => {
    const ours = await nodeTangentGenerator();
    const theirs = (
      createRequire(import.meta.url)('mikktspace') as { generateTangents: TangentGenerator }
    ).generateTangents;
    const corners = 3 * 200;
    const r = (i: number, d: number): number => hashToUnit(sampleKey(5, i, 0), d);
    const p = Float32Array.from({ length: 3 * corners }, (_, i) => r(i, 0) * 2 - 1);
    const n = new Float32Array(3 * corners);
    for (let k = 0; k < corners; k++) {
      const x = r(k, 1) - 0.5,
        y = r(k, 2) - 0.5,
        z = r(k, 3);
      const l = Math.hypot(x, y, z);
      n.set([x / l, y / l, z / l], 3 * k);
    }
    const t = Float32Array.from({ length: 2 * corners }, (_, i) => r(i, 4));
    const a = ours(p, n, t);
    const b = theirs(p, n, t);
    expect(a.length).toBe(4 * corners);
    expect(Array.from(a)).toEqual(Array.from(b));
    // Repeated calls reuse the module's memory correctly.
    expect(Array.from(ours(p, n, t))).toEqual(Array.from(b));
    // Both refuse an empty mesh (the reference implementation has no faces to work on).
    const empty = new Float32Array(0);
    expect(() => theirs(empty, empty, empty)).toThrow('Failed to generate tangents.');
    expect(() => ours(empty, empty, empty)).toThrow('Failed to generate tangents.');
  });
});

describe('welding MikkTSpace corners', () => {
  it('shares a vertex among corners with identical tangents and splits it at seams', () => {
    const corners = Uint32Array.of(0, 1, 2, 0, 2, 3);
    const a = [1, 0, 0, 1];
    const b = [0, 1, 0, -1];
    // Corner 3 (vertex 0 again) has another tangent: a seam.
    const tangents = Float32Array.from([a, a, a, b, a, a].flat());
    const w = weldCorners(corners, tangents, 4);
    expect(Array.from(w.source)).toEqual([0, 1, 2, 0, 3]);
    expect(Array.from(w.triangles)).toEqual([0, 1, 2, 3, 2, 4]);
    expect(Array.from(w.tangents.subarray(12, 16))).toEqual(b);
    expect(w.tangents.length).toBe(20);
  });
});
