/**
 * EXT_meshopt_compression and KHR_meshopt_compression, decoded by the loader itself
 * before glTF-Transform reads the document: every compressed buffer view is checked
 * against the extension's rules and against bounds of our own, decoded with
 * meshoptimizer's decoder (injected: GltfDecoders.meshopt), and pointed at the decoded
 * bytes in a buffer of their own (decoded-buffer.ts). glTF-Transform then reads a plain
 * file; it has no class for the KHR name, and its EXT class checks nothing (decoders.md).
 *
 * The bounds matter because the decoder trusts its arguments: it reserves
 * `count × byteStride` bytes of WebAssembly memory (which never shrinks) before it
 * looks at the stream, so a 64-byte stream that claims 10⁸ elements costs 1.6 GB.
 * Here `count × byteStride` must equal the view's byteLength (a MUST of both
 * extensions), must be within what the stream's size can encode, and all views
 * together must be within a budget set by the size of the file.
 *
 * Spec: KhronosGroup/glTF extensions/2.0/Vendor/EXT_meshopt_compression/README.md and
 * Khronos/KHR_meshopt_compression/README.md ("JSON schema updates", "Filters").
 */
import { quote } from '../util/message.ts';
import type { MeshoptDecoderLike } from '../scene/format/gltf-model.ts';
import { DecodedBuffer, dropExtensionNames } from './decoded-buffer.ts';
import { GltfError, messageOf } from './errors.ts';
import {
  describeValue,
  fail,
  integer,
  isObject,
  list,
  required,
  type Json,
} from './validate-values.ts';

export const MESHOPT_EXTENSIONS = ['EXT_meshopt_compression', 'KHR_meshopt_compression'] as const;

const MODES = ['ATTRIBUTES', 'TRIANGLES', 'INDICES'];
const EXT_FILTERS = ['NONE', 'OCTAHEDRAL', 'QUATERNION', 'EXPONENTIAL'];
/** KHR_meshopt_compression adds the COLOR filter (YCoCg, 4 or 8 bytes per element). */
const KHR_FILTERS = [...EXT_FILTERS, 'COLOR'];

/**
 * Most bytes one stream byte can decode to. Attributes, bitstream v0 (header 0xa0):
 * each byte column of a 16-element group costs at least a 2-bit header, so 16 bytes
 * per ¼ byte. v1 (0xa1, KHR) may zero a column over a whole block with 2 bits of
 * control, so its bound is looser. Triangles cost at least one code byte each (3
 * indices); an index of a sequence at least one varint byte (meshoptimizer's
 * indexcodec.cpp, vertexcodec.cpp).
 */
const ATTRIBUTE_RATIO = [64, 1024];

/** The decode budget when the file is small: below it no file is refused for its ratio. */
const MIN_BUDGET = 16 * 1024 * 1024;
/** The budget, as a multiple of the bytes of the file and its buffers (real files: 2.5–6). */
const BUDGET_RATIO = 64;

/** Whether the file uses either meshopt extension (it must list it in extensionsUsed, §3.12). */
export function usesMeshopt(json: Json): boolean {
  const used = json.extensionsUsed;
  return Array.isArray(used) && MESHOPT_EXTENSIONS.some((n) => used.includes(n));
}

/**
 * The buffers marked `fallback: true` by a meshopt extension: their bytes are never
 * read when the views are decoded (they may have no URI at all).
 */
export function meshoptFallbackBuffers(json: Json): Set<number> {
  const out = new Set<number>();
  list(json, 'buffers').forEach((b, i) => {
    const ext = b.extensions;
    if (!isObject(ext)) return;
    for (const name of MESHOPT_EXTENSIONS) {
      const e = ext[name];
      if (isObject(e) && e.fallback === true) out.add(i);
    }
  });
  return out;
}

/** The decode budget in bytes for a file whose container and buffers hold `inputBytes`. */
export function meshoptBudget(inputBytes: number, limit: number): number {
  return Math.min(limit, Math.max(MIN_BUDGET, BUDGET_RATIO * inputBytes));
}

/**
 * Decodes every compressed view of `json` in place: `data[i]` holds the bytes read for
 * buffers[i] (empty for a fallback buffer), `resources` the bytes glTF-Transform will
 * read. Throws GltfError naming the view (and the property) at the first problem.
 */
export async function decodeMeshoptViews(
  json: Json,
  data: Uint8Array[],
  resources: Record<string, Uint8Array>,
  decoder: MeshoptDecoderLike,
  budget: number,
): Promise<void> {
  const fallback = meshoptFallbackBuffers(json);
  const views = list(json, 'bufferViews');
  const out = new DecodedBuffer(json, '@meshopt');
  let ready = false;
  let decoded = 0;
  for (let i = 0; i < views.length; i++) {
    const view = views[i];
    const ext = isObject(view.extensions) ? view.extensions : undefined;
    const name = MESHOPT_EXTENSIONS.find((n) => ext?.[n] !== undefined);
    if (ext === undefined || name === undefined) {
      if (fallback.has(view.buffer as number))
        fail(
          `bufferViews[${i}]`,
          `lies in buffers[${view.buffer as number}], a meshopt fallback buffer that is not read, ` +
            'but is not compressed itself',
        );
      continue;
    }
    const p = `bufferViews[${i}].extensions.${name}`;
    const e = ext[name];
    if (!isObject(e)) fail(p, `must be an object, got ${describeValue(e)}`);
    const s = checkStream(e, p, name, view, `bufferViews[${i}]`, data, fallback);
    decoded += s.count * s.byteStride;
    if (decoded > budget)
      fail(
        `${p}.count`,
        `the compressed views decode to more than ${budget} bytes, the budget for a file of ` +
          `this size (${BUDGET_RATIO}× its bytes; docs/gltf.md)`,
      );
    if (!ready) {
      await decoder.ready;
      ready = true;
    }
    const target = new Uint8Array(s.count * s.byteStride);
    try {
      decoder.decodeGltfBuffer(
        target,
        s.count,
        s.byteStride,
        s.source,
        s.mode,
        s.filter === 'NONE' ? undefined : s.filter,
      );
    } catch (err) {
      throw new GltfError(`${p}: the compressed stream is malformed (${messageOf(err)})`);
    }
    const { buffer, byteOffset } = out.add(target);
    view.buffer = buffer;
    view.byteOffset = byteOffset;
    delete ext[name];
    if (Object.keys(ext).length === 0) delete view.extensions;
  }
  out.finish(resources, data);
  const buffers = list(json, 'buffers');
  for (const i of fallback) {
    const ext = (buffers[i].extensions ?? {}) as Json;
    for (const n of MESHOPT_EXTENSIONS) delete ext[n];
  }
  dropExtensionNames(json, MESHOPT_EXTENSIONS);
}

