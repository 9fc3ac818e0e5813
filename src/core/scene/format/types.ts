/**
 * The scene format `pathwise-scene/1` as plain data (see docs/scene-format.md).
 * These are the types of a scene *after* validation: every optional key has
 * been filled with its documented default, so consumers never re-derive them.
 */

import type { GltfModel } from './gltf-model.ts';

export type Vec3 = [number, number, number];

export interface CameraDesc {
  position: Vec3;
  target: Vec3;
  up: Vec3;
  /** Full vertical field of view in degrees, 0 < fovY < 180. */
  fovY: number;
  /** Lens radius; 0 is a pinhole. */
  aperture: number;
  /** Distance to the plane in focus, along `forward`. */
  focusDistance: number;
}

export interface SettingsDesc {
  width: number;
  height: number;
  maxBounces: number;
  spp: number;
}

export interface DiffuseDesc {
  type: 'diffuse';
  albedo: Vec3;
  emission: Vec3;
}

export interface ConductorDesc {
  type: 'conductor';
  color: Vec3;
  roughness: number;
  emission: Vec3;
}

export interface DielectricDesc {
  type: 'dielectric';
  ior: number;
  color: Vec3;
  roughness: number;
  emission: Vec3;
}

export type MaterialDesc = DiffuseDesc | ConductorDesc | DielectricDesc;

export interface SphereDesc {
  type: 'sphere';
  center: Vec3;
  radius: number;
  material: string;
}

export interface QuadDesc {
  type: 'quad';
  corner: Vec3;
  u: Vec3;
  v: Vec3;
  material: string;
}

/**
 * A triangle mesh, inline or from an `.obj` / `.ply` file. `data` holds its triangles
 * in world space (after `transform`): the loader fills it for inline meshes, and
 * `resolveSceneFiles` (scene/load/load.ts) for files; a scene whose meshes lack `data`
 * cannot be compiled.
 */
export interface MeshDesc {
  type: 'mesh';
  material: string;
  /** The file named by the scene (relative to it), or null for an inline mesh. */
  file: string | null;
  /** Row-major affine 4×4 (16 numbers), or null for the identity. */
  transform: number[] | null;
  data: MeshData | null;
}

/** The triangles of one mesh in world space, zero-area triangles removed. */
export interface MeshData {
  /** x, y, z per vertex. */
  positions: Float64Array;
  /** Three vertex indices per triangle. */
  indices: Uint32Array;
  /**
   * Unit shading normal per vertex, or null when the mesh has none. A vertex of a
   * face without normals (an OBJ face lacking `vn`) has (0, 0, 0): its triangles use
   * the geometric normal.
   */
  normals: Float32Array | null;
  /** Zero-area triangles skipped (the spec asks the renderer to report them). */
  skipped: number;
}

/**
 * The triangles and materials of a glTF 2.0 file (docs/scene-format.md, Meshes from
 * glTF; docs/gltf.md says what is read). `data` holds the loaded model in world space
 * (after the file's node transforms and `transform`), filled by `resolveSceneFiles`.
 */
export interface GltfDesc {
  type: 'gltf';
  /** The `.gltf` or `.glb` file, relative to the scene file. */
  file: string;
  /** Row-major affine 4×4 applied on top of the file's node transforms, or null. */
  transform: number[] | null;
  /**
   * The file's KHR_materials_variants variant to render, by name (pathwise's addition,
   * docs/scene-format.md, "In pathwise: material variants"); absent: the default materials.
   */
  variant?: string;
  data: GltfModel | null;
}

export type ShapeDesc = SphereDesc | QuadDesc | MeshDesc | GltfDesc;

/** An equirectangular environment map (docs/scene-format.md, Environment maps). */
export interface EnvironmentMapDesc {
  type: 'map';
  file: string;
  scale: Vec3;
  /** Degrees about +y. */
  rotationY: number;
  /** The decoded texels, filled by `resolveSceneFiles`. */
  image: EnvironmentImage | null;
}

export interface EnvironmentImage {
  width: number;
  height: number;
  /** Linear RGB per texel, row 0 at the top (the +y pole), without `scale`. */
  rgb: Float32Array;
}

/**
 * A punctual light: a point, a spot or a directional light, a delta light sampled only by
 * next-event estimation (lights/punctual.ts). From the scene's `lights`
 * (docs/scene-format.md, Lights) or a glTF file's KHR_lights_punctual (docs/gltf.md).
 */
export interface LightDesc {
  type: 'point' | 'spot' | 'directional';
  /** Where a point or spot light is ([0, 0, 0] for a directional light). */
  position: Vec3;
  /** Unit direction the light travels (spot, directional; [0, 0, -1] for a point light). */
  direction: Vec3;
  /** Linear RGB factor of `intensity`. */
  color: Vec3;
  /** Candela (point, spot) or lux (directional). */
  intensity: number;
  /** Degrees from a spot's axis: full intensity within the inner cone, none beyond the outer. */
  innerConeAngle: number;
  outerConeAngle: number;
  /** glTF's `range`: no light beyond this distance; null for none (the scene format's). */
  range: number | null;
}

export interface Scene {
  format: 'pathwise-scene/1';
  name: string;
  camera: CameraDesc;
  settings: SettingsDesc;
  materials: Record<string, MaterialDesc>;
  shapes: ShapeDesc[];
  /** Constant radiance of escaping rays; [0, 0, 0] when an environment map is used. */
  environment: Vec3;
  /**
   * The environment map, or null (or absent, in a scene built by code) for the constant
   * environment. The loader always sets it.
   */
  environmentMap?: EnvironmentMapDesc | null;
  /** Punctual lights; absent when there are none. */
  lights?: LightDesc[];
}

/** Hard limits on input size; each has a clear error in the loader. */
export const LIMITS = {
  fileBytes: 16 * 1024 * 1024,
  shapes: 100_000,
  pixels: 16_777_216,
  spp: 1_048_576,
  maxBounces: 64,
  /** Triangles per scene, over all meshes, counted as read (before zero-area ones are skipped). */
  triangles: 10_000_000,
  /** Bytes of one mesh file. */
  meshFileBytes: 1024 * 1024 * 1024,
  envMapWidth: 16384,
  envMapHeight: 8192,
} as const;

export const DEFAULT_SETTINGS: SettingsDesc = {
  width: 512,
  height: 512,
  maxBounces: 6,
  spp: 512,
};
