// Whole-process A/B of `pathwise render` (several checkouts, each with its CLI built)
// against the native anchor, rounds interleaved: wall and CPU time of each process
// (a 1-spp image of the 10k-sphere field by default), the render window and the compile
// the CLI reports, medians and pathwise/native ratios. The issue-10 figure "10k spheres,
// 1 spp, whole process" in one run, for any set of commits:
//   node bench/ab-cli.mjs [--rounds 7] [--threads 2] [--size 128] [--spp 1] [--scene FILE]
//     NAME=CHECKOUT [NAME=CHECKOUT …]
// A CHECKOUT is a directory holding bin/pathwise.js and dist/cli (npm run build:cli there).
// The anchor: $PATHWISE_NATIVE or /tmp/pathwise-native-anchor/pt (skipped if absent).
import { spawnSync } from 'node:child_process';
import { existsSync, mkdtempSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { spheresField } from './scenes.mjs';

const opts = { rounds: 7, threads: 2, size: 128, spp: 1, scene: '' };
const variants = [];
const argv = process.argv.slice(2);
for (let i = 0; i < argv.length; i++) {
  const a = argv[i];
  if (a.startsWith('--')) {
    const key = a.slice(2);
    opts[key] = key === 'scene' ? argv[++i] : Number(argv[++i]);
  } else {
    const eq = a.indexOf('=');
    variants.push({ name: a.slice(0, eq), dir: a.slice(eq + 1) });
  }
}
if (variants.length === 0) {
  process.stderr.write('usage: node bench/ab-cli.mjs [options] NAME=CHECKOUT [NAME=CHECKOUT …]\n');
  process.exit(2);
}
const work = mkdtempSync(join(tmpdir(), 'pathwise-ab-cli-'));
const scene = opts.scene || join(work, 'spheres-10k.json');
if (!opts.scene) writeFileSync(scene, JSON.stringify(spheresField(10000)));
const native = process.env.PATHWISE_NATIVE ?? '/tmp/pathwise-native-anchor/pt';
if (existsSync(native)) variants.push({ name: 'native', native });

/** Wall and CPU seconds of one process (CPU from /proc via `time`'s format). */
function timed(cmd, args) {
  const out = join(work, 'time.txt');
  const t0 = performance.now();
  const r = spawnSync('/usr/bin/time', ['-o', out, '-f', '%U %S', cmd, ...args], {
    encoding: 'utf8',
  });
  const wall = (performance.now() - t0) / 1000;
  if (r.status !== 0) throw new Error(`${cmd} failed: ${r.stderr}`);
  const [user, sys] = spawnSync('tail', ['-1', out], { encoding: 'utf8' })
    .stdout.trim()
    .split(' ')
    .map(Number);
  return { wall, cpu: user + sys, stdout: r.stdout };
}

const size = String(opts.size);
const runs = new Map(variants.map((v) => [v.name, []]));
for (let r = 0; r < opts.rounds; r++) {
  for (const v of variants) {
    const common = ['--width', size, '--height', size, '--spp', String(opts.spp)];
    if (v.native) {
      const t = timed(v.native, [scene, ...common, '--threads', String(opts.threads), '--quiet']);
      runs.get(v.name).push(t);
      continue;
    }
    const out = join(work, `${v.name}.pfm`);
    const t = timed(process.execPath, [
      join(v.dir, 'bin', 'pathwise.js'),
      'render',
      scene,
      ...common,
      '--threads',
      String(opts.threads),
      '--json',
      '--out',
      out,
    ]);
    const j = JSON.parse(t.stdout);
    runs.get(v.name).push({ ...t, window: j.seconds, compile: j.compile_seconds });
  }
}
const median = (xs) => [...xs].sort((a, b) => a - b)[(xs.length - 1) >> 1];
const nativeWall = runs.has('native') ? median(runs.get('native').map((t) => t.wall)) : null;
const ms = (s) => (s === undefined ? '—' : `${(s * 1000).toFixed(0)} ms`);
process.stdout.write(
  `${opts.rounds} rounds, ${opts.threads} threads, ${size}², ${opts.spp} spp, ${scene}\n` +
    '| variant | wall | wall, fastest | CPU | render window | compile | wall / native |\n' +
    '|---|---|---|---|---|---|---|\n',
);
for (const [name, ts] of runs) {
  const wall = median(ts.map((t) => t.wall));
  const row = [
    name,
    ms(wall),
    // On a shared machine the fastest run is the one least disturbed.
    ms(Math.min(...ts.map((t) => t.wall))),
    ms(median(ts.map((t) => t.cpu))),
    ms(ts[0].window === undefined ? undefined : median(ts.map((t) => t.window))),
    ms(ts[0].compile === undefined ? undefined : median(ts.map((t) => t.compile))),
    nativeWall ? `${(wall / nativeWall).toFixed(2)}×` : '—',
  ];
  process.stdout.write(`| ${row.join(' | ')} |\n`);
}
