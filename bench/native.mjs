// The native C++ anchor (../shared/anchors/native) as the benchmarks run it:
// found or built once, then one render per call with its own JSON line.
import { execFileSync, spawnSync } from 'node:child_process';
import { existsSync } from 'node:fs';
import path from 'node:path';
import { ROOT } from './lib.mjs';

/**
 * The anchor's binary: `explicit` (a --native option), $PATHWISE_NATIVE, or
 * /tmp/pathwise-native-anchor/pt; if none exists and
 * ../shared/anchors/native/build.sh does, it is built first. null without it.
 */
export function findNative(explicit) {
  const candidates = [explicit, process.env.PATHWISE_NATIVE, '/tmp/pathwise-native-anchor/pt'];
  for (const c of candidates) if (c && existsSync(c)) return c;
  const build = path.resolve(ROOT, '../shared/anchors/native/build.sh');
  if (existsSync(build)) {
    process.stderr.write('building the native anchor (../shared/anchors/native/build.sh)\n');
    const r = spawnSync('sh', [build], { encoding: 'utf8' });
    if (r.status === 0 && existsSync('/tmp/pathwise-native-anchor/pt')) {
      return '/tmp/pathwise-native-anchor/pt';
    }
    process.stderr.write(`native anchor build failed: ${r.stderr}\n`);
  }
  return null;
}

/**
 * The anchor's arguments for one render. o: scene, width, height, spp,
 * threads, bounces, out; seed 1, as pathwise's benchmarks use.
 */
export function nativeArgs(o) {
  return [
    o.scene,
    '--width',
    String(o.width),
    '--height',
    String(o.height),
    '--spp',
    String(o.spp),
    '--threads',
    String(o.threads),
    '--seed',
    '1',
    '--max-bounces',
    String(o.bounces),
    '--out',
    o.out,
    '--quiet',
  ];
}

/**
 * One render by the anchor at `native`: its JSON line (`seconds` = threads
 * started to joined) plus the process wall time (o as for nativeArgs).
 */
export function nativeOnce(native, o) {
  const t0 = performance.now();
  const out = execFileSync(native, nativeArgs(o), { encoding: 'utf8' });
  const processSeconds = (performance.now() - t0) / 1000;
  return { ...JSON.parse(out.trim().split('\n').pop()), process_seconds: processSeconds };
}
