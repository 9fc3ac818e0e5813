// `npm run bench:time`: does `pathwise render --time T` keep to its budget,
// measured as the whole process's wall time (spawn to exit, as a batch
// scheduler sees it), and how much of the budget does it use?
//
// For each configuration and budget T: `reps` fresh processes, each timed
// from spawn to exit here, with the spp reached and the pass rate from its
// --json line. Also the wall time of a 1-spp render (start-up, one pass and
// the output) for scale. Results: bench/results/time-budget.json.
//
//   npm run bench:time [-- --budgets 1,3,10 --reps 3 --threads N --out FILE]
import { spawn } from 'node:child_process';
import { mkdirSync, rmSync, writeFileSync } from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { CLI, ROOT, machineInfo, median } from './lib.mjs';

const opt = {};
for (let i = 2; i < process.argv.length; i += 2)
  opt[process.argv[i].slice(2)] = process.argv[i + 1];
const budgets = (opt.budgets ?? '1,3,10').split(',').map(Number);
const reps = Number(opt.reps ?? 3);
const threads = Number(opt.threads ?? os.availableParallelism());
const outFile = path.resolve(ROOT, opt.out ?? 'bench/results/time-budget.json');
const tmpDir = path.join(os.tmpdir(), `pathwise-time-${process.pid}`);
mkdirSync(tmpDir, { recursive: true });

// A small image (passes of a few ms: the budget is cut finely) and a large
// one (passes near a second: whole passes make the cut coarse).
const configs = [
  { name: 'cornell 128×128 → PFM', width: 128, height: 128, out: 'small.pfm' },
  { name: 'cornell 512×512 → .film', width: 512, height: 512, out: 'large.film' },
];

/** Runs the CLI once; resolves to its JSON line and the wall time from spawn to exit. */
function timed(args) {
  return new Promise((resolve, reject) => {
    const t0 = performance.now();
    const child = spawn(process.execPath, [CLI, ...args], { cwd: ROOT });
    let out = '';
    let err = '';
    child.stdout.on('data', (d) => (out += d));
    child.stderr.on('data', (d) => (err += d));
    child.on('error', reject);
    child.on('exit', (code) => {
      const wall = (performance.now() - t0) / 1000;
      if (code !== 0) reject(new Error(`exit ${code}: ${err}`));
      else resolve({ wall, json: JSON.parse(out.trim().split('\n').pop()) });
    });
  });
}

const base = (c) => [
  'render',
  path.join(ROOT, 'scenes/cornell.json'),
  '--width',
  String(c.width),
  '--height',
  String(c.height),
  '--threads',
  String(threads),
  '--seed',
  '1',
  '--json',
  '--out',
  path.join(tmpDir, c.out),
];

const results = [];
try {
  for (const c of configs) {
    await timed([...base(c), '--spp', '1']); // warm-up: file cache, CPU clocks
    const one = [];
    for (let r = 0; r < reps; r++) one.push((await timed([...base(c), '--spp', '1'])).wall);
    const entry = { config: c.name, one_spp_wall_s: median(one), budgets: [] };
    for (const budget of budgets) {
      const runs = [];
      for (let r = 0; r < reps; r++) {
        const { wall, json } = await timed([...base(c), '--time', String(budget)]);
        runs.push({
          wall_s: wall,
          spp: json.spp,
          render_s: json.seconds,
          stopped_by: json.stopped_by,
          pass_s: json.seconds / json.spp,
        });
      }
      const walls = runs.map((r) => r.wall_s);
      const b = {
        budget_s: budget,
        wall_median_s: median(walls),
        wall_max_s: Math.max(...walls),
        over_budget_max_s: Math.max(...walls) - budget,
        used_median: median(walls) / budget,
        spp_median: median(runs.map((r) => r.spp)),
        pass_median_s: median(runs.map((r) => r.pass_s)),
        runs,
      };
      entry.budgets.push(b);
      process.stderr.write(
        `${c.name}, --time ${budget}: wall median ${b.wall_median_s.toFixed(3)} s, max ${b.wall_max_s.toFixed(3)} s (${b.over_budget_max_s >= 0 ? '+' : ''}${b.over_budget_max_s.toFixed(3)} s), ${b.spp_median} spp, pass ${(b.pass_median_s * 1000).toFixed(1)} ms\n`,
      );
    }
    results.push(entry);
  }
} finally {
  rmSync(tmpDir, { recursive: true, force: true });
}

const report = {
  schema: 'pathwise-bench-time-budget/1',
  command: `node bench/time-budget.mjs ${process.argv.slice(2).join(' ')}`.trim(),
  machine: machineInfo(),
  loadavg_end: os.loadavg(),
  config: { scene: 'scenes/cornell.json', threads, reps, budgets },
  results,
};
mkdirSync(path.dirname(outFile), { recursive: true });
writeFileSync(outFile, JSON.stringify(report, null, 1) + '\n');
process.stderr.write(`wrote ${path.relative(ROOT, outFile)}\n`);
