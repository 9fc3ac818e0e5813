/**
 * The scene's glTF shapes in the form the tracer reads (compile.ts): each model's
 * triangles split into one mesh per glTF material (scene/compile/groups.ts), so that an
 * emissive material is one light sampled by area like every emissive mesh; one
 * scene material of kind MATERIAL_GLTF per row of the models' material tables,
 * pointing at that row (M_GLTF_INDEX); the tables of all models in one table and
 * their textures in one store, image indices renumbered.
 *
 * Only what the models use is kept: a texture-coordinate set no texture reads is
 * dropped, tangents exist only where a material has a normal map (flatten.ts).
 */
import {
  MATERIAL_GLTF,
  MATERIAL_STRIDE,
  M_DELTA,
  M_EMISSION,
  M_EMISSIVE,
  M_GEOMETRIC_SIDE,
  M_GLTF_INDEX,
  M_TYPE,
} from '../../bsdf/materials.ts';
import { groupByMaterial } from './groups.ts';
import {
  ALPHA_OPAQUE,
  B_IMAGE,
  B_TEXCOORD,
  BINDING_STRIDE,
  GM_ALPHA_MODE,
  GM_EMISSIVE,
  GM_STRIDE,
  GM_TEXTURES,
  GM_DIFFUSE_TRANSMISSION,
  GM_TRANSMISSION,
  GM_UNLIT,
  TEX_COUNT,
} from '../../gltf-material/material-table.ts';
import {
  EMPTY_TEXTURES,
  INFO_STRIDE,
  I_OFFSET,
  type TextureStore,
} from '../../texture/texture-store.ts';
import type { MeshInput } from './compile-meshes.ts';
import type { GltfDesc } from '../format/types.ts';
import type { GltfTriangles } from '../format/gltf-model.ts';

export interface CompiledGltf {
  /** One mesh per (model, material) with triangles. */
  meshes: MeshInput[];
  /** MATERIAL_STRIDE numbers per row of `table`: the scene materials the meshes use. */
  materials: Float64Array;
  /** GM_STRIDE numbers per row: every model's glTF material table, one after another. */
  table: Float64Array;
  textures: TextureStore;
  /**
   * Instanced meshes (object space), each split by material like `meshes`: the meshes
   * of BLAS b are blasMeshes[blasFirst[b], blasFirst[b + 1]). Empty without instances.
   */
  blasMeshes: MeshInput[];
  blasFirst: number[];
  /** Per instance: its BLAS and object-to-world 3×4 (12 numbers, gltf-model.ts). */
  instanceBlas: number[];
  instanceMatrices: Float64Array;
}

/** Whether row m of a glTF table reads texture-coordinate set `set`. */
function usesSet(table: Float64Array, rows: number, set: number): boolean {
  for (let m = 0; m < rows; m++) {
    for (let s = 0; s < TEX_COUNT; s++) {
      const b = m * GM_STRIDE + GM_TEXTURES + s * BINDING_STRIDE;
      if (table[b + B_IMAGE] >= 0 && table[b + B_TEXCOORD] === set) return true;
    }
  }
  return false;
}

/**
 * Compiles the glTF shapes (their `data` loaded). `firstMaterial` is the number of
 * the scene's own materials: the glTF ones follow them.
 */
