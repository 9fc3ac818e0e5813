/**
 * The types a loaded glTF model is made of, with no import of glTF-Transform: they are
 * part of the public scene types (Scene, ResolveOptions), and the package's published
 * declarations must compile for a consumer without glTF-Transform's own (whose
 * declarations need a newer lib than ES2022). The modules that use glTF-Transform
 * (flatten.ts, io.ts, tangents.ts) re-export them.
 */
import type { TextureStore } from '../../texture/texture-store.ts';

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
   * Meshes the scene uses more than once, kept once in object space and drawn by
   * instances (accel/instances.ts; docs/gltf.md, Instancing); null when there are none.
   * The arrays above then hold the other triangles only; `bounds` covers both. Absent
   * rather than null without instances, so that a loaded scene without them hashes as
   * before (a film's scene_sha256, src/cli/film-file.ts).
   */
  instances?: GltfInstances;
}

/** One set of triangles (GltfGeometry's arrays) without cameras or instances of its own. */
export type GltfTriangles = Omit<GltfGeometry, 'cameras' | 'instances'>;

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
