/**
 * Checkpoints and stop criteria, run as a user runs them: a render killed
 * with SIGKILL at many moments and resumed each time gives the bytes of an
 * uninterrupted run, and every checkpoint left behind is whole; --noise
 * stops at the same sample count whatever the threads or interruptions;
 * a --time render equals a plain render of the samples it reached; resume
 * refuses checkpoints of another render; the progress bar appears only on
 * a terminal.
 */
import { spawn, spawnSync } from 'node:child_process';
import { existsSync, readFileSync } from 'node:fs';
import { join } from 'node:path';
import { beforeAll, describe, expect, it } from 'vitest';
import {
  BIN,
  expectRefusal,
  pathwise,
  pathwiseOk,
  readFilm,
  tempDir,
  writeCornell,
} from '../helpers/batch-cli.ts';
import { ROOT } from '../helpers/render.ts';

const dir = tempDir('resume');
const at = (name: string) => join(dir, name);
let scene: string;

beforeAll(() => {
  scene = writeCornell(dir, { width: 32, height: 24, spp: 48 });
});

/** Starts a render, kills it with SIGKILL after `ms` (if still running); resolves to its exit code (null if killed). */
function runFor(args: string[], ms: number): Promise<{ code: number | null; stdout: string }> {
  return new Promise((resolve, reject) => {
    const child = spawn(process.execPath, [BIN, ...args], { cwd: ROOT });
    let stdout = '';
    let stderr = '';
    child.stdout.on('data', (d) => (stdout += d));
    child.stderr.on('data', (d) => (stderr += d));
    const timer = setTimeout(() => child.kill('SIGKILL'), ms);
    child.on('error', reject);
    child.on('exit', (code) => {
      clearTimeout(timer);
      if (code !== null && code !== 0) reject(new Error(`exit ${code}: ${stderr}`));
      else resolve({ code, stdout });
    });
  });
}

describe('kill and resume', () => {
  it('gives the bytes of an uninterrupted run after SIGKILL at many moments', async () => {
    const small = writeCornell(dir, { width: 48, height: 32, spp: 64 }, 'kill.json');
    // Wall times of a whole render and of start-up alone (a 1-spp render),
    // so that the kills land at chosen moments of the rendering on a fast
    // machine and on a loaded one alike.
    const wall = (args: string[]) => {
      const t = performance.now();
      pathwiseOk(args);
      return (performance.now() - t) / 1000;
    };
    const full = wall(['render', small, '--threads', '2', '--out', at('straight.film')]);
    const startup = wall([
      'render',
      small,
      '--threads',
      '2',
      '--spp',
      '1',
      '--out',
      at('one.film'),
    ]);
    const rendering = Math.max(0.2, full - startup);
    const ckpt = at('run.film');
    const args = [
      'render',
      small,
      '--threads',
      '2',
      '--checkpoint',
      ckpt,
      '--checkpoint-every',
      '0.02',
      '--resume',
      ckpt,
      '--out',
      at('resumed.film'),
      '--json',
    ];
    // Kill moments, as fractions of the rendering time after start-up: the
    // first (negative) falls during start-up, before any checkpoint; the
    // first four together are less than half the work, so they are kills
    // for certain; later ones still let the render advance. After 16
    // attempts the render is left to finish.
    const fractions = [-0.5, 0.1, 0.15, 0.2, 0.3, 0.25, 0.35];
    let kills = 0;
    let lastEnd = 0;
    for (let attempt = 0; ; attempt++) {
      const ms =
        attempt < 16
          ? 1000 * (startup + rendering * fractions[attempt % fractions.length])
          : 600_000;
      const r = await runFor(args, Math.max(10, ms));
      if (r.code === 0) break;
      kills++;
      if (existsSync(ckpt)) {
        // Whatever the moment of the kill, the checkpoint is whole and
        // holds one range from 0 that never moves backwards.
        const { header } = readFilm(ckpt);
        expect(header.ranges).toHaveLength(1);
        expect(header.ranges[0][0]).toBe(0);
        expect(header.ranges[0][1]).toBeGreaterThanOrEqual(lastEnd);
        lastEnd = header.ranges[0][1];
      }
    }
    expect(kills).toBeGreaterThanOrEqual(4);
    expect(lastEnd).toBeGreaterThan(0);
    expect(readFileSync(at('resumed.film')).equals(readFileSync(at('straight.film')))).toBe(true);
  });

  it('continues any .film output to more samples', () => {
    pathwiseOk(['render', scene, '--spp', '20', '--out', at('draft.film')]);
    pathwiseOk(['render', scene, '--resume', at('draft.film'), '--out', at('more.film')]);
    pathwiseOk(['render', scene, '--out', at('plain.film')]);
    expect(readFileSync(at('more.film')).equals(readFileSync(at('plain.film')))).toBe(true);
  });

  it('refuses a checkpoint of another render, range or end', () => {
    pathwiseOk(['render', scene, '--samples', '0:8', '--out', at('c8.film')]);
    expectRefusal(
      pathwise(['render', scene, '--seed', '3', '--resume', at('c8.film'), '--out', at('x.pfm')]),
      /cannot resume: .*c8.film and this render differ in --seed \(0 and 3\)/,
    );
    expectRefusal(
      pathwise([
        'render',
        scene,
        '--samples',
        '4:20',
        '--resume',
        at('c8.film'),
        '--out',
        at('x.pfm'),
      ]),
      /cannot resume: .*c8.film holds samples \[0, 8\), not one range starting at 4/,
    );
    expectRefusal(
      pathwise(['render', scene, '--spp', '6', '--resume', at('c8.film'), '--out', at('x.pfm')]),
      /cannot resume: .*c8.film holds samples \[0, 8\), past this render's end at 6/,
    );
  });
});

