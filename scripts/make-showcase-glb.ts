/**
 * Writes docs/showcase.glb, the glTF model of the README's second picture: three UV
 * spheres on a floor — a checker-textured plastic (baseColorTexture, a normal map whose
 * tangents MikkTSpace makes), gold (metallic 1), clear solid glass (KHR_materials_transmission
 * + KHR_materials_ior, and KHR_materials_volume so that it is a solid, not glTF's default
 * thin wall) — and an emissive bar (KHR_materials_emissive_strength), placed
 * by TRS nodes. Made with glTF-Transform, textures as PNGs by fast-png.
 * Run: node scripts/run-ts.mjs scripts/make-showcase-glb.ts
 * Then: npx pathwise render docs/showcase.glb --width 640 --height 400 --spp 256 --out docs/showcase.png
 */
import { writeFileSync } from 'node:fs';
import { dirname, join, resolve } from 'node:path';
import { Document, type Material } from '@gltf-transform/core';
import {
  KHRMaterialsEmissiveStrength,
  KHRMaterialsIOR,
  KHRMaterialsTransmission,
  KHRMaterialsVolume,
} from '@gltf-transform/extensions';
import { encode as encodePng } from 'fast-png';
import { PreloadedIO } from '../src/core/gltf/io.ts';

const doc = new Document();
const buffer = doc.createBuffer();

function png(w: number, h: number, f: (x: number, y: number) => number[]): Uint8Array {
  const data = new Uint8Array(w * h * 4);
  for (let y = 0; y < h; y++) for (let x = 0; x < w; x++) data.set(f(x, y), 4 * (y * w + x));
  return encodePng({ width: w, height: h, data, channels: 4, depth: 8 });
}

function accessor(type: 'VEC2' | 'VEC3' | 'SCALAR', array: Float32Array | Uint32Array) {
  return doc.createAccessor().setType(type).setArray(array).setBuffer(buffer);
}

/** A UV sphere of radius 1: positions, normals, texture coordinates, indices. */
function sphere(material: Material, rings = 32, segments = 64) {
  const pos: number[] = [];
  const uv: number[] = [];
  const idx: number[] = [];
  for (let j = 0; j <= rings; j++) {
    const theta = (j / rings) * Math.PI;
    for (let i = 0; i <= segments; i++) {
      const phi = (i / segments) * 2 * Math.PI;
      pos.push(Math.sin(theta) * Math.cos(phi), Math.cos(theta), -Math.sin(theta) * Math.sin(phi));
      uv.push(i / segments, j / rings);
    }
  }
  for (let j = 0; j < rings; j++) {
    for (let i = 0; i < segments; i++) {
      const a = j * (segments + 1) + i;
      const b = a + segments + 1;
      // The triangles that would have two corners on a pole are left out (zero area).
      if (j > 0) idx.push(a, b, a + 1);
      if (j < rings - 1) idx.push(a + 1, b, b + 1);
    }
  }
  return doc
    .createPrimitive()
    .setMaterial(material)
    .setAttribute('POSITION', accessor('VEC3', new Float32Array(pos)))
    .setAttribute('NORMAL', accessor('VEC3', new Float32Array(pos)))
    .setAttribute('TEXCOORD_0', accessor('VEC2', new Float32Array(uv)))
    .setIndices(accessor('SCALAR', new Uint32Array(idx)));
}

/** A box from −1 to 1 (flat-shaded: no normals). */
function box(material: Material) {
  const pos: number[] = [];
  for (let axis = 0; axis < 3; axis++) {
    for (const s of [-1, 1]) {
      const u = (axis + 1) % 3;
      const v = (axis + 2) % 3;
      const corner = (a: number, b: number) => {
        const p = [0, 0, 0];
        p[axis] = s;
        p[u] = a;
        p[v] = b;
        return p;
      };
      // Wound so that the normal points out (s along the axis).
      const quad =
        s > 0
          ? [
              corner(-1, -1),
              corner(1, -1),
              corner(1, 1),
              corner(-1, -1),
              corner(1, 1),
              corner(-1, 1),
            ]
          : [
              corner(-1, -1),
              corner(1, 1),
              corner(1, -1),
              corner(-1, -1),
              corner(-1, 1),
              corner(1, 1),
            ];
      pos.push(...quad.flat());
    }
  }
  return doc
    .createPrimitive()
    .setMaterial(material)
    .setAttribute('POSITION', accessor('VEC3', new Float32Array(pos)));
}