interface Stream {
  source: Uint8Array;
  count: number;
  byteStride: number;
  mode: string;
  filter: string;
}

/** The extension's rules and our bounds for one compressed view; its stream bytes. */
function checkStream(
  e: Json,
  p: string,
  name: string,
  view: Json,
  viewPath: string,
  data: Uint8Array[],
  fallback: Set<number>,
): Stream {
  const b = required(e, 'buffer', p, 0);
  if (b >= data.length)
    fail(`${p}.buffer`, `refers to buffers[${b}], but the file has ${data.length}`);
  if (fallback.has(b))
    fail(
      `${p}.buffer`,
      `refers to buffers[${b}], a fallback buffer, which holds no compressed data`,
    );
  const byteOffset = integer(e, 'byteOffset', p, 0) ?? 0;
  const byteLength = required(e, 'byteLength', p, 1);
  const byteStride = required(e, 'byteStride', p, 1, 256);
  const count = required(e, 'count', p, 1);
  const mode = e.mode;
  if (typeof mode !== 'string' || !MODES.includes(mode))
    fail(
      `${p}.mode`,
      `must be one of ${MODES.map((m) => quote(m)).join(', ')}, got ${describeValue(mode)}`,
    );
  const filters = name === 'KHR_meshopt_compression' ? KHR_FILTERS : EXT_FILTERS;
  const filter = e.filter ?? 'NONE';
  if (typeof filter !== 'string' || !filters.includes(filter))
    fail(
      `${p}.filter`,
      `must be one of ${filters.map((m) => quote(m)).join(', ')} for ${name}, got ${describeValue(filter)}`,
    );
  const end = byteOffset + byteLength;
  if (end > data[b].length)
    fail(
      p,
      `the stream ends at byte ${end}, past the end of the ${data[b].length} bytes of buffers[${b}]`,
    );
  // The MUSTs of "JSON schema updates": the view holds exactly the decoded elements.
  if (view.byteLength !== byteStride * count)
    fail(
      `${p}.count`,
      `${count} elements of byteStride ${byteStride} make ${byteStride * count} bytes, but ` +
        `${viewPath}.byteLength is ${view.byteLength as number}`,
    );
  if (view.byteStride !== undefined && view.byteStride !== byteStride)
    fail(
      `${p}.byteStride`,
      `is ${byteStride}, but ${viewPath}.byteStride is ${view.byteStride as number}`,
    );
  if (mode === 'ATTRIBUTES') {
    if (byteStride % 4 !== 0)
      fail(`${p}.byteStride`, `must be a multiple of 4 for ATTRIBUTES, got ${byteStride}`);
  } else {
    if (byteStride !== 2 && byteStride !== 4)
      fail(`${p}.byteStride`, `must be 2 or 4 for ${mode}, got ${byteStride}`);
    if (filter !== 'NONE') fail(`${p}.filter`, `must be NONE for ${mode}, got ${quote(filter)}`);
    if (mode === 'TRIANGLES' && count % 3 !== 0)
      fail(`${p}.count`, `must be a multiple of 3 for TRIANGLES, got ${count}`);
  }
  const strides: Record<string, number[]> = { OCTAHEDRAL: [4, 8], QUATERNION: [8], COLOR: [4, 8] };
  const allowed = strides[filter];
  if (allowed !== undefined && !allowed.includes(byteStride))
    fail(
      `${p}.byteStride`,
      `must be ${allowed.join(' or ')} for the ${filter} filter, got ${byteStride}`,
    );
  const source = data[b].subarray(byteOffset, end);
  let ratio: number;
  if (mode === 'ATTRIBUTES') {
    const version = source[0] - 0xa0;
    if ((source[0] & 0xf0) !== 0xa0 || version > 1)
      fail(
        p,
        `the stream does not start with a meshopt attribute header (0xa0 or 0xa1), got 0x${source[0].toString(16).padStart(2, '0')}`,
      );
    ratio = ATTRIBUTE_RATIO[version];
  } else {
    ratio = mode === 'TRIANGLES' ? byteStride * 3 : byteStride;
  }
  if (count * byteStride > ratio * byteLength)
    fail(
      `${p}.count`,
      `${count} elements of ${byteStride} bytes cannot be encoded in ${byteLength} bytes of ` +
        `${mode} (at most ${ratio}× the stream)`,
    );
  return { source, count, byteStride, mode, filter };
}