describe('stop criteria', () => {
  it('--noise stops at the same sample count and bits for any threads and interruptions', async () => {
    const base = ['render', scene, '--width', '24', '--height', '16', '--noise', '0.25', '--json'];
    const one = JSON.parse(pathwiseOk([...base, '--threads', '1', '--out', at('n1.film')]).stdout);
    expect(one.stopped_by).toBe('noise');
    expect(one.noise).toBeLessThanOrEqual(0.25);
    expect(one.spp).toBeGreaterThan(8);
    const two = JSON.parse(
      pathwiseOk([
        ...base,
        '--threads',
        '2',
        '--checkpoint',
        at('n.ckpt.film'),
        '--checkpoint-every',
        '0.01',
        '--out',
        at('n2.film'),
      ]).stdout,
    );
    expect(two.spp).toBe(one.spp);
    expect(two.checkpoints).toBeGreaterThan(0);
    expect(readFileSync(at('n2.film')).equals(readFileSync(at('n1.film')))).toBe(true);
    // Resumed from a checkpoint taken part way: the same stop, the same bits.
    pathwiseOk([...base, '--spp', String(Math.floor(one.spp / 2)), '--out', at('half.film')]);
    const resumed = JSON.parse(
      pathwiseOk([...base, '--resume', at('half.film'), '--out', at('n3.film')]).stdout,
    );
    expect(resumed.resumed_from).toBe(Math.floor(one.spp / 2));
    expect(resumed.spp).toBe(one.spp);
    const n1 = readFilm(at('n1.film'));
    const n3 = readFilm(at('n3.film'));
    // (The totals differ: one render was given --spp; the pixels may not.)
    expect(
      Buffer.from(n3.film.buffer as ArrayBuffer).equals(Buffer.from(n1.film.buffer as ArrayBuffer)),
    ).toBe(true);
  });

  it('--noise warns when --spp ends the render first', () => {
    const r = pathwise([
      'render',
      scene,
      '--spp',
      '4',
      '--noise',
      '0.001',
      '--out',
      at('w.pfm'),
      '--json',
    ]);
    expect(r.status).toBe(0);
    expect(JSON.parse(r.stdout)).toMatchObject({ spp: 4, stopped_by: 'spp' });
    expect(r.stderr).toMatch(
      /stopped by the sample count at 4 spp with noise .* above the --noise target 0.001/,
    );
  });

  it('--time writes the same bits as a plain render of the samples it reached', () => {
    const r = JSON.parse(
      pathwiseOk(['render', scene, '--time', '2', '--out', at('t.film'), '--json']).stdout,
    );
    expect(r.stopped_by).toBe('time');
    expect(r.spp).toBeGreaterThan(0);
    expect(r.samples).toEqual([0, r.spp]);
    pathwiseOk(['render', scene, '--spp', String(r.spp), '--out', at('t-plain.film')]);
    expect(readFileSync(at('t.film')).equals(readFileSync(at('t-plain.film')))).toBe(true);
  });
});

describe('progress', () => {
  const hasScript = spawnSync('script', ['--version']).status === 0;

  it('draws a bar with an ETA on a terminal, nothing otherwise', () => {
    expect(hasScript, 'script(1) from util-linux is needed to give the render a terminal').toBe(
      true,
    );
    const cmd = [process.execPath, BIN, 'render', scene, '--noise', '0.3', '--out', at('p.pfm')]
      .map((a) => `'${a}'`)
      .join(' ');
    const tty = spawnSync('script', ['-qec', cmd, '/dev/null'], { cwd: ROOT, encoding: 'utf8' });
    expect(tty.status).toBe(0);
    expect(tty.stdout).toMatch(
      /\r\[[#.]+\] +\d+%  \d+\/1048576 spp  \d+:\d\d  ETA \d+:\d\d  noise [\d.?]+ → 0\.3/,
    );
    const plain = pathwise(['render', scene, '--noise', '0.3', '--out', at('p.pfm')]);
    expect(plain.status).toBe(0);
    expect(plain.stderr).toBe('');
  });
});
