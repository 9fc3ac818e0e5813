/**
 * Compiles a validated scene into the flat typed arrays the tracer reads.
 * Only what the scene has is built: no sphere buffer without spheres, no
 * light list without emitters, no BVH below the measured crossover (see
 * BVH_THRESHOLD), so the hot loops never pay for kinds that are absent.
 */
import type { SceneGeometry } from '../../accel/scene-geometry.ts';
import { BVH_NODE_WORDS, Bvh, buildBvh } from '../../accel/bvh.ts';
import { QuadList } from '../../geometry/quad-list.ts';
import {
  instanceBoxesInto,
  PrimitiveBoxes,
  quadBoxes,
  sphereBoxes,
  triangleBoxes,
} from '../../accel/primitives.ts';
import { buildInstances, NO_INSTANCES, type InstanceArrays } from '../../accel/instances.ts';
import { compileMaterials, MATERIAL_STRIDE, M_EMISSION, M_EMISSIVE } from '../../bsdf/materials.ts';
import { LIGHT_ENVIRONMENT, SHAPE_QUAD, SHAPE_SPHERE, SHAPE_TRIANGLE } from '../../geometry/ray.ts';
import { RAY_RECORD_WORDS } from '../../geometry/ray.ts';
import { TriangleHit, TriangleRay } from '../../geometry/triangle.ts';
import {
  compileQuads,
  compileSpheres,
  QUAD_STRIDE,
  Q_AREA,
  quadScale as quadScaleOf,
  SPHERE_STRIDE,
  sphereScale as sphereScaleOf,
} from '../../geometry/shapes.ts';
import { EnvironmentMap } from '../../lights/environment-map.ts';
import { LightList } from '../../lights/lights.ts';
import { LightBvh } from '../../lights/light-bvh.ts';
import { lightBvhInput } from '../../lights/light-bvh-input.ts';
import { MeshLight, triangleArea } from '../../lights/mesh-light.ts';
import { compilePunctualLights } from '../../lights/punctual.ts';
import { sceneRadius } from './bounds.ts';
import { CompiledMeshes, compileMeshArrays, type MeshArrays } from './compile-meshes.ts';
import { compileGltfShapes } from './compile-gltf.ts';
import { GltfScene } from './gltf-scene.ts';
import { gltfMeshPower, gltfTrianglePowers, selectionWeights } from './light-power.ts';
import type { GltfDesc, MeshDesc, QuadDesc, Scene, SphereDesc } from '../format/types.ts';

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

/**
 * Everything the tracer reads of a scene: typed arrays and a few numbers,
 * nothing else, so that it can be packed into one buffer and shared with
 * every worker (pack.ts) instead of being parsed and compiled again there.
 * A new primitive kind adds its arrays here and in SCENE_ARRAYS.
 */
export interface SceneData extends MeshArrays, InstanceArrays {
  materials: Float64Array;
  spheres: Float64Array;
  sphereMaterial: Int32Array;
  /** Light index of each sphere, −1 when it does not emit. */
  sphereLight: Int32Array;
  /**
   * Per shape, the magnitude its hit points' rounding error scales with
   * (largest |coordinate| of the centre plus the radius; of a quad, of the
   * corner plus those of its two edges): the integrator's ray offsets read
   * it rather than recomputing it at every hit.
   */
  sphereScale: Float64Array;
  quads: Float64Array;
  quadMaterial: Int32Array;
  quadLight: Int32Array;
  quadScale: Float64Array;
  /** Light index of each mesh, −1 when it does not emit (the mesh arrays: compile-meshes.ts). */
  meshLight: Int32Array;
  /**
   * Emitters: kind (SHAPE_* or LIGHT_ENVIRONMENT), shape index, selection weight, offset
   * scale and material (−1 for the environment map) (LightList).
   */
  lightKind: Int32Array;
  lightShape: Int32Array;
  lightPower: Float64Array;
  lightScale: Float64Array;
  lightMaterial: Int32Array;
  /**
   * Per triangle of each emissive mesh, in light-list order: its power, for the light
   * BVH's choice among them (lights/light-bvh-input.ts).
   */
  lightTrianglePower: Float64Array;
  /** Punctual lights' records (lights/punctual.ts); empty without them. */
  punctual: Float64Array;
  /** Constant environment radiance, RGB. */
  environment: Float64Array;
  /**
   * The environment map: its texels (RGB, row 0 at the top, without the scale) and
   * [width, height, scale r, g, b, rotationY]; both empty without a map.
   */
  envTexels: Float32Array;
  envParams: Float64Array;
  /**
   * glTF materials (GM_STRIDE numbers per row, src/core/gltf-material/material-table.ts) and
   * their textures (texels and per-image offset, width, height, texture-store.ts); all
   * empty without glTF shapes.
   */
  gltfMaterials: Float64Array;
  texels: Uint16Array;
  textureInfo: Int32Array;
  /** The BVH's nodes (as 32-bit words) and references; empty without a BVH. */
  bvhNodes: Int32Array;
  bvhRefs: Int32Array;
  bvhDepth: number;
}

