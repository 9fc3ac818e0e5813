/**
 * glTF test files made in memory with glTF-Transform (textures as small PNGs
 * by fast-png), and the loader's options over an in-memory file map.
 */
import { Document, type JSONDocument } from '@gltf-transform/core';
import { ALL_EXTENSIONS } from '@gltf-transform/extensions';
import { encode as encodePng } from 'fast-png';
import { nodeTangentGenerator } from '../../src/cli/gltf-node.ts';
import { PreloadedIO } from '../../src/core/gltf/io.ts';
import { type GltfLoadOptions, type GltfModel, loadGltf } from '../../src/core/gltf/load.ts';
import { decodeImageJs } from '../../src/core/texture/decode-js.ts';
import { resolveSceneFiles, validateScene, type Scene } from '../../src/core/index.ts';

export function io(): PreloadedIO {
  return new PreloadedIO().registerExtensions(ALL_EXTENSIONS);
}

export async function toGlb(doc: Document): Promise<Uint8Array> {
  return io().writeBinary(doc);
}

/** The .gltf JSON and its resources (buffers, images) as files, under `dir`. */
export async function toGltfFiles(
  doc: Document,
  name: string,
  dir = '',
): Promise<Map<string, Uint8Array>> {
  const { json, resources } = (await io().writeJSON(doc, { basename: name })) as JSONDocument;
  const files = new Map<string, Uint8Array>();
  files.set(dir + name + '.gltf', new TextEncoder().encode(JSON.stringify(json)));
  for (const [uri, bytes] of Object.entries(resources))
    files.set(dir + decodeURIComponent(uri), bytes);
  return files;
}

export async function memoryOptions(
  files: Map<string, Uint8Array> = new Map(),
): Promise<GltfLoadOptions> {
  return {
    reader: {
      async read(path: string, maxBytes: number): Promise<Uint8Array> {
        const f = files.get(path);
        if (f === undefined) throw new Error('no such file');
        if (f.length > maxBytes) throw new Error(`over ${maxBytes} bytes`);
        return f;
      },
    },
    decodeImage: decodeImageJs,
    generateTangents: await nodeTangentGenerator(),
  };
}

export async function loadGlb(
  doc: Document,
  options?: Partial<GltfLoadOptions>,
): Promise<GltfModel> {
  return loadGltf(await toGlb(doc), 'model.glb', { ...(await memoryOptions()), ...options });
}

/** A w×h RGBA PNG whose texel (x, y) is f(x, y). */
export function png(w: number, h: number, f: (x: number, y: number) => number[]): Uint8Array {
  const data = new Uint8Array(w * h * 4);
  for (let y = 0; y < h; y++) for (let x = 0; x < w; x++) data.set(f(x, y), 4 * (y * w + x));
  return encodePng({ width: w, height: h, data, channels: 4, depth: 8 });
}

/**
 * A unit quad in the xy plane facing +z: corners (0,0), (1,0), (1,1), (0,1),
 * uv = (x, 1 − y) (the image upright), two triangles, indexed.
 */
export function quadPrimitive(
  doc: Document,
  opts: { normals?: boolean; uv?: boolean; indexed?: boolean } = {},
) {
  const buffer = doc.getRoot().listBuffers()[0] ?? doc.createBuffer();
  const corners = [0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0];
  const order = [0, 1, 2, 0, 2, 3];
  const indexed = opts.indexed ?? true;
  const pos = indexed ? corners : order.flatMap((i) => corners.slice(3 * i, 3 * i + 3));
  const prim = doc.createPrimitive();
  prim.setAttribute(
    'POSITION',
    doc.createAccessor().setType('VEC3').setArray(new Float32Array(pos)).setBuffer(buffer),
  );
  const n = pos.length / 3;
  if (opts.normals ?? true) {
    prim.setAttribute(
      'NORMAL',
      doc
        .createAccessor()
        .setType('VEC3')
        .setArray(new Float32Array(Array.from({ length: n }, () => [0, 0, 1]).flat()))
        .setBuffer(buffer),
    );
  }
  if (opts.uv ?? true) {
    const uv: number[] = [];
    for (let i = 0; i < n; i++) uv.push(pos[3 * i], 1 - pos[3 * i + 1]);
    prim.setAttribute(
      'TEXCOORD_0',
      doc.createAccessor().setType('VEC2').setArray(new Float32Array(uv)).setBuffer(buffer),
    );
  }
  if (indexed)
    prim.setIndices(
      doc.createAccessor().setType('SCALAR').setArray(new Uint16Array(order)).setBuffer(buffer),
    );
  return prim;
}

/** A triangle primitive from flat arrays (positions rounded to float32, as glTF stores them). */
export function meshPrimitive(
  doc: Document,
  positions: ArrayLike<number>,
  indices: ArrayLike<number>,
  extra: { normals?: ArrayLike<number>; uv?: ArrayLike<number> } = {},
) {
  const buffer = doc.getRoot().listBuffers()[0] ?? doc.createBuffer();
  const prim = doc
    .createPrimitive()
    .setAttribute(
      'POSITION',
      doc.createAccessor().setType('VEC3').setArray(Float32Array.from(positions)).setBuffer(buffer),
    )
    .setIndices(
      doc.createAccessor().setType('SCALAR').setArray(Uint32Array.from(indices)).setBuffer(buffer),
    );
  if (extra.normals) {
    prim.setAttribute(
      'NORMAL',
      doc
        .createAccessor()
        .setType('VEC3')
        .setArray(Float32Array.from(extra.normals))
        .setBuffer(buffer),
    );
  }
  if (extra.uv) {
    prim.setAttribute(
      'TEXCOORD_0',
      doc.createAccessor().setType('VEC2').setArray(Float32Array.from(extra.uv)).setBuffer(buffer),
    );
  }
  return prim;
}

/** A document whose default scene holds one node per primitive given. */
export function docWith(
  doc: Document,
  ...prims: ReturnType<Document['createPrimitive']>[]
): Document {
  const scene = doc.createScene();
  for (const p of prims) scene.addChild(doc.createNode().setMesh(doc.createMesh().addPrimitive(p)));
  doc.getRoot().setDefaultScene(scene);
  return doc;
}

/**
 * Adds to the default scene a floor of `material`: the unit quad (quadPrimitive)
 * scaled to 3 × 2 and laid flat at (−1, 0, 1) by a TRS node, under docWith's quad.
 */
export function addFloor(doc: Document, material: ReturnType<Document['createMaterial']>): void {
  const node = doc
    .createNode()
    .setMesh(doc.createMesh().addPrimitive(quadPrimitive(doc).setMaterial(material)))
    .setTranslation([-1, 0, 1])
    .setRotation([-Math.SQRT1_2, 0, 0, Math.SQRT1_2])
    .setScale([3, 2, 1]);
  doc.getRoot().listScenes()[0].addChild(node);
}

/**
 * A scene (pathwise-scene/1 JSON) whose files (`name` → bytes) are in memory, read
 * and resolved like the command line does (pure-JS images, MikkTSpace).
 */
export async function sceneWithFiles(
  json: unknown,
  files: Map<string, Uint8Array>,
): Promise<Scene> {
  const options = await memoryOptions(files);
  return resolveSceneFiles(validateScene(json), options.reader, {
    generateTangents: options.generateTangents,
  });
}
