/**
 * BVH build speed and size: n random small boxes (triangle-sized), built
 * three times; prints wall and process-CPU milliseconds per build (CPU time
 * is what other load on a shared machine disturbs least), nodes, depth and
 * bytes per primitive (nodes + references).
 *   node scripts/run-ts.mjs bench/bvh-build.ts [N [NODE_COST]]
 */
import { buildBvh } from '../src/core/accel/bvh.ts';
import { PrimitiveBoxes } from '../src/core/accel/primitives.ts';

const n = Number(process.argv[2] ?? 1_000_000);
const nodeCost = process.argv[3] === undefined ? undefined : Number(process.argv[3]);
let state = 1;
const rand = (): number => (state = (Math.imul(state, 1664525) + 1013904223) >>> 0) / 4294967296;
let sink = 0;
for (let rep = 0; rep < 3; rep++) {
  const c0 = process.cpuUsage();
  const t0 = performance.now();
  const prims = new PrimitiveBoxes(n);
  for (let i = 0; i < n; i++) {
    const x = rand() * 100,
      y = rand() * 100,
      z = rand() * 10;
    prims.add(2, i, x, y, z, x + 0.1 * rand(), y + 0.1 * rand(), z + 0.1 * rand());
  }
  const c1 = process.cpuUsage(c0);
  const t1 = performance.now();
  const bvh = buildBvh(prims.boxes, prims.refs, n, nodeCost)!;
  const c2 = process.cpuUsage(c0);
  const t2 = performance.now();
  sink += bvh.nodeCount;
  const ms = (c: NodeJS.CpuUsage): number => (c.user + c.system) / 1000;
  console.log(
    JSON.stringify({
      n,
      boxes_ms: Math.round(t1 - t0),
      boxes_cpu_ms: Math.round(ms(c1)),
      build_ms: Math.round(t2 - t1),
      build_cpu_ms: Math.round(ms(c2) - ms(c1)),
      nodes: bvh.nodeCount,
      depth: bvh.depth,
      bytes_per_prim: +(bvh.byteLength / n).toFixed(1),
    }),
  );
}
if (sink === 0) console.log('');
