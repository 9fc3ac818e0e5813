/**
 * No silent empty image (issue 27): a render in which the film accepted no
 * sample at all fails with one line naming the cause, and writes nothing.
 * The scene is valid (every radiance at most 1e12, the format's bound), but
 * every path in a closed box of walls that emit 1e12 and reflect half sums
 * to more than the film's per-sample limit of 2^40, so every sample is
 * dropped: before the fix this exited 0 with a black image and a warning.
 */
import { existsSync, mkdtempSync, readFileSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { describe, expect, it } from 'vitest';
import { ROOT } from '../helpers/render.ts';
import { expectOneLine, runCli } from '../helpers/cli.ts';

const dir = mkdtempSync(join(tmpdir(), 'pathwise-empty-'));
const HOT_BOX = join(ROOT, 'tests/browser/fixtures/hot-box.json');

describe('a render whose every sample is dropped', () => {
  it('exits 2 with one line naming the cause, and writes no image', async () => {
    const out = join(dir, 'hot.pfm');
    const r = await runCli(['render', HOT_BOX, '--threads', '2', '--out', out]);
    expect(r.status, r.stderr).toBe(2);
    expectOneLine(r.stderr);
    expect(r.stderr).toContain('hot-box.json: no image: all 256 samples were not finite');
    expect(r.stderr).toContain("every path's radiance was out of range");
    expect(existsSync(out)).toBe(false);
  });

  it('a render with only some samples dropped still writes its image, with a warning', async () => {
    // The box without the wall behind the camera: paths that leave through
    // the opening keep the first wall's 1e12 and are kept; the others are dropped.
    const scene = JSON.parse(readFileSync(HOT_BOX, 'utf8'));
    scene.shapes.splice(1, 1);
    const open = join(dir, 'open-box.json');
    writeFileSync(open, JSON.stringify(scene));
    const out = join(dir, 'open.pfm');
    const r = await runCli(['render', open, '--threads', '2', '--out', out]);
    expect(r.status, r.stderr).toBe(0);
    expect(r.stderr).toMatch(/warning: \d+ of 256 samples were not finite/);
    expect(existsSync(out)).toBe(true);
  });
});
