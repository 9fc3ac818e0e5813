/**
 * `--denoise` and `--raw` (render and merge; docs/denoise.md): `--out` is the image
 * denoised by OIDN's network from the film's colour, albedo and normal; `--raw` is the
 * noisy image, byte for byte what a render without `--denoise` writes; a split render
 * merged with `--denoise` gives the bytes of one denoised run; parts without albedo and
 * normal are denoised from the colour alone, with a note; a `.film` is never denoised.
 * The error check is deterministic (fixed seed): on Cornell at 4 spp the denoised image
 * is far closer to the converged reference than the raw one (relMSE 0.0023 against
 * 0.046 when this was written), the point of denoising.
 */
import { readFileSync } from 'node:fs';
import { join } from 'node:path';
import { beforeAll, describe, expect, it } from 'vitest';
import { decodePfm } from '../../src/core/index.ts';
import { ROOT } from '../helpers/render.ts';
import {
  expectRefusal,
  pathwise,
  pathwiseOk,
  tempDir,
  writeCornell,
} from '../helpers/batch-cli.ts';

const dir = tempDir('denoise');
const at = (name: string) => join(dir, name);
let scene: string;

/** Mean of (x − ref)² / (ref² + 0.01) over every channel (the project's relMSE). */
function relMse(image: Float32Array, ref: Float32Array): number {
  let s = 0;
  for (let i = 0; i < ref.length; i++) {
    const d = image[i] - ref[i];
    s += (d * d) / (ref[i] * ref[i] + 0.01);
  }
  return s / ref.length;
}

const pfm = (path: string) => decodePfm(readFileSync(path)).rgb;

beforeAll(() => {
  scene = writeCornell(dir, { width: 128, height: 128, spp: 4 });
  const common = ['render', scene, '--threads', '2'];
  pathwiseOk([...common, '--denoise', '--raw', at('raw.pfm'), '--out', at('denoised.pfm')]);
  pathwiseOk([...common, '--out', at('plain.pfm')]);
  for (const [range, name] of [
    ['0:2', 'a'],
    ['2:4', 'b'],
  ]) {
    pathwiseOk([...common, '--samples', range, '--aux', '--out', at(`${name}.film`)]);
    pathwiseOk([...common, '--samples', range, '--out', at(`${name}-plain.film`)]);
  }
}, 120_000);

describe('render --denoise', () => {
  it('--raw is the image a render without --denoise writes', () => {
    expect(readFileSync(at('raw.pfm')).equals(readFileSync(at('plain.pfm')))).toBe(true);
  });

  it('the denoised image is far closer to the converged reference than the raw one', () => {
    const ref = pfm(join(ROOT, 'tests/references/cornell.pfm'));
    const raw = relMse(pfm(at('raw.pfm')), ref);
    const denoised = relMse(pfm(at('denoised.pfm')), ref);
    expect(denoised).toBeLessThan(raw / 5);
    for (const v of pfm(at('denoised.pfm'))) expect(Number.isFinite(v)).toBe(true);
  });

  it('refuses a .film output and --raw without --denoise, in one line each', () => {
    expectRefusal(
      pathwise(['render', scene, '--denoise', '--out', at('x.film')]),
      /--denoise writes an image, and a \.film holds the exact sums/,
    );
    expectRefusal(
      pathwise(['render', scene, '--raw', at('r.pfm'), '--out', at('x.pfm')]),
      /--raw needs --denoise/,
    );
    expectRefusal(
      pathwise(['render', scene, '--denoise', '--raw', at('x.pfm'), '--out', at('x.pfm')]),
      /--raw names the same file as --out/,
    );
  });
});

describe('merge --denoise', () => {
  it('parts with albedo and normal give the bytes of one denoised run', () => {
    const r = pathwiseOk([
      'merge',
      at('a.film'),
      at('b.film'),
      '--denoise',
      '--raw',
      at('merged-raw.pfm'),
      '--out',
      at('merged.pfm'),
    ]);
    expect(r.stderr).not.toMatch(/colour alone/);
    expect(readFileSync(at('merged.pfm')).equals(readFileSync(at('denoised.pfm')))).toBe(true);
    expect(readFileSync(at('merged-raw.pfm')).equals(readFileSync(at('raw.pfm')))).toBe(true);
  });

  it('parts without them are denoised from the colour alone, with a note (PNG output)', () => {
    const r = pathwiseOk([
      'merge',
      at('a-plain.film'),
      at('b-plain.film'),
      '--denoise',
      '--out',
      at('colour-only.png'),
    ]);
    expect(r.stderr).toMatch(/denoised from the colour alone/);
    const png = readFileSync(at('colour-only.png'));
    expect(png.subarray(1, 4).toString('latin1')).toBe('PNG');
  });
});
