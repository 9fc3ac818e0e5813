/**
 * fromThree: a three.js scene graph as a pathwise scene. Meshes, their materials and
 * textures become one in-memory GLB (built with glTF-Transform, the library pathwise's
 * own loader reads glTF with), so that everything the glTF path checks, decodes and
 * honours applies unchanged: the conversion only has to say what three's objects mean
 * in glTF's terms. Lights, the camera and the environment go into the pathwise-scene/1
 * document beside it. What cannot be mapped gets one warning each.
 */
import { Document, MathUtils, type Node } from '@gltf-transform/core';
import { EXTMeshGPUInstancing } from '@gltf-transform/extensions';
import { PreloadedIO } from '../core/gltf/io.ts';
import type { SceneFileReader } from '../core/scene/load/load.ts';
import type { CameraDesc } from '../core/scene/format/types.ts';
import { convertCamera, type SceneCamera } from './three-camera.ts';
import { convertEnvironment, type SceneEnvironment } from './three-environment.ts';
import { GeometryConverter } from './three-geometry.ts';
import { convertLight, type SceneLight } from './three-lights.ts';
import { MaterialConverter, type ConvertedMaterial } from './three-material.ts';
import type { ThreeCamera, ThreeMaterial, ThreeObject } from './three-shapes.ts';
import { TextureConverter } from './three-texture.ts';

/** The GLB's name among the converted files. */
export const THREE_MODEL_FILE = 'three.glb';

export interface FromThreeOptions {
  /** The scene's `name`. */
  name?: string;
  /** pathwise-scene/1 `settings` (maxBounces, …), copied as given. */
  settings?: Record<string, unknown>;
}

/** A pathwise-scene/1 document (docs/scene-format.md) made from three.js objects. */
export interface ThreeSceneDocument {
  format: 'pathwise-scene/1';
  name: string;
  camera: SceneCamera;
  materials: Record<string, unknown>;
  shapes: Record<string, unknown>[];
  lights?: SceneLight[];
  environment?: SceneEnvironment;
  settings?: Record<string, unknown>;
}

export interface ThreeConversion {
  scene: ThreeSceneDocument;
  /** The files the scene names (three.glb, environment.pfm), by name. */
  files: Map<string, Uint8Array>;
  /** Reads `files`, for `loadScene`, `PathTracerController.setScene` and the widget. */
  reader: SceneFileReader;
  warnings: string[];
}

/**
 * Converts `root` (a Scene or any Object3D: what is visible under it) seen from
 * `camera`. World matrices are brought up to date first, as a render would.
 */
export async function fromThree(
  root: object,
  camera: object,
  options: FromThreeOptions = {},
): Promise<ThreeConversion> {
  const warnings: string[] = [];
  const said = new Set<string>();
  const warn = (m: string) => {
    if (said.has(m)) return;
    said.add(m);
    if (warnings.length < 200) warnings.push(m);
  };
  const top = root as ThreeObject;
  if (typeof top?.updateWorldMatrix !== 'function' || !Array.isArray(top.children)) {
    throw new Error('fromThree: the first argument must be a three.js Object3D (a Scene, say)');
  }
  top.updateWorldMatrix(true, true);
  const sceneCamera = convertCamera(camera as ThreeCamera, warn);

  const doc = new Document();
  const buffer = doc.createBuffer();
  const textures = new TextureConverter(doc, warn);
  const materials = new MaterialConverter(doc, textures, warn);
  const geometry = new GeometryConverter(doc, buffer, warn);
  const gltfScene = doc.createScene();
  const shapes: Record<string, unknown>[] = [];
  const sceneMaterials: Record<string, unknown> = {};
  const lights: SceneLight[] = [];
  let instancing: EXTMeshGPUInstancing | null = null;

  const visit = (o: ThreeObject, path: string) => {
    if (!o.visible) return;
    const where = o.name ? `${path}/${JSON.stringify(o.name)}` : `${path}/${o.type ?? 'Object3D'}`;
    const list = Array.isArray(o.material) ? o.material : [o.material];
    // A mesh whose materials are all hidden draws nothing, but its children still do.
    if (o.isMesh && o.geometry && !list.every((m) => m?.visible === false)) {
      const converted: ConvertedMaterial[] = list.map((m: ThreeMaterial | undefined) =>
        materials.convert(m?.visible === false ? undefined : m, where),
      );
      if (o.isSkinnedMesh) warn(`${where}: skinning ignored; rendered in the bind pose`);
      const mesh = geometry.mesh(o.geometry, converted, where);
      if (mesh !== null) {
        const node = doc.createNode(o.name ?? '').setMesh(mesh);
        place(node, o.matrixWorld.elements, where, warn);
        if (o.isInstancedMesh) {
          instancing ??= doc.createExtension(EXTMeshGPUInstancing);
          node.setExtension(
            'EXT_mesh_gpu_instancing',
            instances(doc, buffer, instancing, o, where, warn),
          );
        }
        gltfScene.addChild(node);
      }
    } else if (o.isLight) {
      const light = convertLight(o, where, warn);
      if (light !== null && 'shape' in light) {
        const name = `rect-area-light-${shapes.length}`;
        sceneMaterials[name] = light.material;
        shapes.push({ ...light.shape, material: name });
      } else if (light !== null) lights.push(light);
    } else if (o.isPoints || o.isLine || o.isSprite) {
      warn(`${where}: points, lines and sprites have no surface; left out`);
    }
    o.children.forEach((c, i) => visit(c, `${where}[${i}]`));
  };
  visit(top, '');

  const files = new Map<string, Uint8Array>();
  if (gltfScene.listChildren().length > 0) {
    doc.getRoot().setDefaultScene(gltfScene);
    // The writer writes only extensions registered with it: those the document uses.
    const used = doc.getRoot().listExtensionsUsed();
    const io = new PreloadedIO().registerExtensions(
      used.map((e) => e.constructor as unknown as typeof EXTMeshGPUInstancing),
    );
    files.set(THREE_MODEL_FILE, await io.writeBinary(doc));
    shapes.unshift({ type: 'gltf', file: THREE_MODEL_FILE });
  }
  const scene: ThreeSceneDocument = {
    format: 'pathwise-scene/1',
    name: options.name ?? (top.name || 'three.js scene'),
    camera: sceneCamera,
    materials: sceneMaterials,
    shapes,
  };
  if (lights.length > 0) scene.lights = lights;
  const environment = convertEnvironment(top, files, warn);
  if (environment !== null) scene.environment = environment;
  if (options.settings) scene.settings = { ...options.settings };
  return { scene, files, reader: readerOf(files), warnings };
}

