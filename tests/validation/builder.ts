/**
 * The scene builder the generator's archetypes write into: named random
 * materials, shapes in the scene's own unit frame (the generator maps it
 * by a random similarity at the end), light bookkeeping, and the coverage
 * features each scene exercises.
 *
 * Extension points (see docs/validation.md, "Extending the generator"):
 * - a new shape kind (e.g. `mesh` once the core loads it) is one more
 *   `ShapeJson` variant, one `add…` method here that records it, and one
 *   case in `transformShape` (generate.ts); an `OBJECT_MAKERS` entry in
 *   archetypes.ts then places it in scenes;
 * - a new environment kind (an environment map) is one more
 *   `EnvironmentJson` variant and an `ENVIRONMENT_MAKERS` entry in
 *   archetypes.ts.
 */
import type { GltfObject } from './gltf-files.ts';
import type { Rng } from './rng.ts';
import { cross, length, type Vec3 } from './vec.ts';

/** Everything a generated scene can be tagged with; the generator test checks each occurs. */
export const FEATURES = [
  'sphere-light',
  'quad-light',
  'tiny-light',
  'large-light',
  'light-near-receiver',
  'huge-receiver',
  'ground-sphere',
  'ground-sphere-1e5',
  'multiple-lights',
  'power-ratio-1000',
  'environment',
  'no-environment',
  'camera-in-room',
  'camera-outside',
  'camera-in-glass',
  'aperture',
  'bounces-0',
  'bounces-12',
  'scale-1e-4',
  'scale-1e4',
  'rotated',
  'grazing',
  'diffuse',
  'conductor',
  'mirror',
  'dielectric',
  'emissive-non-diffuse',
] as const;

/**
 * What the mesh family (archetypes-mesh.ts) adds; its own coverage list, checked over
 * its consistency scenes and its references (the classic scenes have none of these).
 */
export const MESH_FEATURES = [
  'mesh',
  'closed-mesh',
  'open-mesh',
  'thin-sheet',
  'shading-normals',
  'mirrored',
  'mirrored-inside-out',
  'anisotropic',
  'transform-scale-extreme',
  'mesh-file-obj',
  'mesh-file-ply',
  'emissive-mesh',
  'emissive-mesh-tiny',
  'emissive-mesh-large',
  'emissive-mesh-grazing',
  'emissive-mesh-near-receiver',
  'glass-mesh',
  'camera-in-glass-mesh',
  'bvh',
  'env-map',
  'env-map-constant',
  'env-map-sun',
  'env-map-gradient',
  'env-map-rotated',
  'env-map-rgb-scale',
  'env-map-hdr',
  'env-map-pfm',
  'env-map-only',
] as const;
/** What the glTF family (archetypes-gltf.ts) covers; checked over its consistency scenes. */
export const GLTF_FEATURES = [
  'gltf',
  'gltf-metal',
  'gltf-dielectric',
  'gltf-smooth',
  'gltf-rough',
  'gltf-transmission',
  'gltf-specular',
  'gltf-ior',
  'gltf-clearcoat',
  'gltf-sheen',
  'gltf-thin-glass',
  'gltf-diffuse-transmission',
  'gltf-volume',
  'gltf-attenuation',
  'gltf-dispersion',
  'gltf-iridescence',
  'gltf-anisotropy',
  'gltf-open-mesh',
] as const;
export type GltfFeature = (typeof GLTF_FEATURES)[number];
/** What the punctual family (archetypes-punctual.ts) covers. */
export const PUNCTUAL_FEATURES = [
  'punctual-point',
  'punctual-spot',
  'punctual-directional',
] as const;
export type Feature =
  | (typeof FEATURES)[number]
  | (typeof MESH_FEATURES)[number]
  | GltfFeature
  | (typeof PUNCTUAL_FEATURES)[number];

export type MaterialJson =
  | { type: 'diffuse'; albedo: Vec3; emission?: Vec3 }
  | { type: 'conductor'; color: Vec3; roughness: number; emission?: Vec3 }
  | { type: 'dielectric'; ior: number; color: Vec3; emission?: Vec3 };

export type ShapeJson =
  | { type: 'sphere'; center: Vec3; radius: number; material: string }
  | { type: 'quad'; corner: Vec3; u: Vec3; v: Vec3; material: string }
  | MeshJson
  | GltfShapeJson;

