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
import { GltfError, messageOf } from './errors.ts';

import type { TangentGenerator } from '../scene/format/gltf-model.ts';

export type { TangentGenerator };

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
    throw new GltfError(`${where}: tangent generation failed: ${messageOf(e)}`);
  }
  if (out.length !== 4 * n) {
    throw new GltfError(
      `${where}: tangent generator returned ${out.length} values for ${n} corners`,
    );
  }
  // MikkTSpace's bitangent sign follows a v-up texture convention; glTF's v
  // points down the image, so the handedness flips (as glTF-Transform does).
  for (let k = 3; k < out.length; k += 4) out[k] = -out[k];
  return out;
}

export interface WeldedCorners {
  /** Output vertex → vertex of the primitive. */
  source: Uint32Array;
  /** Corner → output vertex. */
  triangles: Uint32Array;
  /** 4 per output vertex. */
  tangents: Float32Array;
}

/**
 * Welds the corners MikkTSpace saw unwelded back into vertices: corners of
 * the same primitive vertex with bit-identical tangents share one output
 * vertex (MikkTSpace gives shared vertices identical tangents except across
 * UV seams and mirrored halves, which stay split). Keeps the vertex count
 * near the file's instead of three per triangle.
 */
export function weldCorners(
  corners: Uint32Array,
  cornerTangents: Float32Array,
  vertexCount: number,
): WeldedCorners {
  const n = corners.length;
  const head = new Int32Array(vertexCount).fill(-1);
  const next = new Int32Array(n);
  const source = new Uint32Array(n);
  const tangents = new Float32Array(4 * n);
  const triangles = new Uint32Array(n);
  let count = 0;
  for (let k = 0; k < n; k++) {
    const v = corners[k];
    const o = 4 * k;
    let w = head[v];
    while (w >= 0) {
      const p = 4 * w;
      if (
        tangents[p] === cornerTangents[o] &&
        tangents[p + 1] === cornerTangents[o + 1] &&
        tangents[p + 2] === cornerTangents[o + 2] &&
        tangents[p + 3] === cornerTangents[o + 3]
      ) {
        break;
      }
      w = next[w];
    }
    if (w < 0) {
      w = count++;
      source[w] = v;
      tangents.set(cornerTangents.subarray(o, o + 4), 4 * w);
      next[w] = head[v];
      head[v] = w;
    }
    triangles[k] = w;
  }
  return { source: source.slice(0, count), triangles, tangents: tangents.slice(0, 4 * count) };
}
