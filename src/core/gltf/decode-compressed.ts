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
 * Whether buffers[i] is left unread: a meshopt fallback buffer of a file whose
 * compressed views will be decoded (its bytes, if it has a URI, are never used).
 */
export function skipsBuffer(json: Json, i: number, decodable: ReadonlySet<string>): boolean {
  return (
    decodable.has(MESHOPT_EXTENSIONS[0]) && usesMeshopt(json) && meshoptFallbackBuffers(json).has(i)
  );
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
  decoders: GltfDecoders | undefined,
): Promise<number[]> {
  const buffers = list(json, 'buffers');
  const declared = buffers.map((b) => b.byteLength as number);
  const skipped = new Set<number>();
  const decodable = decodableExtensions(decoders);
  for (let i = 0; i < buffers.length; i++) if (skipsBuffer(json, i, decodable)) skipped.add(i);
  if (decoders?.meshopt !== undefined && usesMeshopt(json)) {
    const decoder = await load('EXT_meshopt_compression', decoders.meshopt);
    const input = data.reduce((s, d) => s + d.length, fileBytes);
    await decodeMeshoptViews(json, data, resources, decoder, meshoptBudget(input, GLTF_FILE_BYTES));
  }
  if (decoders?.draco !== undefined && usesDraco(json)) {
    decodeDracoPrimitives(json, data, resources, await load(DRACO_EXTENSION, decoders.draco));
  }
  return data.map((d, i) => (skipped.has(i) ? declared[i] : d.length));
}
