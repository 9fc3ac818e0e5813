/**
 * A corpus of malformed glTF files, each made from a valid one by one
 * mutation: every one is rejected with one clear, one-line GltfError that
 * names the place in the file — never a RangeError from inside a library,
 * a hang, an unbounded allocation or a silent half-load.
 */
import { Document } from '@gltf-transform/core';
import { describe, expect, it } from 'vitest';
import { GltfError } from '../../../src/core/gltf/errors.ts';
import { loadGltf } from '../../../src/core/gltf/load.ts';
import { memoryOptions, png, quadPrimitive, toGlb, toGltfFiles } from '../../helpers/gltf.ts';

type Json = Record<string, any>; // eslint-disable-line @typescript-eslint/no-explicit-any

function quadDoc(): Document {
  const doc = new Document();
  doc.createBuffer();
  const tex = doc
    .createTexture()
    .setImage(png(2, 2, () => [200, 100, 50, 255]))
    .setMimeType('image/png');
  const mesh = doc
    .createMesh()
    .addPrimitive(quadPrimitive(doc).setMaterial(doc.createMaterial().setBaseColorTexture(tex)));
  const scene = doc.createScene().addChild(doc.createNode().setMesh(mesh));
  doc.getRoot().setDefaultScene(scene);
  return doc;
}

/** A GLB from JSON and a BIN chunk (both padded to 4 bytes). */
function makeGlb(json: Json, bin: Uint8Array | null): Uint8Array {
  const text = new TextEncoder().encode(JSON.stringify(json));
  const jl = Math.ceil(text.length / 4) * 4;
  const bl = bin === null ? 0 : Math.ceil(bin.length / 4) * 4;
  const out = new Uint8Array(12 + 8 + jl + (bin === null ? 0 : 8 + bl));
  const v = new DataView(out.buffer);
  v.setUint32(0, 0x46546c67, true);
  v.setUint32(4, 2, true);
  v.setUint32(8, out.length, true);
  v.setUint32(12, jl, true);
  v.setUint32(16, 0x4e4f534a, true);
  out.set(text, 20);
  out.fill(0x20, 20 + text.length, 20 + jl);
  if (bin !== null) {
    v.setUint32(20 + jl, bl, true);
    v.setUint32(24 + jl, 0x004e4942, true);
    out.set(bin, 28 + jl);
  }
  return out;
}

async function parts(): Promise<{ json: Json; bin: Uint8Array }> {
  const glb = await toGlb(quadDoc());
  const v = new DataView(glb.buffer, glb.byteOffset);
  const jl = v.getUint32(12, true);
  const json = JSON.parse(new TextDecoder().decode(glb.subarray(20, 20 + jl)));
  const bl = v.getUint32(20 + jl, true);
  return { json, bin: glb.slice(28 + jl, 28 + jl + bl) };
}

async function expectError(
  bytes: Uint8Array,
  pattern: RegExp,
  files?: Map<string, Uint8Array>,
): Promise<void> {
  let error: unknown = null;
  try {
    await loadGltf(bytes, 'bad.glb', await memoryOptions(files));
  } catch (e) {
    error = e;
  }
  expect(error).toBeInstanceOf(GltfError);
  const message = (error as Error).message;
  expect(message).toMatch(pattern);
  expect(message).not.toMatch(/[\n\r]/);
}

/** Applies `mutate` to the JSON of the valid quad and loads the result. */
async function mutated(
  mutate: (json: Json, bin: Uint8Array) => Uint8Array | void,
  pattern: RegExp,
): Promise<void> {
  const { json, bin } = await parts();
  const b = mutate(json, bin) ?? bin;
  await expectError(makeGlb(json, b), pattern);
}

