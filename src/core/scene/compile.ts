/**
 * Compiles a validated scene into the flat typed arrays the tracer reads.
 * Only what the scene has is built: no sphere buffer without spheres, no
 * light list without emitters, no BVH below the measured crossover (see
 * BVH_THRESHOLD), so the hot loops never pay for kinds that are absent.
 */
import { buildBvh, type Bvh } from '../accel/bvh.ts';
import { PrimitiveBoxes, quadBoxes, sphereBoxes, triangleBoxes } from '../accel/primitives.ts';
import { compileMaterials, MATERIAL_STRIDE, M_EMISSION, M_EMISSIVE } from '../bsdf/materials.ts';
import { LIGHT_ENVIRONMENT, SHAPE_QUAD, SHAPE_SPHERE, SHAPE_TRIANGLE } from '../geometry/ray.ts';
import { TriangleHit, TriangleRay } from '../geometry/triangle.ts';
import {
  compileQuads,
  compileSpheres,
  QUAD_STRIDE,
  Q_AREA,
  quadScale,
  SPHERE_STRIDE,
  sphereScale,
} from '../geometry/shapes.ts';
import { EnvironmentMap } from '../lights/environment-map.ts';
import { LightList } from '../lights/lights.ts';
import { MeshLight } from '../lights/mesh-light.ts';
import { sceneRadius } from './bounds.ts';
import { CompiledMeshes } from './compile-meshes.ts';
import type { MeshDesc, QuadDesc, Scene, SphereDesc } from './types.ts';

/**
 * Shape count from which a BVH beats the plain loop over all shapes,
 * measured with `node scripts/run-ts.mjs bench/bvh-crossover.ts` (random
 * spheres, 80×80, one process per point): on this project's 2-core machine
 * the plain loop won up to 34 shapes and the BVH from 50 on
 * (bench/results/bvh-crossover.json).
 */
export const BVH_THRESHOLD = 48;

export interface CompileOptions {
  /** Force (true) or forbid (false) the BVH; default: by BVH_THRESHOLD. */
  bvh?: boolean;
}

export class CompiledScene {
  readonly materials: Float64Array;
  readonly sphereCount: number;
  readonly spheres: Float64Array;
  readonly sphereMaterial: Int32Array;
  /** Light index of each sphere, −1 when it does not emit. */
  readonly sphereLight: Int32Array;
  readonly quadCount: number;
  readonly quads: Float64Array;
  readonly quadMaterial: Int32Array;
  readonly quadLight: Int32Array;
  /** The triangles of all meshes (compile-meshes.ts), or null without meshes. */
  readonly meshes: CompiledMeshes | null;
  readonly triCount: number;
  readonly triPositions: Float64Array;
  readonly triIndices: Uint32Array;
  /** Light index of each mesh, −1 when it does not emit. */
  readonly meshLight: Int32Array;
  /** Per-ray constants of the triangle test and the barycentrics of the kept hit (trace.ts). */
  readonly triRay = new TriangleRay();
  readonly triHit = new TriangleHit();
  readonly lights: LightList | null;
  /** The environment map, or null for the constant environment (envR, envG, envB). */
  readonly envMap: EnvironmentMap | null;
  readonly envR: number;
  readonly envG: number;
  readonly envB: number;
  readonly hasEnvironment: boolean;
  readonly bvh: Bvh | null;
  /**
   * Traversal stacks (node indices and entry distances), sized for the
   * BVH's depth plus one (stackT[0] holds the nearest hit so far). Per
   * scene object, never shared between threads.
   */
  readonly stack: Int32Array;
  readonly stackT: Float64Array;