/** A SceneFileReader over converted files. */
export function readerOf(files: Map<string, Uint8Array>): SceneFileReader {
  return {
    async read(path: string, maxBytes: number): Promise<Uint8Array> {
      const bytes = files.get(path);
      if (bytes === undefined) throw new Error('no such converted file');
      if (bytes.length > maxBytes) throw new Error(`it is larger than ${maxBytes} bytes`);
      return bytes;
    },
  };
}

/**
 * Sets the node's TRS from a world matrix. A matrix with shear (a non-uniformly scaled
 * parent of a rotated child) has no TRS form, which glTF nodes require (§5.25): warned.
 */
function place(
  node: Node,
  elements: ArrayLike<number>,
  where: string,
  warn: (m: string) => void,
): void {
  const m = Array.from(elements) as Parameters<typeof MathUtils.decompose>[0];
  const t: [number, number, number] = [0, 0, 0];
  const r: [number, number, number, number] = [0, 0, 0, 1];
  const s: [number, number, number] = [1, 1, 1];
  MathUtils.decompose(m, t, r, s);
  const back = MathUtils.compose(t, r, s, new Array(16).fill(0) as typeof m);
  const size = Math.max(...m.slice(0, 12).map(Math.abs), 1e-300);
  if (!MathUtils.eq(back as number[], m as number[], 1e-5 * size)) {
    warn(
      `${where}: its world matrix has shear, which glTF nodes cannot hold; the nearest rotation and scale are used`,
    );
  }
  node.setTranslation(t).setRotation(r).setScale(s);
}

/** EXT_mesh_gpu_instancing from an InstancedMesh's instanceMatrix. */
function instances(
  doc: Document,
  buffer: ReturnType<Document['createBuffer']>,
  ext: EXTMeshGPUInstancing,
  o: ThreeObject,
  where: string,
  warn: (m: string) => void,
) {
  const count = o.count ?? 0;
  const source = o.instanceMatrix!.array;
  const T = new Float32Array(count * 3);
  const R = new Float32Array(count * 4);
  const S = new Float32Array(count * 3);
  const t: [number, number, number] = [0, 0, 0];
  const r: [number, number, number, number] = [0, 0, 0, 1];
  const s: [number, number, number] = [1, 1, 1];
  for (let i = 0; i < count; i++) {
    const m = Array.from({ length: 16 }, (_, k) => source[i * 16 + k]) as Parameters<
      typeof MathUtils.decompose
    >[0];
    MathUtils.decompose(m, t, r, s);
    T.set(t, i * 3);
    R.set(r, i * 4);
    S.set(s, i * 3);
  }
  if (o.instanceColor) warn(`${where}: instanceColor ignored`);
  const acc = (name: string, type: 'VEC3' | 'VEC4', array: Float32Array) =>
    doc.createAccessor(name).setType(type).setArray(array).setBuffer(buffer);
  return ext
    .createInstancedMesh()
    .setAttribute('TRANSLATION', acc('TRANSLATION', 'VEC3', T))
    .setAttribute('ROTATION', acc('ROTATION', 'VEC4', R))
    .setAttribute('SCALE', acc('SCALE', 'VEC3', S));
}

/**
 * The camera alone, whole (aperture and focus distance filled in), for following a
 * three.js camera without converting the scene again.
 */
export function cameraFromThree(camera: object): CameraDesc {
  const c = convertCamera(camera as ThreeCamera, () => {});
  const d = Math.hypot(
    c.target[0] - c.position[0],
    c.target[1] - c.position[1],
    c.target[2] - c.position[2],
  );
  return { ...c, aperture: c.aperture ?? 0, focusDistance: c.focusDistance ?? d };
}
