/**
 * Sparse accessors' indices, read from the buffers once their byte ranges are
 * checked (validate-buffers.ts): glTF 2.0 §3.6.2.3 ("Sparse accessors") asks
 * that they "MUST strictly increase" and each be less than the accessor's
 * count. A loader that substitutes values in order (glTF-Transform does)
 * would otherwise write past the element it means, or leave the geometry
 * silently other than the file describes.
 */
import { fail, list, type Json } from './validate-values.ts';

/**
 * Checks every sparse accessor's indices; `buffers[i]` holds the bytes of buffers[i].
 * Throws GltfError.
 */
export function validateSparseIndices(json: Json, buffers: Uint8Array[]): void {
  const views = list(json, 'bufferViews');
  list(json, 'accessors').forEach((a, i) => {
    const sparse = a.sparse as Json | undefined;
    if (sparse === undefined) return;
    const ind = sparse.indices as Json;
    const view = views[ind.bufferView as number];
    const bytes = buffers[view.buffer as number];
    const start =
      ((view.byteOffset as number | undefined) ?? 0) +
      ((ind.byteOffset as number | undefined) ?? 0);
    const dv = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
    const ct = ind.componentType as number;
    const size = ct === 5121 ? 1 : ct === 5123 ? 2 : 4;
    const read = (k: number): number => {
      const o = start + k * size;
      return size === 1
        ? dv.getUint8(o)
        : size === 2
          ? dv.getUint16(o, true)
          : dv.getUint32(o, true);
    };
    const n = sparse.count as number;
    const count = a.count as number;
    let previous = -1;
    for (let k = 0; k < n; k++) {
      const v = read(k);
      if (v >= count)
        fail(
          `accessors[${i}].sparse.indices`,
          `element ${k} is ${v}, but the accessor has ${count} elements`,
        );
      if (v <= previous)
        fail(
          `accessors[${i}].sparse.indices`,
          `element ${k} is ${v}, not greater than the one before (${previous}); sparse indices must strictly increase`,
        );
      previous = v;
    }
  });
}
