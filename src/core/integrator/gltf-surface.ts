/**
 * What the integrator does at triangles with a glTF material (docs/gltf.md), kept
 * out of the main loop so scenes without glTF never run it:
 * - `shadeGltfHit`: the vertex attributes at the hit (texture coordinates, colour,
 *   tangent), the per-hit BSDF parameters from the material's factors and textures
 *   (gltf-material/shading-fill.ts, pbr-book 4e §10.5: textures evaluated once per hit), and
 *   the normal map applied to the shading normal (gltf-material/normal-map.ts);
 * - `gltfLightEmission`: the emission a light sample sees at a point of an emissive
 *   glTF mesh (emissive texture × coverage);
 * - `shadowTransmittance`: the visibility of a shadow ray through alpha-blended or
 *   alpha-masked surfaces.
 *
 * Alpha as stochastic opacity: a surface of coverage α is there with probability α
 * (pbr-book 4e §7.1.1 "alpha masking" and §14.1.2 for the stochastic version). A path
 * decides that with a random number (the integrator); a shadow ray instead takes the
 * expected value, the product of (1 − α) of every surface it crosses — the same
 * expectation with less noise, and it needs no random numbers. MASK's α is 0 or 1,
 * so both are exact there.
 *
 * Everything here writes into caller-owned records: nothing is allocated per call.
 */
import { MATERIAL_GLTF, MATERIAL_STRIDE, M_GLTF_INDEX, M_TYPE } from '../bsdf/materials.ts';
import type { ShadingParams } from '../bsdf/shading.ts';
import { Hit, type Ray, SHAPE_TRIANGLE } from '../geometry/ray.ts';
import { OFFSET_SCALE } from '../geometry/shapes.ts';
import { intersectScene } from '../accel/trace.ts';
import { interpolateAttributes, interpolateTangent } from '../gltf-material/hit-attributes.ts';
import { applyNormalMap } from '../gltf-material/normal-map.ts';
import { anisotropyToWorld } from '../gltf-material/anisotropy-frame.ts';
import {
  fillGltfShading,
  gltfEmission,
  gltfOpacity,
  HitAttributes,
} from '../gltf-material/shading-fill.ts';
import { triangleNormal } from '../lights/mesh-light.ts';
import type { CompiledScene } from '../scene/compile/compile.ts';
import type { GltfScene } from '../scene/compile/gltf-scene.ts';
import { TriangleSurface } from './triangle-surface.ts';
import { completeInstanceHit, instanceTangent } from './instance-surface.ts';

/**
 * Shadow rays give up after crossing this many alpha surfaces and count as blocked:
 * a bound on the work of one query (a real model never stacks so many along one ray).
 */
export const MAX_ALPHA_CROSSINGS = 256;

/** Scratch of the functions below; one per tracer. */
export class GltfWork {
  readonly attributes = new HitAttributes();
  readonly tangent = new Float64Array(4);
  readonly normal = { x: 0, y: 0, z: 1 };
  readonly emission = { r: 0, g: 0, b: 0 };
  /** The shadow ray's hits. */
  readonly hit = new Hit();
  readonly geometric = { nx: 0, ny: 0, nz: 1 };
  /** World direction of KHR_materials_anisotropy at the hit (when sp.anisotropy > 0). */
  readonly anisotropy = { x: 1, y: 0, z: 0 };
  /** An instance hit of the shadow ray, completed (instance-surface.ts). */
  readonly surface = new TriangleSurface();
}

/** Row of the glTF material table of scene material m. */
export function gltfRow(materials: Float64Array, m: number): number {
  return materials[m * MATERIAL_STRIDE + M_GLTF_INDEX];
}

/**
 * Fills `sp` for the hit on triangle t at barycentrics (b1, b2) of its vertices 1 and
 * 2, with glTF material row `row`, and replaces the shading normal of `ts` by the
 * normal-mapped one where the material has a normal map and the vertices tangents.
 */
