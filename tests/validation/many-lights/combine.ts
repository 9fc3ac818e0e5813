/**
 * Combines the parts of the Mitsuba reference of the many-light scene (README.md beside
 * this file) into mitsuba.pfm (the per-pixel mean) and mitsuba-var.pfm (the per-pixel
 * variance of that mean, s² / P across the P parts).
 *   node scripts/run-ts.mjs tests/validation/many-lights/combine.ts OUT_DIR PART.pfm…
 */
import { readFileSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { decodePfm, encodePfm } from '../../../src/core/index.ts';

const [out, ...files] = process.argv.slice(2);
if (out === undefined || files.length < 2) throw new Error('usage: combine.ts OUT_DIR PART.pfm…');
const parts = files.map((f) => decodePfm(readFileSync(f)));
const { width, height } = parts[0]!;
const n = width * height * 3;
const mean = new Float32Array(n);
const variance = new Float32Array(n);
const P = parts.length;
for (let i = 0; i < n; i++) {
  let s = 0;
  for (const p of parts) s += p.rgb[i]!;
  const m = s / P;
  let ss = 0;
  for (const p of parts) ss += (p.rgb[i]! - m) ** 2;
  mean[i] = m;
  variance[i] = ss / (P - 1) / P;
}
writeFileSync(join(out, 'mitsuba.pfm'), encodePfm(width, height, mean));
writeFileSync(join(out, 'mitsuba-var.pfm'), encodePfm(width, height, variance));
process.stdout.write(`${P} parts of ${width}×${height} combined into ${out}\n`);
