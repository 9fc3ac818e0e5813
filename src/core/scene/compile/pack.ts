/**
 * Compile once, share with every worker: a compiled scene's arrays
 * (SceneData) packed into one buffer plus a small header, which crosses to
 * a worker by postMessage / workerData and is unpacked there into views,
 * without parsing, compiling or building a BVH again.
 *
 * With a SharedArrayBuffer (Node, or a cross-origin-isolated page) every
 * worker reads the one copy; with a plain ArrayBuffer (a page without
 * COOP/COEP) structured cloning copies it once per worker. The arrays are
 * never written after compilation, so sharing them is safe, and a worker's
 * scene is bit-for-bit the scene the main thread compiled.
 */
import { CompiledScene, SCENE_ARRAYS, type SceneData } from './compile.ts';

type ArrayName = (typeof SCENE_ARRAYS)[number];

/** What crosses to a worker: plain data (structured-cloneable). */
export interface PackedScene {
  format: 'pathwise-packed/1';
  buffer: ArrayBuffer | SharedArrayBuffer;
  /** Per array of SCENE_ARRAYS: byte offset, element count and element type. */
  arrays: {
    name: ArrayName;
    offset: number;
    length: number;
    type: 'f64' | 'f32' | 'i32' | 'u16';
  }[];
  bvhDepth: number;
}

type ArrayView = Float64Array | Float32Array | Int32Array | Uint16Array;

function view(
  buffer: ArrayBuffer | SharedArrayBuffer,
  offset: number,
  length: number,
  type: PackedScene['arrays'][number]['type'],
): ArrayView {
  switch (type) {
    case 'f64':
      return new Float64Array(buffer, offset, length);
    case 'f32':
      return new Float32Array(buffer, offset, length);
    case 'u16':
      return new Uint16Array(buffer, offset, length);
    default:
      return new Int32Array(buffer, offset, length);
  }
}

/** Whether SharedArrayBuffer can be created and shared here (Node; an isolated page). */
export function canShareMemory(): boolean {
  if (typeof SharedArrayBuffer === 'undefined') return false;
  // In browsers it exists only when the page is cross-origin isolated.
  const g = globalThis as { crossOriginIsolated?: boolean };
  return g.crossOriginIsolated !== false;
}

/**
 * Packs a compiled scene into one buffer: a SharedArrayBuffer when `shared`
 * (default: whenever memory can be shared here), else an ArrayBuffer.
 * Sections are 8-byte aligned.
 */
export function packScene(scene: CompiledScene, shared = canShareMemory()): PackedScene {
  const data = scene.data;
  const arrays: PackedScene['arrays'] = [];
  let bytes = 0;
  for (const name of SCENE_ARRAYS) {
    const a = data[name];
    arrays.push({
      name,
      offset: bytes,
      length: a.length,
      type:
        a instanceof Float64Array
          ? 'f64'
          : a instanceof Float32Array
            ? 'f32'
            : a instanceof Uint16Array
              ? 'u16'
              : 'i32',
    });
    bytes += Math.ceil(a.byteLength / 8) * 8;
  }
  const buffer = shared ? new SharedArrayBuffer(bytes) : new ArrayBuffer(bytes);
  for (const { name, offset, length, type } of arrays) {
    (view(buffer, offset, length, type) as Float64Array).set(data[name] as Float64Array);
  }
  return { format: 'pathwise-packed/1', buffer, arrays, bvhDepth: data.bvhDepth };
}

/** The scene of a packed buffer, as views into it (no copy). */
export function unpackScene(packed: PackedScene): CompiledScene {
  if (packed.format !== 'pathwise-packed/1') {
    throw new Error(`not a packed pathwise scene (format ${String(packed.format)})`);
  }
  const views: Partial<Record<ArrayName, ArrayView>> = {};
  for (const { name, offset, length, type } of packed.arrays) {
    views[name] = view(packed.buffer, offset, length, type);
  }
  for (const name of SCENE_ARRAYS) {
    if (!views[name]) throw new Error(`packed scene lacks ${name}`);
  }
  const arrays = views as unknown as Omit<SceneData, 'bvhDepth'>;
  return new CompiledScene({ ...arrays, bvhDepth: packed.bvhDepth });
}
