/**
 * Accessor data as the loader needs it: vertex attributes as floats (with
 * glTF's normalised integer encodings decoded, §3.11 "Animations"…
 * "normalized": c / (2^n − 1) unsigned, max(c / (2^(n−1) − 1), −1) signed),
 * indices as integers. glTF-Transform has already de-interleaved the data
 * and applied sparse substitution; `getArray` returns the raw components.
 */
import type { Accessor } from '@gltf-transform/core';

/** The accessor's components as float32, `size` per element (the accessor's own size). */
export function readFloats(accessor: Accessor): Float32Array {
  const a = accessor.getArray();
  if (a === null) return new Float32Array(accessor.getCount() * accessor.getElementSize());
  if (a instanceof Float32Array) return a;
  const out = new Float32Array(a.length);
  if (!accessor.getNormalized()) {
    for (let i = 0; i < a.length; i++) out[i] = a[i];
    return out;
  }
  let scale = 1;
  let signed = false;
  if (a instanceof Uint8Array) scale = 255;
  else if (a instanceof Uint16Array) scale = 65535;
  else if (a instanceof Uint32Array) scale = 4294967295;
  else if (a instanceof Int8Array) ((scale = 127), (signed = true));
  else if (a instanceof Int16Array) ((scale = 32767), (signed = true));
  else if (a instanceof Int32Array) ((scale = 2147483647), (signed = true));
  const inv = 1 / scale;
  for (let i = 0; i < a.length; i++) {
    const v = a[i] * inv;
    out[i] = signed && v < -1 ? -1 : v;
  }
  return out;
}

/** Index data as Uint32 (validated as SCALAR, unsigned, by validate.ts). */
export function readIndices(accessor: Accessor): Uint32Array {
  const a = accessor.getArray();
  if (a === null) return new Uint32Array(accessor.getCount());
  return a instanceof Uint32Array ? a : Uint32Array.from(a as ArrayLike<number>);
}
