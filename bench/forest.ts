/**
 * The instancing goal of issue 25: a forest of 1,000 instances of one 100,000-triangle
 * tree loads in under 2 s and under 300 MB. Generates the forest as a GLB in two forms
 * — 1,000 nodes sharing one mesh (`nodes`), and one node with EXT_mesh_gpu_instancing
 * (`gpu`) — then, in this process, loads it as the command line does (loadBareModel:
 * parse, validate, flatten) and compiles it (the tree's BLAS, the TLAS), and reports
 * the seconds (wall and CPU) and the process's peak resident memory (maxRSS, which
 * includes Node itself). One variant per process, so each peak is its own.
 *
 * Run: node scripts/run-ts.mjs bench/forest.ts nodes|gpu [--write DIR] [--render]
 * (--write also saves forest-nodes.glb / forest-gpu.glb; --render traces one 64×64
 * sample per pixel to show the scene renders).
 */
import { writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { Document } from '@gltf-transform/core';
import { EXTMeshGPUInstancing } from '@gltf-transform/extensions';
import { PreloadedIO } from '../src/core/gltf/io.ts';
import { loadBareModel } from '../src/core/scene/load/bare-scene.ts';
import { compileScene, PathTracer, RenderStats } from '../src/core/index.ts';

const TREE_TRIANGLES = 100_000;
const INSTANCES = 1000;

/**
 * A tree-sized mesh of about `triangles` triangles: a bumpy UV sphere (the crown)
 * stretched upwards, with normals. Deterministic.
 */
function treeMesh(doc: Document, triangles: number) {
  const slices = Math.round(Math.sqrt(triangles));
  const stacks = Math.round(triangles / (2 * slices));
  const positions = new Float32Array((stacks + 1) * (slices + 1) * 3);
  const normals = new Float32Array(positions.length);
  let v = 0;
  for (let i = 0; i <= stacks; i++) {
    const th = (Math.PI * i) / stacks;
    for (let j = 0; j <= slices; j++) {
      const ph = (2 * Math.PI * j) / slices;
      const nx = Math.sin(th) * Math.cos(ph),
        ny = Math.cos(th),
        nz = Math.sin(th) * Math.sin(ph);
      const r = 1 + 0.08 * Math.sin(7 * th) * Math.cos(9 * ph);
      positions.set([nx * r, 2 + 1.6 * ny * r, nz * r], 3 * v);
      normals.set([nx, ny, nz], 3 * v);
      v++;
    }
  }
  const indices = new Uint32Array(stacks * slices * 6);
  let k = 0;
  for (let i = 0; i < stacks; i++) {
    for (let j = 0; j < slices; j++) {
      const a = i * (slices + 1) + j;
      const b = a + slices + 1;
      indices.set([a, b, a + 1, a + 1, b, b + 1], k);
      k += 6;
    }
  }
  const buffer = doc.getRoot().listBuffers()[0];
  const prim = doc
    .createPrimitive()
    .setAttribute(
      'POSITION',
      doc.createAccessor().setType('VEC3').setArray(positions).setBuffer(buffer),
    )
    .setAttribute(
      'NORMAL',
      doc.createAccessor().setType('VEC3').setArray(normals).setBuffer(buffer),
    )
    .setIndices(doc.createAccessor().setType('SCALAR').setArray(indices).setBuffer(buffer))
    .setMaterial(doc.createMaterial('leaves').setBaseColorFactor([0.2, 0.5, 0.15, 1]));
  return doc.createMesh('tree').addPrimitive(prim);
}

/** Instance k's translation, rotation (about y) and scale; a fixed LCG. */
function placements(): { t: number[]; r: number[]; s: number[] }[] {
  let seed = 12345;
  const rand = (): number => (seed = (seed * 1103515245 + 12345) >>> 0) / 2 ** 32;
  const side = Math.ceil(Math.sqrt(INSTANCES));
  const out = [];
  for (let k = 0; k < INSTANCES; k++) {
    const a = rand() * Math.PI;
    const s = 0.8 + 0.4 * rand();
    out.push({
      t: [(k % side) * 3 + rand(), 0, Math.floor(k / side) * 3 + rand()],
      r: [0, Math.sin(a), 0, Math.cos(a)],
      s: [s, s, s],
    });
  }
  return out;
}

export async function forestGlb(variant: 'nodes' | 'gpu'): Promise<Uint8Array> {
  const doc = new Document();
  doc.createBuffer();
  const mesh = treeMesh(doc, TREE_TRIANGLES);
  const scene = doc.createScene();
  const place = placements();
  if (variant === 'nodes') {
    for (const p of place) {
      scene.addChild(
        doc
          .createNode()
          .setMesh(mesh)
          .setTranslation(p.t as [number, number, number])
          .setRotation(p.r as [number, number, number, number])
          .setScale(p.s as [number, number, number]),
      );
    }
  } else {
    const ext = doc.createExtension(EXTMeshGPUInstancing).setRequired(true);
    const buffer = doc.getRoot().listBuffers()[0];
    const acc = (type: 'VEC3' | 'VEC4', key: 't' | 'r' | 's') =>
      doc
        .createAccessor()
        .setType(type)
        .setArray(Float32Array.from(place.flatMap((p) => p[key])))
        .setBuffer(buffer);
    const inst = ext
      .createInstancedMesh()
      .setAttribute('TRANSLATION', acc('VEC3', 't'))
      .setAttribute('ROTATION', acc('VEC4', 'r'))
      .setAttribute('SCALE', acc('VEC3', 's'));
    scene.addChild(doc.createNode().setMesh(mesh).setExtension('EXT_mesh_gpu_instancing', inst));
  }
  doc.getRoot().setDefaultScene(scene);
  return new PreloadedIO().registerExtensions([EXTMeshGPUInstancing]).writeBinary(doc);
}

const args = process.argv.slice(2);
const variant = args[0] === 'gpu' ? 'gpu' : 'nodes';
const glb = await forestGlb(variant);
const wi = args.indexOf('--write');
if (wi >= 0) writeFileSync(join(args[wi + 1], `forest-${variant}.glb`), glb);
const rssBefore = process.resourceUsage().maxRSS / 1024;
const cpu0 = process.cpuUsage();
const t0 = performance.now();
const scene = await loadBareModel(glb, `forest-${variant}.glb`, null);
const t1 = performance.now();
const compiled = compileScene(scene);
const t2 = performance.now();
const cpu = process.cpuUsage(cpu0);
const peakMB = process.resourceUsage().maxRSS / 1024;
let rendered = null;
if (args.includes('--render')) {
  const tracer = new PathTracer(compiled, {
    width: 64,
    height: 64,
    maxBounces: 4,
    camera: scene.camera,
  });
  const stats = new RenderStats();
  let sum = 0;
  const t3 = performance.now();
  for (let y = 0; y < 64; y++)
    for (let x = 0; x < 64; x++) {
      tracer.trace(x, y, 0, stats);
      sum += tracer.lr + tracer.lg + tracer.lb;
    }
  rendered = { meanRadiance: sum / (3 * 64 * 64), ms: Math.round(performance.now() - t3) };
}
const instanceBytes = compiled.instXform.byteLength + compiled.instBlas.byteLength;
console.log(
  JSON.stringify({
    variant,
    fileBytes: glb.length,
    instances: compiled.instanceCount,
    uniqueTriangles: compiled.triCount,
    renderedTriangles: compiled.triCount * compiled.instanceCount,
    loadSeconds: +((t1 - t0) / 1000).toFixed(3),
    compileSeconds: +((t2 - t1) / 1000).toFixed(3),
    totalSeconds: +((t2 - t0) / 1000).toFixed(3),
    // CPU seconds of the loading thread and any helpers (user + system): on a shared,
    // loaded machine the wall time above includes waiting for a core.
    totalCpuSeconds: +((cpu.user + cpu.system) / 1e6).toFixed(3),
    peakRssMB: Math.round(peakMB),
    rssBeforeLoadMB: Math.round(rssBefore),
    instanceRecordBytes: instanceBytes / compiled.instanceCount,
    tlasBytesPerInstance: Math.round(
      (compiled.bvh!.nodes.byteLength + compiled.bvh!.refs.byteLength) / compiled.instanceCount,
    ),
    rendered,
  }),
);