describe('malformed GLB containers', () => {
  it('the valid base file loads', async () => {
    const { json, bin } = await parts();
    const m = await loadGltf(makeGlb(json, bin), 'ok.glb', await memoryOptions());
    expect(m.indices.length).toBe(6);
  });

  it('truncated file', async () => {
    const glb = await toGlb(quadDoc());
    await expectError(
      glb.subarray(0, 8),
      /^glTF: GLB header: file is 8 bytes, the header alone needs 12$/,
    );
    await expectError(
      glb.subarray(0, glb.length - 10),
      /^glTF: GLB header: says \d+ bytes, but the file has \d+ \(truncated\?\)$/,
    );
  });

  it('wrong version, JSON chunk past the end, BIN chunk past the end', async () => {
    const glb = await toGlb(quadDoc());
    const v1 = glb.slice();
    new DataView(v1.buffer).setUint32(4, 1, true);
    await expectError(v1, /^glTF: GLB header: version 1, only glTF 2\.0/);
    const j = glb.slice();
    new DataView(j.buffer).setUint32(12, glb.length, true);
    await expectError(j, /^glTF: GLB chunk 0: JSON chunk of \d+ bytes runs past the end/);
    const b = glb.slice();
    const jl = new DataView(b.buffer).getUint32(12, true);
    new DataView(b.buffer).setUint32(20 + jl, glb.length, true);
    await expectError(b, /^glTF: GLB chunk 1: chunk of \d+ bytes runs past the end/);
  });

  it('JSON that is not JSON, or not UTF-8', async () => {
    const text = new TextEncoder().encode('{"asset": {"version": "2.0"},,}');
    await expectError(makeGlbRaw(text), /^glTF: JSON: line 1, column \d+: /);
    await expectError(
      makeGlbRaw(Uint8Array.of(0x7b, 0xff, 0x7d, 0x20)),
      /^glTF: JSON: not valid UTF-8 at byte 1/,
    );
    await expectError(
      new TextEncoder().encode('[1, 2]'),
      /^glTF: document: the glTF JSON must be an object$/,
    );
    await expectError(
      new TextEncoder().encode('{"asset": {"version": "1.0"}}'),
      /^glTF: asset\.version: glTF "1\.0" is not supported/,
    );
  });
});

function makeGlbRaw(jsonBytes: Uint8Array): Uint8Array {
  const jl = Math.ceil(jsonBytes.length / 4) * 4;
  const out = new Uint8Array(20 + jl).fill(0x20);
  const v = new DataView(out.buffer);
  v.setUint32(0, 0x46546c67, true);
  v.setUint32(4, 2, true);
  v.setUint32(8, out.length, true);
  v.setUint32(12, jl, true);
  v.setUint32(16, 0x4e4f534a, true);
  out.set(jsonBytes, 20);
  return out;
}