/** The typed arrays of SceneData, in packing order (pack.ts). */
export const SCENE_ARRAYS = [
  'materials',
  'spheres',
  'sphereMaterial',
  'sphereLight',
  'sphereScale',
  'quads',
  'quadMaterial',
  'quadLight',
  'quadScale',
  'lightKind',
  'lightShape',
  'lightPower',
  'lightScale',
  'lightMaterial',
  'lightTrianglePower',
  'punctual',
  'environment',
  'envTexels',
  'envParams',
  'triPositions',
  'triIndices',
  'triNormals',
  'meshFirstTriangle',
  'meshMaterial',
  'meshHasNormals',
  'meshScale',
  'meshLight',
  'triUV0',
  'triUV1',
  'triColors',
  'triTangents',
  'gltfMaterials',
  'texels',
  'textureInfo',
  'bvhNodes',
  'bvhRefs',
  'instXform',
  'instBlas',
  'blasNodes',
  'blasRefs',
  'blasDepth',
] as const satisfies readonly (keyof SceneData)[];

export class CompiledScene implements SceneGeometry {
  /** The arrays this scene was made from (what pack.ts ships). */
  readonly data: SceneData;
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
  /** See SceneData.sphereScale. */
  readonly sphereScale: Float64Array;
  readonly quadScale: Float64Array;
  /**
   * The quads regrouped for the plain loops (geometry/quad-list.ts), derived from `quads`;
   * empty when the scene has a BVH, which tests quads from `quads` itself.
   */
  readonly quadList: QuadList;
  /** The triangles of all meshes (compile-meshes.ts), or null without meshes. */
  readonly meshes: CompiledMeshes | null;
  readonly triCount: number;
  readonly triPositions: Float64Array;
  readonly triIndices: Int32Array;
  /** Light index of each mesh, −1 when it does not emit. */
  readonly meshLight: Int32Array;
  /** glTF materials, textures and vertex attributes, or null without glTF shapes. */
  readonly gltf: GltfScene | null;
  /** Per-ray constants of the triangle test and the barycentrics of the kept hit (trace.ts). */
  readonly triRay = new TriangleRay();
  readonly triHit = new TriangleHit();
  readonly lights: LightList | null;
  private lightBvhBuilt = false;
  /** The environment map, or null for the constant environment (envR, envG, envB). */
  readonly envMap: EnvironmentMap | null;
  readonly envR: number;
  readonly envG: number;
  readonly envB: number;
  readonly hasEnvironment: boolean;
  readonly bvh: Bvh | null;
  /**
   * Scratch of the ray queries (accel/trace.ts): the traversal stack,
   * sized for the BVH's depth, and the ray record. Per scene object, never
   * shared between threads.
   */
  readonly stack: Int32Array;
  readonly stackT: Float64Array;
  readonly ray = new Float64Array(RAY_RECORD_WORDS);
  /** Instances and their BLASes (accel/instances.ts; SceneGeometry). */
  readonly instanceCount: number;
  readonly instXform: Float64Array;
  readonly instBlas: Int32Array;
  readonly blasBoxes: Float32Array;
  readonly blasNodes: Int32Array;
  readonly blasRefs: Int32Array;
  readonly blasStack: Int32Array;
  readonly blasStackT: Float64Array;
  readonly objRay = new Float64Array(RAY_RECORD_WORDS);
  readonly objTriRay = new TriangleRay();

