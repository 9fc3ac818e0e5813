/**
 * Loading glTF 2.0 (src/core/gltf/): files generated here with glTF-Transform
 * — GLB and .gltf with external and data-URI resources, the node hierarchy
 * (TRS, matrix, instancing, mirroring), every primitive layout, materials
 * with every honoured extension and textures — read back and checked
 * against what the glTF specification says they mean.
 */
import { Document } from '@gltf-transform/core';
import {
  KHRXMP,
  KHRMaterialsEmissiveStrength,
  KHRMaterialsIOR,
  KHRMaterialsSpecular,
  KHRMaterialsTransmission,
  KHRTextureTransform,
} from '@gltf-transform/extensions';
import { describe, expect, it } from 'vitest';
import { ShadingParams } from '../../../src/core/bsdf/shading.ts';
import { groupByMaterial } from '../../../src/core/scene/compile/groups.ts';
import { loadGltf } from '../../../src/core/gltf/load.ts';
import {
  GM_EMISSIVE,
  GM_IOR,
  GM_METALLIC,
  GM_ROUGHNESS,
  GM_SPECULAR,
  GM_STRIDE,
  GM_TRANSMISSION,
} from '../../../src/core/gltf-material/material-table.ts';
import { fillGltfShading, HitAttributes } from '../../../src/core/gltf-material/shading-fill.ts';
import { srgbToLinear } from '../../../src/core/texture/srgb.ts';
import { loadGlb, memoryOptions, png, quadPrimitive, toGltfFiles } from '../../helpers/gltf.ts';

function sceneWith(doc: Document, ...nodes: ReturnType<Document['createNode']>[]): void {
  const scene = doc.createScene();
  for (const n of nodes) scene.addChild(n);
  doc.getRoot().setDefaultScene(scene);
}

function quadDoc(opts?: Parameters<typeof quadPrimitive>[1]): Document {
  const doc = new Document();
  doc.createBuffer();
  const mesh = doc.createMesh().addPrimitive(quadPrimitive(doc, opts));
  sceneWith(doc, doc.createNode().setMesh(mesh));
  return doc;
}

const close = (a: ArrayLike<number>, b: number[], eps = 1e-6): void => {
  expect(a.length).toBe(b.length);
  for (let i = 0; i < b.length; i++) expect(Math.abs(a[i] - b[i])).toBeLessThan(eps);
};

