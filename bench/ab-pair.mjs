#!/usr/bin/env node
/**
 * A/B of two commits in one process, for a shared machine where separate runs swing with
 * the other processes' load: both builds of bench/ab-pair-entry.ts are loaded, warmed up,
 * and rendered alternately (old first, then new first, in turn); each pair's ratio of CPU
 * times is new speed / old speed, and the images must be equal. Prints the median and
 * quartiles of the ratios.
 *   esbuild bench/ab-pair-entry.ts --bundle --platform=node --format=esm --outfile=OLD.mjs
 *   (at the old commit; likewise NEW.mjs at the new one), then
 *   taskset -c 1 node bench/ab-pair.mjs OLD.mjs NEW.mjs SCENE W H SPP ROUNDS
 */
import { pathToFileURL } from 'node:url';
import { resolve } from 'node:path';

const [oldPath, newPath, file, w, h, spp, rounds] = process.argv.slice(2);
const A = await import(pathToFileURL(resolve(oldPath)).href);
const B = await import(pathToFileURL(resolve(newPath)).href);
const ra = A.prepare(file, +w, +h);
const rb = B.prepare(file, +w, +h);
for (let k = 0; k < 2; k++) (ra(+spp), rb(+spp));
const ratios = [];
for (let r = 0; r < +rounds; r++) {
  const oldFirst = r % 2 === 0;
  const x = oldFirst ? ra(+spp) : rb(+spp);
  const y = oldFirst ? rb(+spp) : ra(+spp);
  const a = oldFirst ? x : y;
  const b = oldFirst ? y : x;
  if (a.sum !== b.sum) throw new Error(`round ${r}: the images differ`);
  ratios.push(a.cpu / b.cpu);
}
ratios.sort((p, q) => p - q);
const at = (f) => ratios[Math.floor(f * (ratios.length - 1))];
console.log(
  JSON.stringify({ file, pairs: ratios.length, median: at(0.5), q1: at(0.25), q3: at(0.75) }),
);