  /** From compiled arrays, which it keeps (views, not copies): see compileScene and unpackScene. */
  constructor(data: SceneData) {
    this.data = data;
    this.materials = data.materials;
    this.spheres = data.spheres;
    this.sphereCount = data.spheres.length / SPHERE_STRIDE;
    this.sphereMaterial = data.sphereMaterial;
    this.sphereLight = data.sphereLight;
    this.sphereScale = data.sphereScale;
    this.quads = data.quads;
    this.quadCount = data.quads.length / QUAD_STRIDE;
    this.quadMaterial = data.quadMaterial;
    this.quadLight = data.quadLight;
    this.quadScale = data.quadScale;
    this.quadList = new QuadList(data.bvhNodes.length > 0 ? new Float64Array(0) : data.quads);
    const meshes = data.meshMaterial.length > 0 ? new CompiledMeshes(data) : null;
    this.meshes = meshes;
    this.triCount = meshes?.triangleCount ?? 0;
    this.triPositions = data.triPositions;
    this.triIndices = data.triIndices;
    this.meshLight = data.meshLight;
    this.gltf = data.gltfMaterials.length > 0 ? new GltfScene(data) : null;
    const p = data.envParams;
    this.envMap =
      p.length > 0
        ? new EnvironmentMap({
            type: 'map',
            file: '',
            scale: [p[2], p[3], p[4]],
            rotationY: p[5],
            image: { width: p[0], height: p[1], rgb: data.envTexels },
          })
        : null;
    // The same arithmetic on the same numbers: a scene unpacked in a worker
    // gets bit-identical light probabilities (and mesh and map distributions).
    const meshLights: (MeshLight | null)[] = [];
    for (let l = 0; l < data.lightKind.length; l++) {
      if (data.lightKind[l] !== SHAPE_TRIANGLE) continue;
      const k = data.lightShape[l];
      const first = data.meshFirstTriangle[k];
      meshLights[k] = new MeshLight(
        data.triPositions,
        data.triIndices,
        first,
        data.meshFirstTriangle[k + 1] - first,
      );
    }
    this.lights =
      data.lightKind.length > 0
        ? new LightList({
            kind: Array.from(data.lightKind),
            shape: Array.from(data.lightShape),
            power: Array.from(data.lightPower),
            scale: Array.from(data.lightScale),
            material: Array.from(data.lightMaterial),
            meshLights,
            environment: this.envMap,
            punctual: data.punctual,
          })
        : null;
    this.envR = data.environment[0];
    this.envG = data.environment[1];
    this.envB = data.environment[2];
    this.hasEnvironment = this.envR > 0 || this.envG > 0 || this.envB > 0;
    const nodes = data.bvhNodes;
    this.bvh =
      nodes.length > 0
        ? new Bvh(
            nodes.buffer,
            nodes.byteOffset,
            nodes.length / BVH_NODE_WORDS,
            data.bvhRefs,
            data.bvhDepth,
          )
        : null;
    this.stack = new Int32Array(data.bvhDepth + 2);
    this.stackT = new Float64Array(this.stack.length);
    this.instanceCount = data.instBlas.length;
    this.instXform = data.instXform;
    this.instBlas = data.instBlas;
    const bn = data.blasNodes;
    this.blasNodes = bn;
    this.blasBoxes = new Float32Array(bn.buffer, bn.byteOffset, bn.length);
    this.blasRefs = data.blasRefs;
    this.blasStack = new Int32Array((data.blasDepth[0] ?? 0) + 2);
    this.blasStackT = new Float64Array(this.blasStack.length);
  }

