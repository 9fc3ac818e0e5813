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

export function allocPlanes(capacity: number, h: number, w: number): Planes {
  const stride = w + 2;
  const plane = (h + 2) * stride;
  return { c: capacity, capacity, h, w, stride, plane, data: new Float32Array(capacity * plane) };
}

/** Index of interior pixel (y, x) of channel ch. */
export function at(p: Planes, ch: number, y: number, x: number): number {
  return ch * p.plane + (y + 1) * p.stride + x + 1;
}
