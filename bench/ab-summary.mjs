// Medians of bench/ab-inproc.sh's runs: M paths and M segments per CPU-second per variant and
// scene, each variant's ratio to the native anchor (paths) and the Cornell/mesh ratios of
// M segments per CPU-second (issue 11's goal: the 1M mesh within 3× of the Cornell box).
//   node bench/ab-summary.mjs runs.jsonl
import { readFileSync } from 'node:fs';

const rows = readFileSync(process.argv[2], 'utf8')
  .split('\n')
  .filter((l) => l.trim() !== '')
  .map((l) => JSON.parse(l));
const median = (xs) => [...xs].sort((a, b) => a - b)[xs.length >> 1];
const scene = (s) =>
  s.includes('10k') ? 'spheres-10k' : s.replace(/^.*\//, '').replace(/\.json$/, '');
const by = new Map();
for (const row of rows) {
  const key = `${row.v} ${scene(row.scene)}`;
  if (!by.has(key)) by.set(key, { paths: [], segs: [], digests: new Set() });
  const e = by.get(key);
  if (row.v === 'native') {
    // Process CPU time when measured, else the anchor's own render time.
    const [user, sys] = (row.cpu || '').split(' ').map(Number);
    const sec = user + sys > 0 ? user + sys : row.r.seconds;
    e.paths.push(row.r.paths / sec / 1e6);
    e.segs.push(row.r.segments / sec / 1e6);
  } else {
    e.paths.push(row.r.mpaths_per_cpu_s);
    e.segs.push(row.r.msegments_per_cpu_s);
    e.digests.add(row.r.film_fnv1a);
  }
}
const out = {};
for (const [key, e] of by) {
  out[key] = {
    mpaths_per_cpu_s: +median(e.paths).toFixed(3),
    msegments_per_cpu_s: +median(e.segs).toFixed(3),
    runs: e.paths.length,
    film_fnv1a: [...e.digests].join(' ') || undefined,
  };
}
const variants = [...new Set(rows.map((r) => r.v))].filter((v) => v !== 'native');
for (const v of variants) {
  const get = (s) => out[`${v} ${s}`];
  const nat = (s) => out[`native ${s}`];
  out[`${v} ratios`] = {
    cornell_over_native:
      nat('cornell') &&
      +(get('cornell').mpaths_per_cpu_s / nat('cornell').mpaths_per_cpu_s).toFixed(3),
    spheres10k_over_native:
      nat('spheres-10k') &&
      +(get('spheres-10k').mpaths_per_cpu_s / nat('spheres-10k').mpaths_per_cpu_s).toFixed(3),
    cornell_over_million_segments: +(
      get('cornell').msegments_per_cpu_s / get('@million').msegments_per_cpu_s
    ).toFixed(2),
    cornell_over_bunny_segments: +(
      get('cornell').msegments_per_cpu_s / get('@bunny').msegments_per_cpu_s
    ).toFixed(2),
  };
}
process.stdout.write(JSON.stringify(out, null, 1) + '\n');
