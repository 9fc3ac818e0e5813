/**
 * The triangles of a glTF primitive as corner lists (glTF 2.0 §3.7.2.1):
 * TRIANGLES in threes, TRIANGLE_STRIP with every other triangle's first two
 * corners swapped so all keep the strip's winding, TRIANGLE_FAN around the
 * first vertex. Every index is checked against the vertex count.
 */
import type { Primitive } from '@gltf-transform/core';
import { readIndices } from './accessors.ts';
import { GltfError } from './errors.ts';
import { MODE_TRIANGLE_FAN, MODE_TRIANGLES } from './validate.ts';

export /** Triangle corners of a primitive from its indices and mode; checks every index. */
function triangleList(prim: Primitive, vertexCount: number, where: string): Uint32Array {
  const mode = prim.getMode();
  const acc = prim.getIndices();
  const idx = acc === null ? null : readIndices(acc);
  const n = idx === null ? vertexCount : idx.length;
  const at = (k: number): number => (idx === null ? k : idx[k]);
  if (idx !== null) {
    for (let k = 0; k < n; k++) {
      if (idx[k] >= vertexCount) {
        throw new GltfError(
          `${where}.indices: index ${idx[k]} at position ${k} is out of range (POSITION has ${vertexCount} vertices)`,
        );
      }
    }
  }
  if (mode === MODE_TRIANGLES) {
    const t = new Uint32Array(Math.floor(n / 3) * 3);
    for (let k = 0; k < t.length; k++) t[k] = at(k);
    return t;
  }
  const count = Math.max(0, n - 2);
  const t = new Uint32Array(count * 3);
  for (let k = 0; k < count; k++) {
    if (mode === MODE_TRIANGLE_FAN) {
      t[3 * k] = at(0);
      t[3 * k + 1] = at(k + 1);
      t[3 * k + 2] = at(k + 2);
    } else {
      // Strips alternate their winding; swap on odd triangles to keep it.
      t[3 * k] = at(k + (k & 1));
      t[3 * k + 1] = at(k + 1 - (k & 1));
      t[3 * k + 2] = at(k + 2);
    }
  }
  return t;
}
