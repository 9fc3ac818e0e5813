import { describe, expect, it } from 'vitest';
import { conv3x3Relu } from '../../../src/core/denoise/conv3x3.ts';
import { allocPlanes, at, type Planes } from '../../../src/core/denoise/planes.ts';
import { maxPool2x2, upsample2x } from '../../../src/core/denoise/pool-upsample.ts';
import { planTiles, TILE_OVERLAP } from '../../../src/core/denoise/tiles.ts';
import {
  autoexposure,
  decodeHdr,
  encodeHdr,
  encodeNormal,
  puForward,
  puInverse,
} from '../../../src/core/denoise/transfer.ts';
import type { ConvLayer } from '../../../src/core/denoise/unet-weights.ts';
import { randomPlanes } from '../../helpers/planes.ts';
import { randomStream } from '../../helpers/tza.ts';

const get = (p: Planes, ch: number, y: number, x: number): number =>
  y < 0 || x < 0 || y >= p.h || x >= p.w ? 0 : p.data[at(p, ch, y, x)]!;

describe('denoiser operations against naive references', () => {
  it('conv3x3Relu over [a, b] matches the textbook sum, borders zero-padded, for 4-blocked and leftover channels', () => {
    const next = randomStream(7);
    const h = 9,
      w = 13;
    const a = randomPlanes(5, h, w, next);
    const b = randomPlanes(3, h, w, next);
    for (const cout of [8, 7, 3]) {
      const cin = 8;
      const layer: ConvLayer = {
        name: 't',
        inChannels: cin,
        outChannels: cout,
        weight: Float32Array.from({ length: cout * cin * 9 }, next),
        bias: Float32Array.from({ length: cout }, next),
      };
      const dst = allocPlanes(8, h, w);
      conv3x3Relu(a, b, layer, dst);
      let worst = 0;
      for (let o = 0; o < cout; o++)
        for (let y = 0; y < h; y++)
          for (let x = 0; x < w; x++) {
            let s = layer.bias[o]!;
            for (let i = 0; i < cin; i++)
              for (let ky = 0; ky < 3; ky++)
                for (let kx = 0; kx < 3; kx++) {
                  const v =
                    i < 5
                      ? get(a, i, y + ky - 1, x + kx - 1)
                      : get(b, i - 5, y + ky - 1, x + kx - 1);
                  s += layer.weight[((o * cin + i) * 3 + ky) * 3 + kx]! * v;
                }
            worst = Math.max(worst, Math.abs(Math.max(s, 0) - get(dst, o, y, x)));
          }
      expect(worst).toBeLessThan(1e-5); // float32 rounding of sums of ~72 terms of order 1
      // The border stays zero: the next layer's padding.
      for (let o = 0; o < cout; o++)
        for (let x = -1; x <= w; x++) expect(dst.data[o * dst.plane + x + 1]).toBe(0);
    }
  });

  it('max-pools 2×2 and upsamples ×2 as PyTorch does', () => {
    const next = randomStream(3);
    const src = randomPlanes(2, 8, 6, next);
    const pooled = allocPlanes(2, 4, 3);
    maxPool2x2(src, pooled);
    const up = allocPlanes(2, 8, 6);
    upsample2x(pooled, up);
    for (let c = 0; c < 2; c++)
      for (let y = 0; y < 8; y++)
        for (let x = 0; x < 6; x++) {
          const py = y >> 1,
            px = x >> 1;
          const m = Math.max(
            get(src, c, 2 * py, 2 * px),
            get(src, c, 2 * py + 1, 2 * px),
            get(src, c, 2 * py, 2 * px + 1),
            get(src, c, 2 * py + 1, 2 * px + 1),
          );
          expect(get(pooled, c, py, px)).toBe(m);
          expect(get(up, c, y, x)).toBe(m);
        }
  });

  it('PU encoding: continuous, inverse of itself, 65504 → 1, NaN and negatives → 0', () => {
    for (const y of [0, 1e-7, 1.5794576e-6, 1e-3, 3.22087631e-2, 0.5, 1, 10, 1000, 65504]) {
      expect(puInverse(puForward(y))).toBeCloseTo(y, 5);
      expect(decodeHdr(encodeHdr(y))).toBeCloseTo(y, Math.max(0, 4 - Math.log10(1 + y)));
    }
    expect(encodeHdr(65504)).toBeCloseTo(1, 6);
    expect(encodeHdr(NaN)).toBe(0);
    expect(encodeHdr(-3)).toBe(0);
    expect(encodeNormal(-2)).toBe(0);
    expect(encodeNormal(NaN)).toBe(0.5);
    expect(encodeNormal(1)).toBe(1);
  });

  it('autoexposure: 0.18 over the geometric mean of 16×16 bin luminances; 1 for a black image', () => {
    const w = 32,
      h = 16;
    const rgb = new Float32Array(w * h * 3);
    for (let y = 0; y < h; y++)
      for (let x = 0; x < w; x++) rgb.fill(x < 16 ? 0.5 : 2, 3 * (y * w + x), 3 * (y * w + x) + 3);
    const lum = 0.212671 + 0.71516 + 0.072169;
    expect(autoexposure(rgb, w, h)).toBeCloseTo(0.18 / Math.sqrt(0.5 * lum * 2 * lum), 6);
    expect(autoexposure(new Float32Array(w * h * 3), w, h)).toBe(1);
  });

  it('plans OIDN-style tiles: one tile for small images; aligned overlapping tiles that partition the output', () => {
    expect(planTiles(96, 64)).toEqual(
      expect.objectContaining({
        tileW: 96,
        tileH: 64,
        tiles: [expect.objectContaining({ outW: 96, outH: 64, bufX: 0, bufY: 0 })],
      }),
    );
    for (const [w, h] of [
      [700, 300],
      [513, 1000],
      [1000, 1000],
    ] as const) {
      const plan = planTiles(w, h, { maxTilePixels: 400 * 400, minTileSide: 0 });
      expect(plan.tiles.length).toBeGreaterThan(1);
      expect(plan.tileW * plan.tileH).toBeLessThanOrEqual(400 * 400);
      const covered = new Uint8Array(w * h);
      for (const t of plan.tiles) {
        expect(t.srcX % 16).toBe(0);
        expect(t.srcY % 16).toBe(0);
        expect(t.bufX % 16).toBe(0);
        // Every output pixel has the full overlap of input around it, or the image's edge.
        expect(t.outX === 0 || t.outX - t.srcX >= TILE_OVERLAP).toBe(true);
        expect(t.outX + t.outW === w || t.srcX + t.srcW - (t.outX + t.outW) >= TILE_OVERLAP).toBe(
          true,
        );
        for (let y = t.outY; y < t.outY + t.outH; y++)
          for (let x = t.outX; x < t.outX + t.outW; x++) covered[y * w + x]!++;
      }
      expect(covered.every((c) => c === 1)).toBe(true);
    }
  });
});