export function shadeGltfHit(
  scene: CompiledScene,
  gltf: GltfScene,
  t: number,
  b1: number,
  b2: number,
  row: number,
  ts: TriangleSurface,
  sp: ShadingParams,
  work: GltfWork,
): void {
  const ix = scene.triIndices;
  const i0 = ix[3 * t],
    i1 = ix[3 * t + 1],
    i2 = ix[3 * t + 2];
  const a = work.attributes;
  interpolateAttributes(gltf, i0, i1, i2, b1, b2, a);
  fillGltfShading(gltf.table, gltf.textures, row, a, sp);
  const tangents = gltf.tangents;
  if (sp.clearcoat > 0) coatNormalToWorld(ts, tangents, i0, i1, i2, b1, b2, sp, work);
  if (tangents !== null && (sp.nx !== 0 || sp.ny !== 0 || sp.nz !== 1)) {
    const tg = work.tangent;
    interpolateTangent(tangents, i0, i1, i2, b1, b2, tg);
    if (ts.instance >= 0) instanceTangent(ts, tg);
    const n = work.normal;
    if (
      applyNormalMap(
        ts.snx,
        ts.sny,
        ts.snz,
        tg[0],
        tg[1],
        tg[2],
        tg[3],
        sp.nx,
        sp.ny,
        sp.nz,
        ts.nx,
        ts.ny,
        ts.nz,
        n,
      )
    ) {
      ts.snx = n.x;
      ts.sny = n.y;
      ts.snz = n.z;
    }
  }
  // KHR_materials_anisotropy needs the tangent frame; without one the lobe is
  // isotropic (flatten.ts generates tangents for such primitives and warns
  // where it cannot).
  if (sp.anisotropy > 0) {
    const tg = work.tangent;
    if (tangents !== null) {
      interpolateTangent(tangents, i0, i1, i2, b1, b2, tg);
      if (ts.instance >= 0) instanceTangent(ts, tg);
    }
    if (tangents === null || !anisotropyToWorld(tg, ts.snx, ts.sny, ts.snz, sp, work.anisotropy))
      sp.anisotropy = 0;
  }
}

/**
 * The coat normal of KHR_materials_clearcoat, from tangent space (fillGltfShading) to
 * world space, in sp.ccnx, ccny, ccnz: through the same TBN frame as the normal map
 * (the unmapped shading normal and the vertex tangent), or the unmapped shading normal
 * itself without a coat normal texture or without tangents. The integrator then takes
 * it into the BSDF's local frame (trace-path.ts).
 */
function coatNormalToWorld(
  ts: TriangleSurface,
  tangents: Float32Array | null,
  i0: number,
  i1: number,
  i2: number,
  b1: number,
  b2: number,
  sp: ShadingParams,
  work: GltfWork,
): void {
  const n = work.normal;
  n.x = ts.snx;
  n.y = ts.sny;
  n.z = ts.snz;
  if (tangents !== null && (sp.ccnx !== 0 || sp.ccny !== 0 || sp.ccnz !== 1)) {
    const tg = work.tangent;
    interpolateTangent(tangents, i0, i1, i2, b1, b2, tg);
    if (ts.instance >= 0) instanceTangent(ts, tg);
    applyNormalMap(
      ts.snx,
      ts.sny,
      ts.snz,
      tg[0],
      tg[1],
      tg[2],
      tg[3],
      sp.ccnx,
      sp.ccny,
      sp.ccnz,
      ts.nx,
      ts.ny,
      ts.nz,
      n,
    );
  }
  sp.ccnx = n.x;
  sp.ccny = n.y;
  sp.ccnz = n.z;
}

/**
 * Emission seen by a light sample on triangle t (barycentrics b1, b2) of a mesh with
 * glTF material row `row`, into work.emission.
 */
