// Thread scaling of pathwise next to the native anchor's and next to
// independent processes, on the same machine in the same run (issue 10,
// point 3). A machine does not give n× to anyone at n threads (shared
// physical cores, all-core clocks, memory, a virtual machine's neighbours),
// so what belongs to pathwise is the gap between its n threads and
//   - n independent single-thread pathwise processes (nothing shared: the
//     machine's own ceiling for pathwise's code), and
//   - the anchor's n threads (and n anchor processes).
//
// Weak scaling: n threads render n× the samples of the one-thread run (the
// same image), n processes render the one-thread job each, at once; so
// efficiency(n) = seconds(1) / seconds(n), with `seconds` the render window
// each reports (threads started to joined; for pathwise warm-up included,
// parsing not; for n processes the mean of theirs). Fixed costs are a small
// part of a multi-second render. Variants alternate within each repetition;
// each figure is the median of the repetitions.
//
//   node bench/scaling.mjs [--threads 16] [--spp 8] [--reps 2] [--native PATH] [--out FILE]
import { spawn } from 'node:child_process';
import { mkdirSync, rmSync, writeFileSync } from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { ROOT, cliArgs, machineInfo, median } from './lib.mjs';
import { findNative, nativeArgs } from './native.mjs';
import { writeSpheresField } from './scenes.mjs';

const opt = {};
for (let i = 2; i < process.argv.length; i += 2) {
  opt[process.argv[i].slice(2)] = process.argv[i + 1];
}
const reps = Number(opt.reps ?? 2);
const n = Number(opt.threads ?? os.availableParallelism());
const spp = Number(opt.spp ?? 8);
const outFile = path.resolve(ROOT, opt.out ?? 'bench/results/scaling.json');
const tmpDir = path.join(os.tmpdir(), `pathwise-scaling-${process.pid}`);
mkdirSync(tmpDir, { recursive: true });
const native = findNative(opt.native);
if (!native) process.stderr.write('no native anchor: pathwise figures only\n');

const spheresFile = writeSpheresField(path.join(tmpDir, 'spheres-10k.json'), 10000);
const cases = [
  { name: 'cornell', scene: path.join(ROOT, 'scenes/cornell.json') },
  { name: 'spheres-10k', scene: spheresFile },
];

/** Runs a command, resolves with the JSON of its last stdout line. */
function runJson(command, args) {
  return new Promise((resolve, reject) => {
    const child = spawn(command, args, { cwd: ROOT });
    let out = '';
    let err = '';
    child.stdout.on('data', (d) => (out += d));
    child.stderr.on('data', (d) => (err += d));
    child.on('error', reject);
    child.on('exit', (code) =>
      code === 0
        ? resolve(JSON.parse(out.trim().split('\n').pop()))
        : reject(new Error(`${command} ${args.join(' ')} failed (${code}): ${err}`)),
    );
  });
}

/** One render by `who` (pathwise | native): its reported seconds. */
async function render(who, scene, samples, threads, k) {
  const o = {
    scene,
    width: 512,
    height: 512,
    spp: samples,
    threads,
    bounces: 6,
    out: path.join(tmpDir, `${who}-${k}.pfm`),
  };
  const r =
    who === 'pathwise'
      ? await runJson(process.execPath, cliArgs(o))
      : await runJson(native, nativeArgs(o));
  return r.seconds;
}

const VARIANTS = ['one', 'threads', 'processes'];
const mean = (xs) => xs.reduce((a, b) => a + b, 0) / xs.length;
const results = [];
try {
  for (const c of cases) {
    for (const who of native ? ['pathwise', 'native'] : ['pathwise']) {
      const t = { one: [], threads: [], processes: [] };
      for (let r = 0; r < reps; r++) {
        for (const v of VARIANTS) {
          if (v === 'one') t.one.push(await render(who, c.scene, spp, 1, 0));
          else if (v === 'threads') t.threads.push(await render(who, c.scene, spp * n, n, 0));
          else {
            const each = await Promise.all(
              Array.from({ length: n }, (_, k) => render(who, c.scene, spp, 1, k)),
            );
            t.processes.push(mean(each));
          }
        }
      }
      const one = median(t.one);
      const row = {
        case: c.name,
        who,
        n,
        spp_per_thread: spp,
        seconds: t,
        threads_efficiency: one / median(t.threads),
        processes_efficiency: one / median(t.processes),
      };
      results.push(row);
      process.stderr.write(
        `${c.name} 512x512, ${spp} spp per thread, ${who}: ${n} threads ${(row.threads_efficiency * 100).toFixed(1)} %, ` +
          `${n} processes ${(row.processes_efficiency * 100).toFixed(1)} % ` +
          `(1 thread ${one.toFixed(2)} s)\n`,
      );
    }
  }
} finally {
  rmSync(tmpDir, { recursive: true, force: true });
}
const doc = {
  schema: 'pathwise-bench-scaling/1',
  command: `node bench/scaling.mjs ${process.argv.slice(2).join(' ')}`.trim(),
  machine: machineInfo(),
  reps,
  native: !!native,
  results,
};
mkdirSync(path.dirname(outFile), { recursive: true });
writeFileSync(outFile, JSON.stringify(doc, null, 2) + '\n');
process.stderr.write(`wrote ${path.relative(ROOT, outFile)}\n`);