describe('malformed buffers and accessors', () => {
  it('a buffer view past the end of its buffer', () =>
    mutated((j) => {
      j.bufferViews[0].byteLength += 1000;
    }, /^glTF: bufferViews\[0\]: ends at byte \d+, past the end of buffers\[0\]/));

  it('a buffer declaring more bytes than the file has', () =>
    mutated((j) => {
      j.buffers[0].byteLength += 64;
      j.bufferViews[0].byteLength += 64;
    }, /^glTF: buffers\[0\]: declares \d+ bytes, but only \d+ could be read$/));

  it('an accessor with a lying count (reads past its view)', () =>
    mutated((j) => {
      j.accessors[0].count = 1_000_000;
    }, /^glTF: accessors\[0\]: needs \d+ bytes of bufferViews\[\d+\], which has \d+ \(count 1000000\)$/));

  it('bad accessor: component type, type, misalignment', async () => {
    await mutated((j) => {
      j.accessors[1].componentType = 1234;
    }, /^glTF: accessors\[1\]\.componentType: 1234 is not a glTF component type$/);
    await mutated((j) => {
      j.accessors[1].type = 'VEC5';
    }, /^glTF: accessors\[1\]\.type: "VEC5" is not a glTF accessor type$/);
    await mutated((j) => {
      j.accessors[0].byteOffset = 2;
    }, /^glTF: accessors\[0\]: starts at byte \d+ of its buffer, not a multiple of its component size 4$/);
    await mutated((j) => {
      j.meshes[0].primitives[0].attributes.POSITION = 99;
    }, /^glTF: meshes\[0\]\.primitives\[0\]\.attributes\.POSITION: refers to accessors\[99\], but the file has \d+$/);
    await mutated((j) => {
      j.meshes[0].primitives[0].indices = j.meshes[0].primitives[0].attributes.POSITION;
    }, /^glTF: meshes\[0\]\.primitives\[0\]\.indices: accessors\[\d+\] must be SCALAR of an unsigned integer type$/);
  });

  it('an index out of range', () =>
    mutated((j, bin) => {
      const acc = j.accessors[j.meshes[0].primitives[0].indices];
      const view = j.bufferViews[acc.bufferView];
      new DataView(bin.buffer).setUint16(
        (view.byteOffset ?? 0) + (acc.byteOffset ?? 0) + 4,
        999,
        true,
      );
    }, /^glTF: meshes\[0\]\.primitives\[0\]\.indices: index 999 at position 2 is out of range \(POSITION has 4 vertices\)$/));

  it('NaN and infinite positions', () =>
    mutated((j, bin) => {
      const acc = j.accessors[j.meshes[0].primitives[0].attributes.POSITION];
      const view = j.bufferViews[acc.bufferView];
      const stride = view.byteStride ?? 12;
      new DataView(bin.buffer).setFloat32(
        (view.byteOffset ?? 0) + (acc.byteOffset ?? 0) + 2 * stride + 4,
        NaN,
        true,
      );
    }, /^glTF: meshes\[0\]\.primitives\[0\]\.attributes\.POSITION: vertex 2 has a non-finite value$/));

  it('an instance bomb: more mesh instances than the limit is refused before allocating', () =>
    mutated((j) => {
      // A mesh drawn by a node with EXT_mesh_gpu_instancing rows, 1,000,001 of them
      // (instances share the mesh, so only their number is bounded: docs/gltf.md, Instancing).
      const view = j.accessors[j.meshes[0].primitives[0].attributes.POSITION].bufferView;
      j.accessors.push({ bufferView: view, componentType: 5126, count: 1_000_001, type: 'VEC3' });
      j.nodes = [
        {
          mesh: 0,
          extensions: {
            EXT_mesh_gpu_instancing: { attributes: { TRANSLATION: j.accessors.length - 1 } },
          },
        },
      ];
      j.scenes = [{ nodes: [0] }];
    }, /^glTF: nodes\[0\]\.extensions\.EXT_mesh_gpu_instancing\.attributes\.TRANSLATION: declares 1,000,001 instances, more than the limit of 1,000,000$/));

  it('buffers adding up to more than 1 GiB are refused before any is read', () =>
    mutated((j) => {
      j.buffers.push({ uri: 'a.bin', byteLength: 2 ** 29 }, { uri: 'b.bin', byteLength: 2 ** 29 });
    }, /^glTF: buffers\[2\]: the buffers add up to more than 1073741824 bytes, the limit$/));

  it('too many objects of one kind', () =>
    mutated((j) => {
      j.nodes = Array.from({ length: 1_000_001 }, () => ({}));
    }, /^glTF: nodes: 1000001 entries, over the limit of 1000000$/));

  it('a huge index count is refused by the triangle limit before anything is read', () =>
    mutated((j) => {
      const acc = j.accessors[j.meshes[0].primitives[0].indices];
      acc.count = 60_000_000;
    }, /^glTF: scene: uses meshes of more than 10,000,000 distinct triangles, the limit$/));
});

