/**
 * The selection weight of an emissive glTF mesh among the scene's lights
 * (lights.ts chooses lights in proportion to power): Σ over its triangles of
 * area × luminance of what a light sample sees at the triangle's centroid
 * (emissive factor × texture × strength × coverage, shading-fill.ts). With an
 * emissive texture that is mostly black, the factor alone would give the mesh
 * far more light samples than it deserves.
 *
 * Only the choice among lights uses this estimate; within the mesh points are
 * drawn uniformly by area (mesh-light.ts) and every sample is weighted by the
 * exact emission at its point, so a rough estimate costs noise, never bias.
 */
import { triangleArea } from '../../lights/mesh-light.ts';
import type { MeshArrays } from './compile-meshes.ts';
import type { TextureStore } from '../../texture/texture-store.ts';
import {
  interpolateAttributes,
  type VertexAttributes,
} from '../../gltf-material/hit-attributes.ts';
import { gltfEmission, HitAttributes } from '../../gltf-material/shading-fill.ts';

/**
 * The luminance a light sample sees at barycentrics (b1, b2) of triangle t of a glTF
 * mesh: emissive factor × texture × strength × coverage (shading-fill.ts). One probe per
 * mesh, at compile time.
 */
function emissionProbe(
  mesh: MeshArrays,
  table: Float64Array,
  material: number,
  textures: TextureStore,
): (t: number, b1: number, b2: number) => number {
  const attributes: VertexAttributes = {
    uv0: mesh.triUV0.length > 0 ? mesh.triUV0 : null,
    uv1: mesh.triUV1.length > 0 ? mesh.triUV1 : null,
    colors: mesh.triColors.length > 0 ? mesh.triColors : null,
    tangents: null,
  };
  const hit = new HitAttributes();
  const e = { r: 0, g: 0, b: 0 };
  const ix = mesh.triIndices;
  return (t, b1, b2) => {
    interpolateAttributes(attributes, ix[3 * t], ix[3 * t + 1], ix[3 * t + 2], b1, b2, hit);
    gltfEmission(table, textures, material, hit, e);
    return 0.2126 * e.r + 0.7152 * e.g + 0.0722 * e.b;
  };
}

export function gltfMeshPower(
  mesh: MeshArrays,
  first: number,
  count: number,
  table: Float64Array,
  material: number,
  textures: TextureStore,
): number {
  const luminance = emissionProbe(mesh, table, material, textures);
  let power = 0;
  for (let t = first; t < first + count; t++) {
    power += luminance(t, 1 / 3, 1 / 3) * triangleArea(mesh.triPositions, mesh.triIndices, t);
  }
  return power;
}

/**
 * Per triangle of an emissive glTF mesh, appended to `out`: its power for the light
 * BVH's choice among triangles (lights/light-bvh-input.ts), area × the mean luminance
 * a light sample sees at seven points spread over it (its centroid, and points toward
 * each vertex and each edge), so that an emissive texture's bright texels draw the
 * samples. Floored at 10⁻⁶ of what the factor alone would give, so a triangle whose
 * points all miss its texture's bright texels is still chosen now and then; as above,
 * each sample is weighted by its exact emission, so the estimate costs noise, never bias.
 */
export function gltfTrianglePowers(
  mesh: MeshArrays,
  first: number,
  count: number,
  table: Float64Array,
  material: number,
  textures: TextureStore,
  floorLuminance: number,
  out: number[],
): void {
  const luminance = emissionProbe(mesh, table, material, textures);
  for (let t = first; t < first + count; t++) {
    let lum = 0;
    for (let k = 0; k < SPREAD.length; k += 2) lum += luminance(t, SPREAD[k], SPREAD[k + 1]);
    const area = triangleArea(mesh.triPositions, mesh.triIndices, t);
    out.push(Math.max((lum / (SPREAD.length / 2)) * area, 1e-6 * floorLuminance * area));
  }
}

/** Barycentrics (weights of vertices 1 and 2) of gltfTrianglePowers' seven points. */
const SPREAD = [
  1 / 3,
  1 / 3,
  1 / 6,
  1 / 6,
  2 / 3,
  1 / 6,
  1 / 6,
  2 / 3,
  5 / 12,
  5 / 12,
  1 / 6,
  5 / 12,
  5 / 12,
  1 / 6,
];

/**
 * The lights' selection weights: their powers as computed, unless a power or their sum
 * overflows (an emitter of radiance 10¹² and area 10³⁰⁰, or an environment map around
 * a scene 10¹⁶⁰ across: both finite, as the format allows). Then Distribution1D would
 * divide Infinity by Infinity and every light sample would be NaN; instead the weights
 * are the powers relative to the largest, 2^(log2 pᵢ − max log2 p), from `logs` (each
 * power's log2, summed from its finite factors). Only the choice among lights changes:
 * each light sample is still weighted by its exact probability, so this costs noise,
 * never bias. Scenes whose powers add up finitely keep their weights bit for bit.
 */
export function selectionWeights(power: number[], logs: number[]): number[] {
  let total = 0;
  for (const p of power) total += p;
  if (Number.isFinite(total)) return power;
  // A factor that is itself infinite (it should not be: extent.ts refuses such areas)
  // counts as the largest possible, 2^3072, three factors of at most 2^1024.
  const clamped = logs.map((l) => (Number.isNaN(l) ? -Infinity : Math.min(l, 3072)));
  let max = -Infinity;
  for (const l of clamped) if (l > max) max = l;
  return clamped.map((l) => 2 ** (l - max));
}
