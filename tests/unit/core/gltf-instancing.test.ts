/**
 * Instancing (docs/gltf.md, Instancing; accel/instances.ts): a mesh used several times
 * is kept once and drawn by instances under the scene's BVH. Checked against the
 * flattened copy of the same file (every use its own mesh, every
 * EXT_mesh_gpu_instancing row a node: tests/helpers/gltf-copies.ts), on two public
 * models, and against hostile extension content and the split triangle limits.
 */
import { readdirSync, readFileSync } from 'node:fs';
import { Document } from '@gltf-transform/core';
import { EXTMeshGPUInstancing, KHRMaterialsAnisotropy } from '@gltf-transform/extensions';
import { describe, expect, it } from 'vitest';
import { compileScene, type Scene } from '../../../src/core/index.ts';
import { GltfError } from '../../../src/core/gltf/errors.ts';
import { intersectScene, occluded } from '../../../src/core/accel/trace.ts';
import { Hit, Ray } from '../../../src/core/geometry/ray.ts';
import { loadGltf } from '../../../src/core/gltf/load.ts';
import { parseGlb } from '../../../src/core/gltf/glb.ts';
import { GLTF_LIMITS } from '../../../src/core/gltf/validate.ts';
import { loadBareModel } from '../../../src/core/scene/load/bare-scene.ts';
import { flattenedCopy, flattenJson, writeGlb } from '../../helpers/gltf-copies.ts';
import { io, memoryOptions, meshPrimitive, sceneWithFiles } from '../../helpers/gltf.ts';
import { renderSampled, ROOT, type RenderOptions } from '../../helpers/render.ts';

const fixture = (name: string): Uint8Array =>
  new Uint8Array(readFileSync(`${ROOT}tests/fixtures/gltf-instancing/${name}`));

/**
 * Largest difference of two renders' pixel means relative to max(|b|, floor), where the
 * floor is 1 % of b's mean pixel value: the normals' rounding (below) is an absolute
 * error in cos θ, so a pixel seen at grazing angles (cos θ ~ 1e-3, 1e-4 of the mean
 * radiance) has relatively more of it; a path that changes its course changes a pixel
 * by about its own value, far beyond 1e-5 of this floor.
 */
function maxRelative(a: Float64Array, b: Float64Array): number {
  let mean = 0;
  for (const v of b) mean += v / b.length;
  const floor = 0.01 * mean;
  let worst = 0;
  for (let i = 0; i < a.length; i++) {
    const d = Math.abs(a[i] - b[i]) / Math.max(floor, Math.abs(b[i]));
    if (!(d <= worst)) worst = d;
  }
  return worst;
}

/**
 * `a` draws `instances` instances and its flattened copy `b` none; their renders agree
 * to 1e-5 (maxRelative), and the camera frames the model: the image is not the bare
 * environment.
 */
function expectImageOfCopy(a: Scene, b: Scene, instances: number, options: RenderOptions): void {
  expect(compileScene(a).instanceCount).toBe(instances);
  expect(compileScene(b).instanceCount).toBe(0);
  const ia = renderSampled(a, options);
  expect(maxRelative(ia.mean, renderSampled(b, options).mean)).toBeLessThan(1e-5);
  expect(Math.max(...ia.mean) - Math.min(...ia.mean)).toBeGreaterThan(0.05);
}