describe('malformed structure', () => {
  it('node cycles and shared children', async () => {
    await mutated((j) => {
      j.nodes = [{ children: [1] }, { children: [2] }, { children: [1], mesh: 0 }];
      j.scenes = [{ nodes: [0] }];
    }, /^glTF: nodes\[1\]: is a child of both nodes\[0\] and nodes\[2\]; glTF nodes form trees$/);
    await mutated((j) => {
      j.nodes = [{ mesh: 0 }, { children: [2] }, { children: [1] }];
      j.scenes = [{ nodes: [0] }];
    }, /^glTF: nodes\[\d\]: is its own ancestor \(the node hierarchy has a cycle\)$/);
    await mutated((j) => {
      j.nodes = [{ children: [0] }];
    }, /^glTF: nodes\[0\]\.children: contains the node itself$/);
  });

  it('non-finite transforms and dangling references', async () => {
    await mutated((j) => {
      j.nodes[0].translation = [0, 1e400, 0];
    }, /^glTF: nodes\[0\]\.translation: must be 3 finite numbers$/);
    await mutated((j) => {
      j.nodes[0].rotation = [0, 0, 0, 0];
    }, /^glTF: nodes\[0\]\.rotation: is not a unit quaternion \(length 0\); glTF requires one$/);
    await mutated((j) => {
      j.nodes[0].mesh = 5;
    }, /^glTF: nodes\[0\]\.mesh: refers to meshes\[5\], but the file has 1$/);
    await mutated((j) => {
      j.materials[0].pbrMetallicRoughness.baseColorTexture.index = 3;
    }, /^glTF: materials\[0\]\.pbrMetallicRoughness\.baseColorTexture\.index: refers to textures\[3\], but the file has 1$/);
  });

  it('material numbers outside their glTF ranges', async () => {
    await mutated((j) => {
      j.materials[0].pbrMetallicRoughness.metallicFactor = 2;
    }, /^glTF: materials\[0\]\.pbrMetallicRoughness\.metallicFactor: must be a number in \[0, 1\], got 2$/);
    await mutated((j) => {
      j.materials[0].extensions = { KHR_materials_ior: { ior: 0.5 } };
    }, /^glTF: materials\[0\]\.extensions\.KHR_materials_ior\.ior: must be 0 or at least 1, got 0\.5$/);
    await mutated((j) => {
      j.materials[0].extensions = { KHR_materials_emissive_strength: { emissiveStrength: 1e300 } };
    }, /^glTF: materials\[0\]\.extensions\.KHR_materials_emissive_strength\.emissiveStrength: must be a number in \[0, 1000000000000\]/);
    await mutated((j) => {
      j.materials[0].extensions = { KHR_materials_anisotropy: { anisotropyStrength: 1.5 } };
    }, /^glTF: materials\[0\]\.extensions\.KHR_materials_anisotropy\.anisotropyStrength: must be a number in \[0, 1\], got 1\.5$/);
    await mutated((j) => {
      j.materials[0].extensions = { KHR_materials_iridescence: { iridescenceIor: 0.5 } };
    }, /^glTF: materials\[0\]\.extensions\.KHR_materials_iridescence\.iridescenceIor: must be a number in \[1, 1000000\], got 0\.5$/);
    await mutated((j) => {
      j.materials[0].pbrMetallicRoughness.baseColorTexture.extensions = {
        KHR_texture_transform: { offset: [0, 'x'] },
      };
    }, /^glTF: materials\[0\]\.pbrMetallicRoughness\.baseColorTexture\.extensions\.KHR_texture_transform\.offset: must be 2 numbers/);
  });

  it('a required extension pathwise lacks', () =>
    mutated((j) => {
      j.extensionsUsed = ['KHR_draco_mesh_compression'];
      j.extensionsRequired = ['KHR_draco_mesh_compression'];
    }, /^glTF: extensionsRequired: the file requires "KHR_draco_mesh_compression", which pathwise does not support$/));

  it('a corrupt texture, and one whose header claims more than the memory limit', async () => {
    await mutated((j, bin) => {
      const view = j.bufferViews[j.images[0].bufferView];
      bin.fill(0, view.byteOffset + 40, view.byteOffset + view.byteLength);
    }, /^glTF: images\[0\] \(materials\[0\]\.baseColorTexture\): cannot decode PNG: /);
    await mutated((j, bin) => {
      const view = j.bufferViews[j.images[0].bufferView];
      new DataView(bin.buffer).setUint32(view.byteOffset + 16, 16000);
      new DataView(bin.buffer).setUint32(view.byteOffset + 20, 16000);
    }, /^glTF: images\[0\] \(materials\[0\]\.baseColorTexture\): decoded textures would need 1\.91 GiB, over the texture memory limit of 1\.00 GiB$/);
  });
});

describe('malformed external resources', () => {
  it('a missing file, a URL, an escaping absolute path', async () => {
    const files = await toGltfFiles(quadDoc(), 'quad');
    const gltf = files.get('quad.gltf')!;
    const json = JSON.parse(new TextDecoder().decode(gltf));
    const bin = json.buffers[0].uri;
    files.delete(bin);
    await expectError(
      gltf,
      /^glTF: buffers\[0\]\.uri: cannot read "quad\.bin": no such file$/,
      files,
    );
    for (const uri of ['https://example.com/quad.bin', '/etc/quad.bin', 'file:///quad.bin']) {
      json.buffers[0].uri = uri;
      await expectError(
        new TextEncoder().encode(JSON.stringify(json)),
        /^glTF: buffers\[0\]\.uri: ".*" is not a relative path; only files beside the model can be read$/,
        files,
      );
    }
    json.buffers[0].uri = 'data:application/octet-stream;base64,@@@@';
    await expectError(
      new TextEncoder().encode(JSON.stringify(json)),
      /^glTF: buffers\[0\]\.uri: data URI has a character that is not base64 at 0$/,
      files,
    );
  });
});
