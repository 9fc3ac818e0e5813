/**
 * SIGINT and SIGTERM end `pathwise render` and `pathwise merge` within a second at every
 * stage: reading (a FIFO nobody writes to, a slow pipe), parsing, loading mesh files and a
 * glTF model, compiling and building the BVH, rendering, checkpointing and writing, and
 * merging. A CPU-bound stage is made slow on purpose through the test hook of
 * src/cli/test-stages.ts (the command's thread kept busy, as a huge input keeps it);
 * reading and rendering are slow for real. Each run must exit with 130 / 143, leave no
 * temporary file, leave an earlier output untouched and an earlier checkpoint loadable.
 *
 * Before main.ts ran the command in a worker thread, every CPU-bound case here ran on
 * past SIGTERM (the handler waited for the event loop the busy stage held).
 */
import { spawn } from 'node:child_process';
import { execFileSync } from 'node:child_process';
import {
  copyFileSync,
  existsSync,
  readdirSync,
  readFileSync,
  writeFileSync,
  rmSync,
} from 'node:fs';
import { join } from 'node:path';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
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

/** Most seconds from the signal to the process's exit. */
const LATENCY_LIMIT = 1;

interface Interrupted {
  status: number | null;
  signal: NodeJS.Signals | null;
  stderr: string;
  /** Seconds from sending the signal to the exit. */
  latency: number;
}

/**
 * Starts `pathwise args`, waits until `ready(stderr)` (or `afterMs`), sends `signal`,
 * and times the exit. `stdin`: bytes written to its standard input, which then stays
 * open with nothing more to read (a slow producer).
 */
async function interrupt(
  args: string[],
  signal: 'SIGINT' | 'SIGTERM',
  options: {
    env?: Record<string, string>;
    ready?: RegExp;
    afterMs?: number;
    stdin?: string;
    cwd?: string;
  },
): Promise<Interrupted> {
  const env = { ...process.env, ...options.env };
  const child = spawn(process.execPath, [BIN, ...args], { cwd: options.cwd, env, stdio: 'pipe' });
  child.stdin.on('error', () => undefined);
  if (options.stdin === undefined) child.stdin.end();
  else child.stdin.write(options.stdin);
  let stderr = '';
  const exited = new Promise<{ status: number | null; signal: NodeJS.Signals | null }>((r) =>
    child.on('exit', (status, sig) => r({ status, signal: sig })),
  );
  const ready = new Promise<void>((resolve) => {
    child.stderr.setEncoding('utf8').on('data', (d: string) => {
      stderr += d;
      if (options.ready?.test(stderr)) resolve();
    });
    if (options.ready === undefined) setTimeout(resolve, options.afterMs ?? 300);
  });
  const guard = setTimeout(() => child.kill('SIGKILL'), 60_000);
  try {
    await Promise.race([ready, exited]);
    const sent = performance.now();
    child.kill(signal);
    const end = await exited;
    const latency = (performance.now() - sent) / 1000;
    return { ...end, stderr, latency };
  } finally {
    clearTimeout(guard);
    child.kill('SIGKILL');
  }
}

const STALL = { PATHWISE_TEST_STALL: '1' };
const stage = (name: string) => ({ PATHWISE_TEST_STAGE: name });
const atStage = (name: string) => new RegExp(`pathwise: test: stage ${name}\\n`);