describe('instanced scene against its flattened copy', () => {
  // Not bit for bit: the copy's triangles are transformed to world space and
  // intersected there, the instance's in object space, each rounding differently (a
  // few ulps in the hit point); and the copy stores its world-space shading normals in
  // Float32 (flatten.ts), where the instance carries its object-space normals to world
  // space in double: 2⁻²⁴ relative in the normal. Both are far below 1e-5 in a pixel;
  // a path that changes its course (a ray grazing an edge that the two roundings decide
  // differently) would exceed it, and on these renders none does (observed maxima: 7e-7
  // for SimpleInstancing, 2e-16 for AttenuationTest).
  for (const [name, instances, unique, copies] of [
    ['SimpleInstancing.glb', 125, 12, 1500],
    ['AttenuationTest.glb', 6, 232, 292],
  ] as const) {
    it(`${name}: ${instances} instances, the image of the copy`, async () => {
      const bytes = fixture(name);
      const a = await loadBareModel(bytes, name, null);
      const b = await loadBareModel(flattenedCopy(bytes), name, null);
      expect(a.camera).toEqual(b.camera);
      const ca = compileScene(a);
      const cb = compileScene(b);
      expect(ca.instanceCount).toBe(instances);
      expect(ca.triCount).toBe(unique);
      expect(cb.instanceCount).toBe(0);
      expect(cb.triCount).toBe(copies);
      const options = { width: 24, height: 24, spp: 2 };
      const ia = renderSampled(a, options);
      const ib = renderSampled(b, options);
      expect(maxRelative(ia.mean, ib.mean)).toBeLessThan(1e-5);
      let lit = 0;
      for (const v of ia.mean) if (v > 0) lit++;
      expect(lit).toBeGreaterThan(ia.mean.length / 2);
    });
  }
});

/** Two quads (one mesh, two nodes) over a third, with the material `make` gives. */
function twoUses(make: (doc: Document) => ReturnType<Document['createMaterial']>): Document {
  const doc = new Document();
  doc.createBuffer();
  const mat = make(doc);
  const quad = (m: ReturnType<Document['createMaterial']> | null) => {
    const p = meshPrimitive(doc, [0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0], [0, 1, 2, 0, 2, 3], {
      normals: [0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1],
    });
    if (m !== null) p.setMaterial(m);
    return doc.createMesh().addPrimitive(p);
  };
  const shared = quad(mat);
  const floor = quad(doc.createMaterial().setBaseColorFactor([0.8, 0.8, 0.8, 1]));
  const s = Math.SQRT1_2;
  const scene = doc.createScene();
  scene.addChild(doc.createNode().setMesh(shared).setTranslation([-0.6, 0, 0.3]));
  scene.addChild(
    doc.createNode().setMesh(shared).setTranslation([0.7, 0, 0.6]).setRotation([0, s, 0, s]),
  );
  scene.addChild(doc.createNode().setMesh(floor).setTranslation([-1, -0.5, 0]).setScale([3, 3, 1]));
  doc.getRoot().setDefaultScene(scene);
  return doc;
}