describe('glTF geometry', () => {
  it('reads an indexed quad from a GLB: positions, normals, uvs, materials, bounds', async () => {
    const m = await loadGlb(quadDoc());
    close(m.positions, [0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0]);
    expect(Array.from(m.indices)).toEqual([0, 1, 2, 0, 2, 3]);
    close(m.normals!, [0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1]);
    close(m.uv0!, [0, 1, 1, 1, 1, 0, 0, 0]);
    expect(m.uv1).toBeNull();
    expect(m.colors).toBeNull();
    expect(m.tangents).toBeNull();
    // No material: glTF's default one, the last row of the table.
    expect(Array.from(m.triangleMaterial)).toEqual([0, 0]);
    expect(m.materials.length).toBe(GM_STRIDE);
    expect(m.materials[GM_METALLIC]).toBe(1);
    expect(m.materials[GM_ROUGHNESS]).toBe(1);
    expect(Array.from(m.bounds)).toEqual([0, 0, 0, 1, 1, 0]);
    expect(m.warnings).toEqual([]);
  });

  it('applies TRS and matrix transforms down the hierarchy, instancing a mesh per node', async () => {
    const doc = new Document();
    doc.createBuffer();
    const mesh = doc.createMesh().addPrimitive(quadPrimitive(doc));
    // Parent: a matrix (translate by (10, 0, 0), column-major); child: scale 2 then rotate 90° about z.
    const parent = doc.createNode().setMatrix([1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 10, 0, 0, 1]);
    const s = Math.SQRT1_2;
    const child = doc.createNode().setMesh(mesh).setScale([2, 2, 2]).setRotation([0, 0, s, s]);
    parent.addChild(child);
    const other = doc.createNode().setMesh(mesh).setTranslation([0, 0, -5]);
    sceneWith(doc, parent, other);
    const m = await loadGlb(doc);
    // A mesh used twice is kept once, in object space, and drawn by two instances
    // (docs/gltf.md, Instancing): no world-space copies.
    expect(m.indices.length).toBe(0);
    const inst = m.instances!;
    expect(Array.from(inst.mesh)).toEqual([0, 0]);
    const obj = inst.meshes[0];
    expect(Array.from(obj.indices)).toEqual([0, 1, 2, 0, 2, 3]);
    const at = (k: number, v: number): number[] => {
      const a = inst.matrices.subarray(12 * k, 12 * k + 12);
      const [x, y, z] = obj.positions.subarray(3 * v, 3 * v + 3);
      return [0, 1, 2].map((r) => a[r] * x + a[3 + r] * y + a[6 + r] * z + a[9 + r]);
    };
    // Corner (1, 0, 0) → scale (2, 0, 0) → rotate (0, 2, 0) → translate (10, 2, 0).
    close(at(0, 1), [10, 2, 0]);
    close(at(0, 2), [8, 2, 0]);
    // The second instance, translated only.
    close(at(1, 2), [1, 1, -5]);
    close(obj.normals!.subarray(0, 3), [0, 0, 1]);
    close(m.bounds, [0, 0, -5, 10, 2, 0]);
  });

  it('a mirroring node keeps the front side: winding swapped, normals and tangent handedness right', async () => {
    const doc = quadDoc();
    const node = doc.getRoot().listNodes()[0].setScale([-1, 1, 1]);
    void node;
    const m = await loadGlb(doc);
    // Mirrored x: the quad spans x ∈ [−1, 0]; its normal stays +z.
    close(m.positions, [0, 0, 0, -1, 0, 0, -1, 1, 0, 0, 1, 0]);
    expect(Array.from(m.indices)).toEqual([0, 2, 1, 0, 3, 2]);
    const [a, b, c] = [0, 2, 1].map((k) => Array.from(m.positions.subarray(3 * k, 3 * k + 3)));
    const e = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
    const f = [c[0] - a[0], c[1] - a[1], c[2] - a[2]];
    expect(e[0] * f[1] - e[1] * f[0]).toBeGreaterThan(0); // geometric normal +z
    close(m.normals!.subarray(0, 3), [0, 0, 1]);
  });

  it('reads non-indexed triangles, strips and fans; skips points and lines with a warning', async () => {
    const doc = new Document();
    const buffer = doc.createBuffer();
    const mesh = doc.createMesh();
    mesh.addPrimitive(quadPrimitive(doc, { indexed: false }));
    const pos = (a: number[]) =>
      doc.createAccessor().setType('VEC3').setArray(new Float32Array(a)).setBuffer(buffer);
    const strip = doc
      .createPrimitive()
      .setMode(5)
      .setAttribute('POSITION', pos([0, 0, 1, 1, 0, 1, 0, 1, 1, 1, 1, 1]));
    const fan = doc
      .createPrimitive()
      .setMode(6)
      .setAttribute('POSITION', pos([0, 0, 2, 1, 0, 2, 1, 1, 2, 0, 1, 2]));
    const points = doc
      .createPrimitive()
      .setMode(0)
      .setAttribute('POSITION', pos([0, 0, 3]));
    const lines = doc
      .createPrimitive()
      .setMode(1)
      .setAttribute('POSITION', pos([0, 0, 3, 1, 0, 3]));
    mesh.addPrimitive(strip).addPrimitive(fan).addPrimitive(points).addPrimitive(lines);
    sceneWith(doc, doc.createNode().setMesh(mesh));
    const m = await loadGlb(doc);
    expect(m.indices.length / 3).toBe(2 + 2 + 2);
    // Strip (v0 v1 v2), (v2 v1 v3) keep counter-clockwise: both normals +z.
    for (let t = 0; t < 6; t++) {
      const [a, b, c] = [0, 1, 2].map((k) => m.indices[3 * t + k]);
      const p = (i: number) => Array.from(m.positions.subarray(3 * i, 3 * i + 3));
      const [pa, pb, pc] = [p(a), p(b), p(c)];
      const cz = (pb[0] - pa[0]) * (pc[1] - pa[1]) - (pb[1] - pa[1]) * (pc[0] - pa[0]);
      expect(cz).toBeGreaterThan(0);
    }
    expect(m.warnings).toEqual([
      'meshes[0].primitives[3]: mode 0 (points or lines) is not rendered; skipped',
      'meshes[0].primitives[4]: mode 1 (points or lines) is not rendered; skipped',
    ]);
    // Primitives without NORMAL get (0, 0, 0): the geometric normal.
    close(m.normals!.subarray(6 * 3, 6 * 3 + 3), [0, 0, 0]);
  });

  it('skips and counts zero-area triangles', async () => {
    const doc = new Document();
    const buffer = doc.createBuffer();
    const prim = doc.createPrimitive().setAttribute(
      'POSITION',
      doc
        .createAccessor()
        .setType('VEC3')
        .setArray(new Float32Array([0, 0, 0, 1, 0, 0, 2, 0, 0, 0, 0, 0, 1, 0, 0, 0, 1, 0]))
        .setBuffer(buffer),
    );
    sceneWith(doc, doc.createNode().setMesh(doc.createMesh().addPrimitive(prim)));
    const m = await loadGlb(doc);
    expect(m.indices.length).toBe(3);
    expect(m.skipped).toBe(1);
  });

  it('decodes normalised integer texture coordinates and vertex colours', async () => {
    const doc = quadDoc({ uv: false });
    const prim = doc.getRoot().listMeshes()[0].listPrimitives()[0];
    const buffer = doc.getRoot().listBuffers()[0];
    prim.setAttribute(
      'TEXCOORD_0',
      doc
        .createAccessor()
        .setType('VEC2')
        .setNormalized(true)
        .setArray(new Uint16Array([0, 65535, 65535, 65535, 65535, 0, 0, 0]))
        .setBuffer(buffer),
    );
    prim.setAttribute(
      'COLOR_0',
      doc
        .createAccessor()
        .setType('VEC3')
        .setNormalized(true)
        .setArray(new Uint8Array([255, 0, 0, 0, 255, 0, 0, 0, 255, 255, 255, 255]))
        .setBuffer(buffer),
    );
    const m = await loadGlb(doc);
    close(m.uv0!, [0, 1, 1, 1, 1, 0, 0, 0]);
    close(m.colors!, [1, 0, 0, 1, 0, 1, 0, 1, 0, 0, 1, 1, 1, 1, 1, 1]);
  });

  it('returns the first perspective camera in world space', async () => {
    const doc = quadDoc();
    const cam = doc
      .createCamera()
      .setType('perspective')
      .setYFov(Math.PI / 3)
      .setZNear(0.1)
      .setAspectRatio(1);
    const s = Math.SQRT1_2;
    // Rotated 90° about +y: looks along −x.
    doc
      .getRoot()
      .listScenes()[0]
      .addChild(
        doc.createNode().setCamera(cam).setTranslation([5, 1, 0]).setRotation([0, s, 0, s]),
      );
    const m = await loadGlb(doc);
    expect(m.cameras.length).toBe(1);
    close(m.cameras[0].position, [5, 1, 0]);
    close(m.cameras[0].target, [4, 1, 0]);
    close(m.cameras[0].up, [0, 1, 0]);
    expect(m.cameras[0].fovY).toBeCloseTo(60, 10);
  });
});

