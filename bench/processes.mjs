// The hardware's own scaling ceiling: n independent single-thread renders
// started at once (separate processes, nothing shared), for n = 1, 2, 4 …
// cores. If their total throughput stops growing linearly, the machine
// (shared physical cores, clock boost, memory) is the limit, not the
// renderer's worker pool; compare with the thread scaling of bench/run.mjs.
//
//   node bench/processes.mjs [--spp N] [--max N] [--out FILE]
import { spawn } from 'node:child_process';
import { mkdirSync, rmSync, writeFileSync } from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { CLI, ROOT, machineInfo } from './lib.mjs';

const opt = {};
for (let i = 2; i < process.argv.length; i += 2)
  opt[process.argv[i].slice(2)] = process.argv[i + 1];
const spp = Number(opt.spp ?? 32);
const max = Number(opt.max ?? os.availableParallelism());
const outFile = path.resolve(ROOT, opt.out ?? 'bench/results/processes.json');
const tmpDir = path.join(os.tmpdir(), `pathwise-proc-${process.pid}`);
mkdirSync(tmpDir, { recursive: true });

function renderAsync(k) {
  return new Promise((resolve, reject) => {
    const args = [
      CLI,
      'render',
      path.join(ROOT, 'scenes/cornell.json'),
      '--width',
      '128',
      '--height',
      '128',
      '--spp',
      String(spp),
      '--threads',
      '1',
      '--json',
      '--out',
      path.join(tmpDir, `p${k}.pfm`),
    ];
    const child = spawn(process.execPath, args, { cwd: ROOT });
    let out = '';
    child.stdout.on('data', (d) => (out += d));
    child.on('error', reject);
    child.on('exit', (code) =>
      code === 0
        ? resolve(JSON.parse(out.trim().split('\n').pop()))
        : reject(new Error(`exit ${code}`)),
    );
  });
}

const counts = [];
for (let n = 1; n < max; n *= 2) counts.push(n);
counts.push(max);
const points = [];
try {
  await renderAsync(0); // warm-up
  for (const n of counts) {
    const runs = await Promise.all(Array.from({ length: n }, (_, k) => renderAsync(k)));
    const perProcess = runs.map((r) => r.paths / r.seconds / 1e6);
    const total = perProcess.reduce((a, b) => a + b, 0);
    points.push({ processes: n, mpaths_per_s_each: perProcess, mpaths_per_s_total: total });
    process.stderr.write(
      `${n} concurrent single-thread renders: ${total.toFixed(3)} M paths/s in total, ${(total / n).toFixed(3)} each\n`,
    );
  }
} finally {
  rmSync(tmpDir, { recursive: true, force: true });
}
const base = points[0].mpaths_per_s_total;
for (const p of points) p.efficiency = p.mpaths_per_s_total / base / p.processes;
const report = {
  schema: 'pathwise-bench-processes/1',
  command: `node bench/processes.mjs ${process.argv.slice(2).join(' ')}`.trim(),
  machine: machineInfo(),
  config: { scene: 'scenes/cornell.json', width: 128, height: 128, spp, threads_per_process: 1 },
  points,
};
mkdirSync(path.dirname(outFile), { recursive: true });
writeFileSync(outFile, JSON.stringify(report, null, 2) + '\n');
