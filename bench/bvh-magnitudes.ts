/**
 * BVH build time over coordinate magnitudes (issue "scenes at the edges of the double
 * range"): n small boxes whose positions are spread over every binade of the double
 * range (x = ±2^k, k from −1074 to 1023, the part beyond Float32 with an infinite box
 * side), against the same n boxes at ordinary magnitudes; three builds each after a
 * warm-up, medians of wall and CPU milliseconds, depth and nodes. Before the fix the
 * spread set did not terminate.
 *   node scripts/run-ts.mjs bench/bvh-magnitudes.ts [N]
 */
import { buildBvh } from '../src/core/accel/bvh.ts';
import { PrimitiveBoxes } from '../src/core/accel/primitives.ts';

const n = Number(process.argv[2] ?? 1_000_000);
let state = 1;
const rand = (): number => (state = (Math.imul(state, 1664525) + 1013904223) >>> 0) / 4294967296;

/** Box i: a cube of side s at (x, y, z), with the exact bounds rounded outwards. */
function boxes(position: (i: number) => [number, number, number, number]): PrimitiveBoxes {
  const prims = new PrimitiveBoxes(n);
  for (let i = 0; i < n; i++) {
    const [x, y, z, s] = position(i);
    prims.add(0, i, x, y, z, x + s, y + s, z + s);
  }
  return prims;
}

const sets: Record<string, () => PrimitiveBoxes> = {
  ordinary: () =>
    boxes(() => {
      const s = 0.001 + 0.01 * rand();
      return [rand() * 100, rand() * 100, rand() * 100, s];
    }),
  'every binade': () =>
    boxes(() => {
      const k = Math.floor(rand() * 2098) - 1074;
      const x = (rand() < 0.5 ? -1 : 1) * 2 ** k;
      const y = (rand() < 0.5 ? -1 : 1) * 2 ** (Math.floor(rand() * 2098) - 1074);
      return [x, y, rand(), Math.abs(x) * 0.25 || 5e-324];
    }),
};

let sink = 0;
for (const [name, make] of Object.entries(sets)) {
  const wall: number[] = [];
  const cpu: number[] = [];
  let depth = 0;
  let nodes = 0;
  for (let rep = 0; rep < 4; rep++) {
    const prims = make();
    const c0 = process.cpuUsage();
    const t0 = performance.now();
    const bvh = buildBvh(prims.boxes, prims.refs, n)!;
    const ms = performance.now() - t0;
    const c = process.cpuUsage(c0);
    sink += bvh.nodeCount;
    if (rep === 0) continue; // warm-up
    wall.push(ms);
    cpu.push((c.user + c.system) / 1000);
    depth = bvh.depth;
    nodes = bvh.nodeCount;
  }
  const median = (a: number[]) => a.sort((p, q) => p - q)[a.length >> 1];
  console.log(
    `${name}: ${n} boxes, build median ${median(wall).toFixed(0)} ms wall, ${median(cpu).toFixed(0)} ms CPU, depth ${depth}, ${nodes} nodes`,
  );
}
if (sink === 0) console.log('');