export function gltfLightEmission(
  scene: CompiledScene,
  gltf: GltfScene,
  t: number,
  b1: number,
  b2: number,
  row: number,
  work: GltfWork,
): void {
  const ix = scene.triIndices;
  const a = work.attributes;
  interpolateAttributes(gltf, ix[3 * t], ix[3 * t + 1], ix[3 * t + 2], b1, b2, a);
  gltfEmission(gltf.table, gltf.textures, row, a, work.emission);
}

/**
 * Visibility along `ray` (origin, unit direction, tMax; modified) through surfaces
 * with alpha: 0 when something opaque lies on it, else the product of (1 − α) of the
 * alpha surfaces it crosses. Only called for scenes that have such materials.
 */
export function shadowTransmittance(
  scene: CompiledScene,
  gltf: GltfScene,
  ray: Ray,
  work: GltfWork,
): number {
  const materials = scene.materials;
  const meshes = scene.meshes!;
  const hit = work.hit;
  const p = scene.triPositions;
  const ix = scene.triIndices;
  // The far end stays where it is while the origin steps over the surfaces crossed.
  const finite = ray.tMax < Infinity;
  const ex = ray.ox + ray.tMax * ray.dx;
  const ey = ray.oy + ray.tMax * ray.dy;
  const ez = ray.oz + ray.tMax * ray.dz;
  let transmittance = 1;
  for (let k = 0; k < MAX_ALPHA_CROSSINGS; k++) {
    if (!intersectScene(scene, ray, hit)) return transmittance;
    if (hit.kind !== SHAPE_TRIANGLE) return 0;
    const t = hit.index;
    const m = meshes.material[meshes.meshOf(t)];
    if (materials[m * MATERIAL_STRIDE + M_TYPE] !== MATERIAL_GLTF) return 0;
    const a = work.attributes;
    const i0 = ix[3 * t],
      i1 = ix[3 * t + 1],
      i2 = ix[3 * t + 2];
    interpolateAttributes(gltf, i0, i1, i2, hit.b1, hit.b2, a);
    const opacity = gltfOpacity(gltf.table, gltf.textures, gltfRow(materials, m), a);
    transmittance *= 1 - opacity;
    if (!(transmittance > 0)) return 0;
    // Past the surface: the hit point, lifted to the side the ray leaves by.
    const b0 = hit.b0,
      b1 = hit.b1,
      b2 = hit.b2;
    let x: number, y: number, z: number, scale: number;
    let g: { nx: number; ny: number; nz: number } = work.geometric;
    if (hit.instance < 0) {
      x = b0 * p[3 * i0] + b1 * p[3 * i1] + b2 * p[3 * i2];
      y = b0 * p[3 * i0 + 1] + b1 * p[3 * i1 + 1] + b2 * p[3 * i2 + 1];
      z = b0 * p[3 * i0 + 2] + b1 * p[3 * i1 + 2] + b2 * p[3 * i2 + 2];
      triangleNormal(p, 3 * i0, 3 * i1, 3 * i2, g);
      scale = meshes.triangleScale(t);
    } else {
      // An instance's triangle is in object space: its world point and normal.
      const s = work.surface;
      completeInstanceHit(scene, hit, s);
      x = s.x;
      y = s.y;
      z = s.z;
      g = s;
      scale = s.scale;
    }
    scale = Math.max(Math.abs(x), Math.abs(y), Math.abs(z), scale) * OFFSET_SCALE;
    const lift = ray.dx * g.nx + ray.dy * g.ny + ray.dz * g.nz >= 0 ? scale : -scale;
    ray.ox = x + g.nx * lift;
    ray.oy = y + g.ny * lift;
    ray.oz = z + g.nz * lift;
    if (finite) {
      ray.tMax = (ex - ray.ox) * ray.dx + (ey - ray.oy) * ray.dy + (ez - ray.oz) * ray.dz;
      if (!(ray.tMax > 0)) return transmittance;
    }
  }
  return 0;
}