describe('what is instanced', () => {
  it('an emissive mesh used twice is copied, not instanced (a mesh light samples world area)', async () => {
    const m = await loadGltf(
      await io().writeBinary(twoUses((doc) => doc.createMaterial().setEmissiveFactor([1, 1, 1]))),
      'm.glb',
      await memoryOptions(),
    );
    expect(m.instances).toBeUndefined();
    expect(m.indices.length).toBe(3 * 6);
  });

  it('a mesh of points drawn twice: its instances and BLAS are dropped', async () => {
    const doc = twoUses((d) => d.createMaterial());
    const shared = doc.getRoot().listMeshes()[0];
    shared.listPrimitives()[0].setMode(0); // POINTS
    // The floor drawn twice too: one BLAS with triangles beside one without.
    const floor = doc.getRoot().listMeshes()[1];
    doc
      .getRoot()
      .listScenes()[0]
      .addChild(doc.createNode().setMesh(floor).setTranslation([0, 0, -1]));
    const scene = await loadBareModel(await io().writeBinary(doc), 'm.glb', null);
    const c = compileScene(scene);
    expect(c.instanceCount).toBe(2);
    expect(c.triCount).toBe(2);
  });

  it('alpha (BLEND) through instances: paths and shadow rays as through the copies', async () => {
    const glb = await io().writeBinary(
      twoUses((doc) =>
        doc.createMaterial().setBaseColorFactor([0.9, 0.3, 0.2, 0.4]).setAlphaMode('BLEND'),
      ),
    );
    const a = await loadBareModel(glb, 'a.glb', null);
    const b = await loadBareModel(flattenedCopy(glb), 'b.glb', null);
    expectImageOfCopy(a, b, 2, { width: 16, height: 16, spp: 4 });
  });

  it('KHR_materials_anisotropy through instances: the tangent is carried to world space', async () => {
    // The shared quads turned by their nodes (one by 90° about y): an object-space
    // tangent read as world space would stretch the highlight the wrong way.
    const doc = twoUses((d) => {
      const ext = d.createExtension(KHRMaterialsAnisotropy);
      return d
        .createMaterial()
        .setBaseColorFactor([0.9, 0.8, 0.6, 1])
        .setMetallicFactor(1)
        .setRoughnessFactor(0.35)
        .setExtension(
          'KHR_materials_anisotropy',
          ext.createAnisotropy().setAnisotropyStrength(0.9).setAnisotropyRotation(0.4),
        );
    });
    const buffer = doc.getRoot().listBuffers()[0];
    const shared = doc.getRoot().listMeshes()[0].listPrimitives()[0];
    shared
      .setAttribute(
        'TEXCOORD_0',
        doc
          .createAccessor()
          .setType('VEC2')
          .setArray(Float32Array.from([0, 0, 1, 0, 1, 1, 0, 1]))
          .setBuffer(buffer),
      )
      .setAttribute(
        'TANGENT',
        doc
          .createAccessor()
          .setType('VEC4')
          .setArray(Float32Array.from([1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 1]))
          .setBuffer(buffer),
      );
    const glb = await io().writeBinary(doc);
    const a = await loadBareModel(glb, 'a.glb', null);
    const b = await loadBareModel(flattenedCopy(glb), 'b.glb', null);
    expectImageOfCopy(a, b, 2, { width: 16, height: 16, spp: 4 });
  });
});

describe('textures through instances', () => {
  it('TextureTransformTest (.gltf, meshes shared by 3 and 2 nodes): the image of the copy', async () => {
    const dir = `${ROOT}tests/fixtures/gltf-instancing/TextureTransformTest/`;
    const files = new Map<string, Uint8Array>();
    for (const f of readdirSync(dir)) files.set(f, new Uint8Array(readFileSync(dir + f)));
    const gltf = files.get('TextureTransformTest.gltf')!;
    const json = JSON.parse(new TextDecoder().decode(gltf));
    flattenJson(json, null);
    const copy = new TextEncoder().encode(JSON.stringify(json));
    const { reader } = await memoryOptions(files);
    const a = await loadBareModel(gltf, 'TextureTransformTest.gltf', reader);
    const b = await loadBareModel(copy, 'TextureTransformTest.gltf', reader);
    expectImageOfCopy(a, b, 5, { width: 32, height: 24, spp: 2 });
  });
});

describe('instances of several models in one scene', () => {
  it('two gltf shapes of one file, moved apart: each keeps its BLAS and instances', async () => {
    const files = new Map([['m.glb', fixture('SimpleInstancing.glb')]]);
    const move = (x: number) => [1, 0, 0, x, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1];
    const scene = await sceneWithFiles(
      {
        format: 'pathwise-scene/1',
        camera: { position: [30, 20, 60], target: [30, 5, 5], up: [0, 1, 0], fovY: 50 },
        settings: { width: 16, height: 8, maxBounces: 3, spp: 2 },
        materials: {},
        shapes: [
          { type: 'gltf', file: 'm.glb' },
          { type: 'gltf', file: 'm.glb', transform: move(40) },
        ],
        environment: [1, 1, 1],
      },
      files,
    );
    const c = compileScene(scene);
    expect(c.instanceCount).toBe(250);
    expect(c.triCount).toBe(24);
    // The second model's instances draw its own BLAS (triangles 12–23), 40 units along x.
    const ray = new Ray();
    const hit = new Hit();
    Object.assign(ray, { ox: 45.5, oy: 0.5, oz: -5, dx: 0, dy: 0, dz: 1, tMax: Infinity });
    expect(intersectScene(c, ray, hit)).toBe(true);
    expect(hit.instance).toBeGreaterThanOrEqual(125);
    expect(hit.index).toBeGreaterThanOrEqual(12);
    const img = renderSampled(scene, { spp: 2 });
    for (const v of img.mean) expect(Number.isFinite(v)).toBe(true);
  });
});

