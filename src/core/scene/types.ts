/**
 * The scene format `pathwise-scene/1` as plain data (see docs/scene-format.md).
 * These are the types of a scene *after* validation: every optional key has
 * been filled with its documented default, so consumers never re-derive them.
 */

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

export type ShapeDesc = SphereDesc | QuadDesc;

export interface Scene {
  format: 'pathwise-scene/1';
  name: string;
  camera: CameraDesc;
  settings: SettingsDesc;
  materials: Record<string, MaterialDesc>;
  shapes: ShapeDesc[];
  environment: Vec3;
}

/** Hard limits on input size; each has a clear error in the loader. */
export const LIMITS = {
  fileBytes: 16 * 1024 * 1024,
  shapes: 100_000,
  pixels: 16_777_216,
  spp: 1_048_576,
  maxBounces: 64,
} as const;

export const DEFAULT_SETTINGS: SettingsDesc = {
  width: 512,
  height: 512,
  maxBounces: 6,
  spp: 512,
};
