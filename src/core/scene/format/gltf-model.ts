/**
 * The types a loaded glTF model is made of, with no import of glTF-Transform: they are
 * part of the public scene types (Scene, ResolveOptions), and the package's published
 * declarations must compile for a consumer without glTF-Transform's own (whose
 * declarations need a newer lib than ES2022). The modules that use glTF-Transform
 * (flatten.ts, io.ts, tangents.ts) re-export them.
 */
import type { DecodedImage } from '../../texture/decoded-image.ts';
import type { Ktx2Transcoder } from '../../texture/ktx2-transcode.ts';
import type { TextureStore } from '../../texture/texture-store.ts';
import type { LightDesc } from './types.ts';

export type { Ktx2Transcoder };

/** Decodes one WebP image to RGBA8 (libwebp in Node, the browser's own decoder). */
export type WebpDecoder = (bytes: Uint8Array) => Promise<DecodedImage>;

export interface GltfCamera {
  position: [number, number, number];
  target: [number, number, number];
  up: [number, number, number];
  /** Full vertical field of view in degrees. */
  fovY: number;
}

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
 * meshoptimizer's decoder (`meshoptimizer/decoder`, MeshoptDecoder), as the loader uses it:
 * decodes one EXT_/KHR_meshopt_compression stream of `count` elements of `size` bytes
 * into `target`; throws on a malformed stream. Structural, so that the core does not
 * import the package.
 */
export interface MeshoptDecoderLike {
  readonly ready: Promise<void>;
  decodeGltfBuffer(
    target: Uint8Array,
    count: number,
    size: number,
    source: Uint8Array,
    mode: string,
    filter?: string,
  ): void;
}

/**
 * The glTF build of the Draco decoder (`draco3dgltf`'s `createDecoderModule()` once
 * resolved), as the loader uses it (core/gltf/draco.ts). Structural: the core does not
 * import the package.
 */
export interface DracoDecoderModule {
  Decoder: new () => object;
  DecoderBuffer: new () => { Init(data: Uint8Array, length: number): void };
  Mesh: new () => { ptr: number; num_faces(): number; num_points(): number };
  TRIANGULAR_MESH: number;
  DT_FLOAT32: number;
  DT_INT8: number;
  DT_UINT8: number;
  DT_INT16: number;
  DT_UINT16: number;
  DT_UINT32: number;
  HEAPU8: Uint8Array;
  _malloc(bytes: number): number;
  _free(ptr: number): void;
  destroy(object: object): void;
}

/**
 * Decoders of compressed glTF data, each a lazy getter: the loader calls one only when
 * the file uses its extension (a plain file calls none), and a platform caches what it
 * returns. A missing getter: the extension is not supported on this platform (the
 * fallback data is read when the file has some, else one error). Structural, so that
 * the core imports none of the packages.
 */
export interface GltfDecoders {
  /** EXT_meshopt_compression and KHR_meshopt_compression. */
  meshopt?(): Promise<MeshoptDecoderLike>;
  /** KHR_draco_mesh_compression. */
  draco?(): Promise<DracoDecoderModule>;
  /** EXT_texture_webp. */
  webp?(): Promise<WebpDecoder>;
  /** KHR_texture_basisu: KTX2 files of Basis Universal data. */
  ktx2?(): Promise<Ktx2Transcoder>;
}

/** Reads the file at `path` (relative to the scene), refusing files longer than maxBytes. */
export interface GltfFileReader {
  read(path: string, maxBytes: number): Promise<Uint8Array>;
  /**
   * Folders, besides the model's and the scene's, whose files a model may name
   * (normalized: relative to the scene's folder, `..` only leading, or absolute); the
   * command line's `--allow-read`. Absent: none (core/gltf/io.ts, resolveUri).
   */
  readonly allowedFolders?: readonly string[];
}

export interface GltfGeometry {
  /** World-space x, y, z per vertex. */
  positions: Float64Array;
  /** Three vertex indices per triangle. */
  indices: Uint32Array;
  /** Unit shading normal per vertex, (0, 0, 0) where the primitive has none; null if none has. */
  normals: Float32Array | null;
  /** TEXCOORD_0 / TEXCOORD_1 per vertex (0 where absent), or null when no primitive has the set. */
  uv0: Float32Array | null;
  uv1: Float32Array | null;
  /** COLOR_0 as linear RGBA per vertex (white where absent), or null. */
  colors: Float32Array | null;
  /**
   * World-space unit tangent and handedness (x, y, z, w) per vertex, for
   * normal maps (from the file, or MikkTSpace); (0, 0, 0, 0) where a vertex
   * has none. Null when no material has a normal map.
   */
  tangents: Float32Array | null;
  /** Material (row of the glTF material table) per triangle. */
  triangleMaterial: Uint32Array;
  /** Zero-area triangles skipped. */
  skipped: number;
  /** Axis-aligned bounds of the positions (min x, y, z, max x, y, z); empty: +∞, −∞. */
  bounds: Float64Array;
  /** Perspective cameras of the scene, in traversal order. */
  cameras: GltfCamera[];
  /**
   * KHR_lights_punctual lights of the scene in world space, in traversal order
   * (gltf/punctual-lights.ts); absent when there are none.
   */
  lights?: LightDesc[];
  /**
   * Meshes the scene uses more than once, kept once in object space and drawn by
   * instances (accel/instances.ts; docs/gltf.md, Instancing); null when there are none.
   * The arrays above then hold the other triangles only; `bounds` covers both. Absent
   * rather than null without instances, so that a loaded scene without them hashes as
   * before (a film's scene_sha256, src/cli/film-file.ts).
   */
  instances?: GltfInstances;
}

/** One set of triangles (GltfGeometry's arrays) without cameras or instances of its own. */
export type GltfTriangles = Omit<GltfGeometry, 'cameras' | 'instances' | 'lights'>;

export interface GltfInstances {
  /** Each instanced mesh in object space (its primitives' triangles, in file order). */
  meshes: GltfTriangles[];
  /** Per instance: the mesh it draws (index into `meshes`). */
  mesh: Uint32Array;
  /**
   * Per instance: the object-to-world affine transform, 12 numbers, column-major 3×4
   * (m00 m10 m20, m01 m11 m21, m02 m12 m22, tx ty tz), times the scene shape's transform.
   */
  matrices: Float64Array;
}

export interface GltfModel extends GltfGeometry {
  /** GM_STRIDE numbers per material (material-table.ts); the last is glTF's default material. */
  materials: Float64Array;
  textures: TextureStore;
  /** One line each, in the order met. */
  warnings: string[];
}
