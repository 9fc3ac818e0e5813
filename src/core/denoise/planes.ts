/**
 * A feature map of the denoiser: `c` channel planes of h × w floats, each stored with a
 * one-pixel zero border ((h + 2) × (w + 2) floats per plane). The border is the 3×3
 * convolution's zero padding (OIDN pads with zeros, training/model.py: padding=1), so the
 * convolution's inner loop reads its neighbours without a bounds test. Only the interior
 * is ever written; the border stays zero from allocation on.
 */
export interface Planes {
  /** Channels in use (at most `capacity`). */
  c: number;
  readonly capacity: number;
  readonly h: number;
  readonly w: number;
  /** Floats per row, w + 2. */
  readonly stride: number;
  /** Floats per plane, (h + 2) × (w + 2). */
  readonly plane: number;
  readonly data: Float32Array;
}

/**
 * Memory that planes are carved from in allocation order. Threads that carve the same
 * sizes in the same order from one SharedArrayBuffer get views of the same planes: the
 * shared workspace of a tile that several threads run together (unet.ts, bands).
 */
export interface PlaneArena {
  readonly buffer: ArrayBufferLike;
  /** Bytes carved so far. */
  offset: number;
}

/** Bytes of a feature map of `capacity` channels of h × w (with its border). */
export function planesBytes(capacity: number, h: number, w: number): number {
  return capacity * (h + 2) * (w + 2) * 4;
}

export function allocPlanes(capacity: number, h: number, w: number, arena?: PlaneArena): Planes {
  const stride = w + 2;
  const plane = (h + 2) * stride;
  let data: Float32Array;
  if (arena) {
    const bytes = planesBytes(capacity, h, w);
    if (arena.offset + bytes > arena.buffer.byteLength)
      throw new RangeError(`planes arena of ${arena.buffer.byteLength} bytes is too small`);
    data = new Float32Array(arena.buffer, arena.offset, capacity * plane);
    arena.offset += bytes;
  } else data = new Float32Array(capacity * plane);
  return { c: capacity, capacity, h, w, stride, plane, data };
}

/** Index of interior pixel (y, x) of channel ch. */
export function at(p: Planes, ch: number, y: number, x: number): number {
  return ch * p.plane + (y + 1) * p.stride + x + 1;
}
