/**
 * The emitters of a light list as the light BVH's input (light-bvh.ts): one bounds
 * record (light-bounds.ts) per sphere, quad, point or spot light and per triangle of
 * an emissive mesh; the environment map and directional lights apart.
 *
 * Power: each entry's selection probability (lights.ts, power relative to the scene's
 * total, so it cannot overflow); a mesh's is shared among its triangles by their own
 * power (`trianglePower`, scene/compile/light-power.ts: area × the emission a light
 * sample sees there, which follows an emissive texture's texels).
 *
 * Directions (pbrt-v4's `Light::Bounds` of each kind): a quad or triangle emits into
 * the hemisphere of its normal (θo = 0, θe = π/2); a sphere and a point light in every
 * direction (θo = π); a spot light within its outer cone (θo = 0, cos θe = cos outer).
 */
import {
  LIGHT_DIRECTIONAL,
  LIGHT_ENVIRONMENT,
  LIGHT_POINT,
  LIGHT_SPOT,
  SHAPE_QUAD,
  SHAPE_SPHERE,
  SHAPE_TRIANGLE,
} from '../geometry/ray.ts';
import { QUAD_STRIDE, Q_CORNER, Q_NORMAL, Q_U, Q_V, SPHERE_STRIDE } from '../geometry/shapes.ts';
import { LB_PHI, LB_STRIDE, setBounds } from './light-bounds.ts';
import type { LightBvhInput } from './light-bvh.ts';
import type { LightList } from './lights.ts';
import { triangleArea, triangleNormal } from './mesh-light.ts';
import { PUNCTUAL_STRIDE, P_COS_OUTER, P_DIRECTION, P_POSITION } from './punctual.ts';

const UP = [0, 0, 1];

export function lightBvhInput(
  lights: LightList,
  spheres: Float64Array,
  quads: Float64Array,
  positions: Float64Array,
  indices: Uint32Array | Int32Array,
  /** Per triangle of every emissive mesh, in light-list order: its power (see above). */
  trianglePower: Float64Array,
): LightBvhInput {
  const n = lights.count;
  let prims = 0;
  const infinite: number[] = [];
  const primBase = new Int32Array(n).fill(-1);
  const firstTriangle = new Int32Array(n);
  for (let l = 0; l < n; l++) {
    const kind = lights.kind[l];
    if (kind === LIGHT_ENVIRONMENT || kind === LIGHT_DIRECTIONAL) {
      infinite.push(l);
      continue;
    }
    primBase[l] = prims;
    if (kind === SHAPE_TRIANGLE) {
      const mesh = lights.meshLights[lights.shape[l]]!;
      firstTriangle[l] = mesh.first;
      prims += mesh.count;
    } else prims++;
  }
  const bounds = new Float64Array(prims * LB_STRIDE);
  const light = new Int32Array(prims);
  const triangle = new Int32Array(prims).fill(-1);
  const area = new Float64Array(prims);
  const lo = [0, 0, 0];
  const hi = [0, 0, 0];
  const w = [0, 0, 1];
  const normal = { nx: 0, ny: 0, nz: 1 };
  const punctual = lights.punctual;
  let powerAt = 0;
  let maxPhi = 0;
  for (let l = 0; l < n; l++) {
    const p = primBase[l];
    if (p < 0) continue;
    const kind = lights.kind[l];
    const s = lights.shape[l];
    const prob = lights.prob[l];
    if (kind === SHAPE_TRIANGLE) {
      const mesh = lights.meshLights[s]!;
      let total = 0;
      for (let k = 0; k < mesh.count; k++) total += trianglePower[powerAt + k];
      for (let k = 0; k < mesh.count; k++) {
        const t = mesh.first + k;
        const i0 = indices[3 * t] * 3,
          i1 = indices[3 * t + 1] * 3,
          i2 = indices[3 * t + 2] * 3;
        for (let c = 0; c < 3; c++) {
          lo[c] = Math.min(positions[i0 + c], positions[i1 + c], positions[i2 + c]);
          hi[c] = Math.max(positions[i0 + c], positions[i1 + c], positions[i2 + c]);
        }
        triangleNormal(positions, i0, i1, i2, normal);
        const a = triangleArea(positions, indices, t);
        const finite = Number.isFinite(normal.nx + normal.ny + normal.nz) && a > 0;
        w[0] = finite ? normal.nx : 0;
        w[1] = finite ? normal.ny : 0;
        w[2] = finite ? normal.nz : 1;
        // A degenerate triangle emits nothing: power 0, never chosen.
        const phi = finite && total > 0 ? prob * (trianglePower[powerAt + k] / total) : 0;
        setBounds(bounds, (p + k) * LB_STRIDE, lo, hi, w, phi, finite ? 1 : -1, 0);
        light[p + k] = l;
        triangle[p + k] = t;
        area[p + k] = a;
        maxPhi = Math.max(maxPhi, phi);
      }
      powerAt += mesh.count;
      continue;
    }
    let cosO = -1;
    let cosE = 0;
    let wv: ArrayLike<number> = UP;
    if (kind === SHAPE_SPHERE) {
      const o = s * SPHERE_STRIDE;
      const r = spheres[o + 3];
      for (let c = 0; c < 3; c++) {
        lo[c] = spheres[o + c] - r;
        hi[c] = spheres[o + c] + r;
      }
    } else if (kind === SHAPE_QUAD) {
      const o = s * QUAD_STRIDE;
      for (let c = 0; c < 3; c++) {
        const p0 = quads[o + Q_CORNER + c];
        const pu = p0 + quads[o + Q_U + c];
        const pv = p0 + quads[o + Q_V + c];
        const puv = pu + quads[o + Q_V + c];
        lo[c] = Math.min(p0, pu, pv, puv);
        hi[c] = Math.max(p0, pu, pv, puv);
        w[c] = quads[o + Q_NORMAL + c];
      }
      wv = w;
      cosO = 1;
    } else {
      // LIGHT_POINT or LIGHT_SPOT.
      const o = s * PUNCTUAL_STRIDE;
      for (let c = 0; c < 3; c++) {
        lo[c] = punctual[o + P_POSITION + c];
        hi[c] = lo[c];
        w[c] = punctual[o + P_DIRECTION + c];
      }
      if (kind === LIGHT_SPOT) {
        wv = w;
        cosO = 1;
        cosE = punctual[o + P_COS_OUTER];
      } else if (kind !== LIGHT_POINT) {
        throw new RangeError(`light ${l}: kind ${kind} has no bounds`);
      }
    }
    setBounds(bounds, p * LB_STRIDE, lo, hi, wv, prob, cosO, cosE);
    light[p] = l;
    maxPhi = Math.max(maxPhi, prob);
  }
  // Relative to the largest: the importances' products stay far from overflow.
  if (maxPhi > 0) for (let p = 0; p < prims; p++) bounds[p * LB_STRIDE + LB_PHI] /= maxPhi;
  return {
    bounds,
    light,
    triangle,
    area,
    infinite: Int32Array.from(infinite),
    primBase,
    firstTriangle,
  };
}