/** A glTF model (generate.ts writes its `.glb` beside the scene and fills in `file`). */
export interface GltfShapeJson {
  type: 'gltf';
  file: string;
  /** Row-major 4×4, last row 0 0 0 1. */
  transform?: number[];
}

/**
 * A mesh as the scene file has it: inline arrays, or a file written beside the
 * scene (generate.ts writes it from the same arrays, after the similarity).
 */
export interface MeshJson {
  type: 'mesh';
  material: string;
  positions?: number[];
  indices?: number[];
  normals?: number[];
  file?: string;
  /** Row-major 4×4, last row 0 0 0 1. */
  transform?: number[];
}

/** How a mesh is stored in the scene file. */
export type MeshStorage = 'inline' | 'obj' | 'ply-ascii' | 'ply-le' | 'ply-be';

/** An equirectangular map as generated: texels (row 0 at the top) and how it is written. */
export interface EnvironmentMapSpec {
  width: number;
  height: number;
  rgb: Float32Array;
  /** The file's bytes; `rgb` is what they decode to. */
  bytes: Uint8Array;
  format: 'hdr' | 'pfm';
  scale: number | Vec3;
  rotationY: number;
  /** What it depicts, for bookkeeping: 'constant', 'gradient', 'sun'. */
  kind: string;
}

/** `null`: no environment (black); a colour; or an environment map. */
export type EnvironmentJson = Vec3 | EnvironmentMapSpec | null;

export interface CameraJson {
  position: Vec3;
  target: Vec3;
  up: Vec3;
  fovY: number;
  aperture?: number;
  focusDistance?: number;
}

export interface SceneJson {
  format: 'pathwise-scene/1';
  name: string;
  camera: CameraJson;
  settings: { width: number; height: number; maxBounces: number; spp: number };
  materials: Record<string, MaterialJson>;
  shapes: ShapeJson[];
  environment?: Vec3 | { type: 'map'; file: string; scale?: number | Vec3; rotationY?: number };
  /** Punctual lights (docs/scene-format.md): the punctual family's. */
  lights?: PunctualLightJson[];
}

/** A scene-format punctual light (gltf-draw-lights.ts draws them): world space, degrees. */
export interface PunctualLightJson {
  type: 'point' | 'spot' | 'directional';
  position?: Vec3;
  direction?: Vec3;
  intensity: number;
  color: Vec3;
  innerConeAngle?: number;
  outerConeAngle?: number;
}

export type MaterialKind = 'diffuse' | 'conductor' | 'dielectric';

/** One emitter as placed, for the archetypes' own bookkeeping. */
export interface LightInfo {
  kind: 'sphere' | 'quad' | 'mesh';
  /** Radius, or the square root of the quad's area. */
  size: number;
  /** The radiance it was given. */
  emission: number;
}

export class SceneBuilder {
  readonly materials: Record<string, MaterialJson> = {};
  readonly shapes: ShapeJson[] = [];
  readonly features = new Set<Feature>();
  readonly lights: LightInfo[] = [];
  /** Storage of each mesh shape, by its index in `shapes` (inline when absent). */
  readonly meshStorage = new Map<number, MeshStorage>();
  environment: EnvironmentJson = null;
  /** The glTF model of each gltf shape, by its index in `shapes`. */
  readonly gltfObjects = new Map<number, GltfObject>();
  /** Punctual lights, in the archetype's unit frame. */
  readonly punctualLights: PunctualLightJson[] = [];
  private count = 0;

  constructor(readonly rng: Rng) {}

  tag(...features: Feature[]): void {
    for (const f of features) this.features.add(f);
  }

  /** A random colour with every channel in [lo, hi]. */
  color(lo: number, hi: number): Vec3 {
    const r = this.rng;
    return [r.uniform(lo, hi), r.uniform(lo, hi), r.uniform(lo, hi)];
  }

  /** A new material of the given kind (random kind by default) with random parameters. */
  material(kind?: MaterialKind, emission?: Vec3): string {
    const r = this.rng;
    const k =
      kind ??
      r.weighted<MaterialKind>([
        ['diffuse', 0.55],
        ['conductor', 0.3],
        ['dielectric', 0.15],
      ]);
    let m: MaterialJson;
    if (k === 'diffuse') {
      m = { type: 'diffuse', albedo: this.color(0.05, 0.9) };
    } else if (k === 'conductor') {
      // A quarter are perfect mirrors (a delta BSDF: no light sampling at all).
      const roughness = r.chance(0.25) ? 0 : r.uniform(0.05, 1);
      m = { type: 'conductor', color: this.color(0.3, 1), roughness };
      this.tag(roughness === 0 ? 'mirror' : 'conductor');
    } else {
      m = { type: 'dielectric', ior: r.uniform(1.1, 2.4), color: this.color(0.6, 1) };
    }
    this.tag(k === 'conductor' ? 'conductor' : k);
    if (emission !== undefined) {
      m.emission = emission;
      if (k !== 'diffuse') this.tag('emissive-non-diffuse');
    }
    const name = `${k}${this.count++}`;
    this.materials[name] = m;
    return name;
  }