describe('ray queries through instances', () => {
  it('nearest hits and occlusion as in the flattened copy (SimpleInstancing, 4,000 rays)', async () => {
    const bytes = fixture('SimpleInstancing.glb');
    const ca = compileScene(await loadBareModel(bytes, 'a.glb', null));
    const cb = compileScene(await loadBareModel(flattenedCopy(bytes), 'b.glb', null));
    const ray = new Ray();
    const ha = new Hit();
    const hb = new Hit();
    let seed = 7;
    const rand = (): number => (seed = (seed * 1103515245 + 12345) >>> 0) / 2 ** 32;
    let hits = 0;
    for (let i = 0; i < 4000; i++) {
      // From points around and inside the 10-unit block of cubes, in every direction.
      const o = [rand() * 16 - 3, rand() * 16 - 3, rand() * 16 - 3];
      const z = 2 * rand() - 1;
      const phi = 2 * Math.PI * rand();
      const s = Math.sqrt(1 - z * z);
      const d = [s * Math.cos(phi), s * Math.sin(phi), z];
      const tMax = i % 2 === 0 ? Infinity : 1 + 8 * rand();
      const set = (): void => {
        [ray.ox, ray.oy, ray.oz] = o;
        [ray.dx, ray.dy, ray.dz] = d;
        ray.tMax = tMax;
      };
      set();
      const fa = intersectScene(ca, ray, ha);
      set();
      const fb = intersectScene(cb, ray, hb);
      expect(fa).toBe(fb);
      if (fa) {
        hits++;
        expect(Math.abs(ha.t - hb.t)).toBeLessThan(1e-12 * (1 + hb.t) * 16);
        expect(ha.instance).toBeGreaterThanOrEqual(0);
      }
      set();
      const oa = occluded(ca, ray);
      set();
      expect(oa).toBe(occluded(cb, ray));
    }
    expect(hits).toBeGreaterThan(1000);
  });
});

/** A document of one quad mesh drawn by EXT_mesh_gpu_instancing rows (edited after). */
async function gpuDoc(count: number): Promise<{ json: Record<string, any>; bin: Uint8Array }> {
  const doc = new Document();
  const buffer = doc.createBuffer();
  const prim = meshPrimitive(doc, [0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0], [0, 1, 2, 0, 2, 3]);
  const mesh = doc.createMesh().addPrimitive(prim);
  const ext = doc.createExtension(EXTMeshGPUInstancing);
  const acc = (type: 'VEC3' | 'VEC4', values: number[]) =>
    doc.createAccessor().setType(type).setArray(Float32Array.from(values)).setBuffer(buffer);
  const t: number[] = [];
  const r: number[] = [];
  for (let k = 0; k < count; k++) (t.push(2 * k, 0, 0), r.push(0, 0, 0, 1));
  const inst = ext
    .createInstancedMesh()
    .setAttribute('TRANSLATION', acc('VEC3', t))
    .setAttribute('ROTATION', acc('VEC4', r))
    .setAttribute('SCALE', acc('VEC3', new Array(3 * count).fill(1)));
  const scene = doc.createScene();
  scene.addChild(doc.createNode().setMesh(mesh).setExtension('EXT_mesh_gpu_instancing', inst));
  doc.getRoot().setDefaultScene(scene);
  const { json, bin } = parseGlb(await io().writeBinary(doc));
  return { json: JSON.parse(new TextDecoder().decode(json)), bin: bin! };
}

async function load(json: Record<string, any>, bin: Uint8Array) {
  return loadGltf(writeGlb(json, bin), 'm.glb', await memoryOptions());
}