  /**
   * The light BVH over this scene's emitters (lights/light-bvh.ts), built on first use
   * (each thread's scene builds its own, bit-identical); null when there is at most one
   * light to choose, where the choice by power is the same and cheaper.
   */
  lightBvh(): LightBvh | null {
    const lights = this.lights;
    if (lights === null) return null;
    if (!this.lightBvhBuilt) {
      this.lightBvhBuilt = true;
      const d = this.data;
      const input = lightBvhInput(
        lights,
        d.spheres,
        d.quads,
        d.triPositions,
        d.triIndices,
        d.lightTrianglePower,
      );
      if (input.light.length + input.infinite.length > 1) lights.bvh = new LightBvh(input);
    }
    return lights.bvh;
  }
}

export function compileScene(scene: Scene, options: CompileOptions = {}): CompiledScene {
  const meshDescs = scene.shapes.filter((s): s is MeshDesc => s.type === 'mesh');
  const gltfDescs = scene.shapes.filter((s): s is GltfDesc => s.type === 'gltf');
  const map = scene.environmentMap ?? null;
  if (
    meshDescs.some((m) => m.data === null) ||
    gltfDescs.some((m) => m.data === null) ||
    (map !== null && map.image === null)
  ) {
    throw new Error(
      'the scene names files that were not read: load it with loadScene or resolveSceneFiles',
    );
  }
  const names = Object.keys(scene.materials);
  const materialIndex = new Map(names.map((n, i) => [n, i]));
  const named = compileMaterials(names.map((n) => scene.materials[n]));
  const gltf = gltfDescs.length > 0 ? compileGltfShapes(gltfDescs, names.length) : null;
  let materials = named;
  if (gltf !== null) {
    materials = new Float64Array(named.length + gltf.materials.length);
    materials.set(named);
    materials.set(gltf.materials, named.length);
  }
  const sphereDescs = scene.shapes.filter((s): s is SphereDesc => s.type === 'sphere');
  const quadDescs = scene.shapes.filter((s): s is QuadDesc => s.type === 'quad');
  const sphereCount = sphereDescs.length;
  const quadCount = quadDescs.length;
  const spheres = compileSpheres(sphereDescs);
  const quads = compileQuads(quadDescs);
  const sphereMaterial = Int32Array.from(sphereDescs, (s) => materialIndex.get(s.material)!);
  const quadMaterial = Int32Array.from(quadDescs, (s) => materialIndex.get(s.material)!);
  const sphereLight = new Int32Array(sphereCount).fill(-1);
  const quadLight = new Int32Array(quadCount).fill(-1);
  const sphereScale = new Float64Array(sphereCount);
  for (let i = 0; i < sphereCount; i++) sphereScale[i] = sphereScaleOf(spheres, i);
  const quadScale = new Float64Array(quadCount);
  for (let i = 0; i < quadCount; i++) quadScale[i] = quadScaleOf(quads, i);

  const worldMeshes = [
    ...meshDescs.map((m) => ({ data: m.data!, material: materialIndex.get(m.material)! })),
    ...(gltf?.meshes ?? []),
  ];
  // Instanced meshes (object space) after every world-space one: triangles
  // [worldTriangles, triCount) are theirs, and only the instances enter the BVH.
  const blasMeshes = gltf?.blasMeshes ?? [];
  const mesh = compileMeshArrays([...worldMeshes, ...blasMeshes]);
  const meshCount = mesh.meshMaterial.length;
  const triCount = mesh.triIndices.length / 3;
  let worldTriangles = 0;
  let worldVertices = 0;
  for (const m of worldMeshes) {
    if (m.data.indices.length === 0) continue;
    worldTriangles += m.data.indices.length / 3;
    worldVertices += m.data.positions.length / 3;
  }
  let instances = NO_INSTANCES;
  let instanceBoxes: Float64Array = new Float64Array(0);
  if (gltf !== null && gltf.instanceBlas.length > 0) {
    const blasTriangles = new Array<number>(gltf.blasFirst.length);
    let t = worldTriangles;
    for (let b = 0; b + 1 < gltf.blasFirst.length; b++) {
      blasTriangles[b] = t;
      for (let k = gltf.blasFirst[b]; k < gltf.blasFirst[b + 1]; k++)
        t += blasMeshes[k].data.indices.length / 3;
    }
    blasTriangles[gltf.blasFirst.length - 1] = t;
    const built = buildInstances(
      mesh.triPositions,
      mesh.triIndices,
      blasTriangles,
      gltf.instanceBlas,
      gltf.instanceMatrices,
    );
    instances = built.arrays;
    instanceBoxes = built.boxes;
  }
  const instanceCount = instances.instBlas.length;
  const meshLight = new Int32Array(meshCount).fill(-1);

  const kinds: number[] = [];
  const shapes: number[] = [];
  const power: number[] = [];
  // log2 of each power from its factors, for when a product overflows (light-power.ts).
  const powerLog: number[] = [];
  const scale: number[] = [];
  const material: number[] = [];
  const trianglePower: number[] = [];
  const emitted = (m: number): number => {
    const o = m * MATERIAL_STRIDE;
    if (materials[o + M_EMISSIVE] === 0) return 0;
    const e = materials;
    // Selection weight: luminance, floored so a pure-blue emitter is still chosen.
    const lum =
      0.2126 * e[o + M_EMISSION] + 0.7152 * e[o + M_EMISSION + 1] + 0.0722 * e[o + M_EMISSION + 2];
    return Math.max(
      lum,
      1e-6 * Math.max(e[o + M_EMISSION], e[o + M_EMISSION + 1], e[o + M_EMISSION + 2]),
    );
  };
  for (let i = 0; i < sphereCount; i++) {
    const lum = emitted(sphereMaterial[i]);
    if (lum === 0) continue;
    const r = spheres[i * SPHERE_STRIDE + 3];
    sphereLight[i] = kinds.length;
    kinds.push(SHAPE_SPHERE);
    shapes.push(i);
    power.push(lum * 4 * Math.PI * r * r);
    powerLog.push(Math.log2(lum) + Math.log2(4 * Math.PI) + 2 * Math.log2(r));
    scale.push(sphereScale[i]);
    material.push(sphereMaterial[i]);
  }
  for (let i = 0; i < quadCount; i++) {
    const lum = emitted(quadMaterial[i]);
    if (lum === 0) continue;
    quadLight[i] = kinds.length;
    kinds.push(SHAPE_QUAD);
    shapes.push(i);
    power.push(lum * quads[i * QUAD_STRIDE + Q_AREA]);
    powerLog.push(Math.log2(lum) + Math.log2(quads[i * QUAD_STRIDE + Q_AREA]));
    scale.push(quadScale[i]);
    material.push(quadMaterial[i]);
  }
  for (let k = 0; k < meshCount; k++) {
    // An emissive mesh is one light, sampled by area over its triangles.
    const lum = emitted(mesh.meshMaterial[k]);
    if (lum === 0) continue;
    const first = mesh.meshFirstTriangle[k];
    const count = mesh.meshFirstTriangle[k + 1] - first;
    const area = new MeshLight(mesh.triPositions, mesh.triIndices, first, count).area;
    meshLight[k] = kinds.length;
    kinds.push(SHAPE_TRIANGLE);
    shapes.push(k);
    // glTF: emission varies over the mesh (emissive texture, alpha); the selection
    // weight follows it (light-power.ts), but never drops to 0.
    const m = mesh.meshMaterial[k];
    const gm = m >= names.length ? m - names.length : -1;
    const p =
      gm < 0
        ? lum * area
        : Math.max(
            gltfMeshPower(mesh, first, count, gltf!.table, gm, gltf!.textures),
            1e-6 * lum * area,
          );
    if (gm < 0) {
      for (let t = first; t < first + count; t++) {
        trianglePower.push(triangleArea(mesh.triPositions, mesh.triIndices, t));
      }
    } else {
      gltfTrianglePowers(mesh, first, count, gltf!.table, gm, gltf!.textures, lum, trianglePower);
    }
    power.push(p);
    powerLog.push(p > 0 && p < Infinity ? Math.log2(p) : Math.log2(lum) + Math.log2(area));
    scale.push(mesh.meshScale[k]);
    material.push(mesh.meshMaterial[k]);
  }
  let envTexels: Float32Array = new Float32Array(0);
  let envParams: Float64Array = new Float64Array(0);
  if (map !== null) {
    const image = map.image!;
    envTexels = image.rgb;
    envParams = Float64Array.from([image.width, image.height, ...map.scale, map.rotationY]);
    const integral = new EnvironmentMap(map).integral;
    if (integral > 0) {
      // The map's power through the scene's bounding disc, in the units of the area
      // lights' luminance × area: ∫ L dω × r² (the π of both cancels).
      const r = sceneRadius(
        spheres,
        sphereCount,
        quads,
        quadCount,
        instanceCount === 0 ? mesh.triPositions : mesh.triPositions.subarray(0, worldVertices * 3),
        instanceBoxes,
      );
      kinds.push(LIGHT_ENVIRONMENT);
      shapes.push(0);
      power.push(integral * r * r);
      powerLog.push(Math.log2(integral) + 2 * Math.log2(r));
      scale.push(0);
      material.push(-1);
    }
  }
  // Punctual lights: the scene's own, then each glTF model's (already in world space).
  const lightDescs = [...(scene.lights ?? []), ...gltfDescs.flatMap((g) => g.data!.lights ?? [])];
  let punctual: Float64Array = new Float64Array(0);
  if (lightDescs.length > 0) {
    const directional = lightDescs.some((l) => l.type === 'directional');
    const r = directional
      ? sceneRadius(
          spheres,
          sphereCount,
          quads,
          quadCount,
          instanceCount === 0
            ? mesh.triPositions
            : mesh.triPositions.subarray(0, worldVertices * 3),
          instanceBoxes,
        )
      : 0;
    const p = compilePunctualLights(lightDescs, r);
    punctual = p.data;
    p.kinds.forEach((kind, i) => {
      kinds.push(kind);
      shapes.push(i);
      power.push(p.power[i]);
      powerLog.push(p.powerLog[i]);
      scale.push(0);
      material.push(-1);
    });
  }
  const total = sphereCount + quadCount + worldTriangles + instanceCount;
  // Instances are reached only through the BVH (traverse-instanced.ts).
  const useBvh = instanceCount > 0 || (options.bvh ?? total >= BVH_THRESHOLD);
  let bvh: Bvh | null = null;
  if (useBvh && total > 0) {
    // One hierarchy over every primitive, whatever its kind (with instances, the TLAS).
    const prims = new PrimitiveBoxes(total);
    sphereBoxes(spheres, sphereCount, prims);
    quadBoxes(quads, quadCount, prims);
    triangleBoxes(mesh.triPositions, mesh.triIndices, worldTriangles, prims);
    instanceBoxesInto(instanceBoxes, instanceCount, prims);
    // Meshes: a node cost of 2 makes leaves of 2–4 triangles, 42 rather than 68 bytes of
    // hierarchy per triangle for a million of them (docs/performance.md; bench/mesh-bvh.ts).
    bvh = buildBvh(prims.boxes, prims.refs, total, triCount > 0 ? 2 : undefined);
  }
  return new CompiledScene({
    materials,
    spheres,
    sphereMaterial,
    sphereLight,
    sphereScale,
    quads,
    quadMaterial,
    quadLight,
    quadScale,
    lightKind: Int32Array.from(kinds),
    lightShape: Int32Array.from(shapes),
    lightPower: Float64Array.from(selectionWeights(power, powerLog)),
    lightScale: Float64Array.from(scale),
    lightMaterial: Int32Array.from(material),
    lightTrianglePower: Float64Array.from(trianglePower),
    punctual,
    environment: Float64Array.from(scene.environment),
    envTexels,
    envParams,
    ...mesh,
    meshLight,
    gltfMaterials: gltf?.table ?? new Float64Array(0),
    texels: gltf?.textures.texels ?? new Uint16Array(0),
    textureInfo: gltf?.textures.info ?? new Int32Array(0),
    bvhNodes: bvh ? bvh.words : new Int32Array(0),
    bvhRefs: bvh ? bvh.refs : new Int32Array(0),
    bvhDepth: bvh ? bvh.depth : 0,
    ...instances,
  });
}
