/**
 * The light-sampling densities MIS reads back when a BSDF-sampled path finds an emitter
 * (pbr-book 4e §13.4): what `sampleLight` (lights.ts) would have given that point, the
 * choice of light included, by the light BVH (light-bvh.ts) or by power. They must equal
 * the densities of the samples themselves (tests/unit/core/light-pdf.test.ts and
 * light-bvh.test.ts check every kind of emitter).
 */
import { QUAD_STRIDE, Q_AREA, SPHERE_STRIDE } from '../geometry/shapes.ts';
import { SHAPE_QUAD, SHAPE_TRIANGLE } from '../geometry/ray.ts';
import type { LightBvh } from './light-bvh.ts';
import type { LightList } from './lights.ts';

/**
 * Solid-angle pdf with which `sampleLight` would have produced the point of
 * light l (triangle `triangle` of a mesh, else −1) hit from (x, y, z) with normal
 * (nx, ny, nz) at distance t with emitter cosine cosLight, the light chosen by `bvh`
 * (null: by power) among up to `split` lights (LightBvh.chooseSplit): the density MIS
 * needs when a BSDF-sampled ray lands on an emitter.
 */
export function lightPdf(
  lights: LightList,
  bvh: LightBvh | null,
  spheres: Float64Array,
  quads: Float64Array,
  l: number,
  triangle: number,
  x: number,
  y: number,
  z: number,
  nx: number,
  ny: number,
  nz: number,
  t: number,
  cosLight: number,
  split = 1,
): number {
  const s = lights.shape[l];
  const kind = lights.kind[l];
  let choose: number;
  let prim = -1;
  if (bvh === null) choose = lights.prob[l];
  else {
    prim = bvh.primOf(l, kind === SHAPE_TRIANGLE ? triangle : -1);
    bvh.setPoint(x, y, z, nx, ny, nz);
    choose = bvh.pmf(prim, split);
  }
  if (!(choose > 0)) return 0;
  if (kind === SHAPE_QUAD) {
    return (choose * t * t) / (quads[s * QUAD_STRIDE + Q_AREA] * cosLight);
  }
  if (kind === SHAPE_TRIANGLE) {
    const area = bvh === null ? lights.meshLights[s]!.area : bvh.primArea[prim];
    return (choose * t * t) / (area * cosLight);
  }
  const o = s * SPHERE_STRIDE;
  const r = spheres[o + 3];
  const dx = spheres[o] - x;
  const dy = spheres[o + 1] - y;
  const dz = spheres[o + 2] - z;
  const dc2 = dx * dx + dy * dy + dz * dz;
  if (dc2 <= r * r * (1 + 1e-9)) return (choose * t * t) / (4 * Math.PI * r * r * cosLight);
  const sin2Max = (r * r) / dc2;
  const cosMax = Math.sqrt(Math.max(0, 1 - sin2Max));
  return choose / ((2 * Math.PI * sin2Max) / (1 + cosMax));
}

/**
 * Solid-angle pdf with which `sampleLight` would have chosen the environment map (by
 * `bvh`, or by power when null) and drawn the unit direction d: what MIS needs when a
 * path escapes.
 */
export function environmentLightPdf(
  lights: LightList,
  bvh: LightBvh | null,
  dx: number,
  dy: number,
  dz: number,
): number {
  const l = lights.environmentLight;
  if (l < 0) return 0;
  return (bvh === null ? lights.prob[l] : bvh.infinitePick) * lights.environment!.pdf(dx, dy, dz);
}