  constructor(scene: Scene, options: CompileOptions = {}) {
    const meshDescs = scene.shapes.filter((s): s is MeshDesc => s.type === 'mesh');
    if (meshDescs.some((m) => m.data === null) || scene.environmentMap?.image === null) {
      throw new Error(
        'the scene names files that were not read: load it with loadScene or resolveSceneFiles',
      );
    }
    const names = Object.keys(scene.materials);
    const materialIndex = new Map(names.map((n, i) => [n, i]));
    this.materials = compileMaterials(names.map((n) => scene.materials[n]));
    const spheres = scene.shapes.filter((s): s is SphereDesc => s.type === 'sphere');
    const quads = scene.shapes.filter((s): s is QuadDesc => s.type === 'quad');
    this.sphereCount = spheres.length;
    this.quadCount = quads.length;
    this.spheres = compileSpheres(spheres);
    this.quads = compileQuads(quads);
    this.sphereMaterial = Int32Array.from(spheres, (s) => materialIndex.get(s.material)!);
    this.quadMaterial = Int32Array.from(quads, (s) => materialIndex.get(s.material)!);
    this.sphereLight = new Int32Array(this.sphereCount).fill(-1);
    this.quadLight = new Int32Array(this.quadCount).fill(-1);
    const meshes =
      meshDescs.length > 0 ? new CompiledMeshes(meshDescs, (n) => materialIndex.get(n)!) : null;
    this.meshes = meshes;
    this.triCount = meshes?.triangleCount ?? 0;
    this.triPositions = meshes?.positions ?? new Float64Array(0);
    this.triIndices = meshes?.indices ?? new Uint32Array(0);
    this.meshLight = new Int32Array(meshes?.count ?? 0).fill(-1);

    const kinds: number[] = [];
    const shapes: number[] = [];
    const power: number[] = [];
    const scale: number[] = [];
    const material: number[] = [];
    const meshLights: (MeshLight | null)[] = [];
    const emitted = (m: number): number => {
      const o = m * MATERIAL_STRIDE;
      if (this.materials[o + M_EMISSIVE] === 0) return 0;
      const e = this.materials;
      // Selection weight: luminance, floored so a pure-blue emitter is still chosen.
      const lum =
        0.2126 * e[o + M_EMISSION] +
        0.7152 * e[o + M_EMISSION + 1] +
        0.0722 * e[o + M_EMISSION + 2];
      return Math.max(
        lum,
        1e-6 * Math.max(e[o + M_EMISSION], e[o + M_EMISSION + 1], e[o + M_EMISSION + 2]),
      );
    };
    for (let i = 0; i < this.sphereCount; i++) {
      const lum = emitted(this.sphereMaterial[i]);
      if (lum === 0) continue;
      const r = this.spheres[i * SPHERE_STRIDE + 3];
      this.sphereLight[i] = kinds.length;
      kinds.push(SHAPE_SPHERE);
      shapes.push(i);
      power.push(lum * 4 * Math.PI * r * r);
      scale.push(sphereScale(this.spheres, i));
      material.push(this.sphereMaterial[i]);
    }
    for (let i = 0; i < this.quadCount; i++) {
      const lum = emitted(this.quadMaterial[i]);
      if (lum === 0) continue;
      this.quadLight[i] = kinds.length;
      kinds.push(SHAPE_QUAD);
      shapes.push(i);
      power.push(lum * this.quads[i * QUAD_STRIDE + Q_AREA]);
      scale.push(quadScale(this.quads, i));
      material.push(this.quadMaterial[i]);
    }
    for (let k = 0; k < (meshes?.count ?? 0); k++) {
      // An emissive mesh is one light, sampled by area over its triangles.
      const lum = emitted(meshes!.material[k]);
      if (lum === 0) continue;
      const first = meshes!.firstTriangle[k];
      const light = new MeshLight(
        meshes!.positions,
        meshes!.indices,
        first,
        meshes!.firstTriangle[k + 1] - first,
      );
      this.meshLight[k] = kinds.length;
      meshLights[k] = light;
      kinds.push(SHAPE_TRIANGLE);
      shapes.push(k);
      power.push(lum * light.area);
      scale.push(meshes!.scale[k]);
      material.push(meshes!.material[k]);
    }
    const map = scene.environmentMap;
    this.envMap = map != null ? new EnvironmentMap(map) : null;
    if (this.envMap !== null && this.envMap.integral > 0) {
      // Power of the map through the scene's bounding disc, in the units of the area
      // lights' luminance × area: ∫ L dω × r² (the π of both cancels).
      const r = sceneRadius(
        this.spheres,
        this.sphereCount,
        this.quads,
        this.quadCount,
        this.triPositions,
      );
      kinds.push(LIGHT_ENVIRONMENT);
      shapes.push(0);
      power.push(this.envMap.integral * r * r);
      scale.push(0);
      material.push(-1);
    }
    this.lights =
      kinds.length > 0
        ? new LightList({
            kind: kinds,
            shape: shapes,
            power,
            scale,
            material,
            meshLights,
            environment: this.envMap,
          })
        : null;
    [this.envR, this.envG, this.envB] = scene.environment;
    this.hasEnvironment = this.envR > 0 || this.envG > 0 || this.envB > 0;
    const total = this.sphereCount + this.quadCount + this.triCount;
    const useBvh = options.bvh ?? total >= BVH_THRESHOLD;
    let bvh: Bvh | null = null;
    if (useBvh && total > 0) {
      // One hierarchy over every primitive, whatever its kind.
      const prims = new PrimitiveBoxes(total);
      sphereBoxes(this.spheres, this.sphereCount, prims);
      quadBoxes(this.quads, this.quadCount, prims);
      triangleBoxes(this.triPositions, this.triIndices, this.triCount, prims);
      bvh = buildBvh(prims.boxes, prims.refs, total);
    }
    this.bvh = bvh;
    this.stack = new Int32Array((bvh?.depth ?? 0) + 2);
    this.stackT = new Float64Array(this.stack.length);
  }
}

export function compileScene(scene: Scene, options?: CompileOptions): CompiledScene {
  return new CompiledScene(scene, options);
}
