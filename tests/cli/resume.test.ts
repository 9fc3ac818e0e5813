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
import {
  closeSync,
  existsSync,
  fstatSync,
  mkdtempSync,
  openSync,
  readFileSync,
  readSync,
  readdirSync,
} from 'node:fs';
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
import { decodeFilmHeader } from '../../src/core/index.ts';

const dir = tempDir('resume');
const at = (name: string) => join(dir, name);
let scene: string;

beforeAll(() => {
  scene = writeCornell(dir, { width: 32, height: 24, spp: 48 });
});

/** Samples [0, n) held by the checkpoint at `path` now, or -1 if there is none yet. */
function checkpointEnd(path: string): number {
  let fd: number;
  try {
    fd = openSync(path, 'r');
  } catch {
    return -1;
  }
  try {
    // The file is replaced by rename, never rewritten: the open one is whole.
    const size = fstatSync(fd).size;
    const prefix = Buffer.alloc(Math.min(size, 1 << 16));
    readSync(fd, prefix, 0, prefix.length, 0);
    const { header } = decodeFilmHeader(prefix, size);
    return header.ranges.length > 0 ? header.ranges[0][1] : 0;
  } finally {
    closeSync(fd);
  }
}

/**
 * Starts a render and kills it with SIGKILL `delayMs` after `when` becomes
 * true (polled every 2 ms), unless it ends first. Resolves to its exit code
 * (null if it was killed).
 */
function runUntil(
  args: string[],
  when: () => boolean,
  delayMs: number,
): Promise<{ code: number | null; stdout: string }> {
  return new Promise((resolve, reject) => {
    const child = spawn(process.execPath, [BIN, ...args], { cwd: ROOT });
    let stdout = '';
    let stderr = '';
    child.stdout.on('data', (d) => (stdout += d));
    child.stderr.on('data', (d) => (stderr += d));
    let killer: NodeJS.Timeout | undefined;
    const poll = setInterval(() => {
      if (killer === undefined && when()) {
        clearInterval(poll);
        killer = setTimeout(() => child.kill('SIGKILL'), delayMs);
      }
    }, 2);
    child.on('error', reject);
    child.on('exit', (code) => {
      clearInterval(poll);
      clearTimeout(killer);
      if (code !== null && code !== 0) reject(new Error(`exit ${code}: ${stderr}`));
      else resolve({ code, stdout });
    });
  });
}

describe('kill and resume', () => {
  it('gives the bytes of an uninterrupted run after SIGKILL at many moments', async () => {
    // 128 passes of 64×48 pixels: the kills below all come with at least 64
    // passes left, far more than the few milliseconds between the trigger
    // and the kill, on any machine.
    const spp = 128;
    const small = writeCornell(dir, { width: 64, height: 48, spp }, 'kill.json');
    pathwiseOk(['render', small, '--threads', '2', '--out', at('straight.film')]);
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
    // Each kill: when it is triggered, and how long after. The first two fall
    // during start-up, before any checkpoint; the others once the checkpoint
    // holds at least n samples, 0–20 ms later, so they land while a round is
    // rendering, while a checkpoint is being written, or between the two.
    const kills: { when: () => boolean; delayMs: number }[] = [
      { when: () => true, delayMs: 0 },
      { when: () => true, delayMs: 40 },
      ...[4, 8, 16, 24, 32, 40, 48, 56, 64].map((n, k) => ({
        when: () => checkpointEnd(ckpt) >= n,
        delayMs: [0, 3, 7, 12, 20][k % 5],
      })),
    ];
    let lastEnd = 0;
    for (const kill of kills) {
      const r = await runUntil(args, kill.when, kill.delayMs);
      expect(r.code, 'the render ended before it was killed').toBeNull();
      // Whatever the moment of the kill, the checkpoint (if any yet) is whole
      // and holds one range from 0 that never moves backwards.
      if (existsSync(ckpt)) {
        const { header } = readFilm(ckpt);
        expect(header.ranges).toHaveLength(1);
        expect(header.ranges[0][0]).toBe(0);
        expect(header.ranges[0][1]).toBeGreaterThanOrEqual(lastEnd);
        expect(header.ranges[0][1]).toBeLessThan(spp);
        lastEnd = header.ranges[0][1];
      }
    }
    expect(lastEnd).toBeGreaterThanOrEqual(64);
    // The last run is left to finish.
    const last = await runUntil(args, () => false, 0);
    expect(last.code).toBe(0);
    expect(JSON.parse(last.stdout).resumed_from).toBe(lastEnd);
    expect(readFileSync(at('resumed.film')).equals(readFileSync(at('straight.film')))).toBe(true);
  });

  it('SIGTERM while checkpointing: exit 143, the last checkpoint whole, no temporary file left', async () => {
    const sub = mkdtempSync(join(dir, 'term-'));
    const ckpt = join(sub, 'c.film');
    const child = spawn(
      process.execPath,
      [
        BIN,
        'render',
        scene,
        '--spp',
        '100000',
        '--checkpoint',
        ckpt,
        '--checkpoint-every',
        '0.001',
        '--out',
        join(sub, 'x.pfm'),
      ],
      { cwd: ROOT },
    );
    const closed = new Promise<number | null>((r) => child.on('close', r));
    try {
      while (checkpointEnd(ckpt) < 8) await new Promise((r) => setTimeout(r, 5));
      child.kill('SIGTERM');
      expect(await closed).toBe(143);
      expect(readdirSync(sub)).toEqual(['c.film']);
      expect(readFilm(ckpt).header.ranges[0][1]).toBeGreaterThanOrEqual(8);
    } finally {
      child.kill('SIGKILL');
    }
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
        '0.001',
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
