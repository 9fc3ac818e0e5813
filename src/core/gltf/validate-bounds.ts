/**
 * POSITION's `min` and `max`: glTF 2.0 §3.7.2.1 says the POSITION accessor "MUST
 * have its min and max properties defined", and §3.6.2.5 that they hold the
 * data's bounds. pathwise takes every bound from the vertices themselves, so a
 * file whose declared bounds are absent or wrong renders as its data says; that
 * is said in one note per accessor, not passed over in silence (a wrong bound
 * is what a damaged or hand-edited file shows first).
 */
import { list, type Json } from './validate-values.ts';

/** Notes for POSITION accessors whose min/max are missing or do not bound their data. */
export function positionBoundsNotes(json: Json, buffers: Uint8Array[]): string[] {
  const notes: string[] = [];
  const accessors = list(json, 'accessors');
  const views = list(json, 'bufferViews');
  const seen = new Set<number>();
  for (const mesh of list(json, 'meshes')) {
    for (const pr of (mesh.primitives as Json[] | undefined) ?? []) {
      const i = (pr.attributes as Json | undefined)?.POSITION;
      if (typeof i !== 'number' || seen.has(i)) continue;
      seen.add(i);
      const a = accessors[i];
      const min = a.min as number[] | undefined;
      const max = a.max as number[] | undefined;
      if (!Array.isArray(min) || !Array.isArray(max)) {
        notes.push(
          `accessors[${i}] (POSITION): has no min and max (§3.7.2.1 requires them); the bounds are taken from the vertices`,
        );
        continue;
      }
      // Float data read directly; quantized or sparse positions are left to the loader.
      if (a.componentType !== 5126 || a.sparse !== undefined || a.bufferView === undefined)
        continue;
      const view = views[a.bufferView as number];
      const bytes = buffers[view.buffer as number];
      const stride = (view.byteStride as number | undefined) ?? 12;
      const start =
        ((view.byteOffset as number | undefined) ?? 0) +
        ((a.byteOffset as number | undefined) ?? 0);
      const dv = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
      const count = a.count as number;
      for (let c = 0; c < 3; c++) {
        // The JSON bounds of float data are float32 values written as decimals (§3.6.2.5).
        const lo = Math.fround(min[c]);
        const hi = Math.fround(max[c]);
        for (let k = 0; k < count; k++) {
          const v = dv.getFloat32(start + k * stride + 4 * c, true);
          if (v < lo || v > hi) {
            notes.push(
              `accessors[${i}] (POSITION): vertex ${k} has ${'xyz'[c]} = ${v}, outside the declared ` +
                `min ${min[c]} and max ${max[c]}; the bounds are taken from the vertices`,
            );
            c = 3;
            break;
          }
        }
      }
    }
  }
  return notes;
}
