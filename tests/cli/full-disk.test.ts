/**
 * A full disk (ENOSPC) during the final write, a checkpoint write or a merge: one line,
 * exit 2, the temporary file removed, an earlier output and an earlier checkpoint left
 * as they were. The disk is a real one: a 500 KiB tmpfs mounted for the test, which
 * needs root (CI runs as root; elsewhere the test says it was not run, by its name).
 */
import { execFileSync } from 'node:child_process';
import { mkdirSync, readdirSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { expectRefusal, pathwise, pathwiseOk, tempDir } from '../helpers/batch-cli.ts';
import { ROOT } from '../helpers/render.ts';

const root = process.getuid?.() === 0;

describe.runIf(root)('a full disk (a 500 KiB tmpfs; needs root to mount it)', () => {
  let base: string;
  let disk: string;
  const cornell = join(ROOT, 'scenes/cornell.json');

  beforeAll(() => {
    base = tempDir('full-disk');
    disk = join(base, 'disk');
    mkdirSync(disk);
    execFileSync('mount', ['-t', 'tmpfs', '-o', 'size=500k', 'tmpfs', disk]);
  });
  afterAll(() => {
    execFileSync('umount', [disk]);
    rmSync(base, { recursive: true, force: true });
  });

  const temps = () => readdirSync(disk).filter((f) => f.endsWith('.tmp'));

  it('the final write, a checkpoint and a merge each stop with one line, leaving what was there', () => {
    // An earlier checkpoint (64² film, 279 KB) and an earlier output: room for no second film.
    const checkpoint = join(disk, 'c.film');
    const args = ['render', cornell, '--width', '64', '--height', '64', '--spp', '64'];
    pathwiseOk([...args, '--samples', '0:8', '--out', checkpoint]);
    const before = readFileSync(checkpoint);
    const out = join(disk, 'out.pfm');
    writeFileSync(out, 'kept');

    // A checkpoint write fills the disk.
    const a = pathwise([
      ...args,
      '--resume',
      checkpoint,
      '--checkpoint',
      checkpoint,
      '--checkpoint-every',
      '0.001',
      '--out',
      out,
    ]);
    expectRefusal(a, /^pathwise: cannot write .*c\.film: no space left on device$/);
    expect(readFileSync(checkpoint).equals(before)).toBe(true);
    expect(readFileSync(out, 'utf8')).toBe('kept');
    expect(temps()).toEqual([]);

    // The final write fills it (a 256² PFM, 786 KB).
    const b = pathwise([
      'render',
      cornell,
      '--width',
      '256',
      '--height',
      '256',
      '--spp',
      '1',
      '--out',
      out,
    ]);
    expectRefusal(b, /^pathwise: cannot write .*out\.pfm: no space left on device$/);
    expect(readFileSync(out, 'utf8')).toBe('kept');
    expect(temps()).toEqual([]);

    // A merge fills it.
    const c = pathwise(['merge', checkpoint, '--allow-gaps', '--out', join(disk, 'm.film')]);
    expectRefusal(c, /^pathwise: cannot write .*m\.film: no space left on device$/);
    expect(readdirSync(disk).sort()).toEqual(['c.film', 'out.pfm']);

    // The checkpoint is still the one to resume from.
    const resumed = join(base, 'resumed.pfm');
    const whole = join(base, 'whole.pfm');
    pathwiseOk([...args, '--resume', checkpoint, '--out', resumed]);
    pathwiseOk([...args, '--out', whole]);
    expect(readFileSync(resumed).equals(readFileSync(whole))).toBe(true);
  });
});
