/**
 * Time and memory to load a large glTF in Node: a generated GLB grid of
 * about 1,000,000 triangles with normals and texture coordinates (and,
 * with --textured, a 2048² base-colour PNG and a normal map whose tangents
 * MikkTSpace must generate). Reports the median over repetitions of each
 * stage (parse: container, JSON checks, glTF-Transform; textures; geometry:
 * flattening and tangents) and the bytes of the arrays the loader returns.
 * Run: node scripts/run-ts.mjs bench/gltf-load.ts [--textured] [--triangles N]
 */
import { Document } from '@gltf-transform/core';
import { encode as encodePng } from 'fast-png';
import { nodeTangentGenerator } from '../src/cli/gltf-node.ts';
import { PreloadedIO } from '../src/core/gltf/io.ts';
import { type GltfModel, type GltfStage, loadGltf } from '../src/core/gltf/load.ts';
import { decodeImageJs } from '../src/core/texture/decode-js.ts';

const args = process.argv.slice(2);
const textured = args.includes('--textured');
const ti = args.indexOf('--triangles');
const triangles = ti >= 0 ? Number(args[ti + 1]) : 1_000_000;
const reps = Number(process.env.REPS ?? 5);

function grid(): Document {
  const n = Math.ceil(Math.sqrt(triangles / 2));
  const doc = new Document();
  const buffer = doc.createBuffer();
  const pos = new Float32Array((n + 1) * (n + 1) * 3);
  const nrm = new Float32Array((n + 1) * (n + 1) * 3);
  const uv = new Float32Array((n + 1) * (n + 1) * 2);
  for (let j = 0; j <= n; j++) {
    for (let i = 0; i <= n; i++) {
      const k = j * (n + 1) + i;
      const x = i / n;
      const y = j / n;
      const z = 0.05 * Math.sin(10 * x) * Math.cos(10 * y);
      pos.set([x, y, z], 3 * k);
      nrm.set([0, 0, 1], 3 * k);
      uv.set([x, 1 - y], 2 * k);
    }
  }
  const idx = new Uint32Array(n * n * 6);
  for (let j = 0, t = 0; j < n; j++) {
    for (let i = 0; i < n; i++) {
      const a = j * (n + 1) + i;
      idx.set([a, a + 1, a + n + 2, a, a + n + 2, a + n + 1], t);
      t += 6;
    }
  }
  const prim = doc
    .createPrimitive()
    .setAttribute('POSITION', doc.createAccessor().setType('VEC3').setArray(pos).setBuffer(buffer))
    .setAttribute('NORMAL', doc.createAccessor().setType('VEC3').setArray(nrm).setBuffer(buffer))
    .setAttribute('TEXCOORD_0', doc.createAccessor().setType('VEC2').setArray(uv).setBuffer(buffer))
    .setIndices(doc.createAccessor().setType('SCALAR').setArray(idx).setBuffer(buffer));
  if (textured) {
    const size = 2048;
    const data = new Uint8Array(size * size * 4);
    for (let p = 0; p < size * size; p++)
      data.set([(p * 7) & 255, (p >> 11) & 255, 128, 255], 4 * p);
    const image = encodePng({ width: size, height: size, data, channels: 4, depth: 8 });
    const normal = encodePng({
      width: 4,
      height: 4,
      data: new Uint8Array(64).fill(200),
      channels: 4,
      depth: 8,
    });
    const mat = doc
      .createMaterial()
      .setBaseColorTexture(doc.createTexture().setImage(image).setMimeType('image/png'))
      .setNormalTexture(doc.createTexture().setImage(normal).setMimeType('image/png'));
    prim.setMaterial(mat);
  }
  doc
    .getRoot()
    .setDefaultScene(
      doc.createScene().addChild(doc.createNode().setMesh(doc.createMesh().addPrimitive(prim))),
    );
  return doc;
}

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

const glb = await new PreloadedIO().writeBinary(grid());
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