describe('signals end the command at every stage', () => {
  let dir: string;
  let scene: string;
  const latencies: string[] = [];

  beforeAll(() => {
    dir = tempDir('signals');
    scene = writeCornell(dir, { width: 32, height: 32, spp: 4 });
  });
  afterAll(() => {
    console.log(`signal-to-exit latency per stage: ${latencies.join(', ')}`);
    rmSync(dir, { recursive: true, force: true });
  });

  /**
   * The checks every interrupted run must pass; `out` held "kept" before the run. The
   * process exits with 130 / 143; where the command's thread does not stop within
   * main.ts's STOP_MS (a read the system cannot cancel: a FIFO nobody writes to, a pipe
   * without data; or a heavily loaded machine), it leaves by the signal itself, which a
   * shell reports as 130 / 143 all the same. `blocked`: that is the expected way.
   */
  function expectClean(
    r: Interrupted,
    signal: 'SIGINT' | 'SIGTERM',
    out: string,
    what: string,
    blocked = false,
  ) {
    latencies.push(
      `${what} ${(r.latency * 1000).toFixed(0)} ms${r.signal ? ' (by the signal)' : ''}`,
    );
    const code = signal === 'SIGINT' ? 130 : 143;
    expect(r.signal === signal || (r.signal === null && r.status === code), r.stderr).toBe(true);
    if (blocked) expect(r.stderr).not.toMatch(/pathwise: (?!test:)/);
    expect(r.latency, what).toBeLessThan(LATENCY_LIMIT);
    expect(readFileSync(out, 'utf8')).toBe('kept');
    const folder = join(out, '..');
    expect(readdirSync(folder).filter((f) => f.endsWith('.tmp'))).toEqual([]);
  }

  function outFile(name: string): string {
    const out = join(dir, name);
    writeFileSync(out, 'kept');
    return out;
  }

  it('reading: a FIFO nobody writes to (SIGTERM), a slow standard input (SIGINT)', async () => {
    const fifo = join(dir, 'scene.fifo');
    execFileSync('mkfifo', [fifo]);
    const out = outFile('fifo.pfm');
    const a = await interrupt(['render', fifo, '--out', out], 'SIGTERM', {
      env: stage('read'),
      ready: atStage('read'),
    });
    expectClean(a, 'SIGTERM', out, 'read (FIFO)', true);
    const b = await interrupt(['render', '-', '--out', out], 'SIGINT', {
      stdin: '{"format": ',
      afterMs: 400,
    });
    expectClean(b, 'SIGINT', out, 'read (slow stdin)', true);
  });

  it('parsing, loading a mesh file and a glTF model, compiling (the thread kept busy)', async () => {
    const withMesh = join(dir, 'mesh.json');
    copyFileSync(join(ROOT, 'scenes/meshes/torus.obj'), join(dir, 'torus.obj'));
    const s = JSON.parse(readFileSync(scene, 'utf8'));
    s.shapes.push({ type: 'mesh', file: 'torus.obj', material: Object.keys(s.materials)[0] });
    writeFileSync(withMesh, JSON.stringify(s));
    const glb = join(dir, 'model.glb');
    copyFileSync(join(ROOT, 'docs/showcase.glb'), glb);
    const cases: [string, string, 'SIGINT' | 'SIGTERM', string][] = [
      ['parse', scene, 'SIGTERM', 'parse'],
      ['load', withMesh, 'SIGINT', 'load (OBJ)'],
      ['load', glb, 'SIGTERM', 'load (glTF)'],
      ['compile', scene, 'SIGINT', 'compile (BVH)'],
    ];
    for (const [name, file, signal, what] of cases) {
      const out = outFile(`${name}.png`);
      const r = await interrupt(
        ['render', file, '--width', '32', '--height', '32', '--out', out],
        signal,
        { env: { ...stage(name), ...STALL }, ready: atStage(name) },
      );
      expectClean(r, signal, out, what);
    }
  });

  it('rendering (SIGTERM), writing (SIGINT)', async () => {
    const long = writeCornell(dir, { width: 64, height: 64, spp: 1 << 20 }, 'long.json');
    const out = outFile('render.pfm');
    const a = await interrupt(['render', long, '--out', out], 'SIGTERM', {
      env: stage('render'),
      ready: atStage('render'),
      afterMs: 0,
    });
    expectClean(a, 'SIGTERM', out, 'render');
    const b = await interrupt(['render', scene, '--out', out], 'SIGINT', {
      env: { ...stage('write'), ...STALL },
      ready: atStage('write'),
    });
    expectClean(b, 'SIGINT', out, 'write');
  });

  it('checkpointing: the earlier checkpoint stays loadable and resumable', async () => {
    const checkpoint = join(dir, 'c.film');
    const long = writeCornell(dir, { width: 32, height: 32, spp: 64 }, 'ck.json');
    // An earlier checkpoint: the first 8 samples.
    pathwiseOk(['render', long, '--samples', '0:8', '--out', checkpoint]);
    const before = readFileSync(checkpoint);
    const out = outFile('ck.pfm');
    const r = await interrupt(
      [
        'render',
        long,
        '--resume',
        checkpoint,
        '--checkpoint',
        checkpoint,
        '--checkpoint-every',
        '0.001',
        '--out',
        out,
      ],
      'SIGTERM',
      { env: { ...stage('checkpoint'), ...STALL }, ready: atStage('checkpoint') },
    );
    expectClean(r, 'SIGTERM', out, 'checkpoint');
    // The checkpoint is whole: the earlier one or a newer one, never half of one.
    const film = readFilm(checkpoint);
    expect(film.header.ranges[0][0]).toBe(0);
    expect(readFileSync(checkpoint).equals(before) || film.header.ranges[0][1] > 8).toBe(true);
    // And the render resumes from it to the bytes of one uninterrupted run.
    const resumed = join(dir, 'resumed.pfm');
    const whole = join(dir, 'whole.pfm');
    pathwiseOk(['render', long, '--resume', checkpoint, '--out', resumed]);
    pathwiseOk(['render', long, '--out', whole]);
    expect(readFileSync(resumed).equals(readFileSync(whole))).toBe(true);
  });

  it('a checkpoint that cannot be written leaves no temporary output behind', () => {
    const out = outFile('no-checkpoint.pfm');
    const r = pathwise([
      'render',
      scene,
      '--checkpoint',
      join(dir, 'missing', 'c.film'),
      '--out',
      out,
    ]);
    expectRefusal(r, /^pathwise: cannot write .*c\.film: the directory .* does not exist$/);
    expect(readFileSync(out, 'utf8')).toBe('kept');
    expect(readdirSync(dir).filter((f) => f.endsWith('.tmp'))).toEqual([]);
  });

  it('merging: reading parts, adding them, writing', async () => {
    const parts = [0, 1].map((k) => {
      const part = join(dir, `part${k}.film`);
      pathwiseOk(['render', scene, '--samples', `${2 * k}:${2 * k + 2}`, '--out', part]);
      return part;
    });
    const cases: [string, 'SIGINT' | 'SIGTERM'][] = [
      ['read', 'SIGINT'],
      ['merge', 'SIGTERM'],
      ['write', 'SIGINT'],
    ];
    for (const [name, signal] of cases) {
      const out = outFile(`merged-${name}.png`);
      const r = await interrupt(['merge', ...parts, '--out', out], signal, {
        env: { ...stage(name), ...STALL },
        ready: atStage(name),
      });
      expectClean(r, signal, out, `merge ${name}`);
    }
    expect(existsSync(parts[0])).toBe(true);
  });
});
