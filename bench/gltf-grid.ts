/**
 * A GLB-ready grid of about `triangles` triangles with normals and texture coordinates
 * (and, when `textured`, a 2048² base-colour PNG and a normal map whose tangents
 * MikkTSpace must generate): the large model of the glTF benchmarks.
 */
import { Document } from '@gltf-transform/core';
import { encode as encodePng } from 'fast-png';

export function gridDocument(triangles: number, textured: boolean): Document {
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
