/**
 * Tangents for normal maps when a file has none, by MikkTSpace — the
 * tangent space normal-map bakers use and glTF 2.0 §3.7.2.1 asks for ("When
 * tangents are not specified, client implementations SHOULD calculate
 * tangents using default MikkTSpace algorithms"). The generator is
 * injected (Node: the `mikktspace` package's WebAssembly build of the
 * reference implementation; the browser loads the same module), so the core
 * stays free of WebAssembly loading details.
 */
import type { Primitive } from '@gltf-transform/core';
import { readFloats } from './accessors.ts';
import { GltfError } from './errors.ts';

/**
 * MikkTSpace over unindexed triangles: positions and normals (3 per corner),
 * uvs (2 per corner) in; tangents (x, y, z, w per corner) out.
 */
export type TangentGenerator = (
  positions: Float32Array,
  normals: Float32Array,
  uvs: Float32Array,
) => Float32Array;

/**
 * Tangents (4 per corner, primitive space) for the corners `triangles`
 * (vertex numbers) of `prim`, with texture coordinates `uv`. A primitive
 * without normals is flat-shaded, so its face normals are what MikkTSpace
 * gets.
 */
export function generatePrimitiveTangents(
  prim: Primitive,
  triangles: Uint32Array,
  uv: Float32Array,
  generate: TangentGenerator,
  where: string,
): Float32Array {
  const pos = readFloats(prim.getAttribute('POSITION')!);
  const nrmAcc = prim.getAttribute('NORMAL');
  const nrm = nrmAcc === null ? null : readFloats(nrmAcc);
  const n = triangles.length;
  const p = new Float32Array(3 * n);
  const q = new Float32Array(3 * n);
  const t = new Float32Array(2 * n);
  for (let k = 0; k < n; k++) {
    const v = triangles[k];
    p[3 * k] = pos[3 * v];
    p[3 * k + 1] = pos[3 * v + 1];
    p[3 * k + 2] = pos[3 * v + 2];
    t[2 * k] = uv[2 * v];
    t[2 * k + 1] = uv[2 * v + 1];
    if (nrm !== null) {
      q[3 * k] = nrm[3 * v];
      q[3 * k + 1] = nrm[3 * v + 1];
      q[3 * k + 2] = nrm[3 * v + 2];
    }
  }
  if (nrm === null) {
    for (let k = 0; k < n; k += 3) {
      const ex = p[3 * k + 3] - p[3 * k],
        ey = p[3 * k + 4] - p[3 * k + 1],
        ez = p[3 * k + 5] - p[3 * k + 2];
      const fx = p[3 * k + 6] - p[3 * k],
        fy = p[3 * k + 7] - p[3 * k + 1],
        fz = p[3 * k + 8] - p[3 * k + 2];
      const cx = ey * fz - ez * fy,
        cy = ez * fx - ex * fz,
        cz = ex * fy - ey * fx;
      const l = Math.hypot(cx, cy, cz) || 1;
      for (let c = 0; c < 3; c++) {
        q[3 * (k + c)] = cx / l;
        q[3 * (k + c) + 1] = cy / l;
        q[3 * (k + c) + 2] = cz / l;
      }
    }
  }
  let out: Float32Array;
  try {
    out = generate(p, q, t);
  } catch (e) {
    throw new GltfError(`${where}: tangent generation failed: ${e instanceof Error ? e.message : String(e)}`); // prettier-ignore
  }
  if (out.length !== 4 * n) {
    throw new GltfError(`${where}: tangent generator returned ${out.length} values for ${n} corners`); // prettier-ignore
  }
  // MikkTSpace's bitangent sign follows a v-up texture convention; glTF's v
  // points down the image, so the handedness flips (as glTF-Transform does).
  for (let k = 3; k < out.length; k += 4) out[k] = -out[k];
  return out;
}
