/**
 * The `pathwise render` command line, run as a user runs it (the bundle
 * built by tests/global-setup.ts): determinism across threads and stripe
 * layouts, output formats, JSON statistics, exit codes and messages.
 */
import { execFileSync, spawnSync } from 'node:child_process';
import { mkdtempSync, readFileSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { describe, expect, it } from 'vitest';
import { decodePfm } from '../../../src/core/index.ts';
import { ROOT } from '../../helpers/render.ts';

const dir = mkdtempSync(join(tmpdir(), 'pathwise-cli-'));
const bin = join(ROOT, 'bin/pathwise.js');

function run(args: string[]): { status: number | null; stdout: string; stderr: string } {
  const r = spawnSync(process.execPath, [bin, ...args], { cwd: ROOT, encoding: 'utf8' });
  return { status: r.status, stdout: r.stdout, stderr: r.stderr };
}

function render(out: string, extra: string[], seed = 9): Buffer {
  execFileSync(
    process.execPath,
    [
      bin,
      'render',
      'scenes/cornell.json',
      '--width',
      '48',
      '--height',
      '40',
      '--spp',
      '6',
      '--seed',
      String(seed),
      '--out',
      out,
      ...extra,
    ],
    { cwd: ROOT },
  );
  return readFileSync(out);
}

describe('pathwise render', () => {
  it('writes bit-identical PFMs for 1, 2 and 3 threads and any stripe layout', () => {
    const a = render(join(dir, 'a.pfm'), ['--threads', '1']);
    const b = render(join(dir, 'b.pfm'), ['--threads', '2']);
    const c = render(join(dir, 'c.pfm'), ['--threads', '3', '--stripe-rows', '7']);
    const d = render(join(dir, 'd.pfm'), ['--threads', '2', '--stripe-rows', '1']);
    expect(b.equals(a)).toBe(true);
    expect(c.equals(a)).toBe(true);
    expect(d.equals(a)).toBe(true);
    // And a different seed gives a different image (the comparison can fail).
    const e = render(join(dir, 'e.pfm'), ['--threads', '2'], 10);
    expect(e.equals(a)).toBe(false);
  });

  it('writes a standard PFM: PF, scale -1, rows bottom to top', () => {
    const bytes = render(join(dir, 'f.pfm'), []);
    expect(bytes.subarray(0, 14).toString('latin1')).toBe('PF\n48 40\n-1.0\n');
    const img = decodePfm(bytes);
    expect(img.width).toBe(48);
    expect(img.height).toBe(40);
    // The Cornell light is at the top of the image: the brightest row is near row 0.
    let best = -1;
    let bestRow = -1;
    for (let y = 0; y < 40; y++) {
      let s = 0;
      for (let x = 0; x < 48; x++) s += img.rgb[(y * 48 + x) * 3];
      if (s > best) [best, bestRow] = [s, y];
    }
    expect(bestRow).toBeLessThan(8);
  });

  it('writes a PNG and prints one JSON line of statistics', () => {
    const out = join(dir, 'g.png');
    const r = run([
      'render',
      'scenes/cornell.json',
      '--width',
      '32',
      '--height',
      '32',
      '--spp',
      '4',
      '--out',
      out,
      '--json',
      '--exposure',
      '1.5',
    ]);
    expect(r.status).toBe(0);
    const png = readFileSync(out);
    expect([...png.subarray(0, 8)]).toEqual([0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a]);
    const lines = r.stdout.trim().split('\n');
    expect(lines).toHaveLength(1);
    const stats = JSON.parse(lines[0]);
    for (const key of [
      'seconds',
      'spp',
      'width',
      'height',
      'paths',
      'segments',
      'mpaths_per_s',
      'msegments_per_s',
      'rejected_samples',
    ]) {
      expect(stats).toHaveProperty(key);
    }
    expect(stats.paths).toBe(32 * 32 * 4);
    expect(stats.segments).toBeGreaterThan(stats.paths);
    expect(stats.rejected_samples).toBe(0);
    expect(stats.spp).toBe(4);
  });

  it.each([
    [
      ['render', 'scenes/cornell.json', '--out', 'x.pfm', '--spp', '0'],
      /--spp must be an integer in \[1, 1048576\], got 0/,
    ],
    [
      ['render', 'scenes/cornell.json', '--out', 'x.pfm', '--width', '5000', '--height', '5000'],
      /16777216/,
    ],
    [['render', 'scenes/cornell.json', '--out', 'x.pfm', '--bounces', '65'], /--bounces/],
    [['render', 'scenes/cornell.json', '--out', 'x.jpg'], /--out must end in .pfm, .png or .film/],
    [['render', 'scenes/cornell.json'], /missing --out/],
    [['render', '--out', 'x.pfm'], /missing the scene file/],
    [['render', 'scenes/nope.json', '--out', 'x.pfm'], /cannot read scenes\/nope.json/],
    [
      ['render', 'scenes/cornell.json', '--out', 'x.pfm', '--threads', 'two'],
      /--threads must be an integer/,
    ],
    [
      ['render', 'scenes/cornell.json', '--out', 'x.pfm', '--frobnicate', '1'],
      /unknown option --frobnicate/,
    ],
    [
      ['render', 'scenes/cornell.json', '--out', 'x.pfm', '--estimator', 'magic'],
      /--estimator must be nee-mis or bsdf/,
    ],
    [['frobnicate'], /unknown command/],
  ])('exits 2 with a one-line message for %j', (args, message) => {
    const r = run(args);
    expect(r.status).toBe(2);
    expect(r.stderr).toMatch(message);
    expect(r.stderr.trim().split('\n')).toHaveLength(1);
  });

  it('exits 2 naming the offending path for a bad scene', () => {
    const bad = JSON.parse(readFileSync(join(ROOT, 'scenes/spheres.json'), 'utf8'));
    bad.shapes[3].radius = -2;
    const file = join(dir, 'bad.json');
    writeFileSync(file, JSON.stringify(bad));
    const r = run(['render', file, '--out', join(dir, 'bad.pfm')]);
    expect(r.status).toBe(2);
    expect(r.stderr).toMatch(/shapes\[3\]\.radius must be > 0, got -2/);
  });
});
