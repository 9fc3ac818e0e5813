/**
 * Small equirectangular environment maps made by code for the generator's mesh
 * family (docs/scene-format.md, Environment maps: row 0 is the +y pole, column
 * u = 0 looks along −z):
 * - constant: every texel one colour (1×1 up to 8×4) — equal to the constant
 *   environment, through the map's code;
 * - gradient: a sky from zenith to horizon over a darker ground, with a slow
 *   variation in azimuth (32×16);
 * - sun: a dim sky with one texel (or a 2×2 block) 1e2…1e5 times brighter, at a
 *   random elevation (64×32 or 128×64): a tiny, very bright region that BSDF
 *   sampling rarely finds and importance sampling must;
 * with a random `rotationY` and a scalar or RGB `scale`, written as .hdr or .pfm.
 */
import { decodeHdr, decodePfm, encodeHdr, encodePfm } from '../../src/core/index.ts';
import type { EnvironmentMapSpec } from './builder.ts';
import type { Rng } from './rng.ts';
import type { Vec3 } from './vec.ts';

export type MapKind = 'constant' | 'gradient' | 'sun';

export function makeEnvironmentMap(rng: Rng, kind: MapKind, level: number): EnvironmentMapSpec {
  let width: number;
  let height: number;
  let rgb: Float32Array;
  const tint = (lo: number): Vec3 => [rng.uniform(lo, 1), rng.uniform(lo, 1), rng.uniform(lo, 1)];
  if (kind === 'constant') {
    [width, height] = rng.pick([
      [1, 1],
      [2, 1],
      [8, 4],
    ] as const);
    const c = tint(0.4);
    rgb = new Float32Array(width * height * 3);
    for (let i = 0; i < width * height; i++)
      rgb.set(
        c.map((x) => x * level),
        3 * i,
      );
  } else {
    [width, height] =
      kind === 'gradient'
        ? [32, 16]
        : rng.pick([
            [64, 32],
            [128, 64],
          ] as const);
    const zenith = tint(0.3);
    const horizon = tint(0.6);
    const ground = tint(0.2).map((x) => x * rng.uniform(0.05, 0.5));
    const wobble = rng.uniform(0, 0.6);
    const phase = rng.uniform(0, 2 * Math.PI);
    const skyLevel = kind === 'sun' ? level * rng.logUniform(0.02, 0.3) : level;
    rgb = new Float32Array(width * height * 3);
    for (let y = 0; y < height; y++) {
      const cosTheta = Math.cos((Math.PI * (y + 0.5)) / height);
      for (let x = 0; x < width; x++) {
        const azimuth = 1 + wobble * Math.sin((2 * Math.PI * (x + 0.5)) / width + phase);
        for (let c = 0; c < 3; c++) {
          const sky = cosTheta > 0 ? horizon[c] + (zenith[c] - horizon[c]) * cosTheta : ground[c];
          rgb[3 * (y * width + x) + c] = skyLevel * sky * azimuth;
        }
      }
    }
    if (kind === 'sun') {
      const elevation = rng.uniform(5, 80) * (Math.PI / 180);
      const y0 = Math.min(height - 1, Math.floor(((Math.PI / 2 - elevation) / Math.PI) * height));
      const x0 = rng.int(0, width - 1);
      const block = rng.chance(0.5) ? 1 : 2;
      const sun = skyLevel * rng.logUniform(1e2, 1e5);
      const color = tint(0.7);
      for (let dy = 0; dy < block; dy++) {
        for (let dx = 0; dx < block; dx++) {
          const o = 3 * (Math.min(height - 1, y0 + dy) * width + ((x0 + dx) % width));
          for (let c = 0; c < 3; c++) rgb[o + c] = sun * color[c];
        }
      }
    }
  }
  const scale: number | Vec3 = rng.chance(0.4)
    ? tint(0.3)
    : rng.chance(0.5)
      ? 1
      : rng.logUniform(0.3, 3);
  const rotationY = rng.chance(0.7) ? rng.uniform(-360, 360) : 0;
  const format = rng.chance(0.5) ? 'hdr' : 'pfm';
  // The texels as the file holds them (RGBE keeps 8 bits of mantissa): what every
  // renderer reads back.
  const bytes = encodeMap({ width, height, rgb, format });
  const decoded =
    format === 'hdr'
      ? decodeHdr(bytes, { maxWidth: width, maxHeight: height })
      : decodePfm(bytes, { maxWidth: width, maxHeight: height });
  return { width, height, rgb: decoded.rgb, bytes, format, scale, rotationY, kind };
}

function encodeMap(m: { width: number; height: number; rgb: Float32Array; format: 'hdr' | 'pfm' }) {
  return m.format === 'hdr'
    ? encodeHdr(m.width, m.height, m.rgb)
    : encodePfm(m.width, m.height, m.rgb);
}