describe('glTF files with external resources', () => {
  it('reads a .gltf with its .bin and .png beside it (URI-encoded names, a sub-folder)', async () => {
    const doc = quadDoc();
    doc.getRoot().listBuffers()[0].setURI('data files/quad.bin');
    const tex = doc
      .createTexture()
      .setImage(png(2, 2, () => [255, 0, 0, 255]))
      .setMimeType('image/png')
      .setURI('tex/red.png');
    const mat = doc.createMaterial().setBaseColorTexture(tex);
    doc.getRoot().listMeshes()[0].listPrimitives()[0].setMaterial(mat);
    const files = await toGltfFiles(doc, 'quad', 'models/');
    expect([...files.keys()].sort()).toEqual([
      'models/data files/quad.bin',
      'models/quad.gltf',
      'models/tex/red.png',
    ]);
    const m = await loadGltf(
      files.get('models/quad.gltf')!,
      'models/quad.gltf',
      await memoryOptions(files),
    );
    expect(m.indices.length).toBe(6);
    expect(m.textures.info.length).toBe(3);
    expect(m.textures.texels[0]).toBe(65535);
  });

  it('reads data: URI buffers', async () => {
    const doc = quadDoc();
    const files = await toGltfFiles(doc, 'quad');
    const json = JSON.parse(new TextDecoder().decode(files.get('quad.gltf')!));
    const bin = files.get(json.buffers[0].uri)!;
    json.buffers[0].uri =
      'data:application/octet-stream;base64,' + Buffer.from(bin).toString('base64');
    const m = await loadGltf(
      new TextEncoder().encode(JSON.stringify(json)),
      'quad.gltf',
      await memoryOptions(),
    );
    close(m.positions, [0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0]);
  });
});