  /**
   * An emitter's material: radiance `radiance` with a random tint; mostly
   * diffuse (black or grey albedo), sometimes a conductor or glass.
   */
  emitter(radiance: number): string {
    const r = this.rng;
    const tint = this.color(0.5, 1);
    const emission: Vec3 = [radiance * tint[0], radiance * tint[1], radiance * tint[2]];
    const kind = r.weighted<MaterialKind>([
      ['diffuse', 0.88],
      ['conductor', 0.06],
      ['dielectric', 0.06],
    ]);
    if (kind === 'diffuse' && r.chance(0.6)) {
      const name = `lamp${this.count++}`;
      this.materials[name] = { type: 'diffuse', albedo: [0, 0, 0], emission };
      this.tag('diffuse');
      return name;
    }
    return this.material(kind, emission);
  }

  /** A glTF model; its material is its own (not in `materials`). */
  gltf(o: GltfObject): void {
    this.gltfObjects.set(this.shapes.length, o);
    this.shapes.push({ type: 'gltf', file: '', transform: o.transform });
  }

  sphere(center: Vec3, radius: number, material: string): void {
    this.shapes.push({ type: 'sphere', center, radius, material });
    this.noteLight(material, 'sphere', radius);
  }

  quad(corner: Vec3, u: Vec3, v: Vec3, material: string): void {
    this.shapes.push({ type: 'quad', corner, u, v, material });
    this.noteLight(material, 'quad', Math.sqrt(length(cross(u, v))));
  }

  /**
   * A triangle mesh (world-space arrays, or local ones with a `transform`), stored
   * inline or as a file; `area` is its world-space area, for the light bookkeeping.
   */
  mesh(
    mesh: Omit<MeshJson, 'type' | 'material' | 'file'>,
    material: string,
    area: number,
    storage: MeshStorage = 'inline',
  ): void {
    this.shapes.push({ type: 'mesh', material, ...mesh });
    if (storage !== 'inline') this.meshStorage.set(this.shapes.length - 1, storage);
    this.tag('mesh');
    this.noteLight(material, 'mesh', Math.sqrt(area));
  }

  /**
   * An axis-aligned box of six quads from `lo` to `hi`, normals outward
   * (a closed solid: glass when the material is a dielectric) or inward
   * (a room). `skip` leaves out faces by name.
   */
  box(lo: Vec3, hi: Vec3, material: string, outward: boolean, skip: string[] = []): void {
    const [x0, y0, z0] = lo;
    const [x1, y1, z1] = hi;
    const dx = x1 - x0;
    const dy = y1 - y0;
    const dz = z1 - z0;
    // Each face as (corner, u, v) with cross(u, v) pointing outward.
    const faces: [string, Vec3, Vec3, Vec3][] = [
      ['floor', [x0, y0, z0], [dx, 0, 0], [0, 0, dz]],
      ['ceiling', [x0, y1, z0], [0, 0, dz], [dx, 0, 0]],
      ['left', [x0, y0, z0], [0, 0, dz], [0, dy, 0]],
      ['right', [x1, y0, z0], [0, dy, 0], [0, 0, dz]],
      ['back', [x0, y0, z1], [dx, 0, 0], [0, dy, 0]],
      ['front', [x0, y0, z0], [0, dy, 0], [dx, 0, 0]],
    ];
    for (const [name, corner, u, v] of faces) {
      if (skip.includes(name)) continue;
      if (outward) this.quad(corner, u, v, material);
      else this.quad(corner, v, u, material);
    }
  }

  private noteLight(material: string, kind: LightInfo['kind'], size: number): void {
    const e = this.materials[material].emission;
    if (e === undefined) return;
    this.lights.push({ kind, size, emission: Math.max(...e) });
    this.tag(kind === 'sphere' ? 'sphere-light' : kind === 'quad' ? 'quad-light' : 'emissive-mesh');
  }
}
