/**
 * The batch recipes of docs/batch-rendering.md, run locally with their
 * exact command lines: the Kubernetes Indexed Job's container script (read
 * out of the YAML), the Slurm array's sbatch script, and the xargs -P
 * script, each as 4 processes at once, then each recipe's merge step. The
 * merged image must be byte-identical to one render of all the samples.
 *
 * Only what the scheduler would provide is supplied: the index variables
 * (JOB_COMPLETION_INDEX; SLURM_ARRAY_TASK_ID and friends), and the recipe's
 * own variables pointed at a temporary folder, with a small SPP.
 */
import { spawn } from 'node:child_process';
import { chmodSync, mkdirSync, readFileSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { beforeAll, describe, expect, it } from 'vitest';
import { BIN, pathwiseOk, readFilm, tempDir, writeCornell } from '../helpers/batch-cli.ts';
import { ROOT } from '../helpers/render.ts';

const SPP = 16;
const dir = tempDir('recipes');
const shim = join(dir, 'bin');
let scene: string;
let single: Buffer;

/** Runs a command with `pathwise` on PATH; rejects on a non-zero exit. */
function sh(argv: string[], env: Record<string, string>, cwd = dir): Promise<string> {
  return new Promise((resolve, reject) => {
    const child = spawn(argv[0], argv.slice(1), {
      cwd,
      env: { PATH: `${shim}:${process.env.PATH}`, HOME: dir, ...env },
    });
    let out = '';
    let err = '';
    child.stdout.on('data', (d) => (out += d));
    child.stderr.on('data', (d) => (err += d));
    child.on('error', reject);
    child.on('exit', (code) =>
      code === 0 ? resolve(out) : reject(new Error(`${argv.join(' ')} exited ${code}: ${err}`)),
    );
  });
}

/** The block scalar under `args: - |` of a Kubernetes manifest (the container's script). */
function containerScript(yaml: string): string {
  const lines = yaml.split('\n');
  const start = lines.findIndex((l) => /^\s*- \|\s*$/.test(l));
  expect(start, 'no "- |" script block in the manifest').toBeGreaterThan(0);
  const indent = /^(\s*)/.exec(lines[start + 1])![1].length;
  const body: string[] = [];
  for (const l of lines.slice(start + 1)) {
    if (l.trim() !== '' && /^(\s*)/.exec(l)![1].length < indent) break;
    body.push(l.slice(indent));
  }
  return body.join('\n');
}

/** `- { name: X, value: 'Y' }` entries of a manifest's env list. */
function containerEnv(yaml: string): Record<string, string> {
  const env: Record<string, string> = {};
  for (const m of yaml.matchAll(/- \{ name: (\w+), value: '?([^'}]*?)'? \}/g)) env[m[1]] = m[2];
  return env;
}

function checkParts(out: string): void {
  for (let i = 0; i < 4; i++) {
    expect(readFilm(join(out, `part-${i}.film`)).header.ranges).toEqual([[i * 4, i * 4 + 4]]);
  }
}

beforeAll(() => {
  mkdirSync(shim, { recursive: true });
  writeFileSync(join(shim, 'pathwise'), `#!/bin/sh\nexec '${process.execPath}' '${BIN}' "$@"\n`);
  chmodSync(join(shim, 'pathwise'), 0o755);
  scene = writeCornell(dir, { width: 32, height: 24, spp: 8 });
  pathwiseOk([
    'render',
    scene,
    '--spp',
    String(SPP),
    '--seed',
    '1',
    '--out',
    join(dir, 'single.pfm'),
  ]);
  single = readFileSync(join(dir, 'single.pfm'));
});

describe('batch recipes, 4 processes each', () => {
  it('Kubernetes Indexed Job: the container script per JOB_COMPLETION_INDEX, then the merge job', async () => {
    const render = readFileSync(join(ROOT, 'examples/batch/kubernetes/render-job.yaml'), 'utf8');
    const merge = readFileSync(join(ROOT, 'examples/batch/kubernetes/merge-job.yaml'), 'utf8');
    expect(render).toMatch(/completionMode: Indexed/);
    expect(render).toMatch(/completions: 4/);
    const env = containerEnv(render);
    expect(env).toMatchObject({ PARTS: '4', SEED: '1' });
    const out = join(dir, 'k8s/parts');
    const local = { ...env, SCENE: scene, SPP: String(SPP), OUT: out };
    const script = containerScript(render);
    expect(script).toMatch(
      /pathwise render "\$SCENE" --spp "\$SPP" --seed "\$SEED" --samples "\$A:\$B"/,
    );
    await Promise.all(
      [0, 1, 2, 3].map((i) =>
        sh(['sh', '-c', script], { ...local, JOB_COMPLETION_INDEX: String(i) }),
      ),
    );
    checkParts(out);
    const final = join(dir, 'k8s/final.pfm');
    const mergeEnv = { ...containerEnv(merge), OUT: out, FINAL: final };
    const json = JSON.parse(await sh(['sh', '-c', containerScript(merge)], mergeEnv));
    expect(json).toMatchObject({ parts: 4, spp: SPP, missing: [] });
    expect(readFileSync(final).equals(single)).toBe(true);
  });

  it('Slurm job array: the sbatch script per SLURM_ARRAY_TASK_ID, then merge.sbatch', async () => {
    const script = join(ROOT, 'examples/batch/slurm/render-array.sbatch');
    expect(readFileSync(script, 'utf8')).toMatch(/#SBATCH --array=0-3/);
    const out = join(dir, 'slurm/parts');
    const env = { SCENE: scene, SPP: String(SPP), OUT: out };
    await Promise.all(
      [0, 1, 2, 3].map((i) =>
        sh(['bash', script], {
          ...env,
          SLURM_ARRAY_TASK_ID: String(i),
          SLURM_ARRAY_TASK_COUNT: '4',
          SLURM_CPUS_PER_TASK: '1',
        }),
      ),
    );
    checkParts(out);
    const final = join(dir, 'slurm/final.pfm');
    await sh(['bash', join(ROOT, 'examples/batch/slurm/merge.sbatch')], { OUT: out, FINAL: final });
    expect(readFileSync(final).equals(single)).toBe(true);
  });

  it('xargs -P on one machine: the script starts the 4 processes and merges', async () => {
    const out = join(dir, 'local/parts');
    const final = join(dir, 'local/final.pfm');
    await sh(['sh', join(ROOT, 'examples/batch/local/render-parts.sh')], {
      SCENE: scene,
      SPP: String(SPP),
      PARTS: '4',
      OUT: out,
      FINAL: final,
    });
    checkParts(out);
    expect(readFileSync(final).equals(single)).toBe(true);
  });
});
