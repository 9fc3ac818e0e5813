// Keeps the benchmark harness from rotting: runs `bench/run.mjs --quick`
// on a tiny spp range into a temporary directory and checks the structure
// of what it writes. No assertion on any time: those depend on the machine.
import { execFileSync } from 'node:child_process';
import { existsSync, mkdtempSync, readFileSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { afterAll, describe, expect, it } from 'vitest';

const root = fileURLToPath(new URL('../..', import.meta.url));
const dir = mkdtempSync(path.join(tmpdir(), 'pathwise-bench-test-'));
afterAll(() => rmSync(dir, { recursive: true, force: true }));

const positive = (v: unknown): boolean => typeof v === 'number' && Number.isFinite(v) && v > 0;

describe('npm run bench -- --quick', () => {
  it('writes bench.json, plots and a report with finite positive figures', () => {
    execFileSync(
      process.execPath,
      ['bench/run.mjs', '--quick', '--max-spp', '4', '--reps', '1', '--out-dir', dir],
      { cwd: root, stdio: ['ignore', 'ignore', 'pipe'] },
    );
    const result = JSON.parse(readFileSync(path.join(dir, 'bench.json'), 'utf8'));
    expect(result.schema).toBe('pathwise-bench/1');
    expect(typeof result.machine.cpu).toBe('string');
    expect(positive(result.machine.cores)).toBe(true);
    expect(result.machine.node).toMatch(/^v\d+/);

    const scenes = new Set(result.series.map((s: { scene: string }) => s.scene));
    expect([...scenes].sort()).toEqual(['cornell', 'mirror', 'spheres']);
    expect(result.series.length).toBe(9);
    for (const s of result.series) {
      expect(s.points.map((p: { spp: number }) => p.spp)).toEqual([1, 2, 4]);
      for (const p of s.points) {
        for (const key of [
          'seconds',
          'paths',
          'segments',
          'msegments_per_s',
          'mpaths_per_s',
          'relmse',
          'block_mare_8',
        ]) {
          expect(positive(p[key]), `${s.scene} ${s.config} spp ${p.spp} ${key}`).toBe(true);
        }
        expect(p.paths).toBe(s.width * s.height * p.spp);
      }
      expect(Number.isFinite(s.slope_relmse_vs_spp)).toBe(true);
    }
    for (const c of [...result.comparisons.estimator, ...result.comparisons.sampler]) {
      expect(positive(c.equal_time_ratio)).toBe(true);
      expect(positive(c.equal_spp_ratio_geomean)).toBe(true);
    }
    expect(['sobol', 'independent']).toContain(result.recommendation.sampler);
    expect(result.scaling.points.length).toBe(result.machine.cores);
    for (const p of result.scaling.points) {
      expect(positive(p.msegments_per_s) && positive(p.efficiency)).toBe(true);
    }
    for (const t of result.time_to_target) {
      if (t.reached) expect(positive(t.threads_1.seconds)).toBe(true);
    }
    for (const f of result.plots) {
      const svg = readFileSync(path.join(dir, f), 'utf8');
      expect(svg.startsWith('<svg')).toBe(true);
    }
    expect(existsSync(path.join(dir, 'BENCHMARKS.md'))).toBe(true);
  });
});