describe('glTF materials and textures', () => {
  const hit = new HitAttributes();
  const sp = new ShadingParams();

  it('honours the factors of every supported extension', async () => {
    const doc = quadDoc();
    const ior = doc.createExtension(KHRMaterialsIOR).createIOR().setIOR(1.8);
    const tr = doc
      .createExtension(KHRMaterialsTransmission)
      .createTransmission()
      .setTransmissionFactor(0.7);
    const es = doc
      .createExtension(KHRMaterialsEmissiveStrength)
      .createEmissiveStrength()
      .setEmissiveStrength(5);
    const spec = doc
      .createExtension(KHRMaterialsSpecular)
      .createSpecular()
      .setSpecularFactor(0.5)
      .setSpecularColorFactor([1, 0.5, 0.25]);
    const mat = doc
      .createMaterial()
      .setBaseColorFactor([0.5, 0.25, 1, 1])
      .setMetallicFactor(0.3)
      .setRoughnessFactor(0.6)
      .setEmissiveFactor([1, 0.5, 0]);
    mat.setExtension('KHR_materials_ior', ior).setExtension('KHR_materials_transmission', tr);
    mat
      .setExtension('KHR_materials_emissive_strength', es)
      .setExtension('KHR_materials_specular', spec);
    doc.getRoot().listMeshes()[0].listPrimitives()[0].setMaterial(mat);
    const m = await loadGlb(doc);
    const t = m.materials;
    expect([t[GM_IOR], t[GM_TRANSMISSION], t[GM_SPECULAR]]).toEqual([1.8, 0.7, 0.5]);
    close(t.subarray(GM_EMISSIVE, GM_EMISSIVE + 3), [5, 2.5, 0]);
    fillGltfShading(t, m.textures, 0, hit, sp);
    close(
      [sp.baseR, sp.baseG, sp.baseB, sp.metallic, sp.alpha, sp.transmission, sp.ior],
      [0.5, 0.25, 1, 0.3, 0.36, 0.7, 1.8],
    );
    close(
      [sp.specular, sp.specR, sp.specG, sp.specB, sp.emR, sp.emG, sp.emB],
      [0.5, 1, 0.5, 0.25, 5, 2.5, 0],
    );
    expect(sp.opacity).toBe(1);
    expect(m.warnings).toEqual([]);
  });

  it('looks up base colour (sRGB → linear), metallic-roughness, emissive and transmission textures', async () => {
    const doc = quadDoc();
    // 2×1 textures: left texel and right texel; sampled at their centres.
    const mk = (a: number[], b: number[]) =>
      doc
        .createTexture()
        .setImage(png(2, 1, (x) => (x === 0 ? a : b)))
        .setMimeType('image/png');
    const base = mk([255, 128, 0, 255], [0, 0, 255, 64]);
    const mr = mk([0, 51, 204, 0], [0, 255, 0, 0]);
    const em = mk([128, 128, 128, 255], [0, 0, 0, 255]);
    const trt = mk([128, 0, 0, 255], [255, 0, 0, 255]);
    const tr = doc
      .createExtension(KHRMaterialsTransmission)
      .createTransmission()
      .setTransmissionFactor(1)
      .setTransmissionTexture(trt);
    const mat = doc
      .createMaterial()
      .setBaseColorTexture(base)
      .setMetallicRoughnessTexture(mr)
      .setEmissiveTexture(em)
      .setEmissiveFactor([1, 1, 1])
      .setAlphaMode('BLEND');
    mat.setExtension('KHR_materials_transmission', tr);
    doc.getRoot().listMeshes()[0].listPrimitives()[0].setMaterial(mat);
    const m = await loadGlb(doc);
    hit.u0 = 0.25;
    hit.v0 = 0.5;
    fillGltfShading(m.materials, m.textures, 0, hit, sp);
    close([sp.baseR, sp.baseG, sp.baseB], [1, srgbToLinear(128 / 255), 0], 1e-4);
    expect(sp.opacity).toBeCloseTo(1, 9);
    close([sp.alpha, sp.metallic], [(51 / 255) ** 2, 204 / 255], 1e-4);
    close(
      [sp.emR, sp.emG, sp.emB],
      [srgbToLinear(128 / 255), srgbToLinear(128 / 255), srgbToLinear(128 / 255)],
      1e-4,
    );
    expect(sp.transmission).toBeCloseTo(128 / 255, 4);
    hit.u0 = 0.75;
    fillGltfShading(m.materials, m.textures, 0, hit, sp);
    close([sp.baseR, sp.baseG, sp.baseB, sp.opacity], [0, 0, 1, 64 / 255], 1e-4);
    close([sp.alpha, sp.metallic, sp.transmission], [1, 0, 1], 1e-4);
  });

  it('alpha MASK is 0 or 1 about the cutoff; OPAQUE ignores alpha', async () => {
    const doc = quadDoc();
    const base = doc
      .createTexture()
      .setImage(png(2, 1, (x) => [255, 255, 255, x === 0 ? 100 : 200]))
      .setMimeType('image/png');
    const mask = doc
      .createMaterial()
      .setBaseColorTexture(base)
      .setAlphaMode('MASK')
      .setAlphaCutoff(0.5);
    const opaque = doc.createMaterial().setBaseColorTexture(base);
    doc.getRoot().listMeshes()[0].listPrimitives()[0].setMaterial(mask);
    doc.getRoot().listMeshes()[0].addPrimitive(quadPrimitive(doc).setMaterial(opaque));
    const m = await loadGlb(doc);
    hit.v0 = 0.5;
    for (const [u, mat, want] of [
      [0.25, 0, 0],
      [0.75, 0, 1],
      [0.25, 1, 1],
    ] as const) {
      hit.u0 = u;
      fillGltfShading(m.materials, m.textures, mat, hit, sp);
      expect(sp.opacity).toBe(want);
    }
  });

  it('KHR_texture_transform: offset, rotation, scale and texCoord override', async () => {
    const doc = quadDoc();
    const prim = doc.getRoot().listMeshes()[0].listPrimitives()[0];
    prim.setAttribute('TEXCOORD_1', prim.getAttribute('TEXCOORD_0'));
    // 4×4 texture whose red channel encodes the column, green the row.
    const tex = doc
      .createTexture()
      .setImage(png(4, 4, (x, y) => [x * 80, y * 80, 0, 255]))
      .setMimeType('image/png');
    const ext = doc.createExtension(KHRTextureTransform);
    const mat = doc.createMaterial().setMetallicRoughnessTexture(tex);
    // Rotation π/2: uv' = (v, −u)·scale + offset, on set 1.
    const t = ext
      .createTransform()
      .setOffset([0.25, 1])
      .setRotation(Math.PI / 2)
      .setScale([0.5, 0.5])
      .setTexCoord(1);
    mat.getMetallicRoughnessTextureInfo()!.setExtension('KHR_texture_transform', t);
    prim.setMaterial(mat);
    const m = await loadGlb(doc);
    hit.u0 = 99;
    hit.v0 = 99;
    // uv1 = (0.25, 0.25) → (0.5·0.25 + 0.25, −0.5·0.25 + 1) = (0.375, 0.875): texel (1, 3).
    hit.u1 = 0.25;
    hit.v1 = 0.25;
    fillGltfShading(m.materials, m.textures, 0, hit, sp);
    // roughness = G = row/… : texel row 3 → 240/255; metallic = B = 0.
    expect(Math.sqrt(sp.alpha)).toBeCloseTo(240 / 255, 3);
  });

  it('normal maps: tangent-space normal with scale; MikkTSpace tangents when the file has none', async () => {
    const doc = quadDoc();
    // Tilted toward +u: (0.5, 0, 0.866) encoded.
    const enc = (v: number) => Math.round((v * 0.5 + 0.5) * 255);
    const nt = doc
      .createTexture()
      .setImage(png(1, 1, () => [enc(0.5), enc(0), enc(0.866), 255]))
      .setMimeType('image/png');
    const mat = doc.createMaterial().setNormalTexture(nt).setNormalScale(1);
    doc.getRoot().listMeshes()[0].listPrimitives()[0].setMaterial(mat);
    const m = await loadGlb(doc);
    fillGltfShading(m.materials, m.textures, 0, hit, sp);
    close([sp.nx, sp.ny, sp.nz], [0.5, 0, 0.866], 0.01);
    // uv = (x, 1 − y) on a +z quad: T = +x, w = +1 (bitangent cross(N, T)·w = +y = up
    // in the image, glTF's convention). The corners MikkTSpace saw are welded back: 4 vertices.
    expect(m.tangents).not.toBeNull();
    expect(m.positions.length).toBe(12);
    for (let k = 0; k < 4; k++) close(m.tangents!.subarray(4 * k, 4 * k + 4), [1, 0, 0, 1], 1e-5);
    // With the file's own tangents, those are used (and kept welded).
    const doc2 = quadDoc();
    const p2 = doc2.getRoot().listMeshes()[0].listPrimitives()[0];
    p2.setAttribute(
      'TANGENT',
      doc2
        .createAccessor()
        .setType('VEC4')
        .setArray(new Float32Array(Array.from({ length: 4 }, () => [0, 1, 0, -1]).flat()))
        .setBuffer(doc2.getRoot().listBuffers()[0]),
    );
    const nt2 = doc2
      .createTexture()
      .setImage(png(1, 1, () => [128, 128, 255, 255]))
      .setMimeType('image/png');
    p2.setMaterial(doc2.createMaterial().setNormalTexture(nt2));
    doc2.getRoot().listNodes()[0].setScale([1, -1, 1]);
    const m2 = await loadGlb(doc2);
    expect(m2.positions.length).toBe(12);
    // Mirrored in y: the tangent (0, 1, 0) becomes (0, −1, 0) and its handedness flips.
    close(m2.tangents!.subarray(0, 4), [0, -1, 0, 1], 1e-6);
  });

  it('warns for extensions it ignores and for images it cannot decode', async () => {
    const doc = quadDoc();
    // Metadata pathwise has no use for (KHR_xmp_json_ld) stands for any ignored extension.
    const xmp = doc
      .createExtension(KHRXMP)
      .createPacket()
      .setContext({ dc: 'http://purl.org/dc/elements/1.1/' });
    const tex = doc
      .createTexture()
      .setImage(Uint8Array.of(1, 2, 3, 4))
      .setMimeType('image/webp');
    const mat = doc.createMaterial().setExtension('KHR_xmp_json_ld', xmp).setBaseColorTexture(tex);
    doc.getRoot().listMeshes()[0].listPrimitives()[0].setMaterial(mat);
    // A skin and a morph target: rendered in the rest pose.
    const prim = doc.getRoot().listMeshes()[0].listPrimitives()[0];
    doc.createSkin().addJoint(doc.getRoot().listNodes()[0]);
    prim.addTarget(
      doc.createPrimitiveTarget().setAttribute('POSITION', prim.getAttribute('POSITION')),
    );
    const m = await loadGlb(doc);
    expect(m.warnings).toEqual([
      'extension "KHR_xmp_json_ld" is not supported; its content is ignored',
      '1 skin(s) ignored: the model is rendered in its rest pose',
      'morph targets ignored: the model is rendered in its rest pose',
      'images[0] (materials[0].baseColorTexture): image/webp needs a WebP decoder, which this platform lacks; the texture is ignored',
    ]);
    expect(m.textures.info.length).toBe(0);
  });
});

