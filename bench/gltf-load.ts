/**
 * Time and memory to load a large glTF in Node: a generated GLB grid of
 * about 1,000,000 triangles with normals and texture coordinates (and,
 * with --textured, a 2048² base-colour PNG and a normal map whose tangents
 * MikkTSpace must generate). Reports the median over repetitions of each
 * stage (parse: container, JSON checks, glTF-Transform; textures; geometry:
 * flattening and tangents) and the bytes of the arrays the loader returns.
 * Run: node scripts/run-ts.mjs bench/gltf-load.ts [--textured] [--triangles N]
 */
import { gridDocument } from './gltf-grid.ts';
import { nodeTangentGenerator } from '../src/cli/gltf-node.ts';
import { PreloadedIO } from '../src/core/gltf/io.ts';
import { type GltfModel, type GltfStage, loadGltf } from '../src/core/gltf/load.ts';
import { decodeImageJs } from '../src/core/texture/decode-js.ts';

const args = process.argv.slice(2);
const textured = args.includes('--textured');
const ti = args.indexOf('--triangles');
const triangles = ti >= 0 ? Number(args[ti + 1]) : 1_000_000;
const reps = Number(process.env.REPS ?? 5);

function bytesOf(m: GltfModel): number {
  const arrays = [
    m.positions,
    m.indices,
    m.normals,
    m.uv0,
    m.uv1,
    m.colors,
    m.tangents,
    m.triangleMaterial,
    m.textures.texels,
  ];
  return arrays.reduce((s, a) => s + (a === null ? 0 : a.byteLength), 0);
}

const median = (a: number[]): number => [...a].sort((x, y) => x - y)[Math.floor(a.length / 2)];

const glb = await new PreloadedIO().writeBinary(gridDocument(triangles, textured));
const mikk = await nodeTangentGenerator();
let mikkMs = 0;
const generateTangents = (p: Float32Array, n: Float32Array, t: Float32Array): Float32Array => {
  const t0 = performance.now();
  const out = mikk(p, n, t);
  mikkMs += performance.now() - t0;
  return out;
};
const totals: number[] = [];
const stages: Record<GltfStage, number[]> = { parse: [], textures: [], geometry: [] };
let sink = 0;
let model: GltfModel | null = null;
for (let r = 0; r < reps + 1; r++) {
  const start: Partial<Record<GltfStage, number>> = {};
  const end: Partial<Record<GltfStage, number>> = {};
  const t0 = performance.now();
  model = await loadGltf(glb, 'grid.glb', {
    reader: null,
    decodeImage: decodeImageJs,
    generateTangents,
    onProgress(stage, done, total) {
      if (done === 0) start[stage] ??= performance.now();
      if (done === total) end[stage] = performance.now();
    },
  });
  const t1 = performance.now();
  sink += model.indices.length;
  if (r === 0) {
    mikkMs = 0;
    continue; // warm-up
  }
  totals.push(t1 - t0);
  for (const s of ['parse', 'textures', 'geometry'] as const) {
    stages[s].push((end[s] ?? t1) - (start[s] ?? t1));
  }
}
const m = model!;
const result = {
  file: { bytes: glb.length, triangles: m.indices.length / 3, vertices: m.positions.length / 3 },
  textured,
  medianMs: {
    total: Math.round(median(totals)),
    parse: Math.round(median(stages.parse)),
    textures: Math.round(median(stages.textures)),
    geometry: Math.round(median(stages.geometry)),
    /** Of geometry: MikkTSpace itself (mean over the repetitions). */
    mikktspace: Math.round(mikkMs / reps),
  },
  outputBytes: bytesOf(m),
  bytesPerTriangle: Math.round(bytesOf(m) / (m.indices.length / 3)),
  rssMiB: Math.round(process.memoryUsage().rss / 2 ** 20),
  reps,
  sink,
};
console.log(JSON.stringify(result, null, 2));