describe('EXT_mesh_gpu_instancing', () => {
  it('draws the mesh once per row, never at the node itself', async () => {
    const { json, bin } = await gpuDoc(3);
    const m = await load(json, bin);
    expect(m.indices.length).toBe(0);
    expect(m.instances!.mesh.length).toBe(3);
    expect(Array.from(m.instances!.matrices.subarray(12 * 2 + 9, 12 * 3))).toEqual([4, 0, 0]);
    expect(Array.from(m.bounds)).toEqual([0, 0, 0, 5, 1, 0]);
  });

  it('reads a normalized short ROTATION (KHR_mesh_quantization)', async () => {
    const { json, bin } = await gpuDoc(2);
    const at = json.nodes[0].extensions.EXT_mesh_gpu_instancing.attributes;
    // A quarter turn about z, (0, 0, sin 45°, cos 45°), as normalized shorts.
    const q = Math.round(Math.SQRT1_2 * 32767);
    const extra = new Uint8Array(16);
    new Int16Array(extra.buffer).set([0, 0, q, q, 0, 0, q, q]);
    const all = new Uint8Array(bin.length + 16);
    all.set(bin);
    all.set(extra, bin.length);
    json.buffers[0].byteLength = all.length;
    json.bufferViews.push({ buffer: 0, byteOffset: bin.length, byteLength: 16 });
    json.accessors.push({
      bufferView: json.bufferViews.length - 1,
      componentType: 5122,
      normalized: true,
      count: 2,
      type: 'VEC4',
    });
    at.ROTATION = json.accessors.length - 1;
    json.extensionsUsed = [...json.extensionsUsed, 'KHR_mesh_quantization'];
    const m = await load(json, bin.length === all.length ? bin : all);
    const mat = m.instances!.matrices;
    // Column 0 (the x axis) turned to +y.
    expect(mat[0]).toBeCloseTo(0, 4);
    expect(mat[1]).toBeCloseTo(1, 4);
  });

  const hostile: [string, (json: Record<string, any>) => void, RegExp][] = [
    [
      'accessor counts that differ',
      (json) =>
        (json.accessors[json.nodes[0].extensions.EXT_mesh_gpu_instancing.attributes.SCALE].count =
          2),
      /^glTF: nodes\[0\]\.extensions\.EXT_mesh_gpu_instancing\.attributes\.SCALE: accessors\[\d+\] has 2 elements, but TRANSLATION has 3/,
    ],
    [
      'two million instances declared',
      (json) => {
        for (const i of Object.values(json.nodes[0].extensions.EXT_mesh_gpu_instancing.attributes))
          json.accessors[i as number].count = 2e6;
      },
      /^glTF: nodes\[0\]\.extensions\.EXT_mesh_gpu_instancing\.attributes\.TRANSLATION: declares 2,000,000 instances, more than the limit of 1,000,000/,
    ],
    [
      // Past the accessor limit (2^28), the accessor is refused first.
      'a billion instances declared',
      (json) => {
        for (const i of Object.values(json.nodes[0].extensions.EXT_mesh_gpu_instancing.attributes))
          json.accessors[i as number].count = 1e9;
      },
      /^glTF: accessors\[\d+\]\.count: /,
    ],
    [
      'a ROTATION of the wrong type',
      (json) =>
        (json.accessors[json.nodes[0].extensions.EXT_mesh_gpu_instancing.attributes.ROTATION].type =
          'VEC3'),
      /^glTF: nodes\[0\]\.extensions\.EXT_mesh_gpu_instancing\.attributes\.ROTATION: accessors\[\d+\] must be VEC4/,
    ],
    [
      'an accessor index out of range',
      (json) => (json.nodes[0].extensions.EXT_mesh_gpu_instancing.attributes.SCALE = 99),
      /^glTF: nodes\[0\]\.extensions\.EXT_mesh_gpu_instancing\.attributes\.SCALE/,
    ],
  ];
  for (const [what, edit, message] of hostile) {
    it(`refuses ${what}, naming the path`, async () => {
      const { json, bin } = await gpuDoc(3);
      edit(json);
      await expect(load(json, bin)).rejects.toThrow(GltfError);
      await expect(load(json, bin)).rejects.toThrow(message);
    });
  }

  it('refuses a non-finite TRS value, naming the accessor and the instance', async () => {
    const { json, bin } = await gpuDoc(3);
    const t =
      json.accessors[json.nodes[0].extensions.EXT_mesh_gpu_instancing.attributes.TRANSLATION];
    const view = json.bufferViews[t.bufferView];
    const copy = bin.slice();
    new DataView(copy.buffer).setFloat32(
      (view.byteOffset ?? 0) + (t.byteOffset ?? 0) + 4 * 4,
      NaN,
      true,
    );
    await expect(load(json, copy)).rejects.toThrow(
      /^glTF: nodes\[0\]\.extensions\.EXT_mesh_gpu_instancing\.attributes\.TRANSLATION: instance 1 has a non-finite value/,
    );
  });
});

