/**
 * The byte ranges of a glTF document, checked once its buffers are read:
 * each buffer at least as long as it says, each buffer view inside its
 * buffer, each accessor (and sparse part) inside its view and aligned to its
 * component size (glTF 2.0 §3.6.2.4 "Data alignment"). What glTF-Transform
 * would otherwise meet as a RangeError deep inside a typed-array constructor.
 */
import { COMPONENT_SIZE, fail, list, TYPE_SIZE } from './validate.ts';

type Json = Record<string, unknown>;

/**
 * Checks the byte ranges once the buffers are known: `bufferBytes[i]` is
 * the length of the bytes actually read for buffers[i]. Throws GltfError.
 */
export function validateGltfBuffers(json: Json, bufferBytes: number[]): void {
  const buffers = list(json, 'buffers');
  const views = list(json, 'bufferViews');
  const accessors = list(json, 'accessors');
  buffers.forEach((b, i) => {
    if (bufferBytes[i] < (b.byteLength as number)) {
      fail(
        `buffers[${i}]`,
        `declares ${b.byteLength as number} bytes, but only ${bufferBytes[i]} could be read`,
      );
    }
  });
  views.forEach((v, i) => {
    const end = ((v.byteOffset as number | undefined) ?? 0) + (v.byteLength as number);
    const b = v.buffer as number;
    if (end > (buffers[b].byteLength as number)) {
      fail(
        `bufferViews[${i}]`,
        `ends at byte ${end}, past the end of buffers[${b}] (${buffers[b].byteLength as number} bytes)`,
      );
    }
  });
  const range = (
    p: string,
    viewIndex: number,
    offset: number,
    count: number,
    element: number,
    stride: number,
    align: number,
  ): void => {
    const v = views[viewIndex];
    const end = offset + stride * (count - 1) + element;
    if (end > (v.byteLength as number)) {
      fail(
        p,
        `needs ${end} bytes of bufferViews[${viewIndex}], which has ${v.byteLength as number} (count ${count})`,
      );
    }
    const start = ((v.byteOffset as number | undefined) ?? 0) + offset;
    if (start % align !== 0)
      fail(
        p,
        `starts at byte ${start} of its buffer, not a multiple of its component size ${align}`,
      );
  };
  accessors.forEach((a, i) => {
    const p = `accessors[${i}]`;
    const size = COMPONENT_SIZE[a.componentType as number];
    const element = size * TYPE_SIZE[a.type as string];
    const count = a.count as number;
    if (a.bufferView !== undefined) {
      const v = views[a.bufferView as number];
      const stride = (v.byteStride as number | undefined) ?? element;
      if (stride < element)
        fail(
          p,
          `elements of ${element} bytes do not fit bufferViews[${a.bufferView as number}].byteStride ${stride}`,
        );
      range(
        p,
        a.bufferView as number,
        (a.byteOffset as number | undefined) ?? 0,
        count,
        element,
        stride,
        size,
      );
    }
    const sparse = a.sparse as Json | undefined;
    if (sparse !== undefined) {
      const n = sparse.count as number;
      const ind = sparse.indices as Json;
      const isz = COMPONENT_SIZE[ind.componentType as number];
      range(
        `${p}.sparse.indices`,
        ind.bufferView as number,
        (ind.byteOffset as number | undefined) ?? 0,
        n,
        isz,
        isz,
        isz,
      );
      const val = sparse.values as Json;
      range(
        `${p}.sparse.values`,
        val.bufferView as number,
        (val.byteOffset as number | undefined) ?? 0,
        n,
        element,
        element,
        size,
      );
    }
  });
}
