/**
 * A real model with transmission, volumes and dispersion, rendered as a user would
 * (`pathwise render MODEL.glb`): Khronos's AttenuationTest with KHR_materials_dispersion
 * added (tests/fixtures/gltf-volume/README.md). It renders finite and not blank, with
 * none of its extensions ignored.
 */
import { mkdtempSync, readFileSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, describe, expect, it } from 'vitest';
import { decodePfm } from '../../src/core/io/pfm.ts';
import { runCli } from '../helpers/cli.ts';
import { ROOT } from '../helpers/render.ts';

const dir = mkdtempSync(join(tmpdir(), 'pathwise-volume-'));
afterAll(() => rmSync(dir, { recursive: true, force: true }));

describe('AttenuationTest (volume, dispersion) on the command line', () => {
  it('renders finite, not blank, with no extension ignored', async () => {
    const out = join(dir, 'a.pfm');
    const model = join(ROOT, 'tests/fixtures/gltf-volume/AttenuationTest.dispersion.glb');
    const r = await runCli(
      ['render', model, '--width', '48', '--height', '32', '--spp', '4', '--out', out],
      { timeoutMs: 120_000 },
    );
    expect(r.status, r.stderr).toBe(0);
    expect(r.stderr).not.toMatch(/not supported|ignored/);
    const img = decodePfm(new Uint8Array(readFileSync(out)));
    let sum = 0;
    let nonFinite = 0;
    let lo = Infinity;
    let hi = -Infinity;
    for (const v of img.rgb) {
      if (!Number.isFinite(v)) nonFinite++;
      sum += v;
      lo = Math.min(lo, v);
      hi = Math.max(hi, v);
    }
    expect(nonFinite).toBe(0);
    expect(sum / img.rgb.length).toBeGreaterThan(0.01);
    expect(hi - lo).toBeGreaterThan(0.1);
  }, 150_000);
});
