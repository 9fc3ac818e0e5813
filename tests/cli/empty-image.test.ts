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
    // The box without the wall behind the camera, only the wall ahead hot: a path
    // that starts on it carries its 1e12 plus what later bounces gather, and some
    // pass 2^40; a path that starts on a cold wall stays below. So some samples are
    // dropped, not all. (With every wall hot, light splitting sums several walls at
    // each vertex and every path passes 2^40.)
    const scene = JSON.parse(readFileSync(HOT_BOX, 'utf8'));
    scene.shapes.splice(1, 1);
    scene.materials.cold = { type: 'diffuse', albedo: [0.5, 0.5, 0.5] };
    for (const shape of scene.shapes.slice(1)) shape.material = 'cold';
    const open = join(dir, 'open-box.json');
    writeFileSync(open, JSON.stringify(scene));
    const out = join(dir, 'open.pfm');
    const r = await runCli(['render', open, '--threads', '2', '--out', out]);
    expect(r.status, r.stderr).toBe(0);
    expect(r.stderr).toMatch(/warning: \d+ of 256 samples were not finite/);
    expect(existsSync(out)).toBe(true);
  });
});