describe('limits: distinct triangles and instances', () => {
  it('copies of an emissive mesh drawn many times are refused past the limit, before allocating', async () => {
    // 20,000 emissive triangles × 600 nodes: 12 M copied triangles (emissive meshes are
    // not instanced), over the 10 M limit although the file holds 20,000.
    const doc = new Document();
    doc.createBuffer();
    const pos: number[] = [];
    const idx: number[] = [];
    for (let k = 0; k < 20_000; k++) {
      pos.push(k, 0, 0, k + 1, 0, 0, k, 1, 0);
      idx.push(3 * k, 3 * k + 1, 3 * k + 2);
    }
    const prim = meshPrimitive(doc, pos, idx).setMaterial(
      doc.createMaterial().setEmissiveFactor([1, 1, 1]),
    );
    const mesh = doc.createMesh().addPrimitive(prim);
    const scene = doc.createScene();
    for (let k = 0; k < 600; k++) scene.addChild(doc.createNode().setMesh(mesh));
    doc.getRoot().setDefaultScene(scene);
    await expect(
      loadGltf(await io().writeBinary(doc), 'm.glb', await memoryOptions()),
    ).rejects.toThrow(
      /^glTF: scene: holds 12000000 triangles once emissive meshes drawn several times are copied, more than the limit of 10000000$/,
    );
  });

  it('a mesh used by many nodes counts its triangles once', async () => {
    // 40,000 triangles × 300 nodes = 12 M drawn, over the 10 M limit of distinct ones.
    const doc = new Document();
    doc.createBuffer();
    const n = 100;
    const pos: number[] = [];
    const idx: number[] = [];
    for (let y = 0; y <= n * 2; y++) for (let x = 0; x <= n; x++) pos.push(x, y, 0);
    for (let y = 0; y < n * 2; y++)
      for (let x = 0; x < n; x++) {
        const a = y * (n + 1) + x;
        idx.push(a, a + 1, a + n + 2, a, a + n + 2, a + n + 1);
      }
    const mesh = doc.createMesh().addPrimitive(meshPrimitive(doc, pos, idx));
    const scene = doc.createScene();
    for (let k = 0; k < 300; k++)
      scene.addChild(doc.createNode().setMesh(mesh).setTranslation([0, 0, k]));
    doc.getRoot().setDefaultScene(scene);
    expect(300 * (idx.length / 3)).toBeGreaterThan(GLTF_LIMITS.triangles);
    const m = await loadGltf(await io().writeBinary(doc), 'm.glb', await memoryOptions());
    expect(m.instances!.mesh.length).toBe(300);
    expect(m.instances!.meshes[0].indices.length).toBe(idx.length);
    // ≤ 128 bytes per instance record (accel/instances.ts).
    const scene2: Scene = {
      ...(await loadBareModel(await io().writeBinary(doc), 'm.glb', null)),
    };
    const c = compileScene(scene2);
    expect((c.instXform.byteLength + c.instBlas.byteLength) / c.instanceCount).toBeLessThanOrEqual(
      128,
    );
  });
});
