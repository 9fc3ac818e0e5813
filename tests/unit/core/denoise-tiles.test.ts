/**
 * Tiling changes only rounding; threads change no bit. A tiny U-Net (the RT wiring, 4
 * channels a layer, random weights: tests/helpers/tza.ts) keeps this cheap; the
 * properties do not depend on the widths. (1) An image cut into OIDN's overlapped tiles
 * agrees with the same image in one tile to float rounding: the overlap covers the
 * receptive field and tile origins keep the pooling grid, but a Winograd block's rounding
 * depends on its whole 6×6 window and on where the block grid falls (winograd.ts), so the
 * bits may differ. (2) denoiseInWorkers with 1, 2 and 4 worker threads gives the same
 * bits: the tile plan does not depend on the thread count.
 */
import { pathToFileURL } from 'node:url';
import { describe, expect, it } from 'vitest';
import { denoiseInWorkers } from '../../../src/cli/denoise-pool.ts';
import { denoise } from '../../../src/core/denoise/denoise.ts';
import { planTiles } from '../../../src/core/denoise/tiles.ts';
import { parseTza } from '../../../src/core/denoise/tza.ts';
import { unetWeights } from '../../../src/core/denoise/unet-weights.ts';
import { randomStream, tinyUNetTza } from '../../helpers/tza.ts';

const W = 520,
  H = 420;
function image(seed: number, lo: number, hi: number): Float32Array {
  const next = randomStream(seed);
  return Float32Array.from({ length: W * H * 3 }, (_, i) => {
    const x = (i / 3) % W;
    return lo + (hi - lo) * (0.5 + 0.25 * Math.sin(x / 17) + 0.25 * next());
  });
}
const images = {
  width: W,
  height: H,
  color: image(1, 0, 4),
  albedo: image(2, 0, 1),
  normal: image(3, -1, 1),
};
const tza = tinyUNetTza(9, 4, 11);
const tiles = { maxTilePixels: 400 * 400, minTileSide: 0 }; // 2 × 2 tiles of 384²

describe('denoiser tiles and threads', () => {
  it('overlapped tiles agree with one tile to float rounding', () => {
    expect(planTiles(W, H, tiles).tiles.length).toBe(4);
    const weights = unetWeights(parseTza(tza));
    const whole = denoise(images, weights);
    const tiled = denoise(images, weights, tiles);
    let worst = 0;
    let peak = 0;
    for (let i = 0; i < whole.length; i++) {
      worst = Math.max(worst, Math.abs(whole[i]! - tiled[i]!)); // NaN fails below
      peak = Math.max(peak, Math.abs(whole[i]!));
    }
    // Rounding through 16 layers: measured 1.7e-7 of the peak (a few float32 ulps). A
    // tile cut in the wrong place (overlap short of the receptive field, a pooling grid
    // shifted) changes values by the size of the image's detail: 0.098 at a peak of 226
    // with the kept region 48 pixels too wide.
    expect(worst).toBeLessThan(1e-6 * peak);
    expect(peak).toBeGreaterThan(0);
  });

  it('1, 2 and 4 worker threads give the same bits', async () => {
    const workerUrl = pathToFileURL('dist/cli/denoise-worker.js');
    const [one, two, four] = await Promise.all(
      [1, 2, 4].map((threads) => denoiseInWorkers(images, tza, { threads, workerUrl, tiles })),
    );
    expect(Buffer.from(two!.buffer).equals(Buffer.from(one!.buffer))).toBe(true);
    expect(Buffer.from(four!.buffer).equals(Buffer.from(one!.buffer))).toBe(true);
    expect(
      Buffer.from(one!.buffer).equals(
        Buffer.from(denoise(images, unetWeights(parseTza(tza)), tiles).buffer),
      ),
    ).toBe(true);
  });

  it('more threads than block rows at the deepest level: the idle bands change no bit', async () => {
    // A 40×24 image is one 48×32 tile; its 1/16 level is 3×2, one row of Winograd blocks,
    // so with 3 threads two bands are empty there.
    const small = {
      width: 40,
      height: 24,
      color: images.color.subarray(0, 40 * 24 * 3),
      albedo: images.albedo.subarray(0, 40 * 24 * 3),
      normal: images.normal.subarray(0, 40 * 24 * 3),
    };
    const workerUrl = pathToFileURL('dist/cli/denoise-worker.js');
    const alone = denoise(small, unetWeights(parseTza(tza)));
    for (const threads of [2, 3]) {
      const banded = await denoiseInWorkers(small, tza, { threads, workerUrl });
      expect(Buffer.from(banded.buffer).equals(Buffer.from(alone.buffer))).toBe(true);
    }
  });

  it('a band that fails mid-tile rejects the call with its error and frees the others', async () => {
    const workerUrl = pathToFileURL('tests/fixtures/denoise/failing-band-worker.mjs');
    await expect(denoiseInWorkers(images, tza, { threads: 3, workerUrl, tiles })).rejects.toThrow(
      /band 1 failed on purpose/,
    );
  });

  it('a worker that fails rejects the call with its error instead of hanging', async () => {
    const workerUrl = pathToFileURL('dist/cli/no-such-denoise-worker.js');
    await expect(denoiseInWorkers(images, tza, { threads: 2, workerUrl, tiles })).rejects.toThrow(
      /no-such-denoise-worker|Cannot find/,
    );
  });
  it('refuses mismatched inputs before starting a thread', async () => {
    await expect(
      denoiseInWorkers({ ...images, normal: null }, tza, { threads: 2, tiles }),
    ).rejects.toThrow(/the weights take 9 input channels, the images give 6/);
  });
});