export function compileGltfShapes(shapes: GltfDesc[], firstMaterial: number): CompiledGltf {
  const models = shapes.map((s) => s.data!);
  let rows = 0;
  let images = 0;
  let texels = 0;
  for (const m of models) {
    rows += m.materials.length / GM_STRIDE;
    images += m.textures.info.length / INFO_STRIDE;
    texels += m.textures.texels.length;
  }
  const table = new Float64Array(rows * GM_STRIDE);
  const materials = new Float64Array(rows * MATERIAL_STRIDE);
  // One model's store is used as it is (it may already be shared memory); several are
  // concatenated once.
  const withTextures = models.filter((m) => m.textures.info.length > 0);
  let textures: TextureStore = EMPTY_TEXTURES;
  if (withTextures.length === 1) textures = withTextures[0].textures;
  else if (withTextures.length > 1) {
    // Plain memory: pack.ts copies the store into the scene's (shared) buffer anyway.
    textures = { texels: new Uint16Array(texels), info: new Int32Array(images * INFO_STRIDE) };
  }
  const meshes: MeshInput[] = [];
  const blasMeshes: MeshInput[] = [];
  const blasFirst: number[] = [0];
  const instanceBlas: number[] = [];
  const matrixParts: Float64Array[] = [];
  let row = 0;
  let image = 0;
  let texel = 0;
  for (const model of models) {
    const n = model.materials.length / GM_STRIDE;
    const own = model.textures;
    const ownImages = own.info.length / INFO_STRIDE;
    table.set(model.materials, row * GM_STRIDE);
    if (withTextures.length > 1 && ownImages > 0) {
      textures.texels.set(own.texels, texel);
      for (let i = 0; i < ownImages; i++) {
        const o = (image + i) * INFO_STRIDE;
        textures.info.set(own.info.subarray(i * INFO_STRIDE, (i + 1) * INFO_STRIDE), o);
        // Offsets count texels (4 samples each).
        textures.info[o + I_OFFSET] += texel / 4;
      }
    }
    for (let m = 0; m < n; m++) {
      const o = (row + m) * GM_STRIDE;
      for (let s = 0; s < TEX_COUNT; s++) {
        const b = o + GM_TEXTURES + s * BINDING_STRIDE;
        if (table[b + B_IMAGE] >= 0) table[b + B_IMAGE] += image;
      }
      const r = (row + m) * MATERIAL_STRIDE;
      materials[r + M_TYPE] = MATERIAL_GLTF;
      materials[r + M_GLTF_INDEX] = row + m;
      const er = table[o + GM_EMISSIVE],
        eg = table[o + GM_EMISSIVE + 1],
        eb = table[o + GM_EMISSIVE + 2];
      // The factor; an emissive texture only scales it (and is looked up per hit).
      materials[r + M_EMISSION] = er;
      materials[r + M_EMISSION + 1] = eg;
      materials[r + M_EMISSION + 2] = eb;
      materials[r + M_EMISSIVE] = er > 0 || eg > 0 || eb > 0 ? 1 : 0;
      if (table[o + GM_UNLIT] !== 0) {
        // KHR_materials_unlit: its base colour is seen (emission, per hit) but it is no
        // light (zero power: not in the light list), and nothing is lit at it (no NEE).
        materials[r + M_EMISSION] = 0;
        materials[r + M_EMISSION + 1] = 0;
        materials[r + M_EMISSION + 2] = 0;
        materials[r + M_EMISSIVE] = 1;
        materials[r + M_DELTA] = 1;
      }
      // A transmissive material (specular or diffuse) scatters to the far side too: its
      // BSDF needs the outward normal to tell the sides apart.
      materials[r + M_GEOMETRIC_SIDE] =
        table[o + GM_TRANSMISSION] > 0 || table[o + GM_DIFFUSE_TRANSMISSION] > 0 ? 1 : 0;
    }
    const keepUv0 = usesSet(model.materials, n, 0);
    const keepUv1 = usesSet(model.materials, n, 1);
    const groups = (g: GltfTriangles, out: MeshInput[]): void => {
      for (const grp of groupByMaterial(g)) {
        out.push({
          data: {
            positions: grp.positions,
            indices: grp.indices,
            normals: grp.normals,
            skipped: 0,
          },
          material: firstMaterial + row + grp.material,
          attributes: {
            uv0: keepUv0 ? grp.uv0 : null,
            uv1: keepUv1 ? grp.uv1 : null,
            colors: grp.colors,
            tangents: grp.tangents,
          },
        });
      }
    };
    groups(model, meshes);
    const inst = model.instances ?? null;
    if (inst !== null) {
      const base = blasFirst.length - 1;
      for (const g of inst.meshes) {
        groups(g, blasMeshes);
        blasFirst.push(blasMeshes.length);
      }
      for (const b of inst.mesh) instanceBlas.push(base + b);
      matrixParts.push(inst.matrices);
    }
    row += n;
    image += ownImages;
    texel += own.texels.length;
  }
  const instanceMatrices = new Float64Array(instanceBlas.length * 12);
  let at = 0;
  for (const m of matrixParts) {
    instanceMatrices.set(m, at);
    at += m.length;
  }
  return {
    meshes,
    materials,
    table,
    textures,
    blasMeshes,
    blasFirst,
    instanceBlas,
    instanceMatrices,
  };
}

/** Whether any row of a glTF table is not opaque (MASK or BLEND). */
export function hasAlphaMaterials(table: Float64Array): boolean {
  for (let o = 0; o < table.length; o += GM_STRIDE) {
    if (table[o + GM_ALPHA_MODE] !== ALPHA_OPAQUE) return true;
  }
  return false;
}