describe('glTF triangles grouped by material', () => {
  it('one group per material with compact vertices, shared boundary vertices duplicated', async () => {
    const doc = quadDoc();
    const mesh = doc.getRoot().listMeshes()[0];
    const a = doc.createMaterial().setBaseColorFactor([1, 0, 0, 1]);
    const b = doc.createMaterial().setBaseColorFactor([0, 1, 0, 1]);
    mesh.listPrimitives()[0].setMaterial(a);
    // A second quad beside the first, and a third with material a again.
    mesh.addPrimitive(quadPrimitive(doc).setMaterial(b));
    doc
      .getRoot()
      .listScenes()[0]
      .addChild(
        doc
          .createNode()
          .setMesh(doc.createMesh().addPrimitive(quadPrimitive(doc).setMaterial(a)))
          .setTranslation([5, 0, 0]),
      );
    const m = await loadGlb(doc);
    const groups = groupByMaterial(m);
    expect(groups.map((g) => g.material)).toEqual([0, 1]);
    expect(groups.map((g) => g.indices.length / 3)).toEqual([4, 2]);
    expect(groups.map((g) => g.positions.length / 3)).toEqual([8, 4]);
    // Every group triangle is a model triangle of that material, in file order.
    const g0 = groups[0];
    const tri = (pos: Float64Array, idx: Uint32Array, t: number) =>
      [0, 1, 2].flatMap((c) =>
        Array.from(pos.subarray(3 * idx[3 * t + c], 3 * idx[3 * t + c] + 3)),
      );
    const modelTris = [0, 1, 4, 5].map((t) => tri(m.positions, m.indices, t));
    expect([0, 1, 2, 3].map((t) => tri(g0.positions, g0.indices, t))).toEqual(modelTris);
    expect(g0.uv0!.length).toBe(16);
    expect(g0.normals!.length).toBe(24);
    expect(g0.tangents).toBeNull();
  });
});