const checker = doc
  .createTexture('checker')
  .setMimeType('image/png')
  .setImage(
    png(64, 64, (x, y) => (((x >> 3) + (y >> 3)) % 2 ? [230, 90, 40, 255] : [240, 236, 226, 255])),
  );
// Bumps: a normal map of ridges across u.
const ridges = doc
  .createTexture('ridges')
  .setMimeType('image/png')
  .setImage(
    png(64, 8, (x) => {
      const s = Math.sin((x / 64) * 2 * Math.PI * 8);
      return [Math.round(128 + 90 * s), 128, Math.round(255 * Math.sqrt(1 - 0.5 * s * s)), 255];
    }),
  );
const plastic = doc
  .createMaterial('checker plastic')
  .setBaseColorTexture(checker)
  .setNormalTexture(ridges)
  .setNormalScale(0.6)
  .setMetallicFactor(0)
  .setRoughnessFactor(0.35);
const gold = doc
  .createMaterial('gold')
  .setBaseColorFactor([1, 0.78, 0.34, 1])
  .setMetallicFactor(1)
  .setRoughnessFactor(0.3);
const glass = doc
  .createMaterial('glass')
  .setBaseColorFactor([0.95, 0.98, 1, 1])
  .setMetallicFactor(0)
  .setRoughnessFactor(0)
  .setExtension(
    'KHR_materials_transmission',
    doc.createExtension(KHRMaterialsTransmission).createTransmission().setTransmissionFactor(1),
  )
  .setExtension('KHR_materials_ior', doc.createExtension(KHRMaterialsIOR).createIOR().setIOR(1.5))
  .setExtension(
    'KHR_materials_volume',
    doc.createExtension(KHRMaterialsVolume).createVolume().setThicknessFactor(1),
  );
const floor = doc
  .createMaterial('floor')
  .setBaseColorFactor([0.55, 0.56, 0.6, 1])
  .setMetallicFactor(0)
  .setRoughnessFactor(0.6);
const lamp = doc
  .createMaterial('lamp')
  .setBaseColorFactor([0.1, 0.1, 0.1, 1])
  .setEmissiveFactor([1, 0.75, 0.45])
  .setExtension(
    'KHR_materials_emissive_strength',
    doc
      .createExtension(KHRMaterialsEmissiveStrength)
      .createEmissiveStrength()
      .setEmissiveStrength(6),
  );

const scene = doc.createScene('showcase');
const place = (
  prim: ReturnType<typeof sphere>,
  t: [number, number, number],
  s: [number, number, number],
  r: [number, number, number, number] = [0, 0, 0, 1],
) =>
  scene.addChild(
    doc
      .createNode()
      .setMesh(doc.createMesh().addPrimitive(prim))
      .setTranslation(t)
      .setScale(s)
      .setRotation(r),
  );
place(sphere(plastic), [-2.2, 1, 0], [1, 1, 1], [0, Math.sin(0.4), 0, Math.cos(0.4)]);
place(sphere(gold), [0, 1, -0.4], [1, 1, 1]);
place(sphere(glass), [2.2, 1, 0], [1, 1, 1]);
place(box(floor), [0, -0.05, 0], [3.6, 0.05, 1.8]);
place(box(lamp), [0, 2.4, -1.6], [2.4, 0.06, 0.06]);
doc.getRoot().setDefaultScene(scene);

const glb = await new PreloadedIO()
  .registerExtensions([
    KHRMaterialsEmissiveStrength,
    KHRMaterialsIOR,
    KHRMaterialsTransmission,
    KHRMaterialsVolume,
  ])
  .writeBinary(doc);
// run-ts.mjs bundles this file elsewhere; argv[1] is where it really is.
const out = join(resolve(dirname(process.argv[1]), '..'), 'docs/showcase.glb');
writeFileSync(out, glb);
console.log(`${out}: ${glb.length} bytes`);
