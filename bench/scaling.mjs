// Thread scaling of pathwise and of the native anchor on the same machine,
// in the same run (issue 10, point 3). A machine does not give n× to anyone
// at n threads (shared physical cores, all-core clocks, memory), so the
// figure that belongs to pathwise is its efficiency next to native threads'
// on the same image: efficiency(n) = time(1) / (n · time(n)), with time the
// render window each reports (`seconds`: threads started to joined; for
// pathwise warm-up included, parsing not). pathwise and native runs
// alternate; each time is the median of the repetitions.
//
//   node bench/scaling.mjs [--threads 1,16] [--reps 3] [--native PATH] [--out FILE]
import { mkdirSync, rmSync, writeFileSync } from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { ROOT, machineInfo, median, renderOnce } from './lib.mjs';
import { findNative, nativeOnce } from './native.mjs';
import { writeSpheresField } from './scenes.mjs';

const opt = {};
for (let i = 2; i < process.argv.length; i += 2) {
  opt[process.argv[i].slice(2)] = process.argv[i + 1];
}
const reps = Number(opt.reps ?? 3);
const threadCounts = (opt.threads ?? `1,${os.availableParallelism()}`).split(',').map(Number);
const outFile = path.resolve(ROOT, opt.out ?? 'bench/results/scaling.json');
const tmpDir = path.join(os.tmpdir(), `pathwise-scaling-${process.pid}`);
mkdirSync(tmpDir, { recursive: true });
const native = findNative(opt.native);
if (!native) process.stderr.write('no native anchor: pathwise figures only\n');

const spheresFile = writeSpheresField(path.join(tmpDir, 'spheres-10k.json'), 10000);
const cases = [
  { name: 'cornell', scene: path.join(ROOT, 'scenes/cornell.json'), spp: 16 },
  { name: 'spheres-10k', scene: spheresFile, spp: 8 },
];

const results = [];
try {
  for (const c of cases) {
    const base = { scene: c.scene, width: 512, height: 512, spp: c.spp, bounces: 6 };
    const times = { pathwise: {}, native: {} };
    for (const threads of threadCounts) {
      const o = { ...base, threads };
      const pw = [];
      const nat = [];
      for (let r = 0; r < reps; r++) {
        pw.push(renderOnce({ ...o, seed: 1, out: path.join(tmpDir, 'pw.pfm') }).seconds);
        if (native) nat.push(nativeOnce(native, { ...o, out: path.join(tmpDir, 'n.pfm') }).seconds);
      }
      times.pathwise[threads] = { median: median(pw), all: pw };
      if (native) times.native[threads] = { median: median(nat), all: nat };
    }
    const t1 = threadCounts[0];
    const efficiency = (t, n) => t[t1].median / ((n / t1) * t[n].median);
    for (const n of threadCounts.slice(1)) {
      const pe = efficiency(times.pathwise, n);
      const ne = native ? efficiency(times.native, n) : null;
      const row = {
        case: c.name,
        threads: n,
        pathwise_efficiency: pe,
        native_efficiency: ne,
        pathwise_over_native: ne ? pe / ne : null,
      };
      results.push(row);
      process.stderr.write(
        `${c.name} 512x512 ${c.spp} spp, ${t1} -> ${n} threads: pathwise ${(pe * 100).toFixed(1)} %` +
          (ne
            ? `, native ${(ne * 100).toFixed(1)} %, pathwise/native ${(pe / ne).toFixed(3)}`
            : '') +
          '\n',
      );
    }
    results.push({ case: c.name, times });
  }
} finally {
  rmSync(tmpDir, { recursive: true, force: true });
}
const doc = { machine: machineInfo(), reps, threads: threadCounts, native: !!native, results };
writeFileSync(outFile, JSON.stringify(doc, null, 2) + '\n');
process.stderr.write(`wrote ${path.relative(ROOT, outFile)}\n`);
