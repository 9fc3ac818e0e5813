/**
 * Compressed meshes in the loader: which compression extensions the platform can
 * decode (those whose getter GltfDecoders has), and the decoding pre-passes run once
 * the buffers are read and before the byte ranges are checked (meshopt.ts, draco.ts).
 * A getter is called only when the file lists its extension in extensionsUsed, so a
 * plain file loads no decoder (docs/gltf.md, "Compressed meshes").
 */
import type { GltfDecoders } from '../scene/format/gltf-model.ts';
import { DRACO_EXTENSION, decodeDracoPrimitives, usesDraco } from './draco.ts';
import { GltfError, messageOf } from './errors.ts';
import { GLTF_FILE_BYTES } from './file-names.ts';
import {
  decodeMeshoptViews,
  MESHOPT_EXTENSIONS,
  meshoptBudget,
  meshoptFallbackBuffers,
  usesMeshopt,
} from './meshopt.ts';
import { list, type Json } from './validate-values.ts';

/** The extension names this platform decodes (a file may require them). */
export function decodableExtensions(decoders: GltfDecoders | undefined): Set<string> {
  const out = new Set<string>();
  if (decoders?.meshopt !== undefined) for (const n of MESHOPT_EXTENSIONS) out.add(n);
  if (decoders?.draco !== undefined) out.add(DRACO_EXTENSION);
  return out;
}

/**
 * The buffers left unread: the meshopt fallback buffers of a file whose compressed views
 * will be decoded (their bytes, if they have a URI, are never used).
 */
export function skippedBuffers(json: Json, decodable: ReadonlySet<string>): Set<number> {
  if (!decodable.has(MESHOPT_EXTENSIONS[0]) || !usesMeshopt(json)) return new Set();
  return meshoptFallbackBuffers(json);
}

/** A getter's decoder; its failure to load is one GltfError naming the extension. */
async function load<T>(name: string, get: () => Promise<T>): Promise<T> {
  try {
    return await get();
  } catch (e) {
    throw new GltfError(`${name}: the decoder could not be loaded (${messageOf(e)})`);
  }
}

/**
 * Decodes the file's compressed views and primitives in place (`data`, `resources`
 * and the JSON), when the platform can. Returns, per buffer, the bytes the range
 * checks may count on: the bytes read, or the declared length of a skipped fallback
 * buffer (no view lies in it any more: meshopt.ts refuses one that would).
 */
export async function decodeCompressed(
  json: Json,
  data: Uint8Array[],
  resources: Record<string, Uint8Array>,
  fileBytes: number,
  skipped: ReadonlySet<number>,
  decoders: GltfDecoders | undefined,
): Promise<number[]> {
  const declared = list(json, 'buffers').map((b) => b.byteLength as number);
  if (decoders?.meshopt !== undefined && usesMeshopt(json)) {
    const decoder = await load(MESHOPT_EXTENSIONS[0], decoders.meshopt);
    const input = data.reduce((s, d) => s + d.length, fileBytes);
    const budget = meshoptBudget(input, GLTF_FILE_BYTES);
    await guarded(MESHOPT_EXTENSIONS[0], () =>
      decodeMeshoptViews(json, data, resources, decoder, budget),
    );
  }
  if (decoders?.draco !== undefined && usesDraco(json)) {
    const draco = await load(DRACO_EXTENSION, decoders.draco);
    await guarded(DRACO_EXTENSION, async () => decodeDracoPrimitives(json, data, resources, draco));
  }
  return data.map((d, i) => (skipped.has(i) ? declared[i] : d.length));
}

/**
 * Runs a pre-pass; what escapes its checks (a WebAssembly trap, the decoder's heap
 * exhausted) is still one GltfError naming the extension, never a RuntimeError.
 */
async function guarded(name: string, pass: () => Promise<void>): Promise<void> {
  try {
    await pass();
  } catch (e) {
    if (e instanceof GltfError) throw e;
    throw new GltfError(`${name}: decoding failed (${messageOf(e)})`);
  }
}
