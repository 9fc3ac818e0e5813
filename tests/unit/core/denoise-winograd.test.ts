import { describe, expect, it } from 'vitest';
import { conv3x3Relu } from '../../../src/core/denoise/conv3x3.ts';
import { allocPlanes, at, type Planes } from '../../../src/core/denoise/planes.ts';
import type { ConvLayer } from '../../../src/core/denoise/unet-weights.ts';
import {
  allocWinogradScratch,
  WINOGRAD_TILES,
  winogradConv3x3Relu,
  winogradFits,
} from '../../../src/core/denoise/winograd.ts';
import { randomPlanes } from '../../helpers/planes.ts';
import { randomStream } from '../../helpers/tza.ts';

function randomLayer(cin: number, cout: number, next: () => number): ConvLayer {
  return {
    name: 't',
    inChannels: cin,
    outChannels: cout,
    weight: Float32Array.from({ length: cout * cin * 9 }, () => next() - 0.5),
    bias: Float32Array.from({ length: cout }, () => 0.2 * (next() - 0.5)),
  };
}

describe('Winograd F(6×6, 3×3) convolution', () => {
  // Sizes: whole 6×6 tiles, ragged right and bottom edges, one pixel, and more tiles than
  // are transformed together (WINOGRAD_TILES), the last group ragged.
  const sizes: [number, number][] = [
    [12, 18],
    [12, 13], // whole tiles down, ragged across: the last row's windows end at the array's end
    [8, 8],
    [9, 13],
    [1, 1],
    [2, 3],
    [6 * 5 + 2, 6 * 13 + 1], // 6 × 14 tiles
  ];
  // Channels: [a, b] of 5 + 4 → 8 (out-channels all left over, in-channels by 4 and one
  // left over), and 14 + 8 → 28 (by 16 and 12 left over; 22 in-channels, two left over).
  const cases = [
    ...sizes.map(([h, w]) => [h, w, 5, 4, 8] as const),
    [9, 13, 14, 8, 28] as const,
    [20, 24, 14, 8, 28] as const,
  ];
  for (const [h, w, ca, cb, cout] of cases)
    it(`matches the direct convolution over [a, b] to float rounding, ${w}×${h}, ${ca}+${cb} → ${cout}`, () => {
      const next = randomStream(h * 100 + w + cout);
      const a = randomPlanes(ca, h, w, next);
      const b = randomPlanes(cb, h, w, next);
      const layer = randomLayer(ca + cb, cout, next);
      const direct = allocPlanes(cout, h, w);
      const wino = allocPlanes(cout, h, w);
      conv3x3Relu(a, b, layer, direct);
      winogradConv3x3Relu(a, b, layer, wino, allocWinogradScratch(ca + cb, cout));
      // The scale of each output's rounding: Σ|w·x| + |bias|, the same convolution of
      // absolute values (all terms positive, so ReLU leaves it alone).
      const scale = allocPlanes(cout, h, w);
      const abs = (p: Planes): Planes => ({ ...p, data: p.data.map(Math.abs) });
      conv3x3Relu(
        abs(a),
        abs(b),
        { ...layer, weight: layer.weight.map(Math.abs), bias: layer.bias.map(Math.abs) },
        scale,
      );
      let worst = 0;
      let positives = 0;
      for (let i = 0; i < direct.data.length; i++) {
        const d = Math.abs(direct.data[i]! - wino.data[i]!);
        // NaN (a read past the map) must fail: !(d <= 0) lets it into the maximum.
        if (!(d <= 0)) worst = Math.max(worst, d / scale.data[i]!); // border: both zero
        if (direct.data[i]! > 0) positives++;
      }
      // Float32 rounding of the transformed weights (2⁻²⁴ relative each) and of both
      // results, amplified by the transforms' constants (up to 8 in Aᵀ, 5 in Bᵀ): well
      // inside 64 ulps of the sum's scale. An error in a transform matrix is of order 1.
      expect(worst).toBeLessThan(64 * 2 ** -24);
      expect(positives).toBeGreaterThan(0);
    });

  it('gives the same bits whatever part of the map a tile is computed in', () => {
    // A 16×16 map holds 9 tiles, transformed together. Embedded as the top-left corner of
    // a larger map (zero elsewhere), the same tiles fall in other groups at other places
    // in them; the top-left 12×12 outputs (whose windows see only the corner) agree.
    const next = randomStream(5);
    const small = randomPlanes(6, 16, 16, next);
    const big = allocPlanes(6, 40, 72);
    for (let c = 0; c < 6; c++)
      for (let y = 0; y < 16; y++)
        for (let x = 0; x < 16; x++) big.data[at(big, c, y, x)] = small.data[at(small, c, y, x)]!;
    const layer = randomLayer(6, 12, next);
    const s = allocWinogradScratch(6, 12);
    const o1 = allocPlanes(12, 16, 16);
    const o2 = allocPlanes(12, 40, 72);
    winogradConv3x3Relu(small, null, layer, o1, s);
    winogradConv3x3Relu(big, null, layer, o2, s);
    for (let c = 0; c < 12; c++)
      for (let y = 0; y < 12; y++)
        for (let x = 0; x < 12; x++)
          expect(o2.data[at(o2, c, y, x)]).toBe(o1.data[at(o1, c, y, x)]);
  });

  it('refuses a layer whose outputs are not in fours, and mismatched channels', () => {
    const next = randomStream(3);
    const a = randomPlanes(4, 8, 8, next);
    const dst = allocPlanes(8, 8, 8);
    const three = randomLayer(4, 3, next);
    expect(winogradFits(three)).toBe(false);
    expect(() => winogradConv3x3Relu(a, null, three, dst, allocWinogradScratch(4, 8))).toThrow(
      /not in fours/,
    );
    expect(() =>
      winogradConv3x3Relu(a, null, randomLayer(5, 8, next), dst, allocWinogradScratch(8, 8)),
    ).toThrow(/4 input channels, expected 5/);
  });
});
