/**
 * The glTF part of a compiled scene as the integrator reads it: the material
 * table, the texture store and the per-vertex attributes, as views of the
 * scene's arrays (so a scene unpacked in a worker shares them), and whether
 * any material lets light through by its alpha (then shadow rays must look
 * at what they cross; see integrator/gltf-surface.ts).
 */
import type { HitAttributes } from '../../gltf-material/shading-fill.ts';
import type { VertexAttributes } from '../../gltf-material/hit-attributes.ts';
import type { TextureStore } from '../../texture/texture-store.ts';
import { hasAlphaMaterials } from './compile-gltf.ts';
import type { SceneData } from './compile.ts';

export class GltfScene implements VertexAttributes {
  readonly table: Float64Array;
  readonly textures: TextureStore;
  readonly uv0: Float32Array | null;
  readonly uv1: Float32Array | null;
  readonly colors: Float32Array | null;
  readonly tangents: Float32Array | null;
  /** Some material is MASK or BLEND. */
  readonly hasAlpha: boolean;

  constructor(data: SceneData) {
    this.table = data.gltfMaterials;
    this.textures = { texels: data.texels, info: data.textureInfo };
    this.uv0 = data.triUV0.length > 0 ? data.triUV0 : null;
    this.uv1 = data.triUV1.length > 0 ? data.triUV1 : null;
    this.colors = data.triColors.length > 0 ? data.triColors : null;
    this.tangents = data.triTangents.length > 0 ? data.triTangents : null;
    this.hasAlpha = hasAlphaMaterials(this.table);
  }
}

export type { HitAttributes };
