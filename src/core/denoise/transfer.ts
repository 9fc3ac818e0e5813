/**
 * What OIDN does to HDR colour before and after its network (core/color.h, TransferFunction;
 * devices/cpu/cpu_autoexposure.*, cpu_input_process.isph, cpu_output_process.isph):
 *
 * - autoexposure: the image is cut into bins of at most 16×16 pixels; each bin's mean
 *   luminance L (Rec. 709 weights, negatives and NaN taken as 0) with L > 1e-8 adds log2 L;
 *   the input scale is 0.18 / 2^(mean log2 L), or 1 when no bin is lit;
 * - input: colour × scale, NaN → 0, clamped to [0, FLT_MAX], then the "PU" curve (a
 *   perceptually uniform encoding fitted by OIDN: linear, then power, then log), divided
 *   by PU(65504) so that the largest half float maps to 1; albedo clamped to [0, 1];
 *   normal clamped to [-1, 1] and mapped to [0, 1] by n/2 + 1/2;
 * - output: NaN → 0, clamped to [0, FLT_MAX], the inverse curve, then ÷ scale.
 */
const PU_A = 1.41283765e3;
const PU_B = 1.64593172;
const PU_C = 4.31384981e-1;
const PU_D = -2.94139609e-3;
const PU_E = 1.92653254e-1;
const PU_F = 6.26026094e-3;
const PU_G = 9.98620152e-1;
const PU_Y0 = 1.5794576e-6;
const PU_Y1 = 3.22087631e-2;
const PU_X0 = 2.23151711e-3;
const PU_X1 = 3.70974749e-1;
const FLT_MAX = 3.4028234663852886e38;
/** The largest binary16 value: OIDN's HDR range. */
const Y_MAX = 65504;

export function puForward(y: number): number {
  if (y <= PU_Y0) return PU_A * y;
  if (y <= PU_Y1) return PU_B * Math.pow(y, PU_C) + PU_D;
  return PU_E * Math.log(y + PU_F) + PU_G;
}

export function puInverse(x: number): number {
  if (x <= PU_X0) return x / PU_A;
  if (x <= PU_X1) return Math.pow((x - PU_D) / PU_B, 1 / PU_C);
  return Math.exp((x - PU_G) / PU_E) - PU_F;
}

/** PU(65504): dividing by it puts the encoded range in [0, 1]. */
const PU_X_MAX = Math.fround(puForward(Y_MAX));
const NORM_SCALE = Math.fround(1 / PU_X_MAX);

/** Encoded network input for one linear HDR value already multiplied by the input scale. */
export function encodeHdr(v: number): number {
  const y = v > 0 ? Math.min(v, FLT_MAX) : 0; // NaN and negatives → 0
  return Math.fround(puForward(y)) * NORM_SCALE;
}

/** Linear value for one network output, before the division by the input scale. */
export function decodeHdr(x: number): number {
  const c = x > 0 ? Math.min(x, FLT_MAX) : 0;
  return puInverse(Math.fround(c * PU_X_MAX));
}

export function encodeAlbedo(v: number): number {
  return v > 0 ? Math.min(v, 1) : 0;
}

export function encodeNormal(v: number): number {
  const n = v > -1 ? Math.min(v, 1) : v !== v ? 0 : -1;
  return n * 0.5 + 0.5;
}

/** OIDN's autoexposure input scale for an RGB image (row-major, 3 floats a pixel). */
export function autoexposure(rgb: Float32Array, width: number, height: number): number {
  const binsH = Math.ceil(height / 16);
  const binsW = Math.ceil(width / 16);
  let sum = 0;
  let count = 0;
  for (let i = 0; i < binsH; i++) {
    const y0 = Math.floor((i * height) / binsH);
    const y1 = Math.floor(((i + 1) * height) / binsH);
    for (let j = 0; j < binsW; j++) {
      const x0 = Math.floor((j * width) / binsW);
      const x1 = Math.floor(((j + 1) * width) / binsW);
      let l = 0;
      for (let y = y0; y < y1; y++) {
        for (let x = x0; x < x1; x++) {
          const p = 3 * (y * width + x);
          const r = rgb[p]! > 0 ? Math.min(rgb[p]!, FLT_MAX) : 0;
          const g = rgb[p + 1]! > 0 ? Math.min(rgb[p + 1]!, FLT_MAX) : 0;
          const b = rgb[p + 2]! > 0 ? Math.min(rgb[p + 2]!, FLT_MAX) : 0;
          l += 0.212671 * r + 0.71516 * g + 0.072169 * b;
        }
      }
      l /= (y1 - y0) * (x1 - x0);
      if (l > 1e-8) {
        sum += Math.log2(l);
        count++;
      }
    }
  }
  return count > 0 ? Math.fround(0.18 / Math.pow(2, sum / count)) : 1;
}
