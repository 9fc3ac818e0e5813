/**
 * `pathwise render MODEL.glb --variant NAME` (KHR_materials_variants) on the corpus's
 * GlamVelvetSofa, whose fabric has five variants and whose default fabric material is
 * the one "Navy" maps: "Navy" renders the same bits as no selection, "Champagne" a
 * different (lighter) image; an unknown name is refused with exit status 2 and the
 * file's names; `--variant` is refused for a scene file, which names a variant per
 * gltf shape.
 */
import { mkdtempSync, readFileSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { describe, expect, it } from 'vitest';
import { decodePfm } from '../../src/core/index.ts';
import { ROOT } from '../helpers/render.ts';
import { runCli } from '../helpers/cli.ts';

const dir = mkdtempSync(join(tmpdir(), 'pathwise-cli-variants-'));
const sofa = join(ROOT, 'tests/corpus/GlamVelvetSofa/GlamVelvetSofa.glb');
const small = ['--width', '24', '--height', '16', '--spp', '2', '--threads', '1'];

function render(out: string, ...extra: string[]) {
  return runCli(['render', sofa, ...small, ...extra, '--out', join(dir, out)], {
    timeoutMs: 60_000,
  });
}

/** Per-channel sums of `a` minus those of `b` (two PFMs of one size). */
function channelChange(a: string, b: string): number[] {
  const x = decodePfm(readFileSync(join(dir, a))).rgb;
  const y = decodePfm(readFileSync(join(dir, b))).rgb;
  const d = [0, 0, 0];
  for (let i = 0; i < x.length; i++) d[i % 3] += x[i] - y[i];
  return d;
}

describe('pathwise render --variant', () => {
  it('renders the named variant: the default one gives the same bits, another a different image', async () => {
    const [plain, navy, champagne] = await Promise.all([
      render('plain.pfm'),
      render('navy.pfm', '--variant', 'Navy'),
      render('champagne.pfm', '--variant=Champagne'),
    ]);
    for (const r of [plain, navy, champagne]) {
      expect(r.status, r.stderr).toBe(0);
      // Nothing about the extension: it is honoured.
      expect(r.stderr).not.toContain('KHR_materials_variants');
    }
    const bytes = (f: string) => readFileSync(join(dir, f));
    expect(bytes('navy.pfm').equals(bytes('plain.pfm'))).toBe(true);
    expect(bytes('champagne.pfm').equals(bytes('plain.pfm'))).toBe(false);
    // Navy's fabric is a blue sheen (0.05, 0.17, 0.5) on a near-black base, Champagne's a
    // warm one (0.9, 0.7, 0.6) on a warm base: the change is brighter and redder.
    const [r, g, b] = channelChange('champagne.pfm', 'plain.pfm');
    expect(r).toBeGreaterThan(0);
    expect(r).toBeGreaterThan(b);
  }, 120_000);

  it('refuses an unknown name with exit status 2, listing the file’s variants', async () => {
    const r = await render('x.pfm', '--variant', 'Purple');
    expect(r.status).toBe(2);
    expect(r.stderr).toContain(
      'glTF: extensions.KHR_materials_variants.variants: has no variant "Purple"; the file\'s ' +
        'variants are "Champagne", "Navy", "Gray", "Black", "Pale Pink"',
    );
    expect(r.stderr.trim().split('\n')).toHaveLength(1);
  }, 60_000);

  it('refuses --variant for a scene file', async () => {
    writeFileSync(
      join(dir, 'scene.json'),
      JSON.stringify({
        format: 'pathwise-scene/1',
        camera: { position: [0, 0, 3], target: [0, 0, 0], up: [0, 1, 0], fovY: 30 },
        materials: {},
        shapes: [],
      }),
    );
    const r = await runCli([
      'render',
      join(dir, 'scene.json'),
      '--variant',
      'Navy',
      '--out',
      join(dir, 'y.pfm'),
    ]);
    expect(r.status).toBe(2);
    expect(r.stderr).toContain(
      '--variant applies to a glTF model; in a scene file, a gltf shape names its own variant',
    );
  });
});
