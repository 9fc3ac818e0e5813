/**
 * The glTF check of what is read (src/core/gltf/validate*.ts), case by case from
 * issue 27: each mutation of a valid quad is refused with one GltfError line that
 * names the JSON path, the problem and the value, or (for what pathwise honestly
 * ignores) loads with a warning that says so.
 */
import { describe, expect, it } from 'vitest';
import { GltfError } from '../../../src/core/gltf/errors.ts';
import { loadGltf } from '../../../src/core/gltf/load.ts';
import { imageCount } from '../../../src/core/texture/texture-store.ts';
import type { GltfModel } from '../../../src/core/scene/format/gltf-model.ts';
import { quadGlb } from '../../fuzz/gltf-samples.ts';
import { memoryOptions } from '../../helpers/gltf.ts';

type Json = Record<string, any>; // eslint-disable-line @typescript-eslint/no-explicit-any
type Edit = (json: Json, bin: Uint8Array) => void;

async function load(edit: Edit, texture = false): Promise<GltfModel> {
  return loadGltf(quadGlb({ texture, edit }), 'bad.glb', await memoryOptions());
}

async function refused(edit: Edit, pattern: RegExp, texture = false): Promise<void> {
  let error: unknown = null;
  try {
    await load(edit, texture);
  } catch (e) {
    error = e;
  }
  expect(error).toBeInstanceOf(GltfError);
  const message = (error as Error).message;
  expect(message).toMatch(pattern);
  expect(message).not.toMatch(/[\n\r]|Cannot read|\[object Object\]|undefined/);
}

const prim = (j: Json): Json => j.meshes[0].primitives[0];

describe('values of the wrong JSON type are named as such', () => {
  it('"scene": "0" and "bufferView": [0]', async () => {
    await refused((j) => {
      j.scene = '0';
    }, /^glTF: document\.scene: must be an integer index into scenes, got the string "0"$/);
    await refused((j) => {
      j.accessors[0].bufferView = [0];
    }, /^glTF: accessors\[0\]\.bufferView: must be an integer index into bufferViews, got an array of 1 element$/);
    await refused((j) => {
      prim(j).attributes.NORMAL = '1';
    }, /attributes\.NORMAL: must be an integer index into accessors, got the string "1"$/);
  });
});

describe('attributes: the accessor fits the semantic (glTF 2.0 §3.7.2.1)', () => {
  it('POSITION as VEC2 or UNSIGNED_INT', async () => {
    await refused((j) => {
      j.accessors[0].type = 'VEC2';
    }, /^glTF: meshes\[0\]\.primitives\[0\]\.attributes\.POSITION: accessors\[0\] is VEC2, but POSITION must be VEC3$/);
    await refused((j) => {
      j.accessors[0].componentType = 5125;
    }, /attributes\.POSITION: accessors\[0\] is UNSIGNED_INT, but POSITION must be FLOAT$/);
  });

  it('NORMAL as VEC4, TEXCOORD as VEC3, TANGENT as VEC3', async () => {
    await refused((j) => {
      j.accessors[1].type = 'VEC4';
      j.accessors[1].count = 3; // 48 bytes: inside its view, so only the type is wrong
    }, /attributes\.NORMAL: accessors\[1\] is VEC4, but NORMAL must be VEC3$/);
    await refused((j) => {
      j.accessors[2].type = 'VEC3';
      j.accessors[2].count = 2;
    }, /attributes\.TEXCOORD_0: accessors\[2\] is VEC3, but TEXCOORD_0 must be VEC2$/);
    await refused((j) => {
      prim(j).attributes.TANGENT = 1; // a VEC3
    }, /attributes\.TANGENT: accessors\[1\] is VEC3, but TANGENT must be VEC4$/);
  });

  it('integer encodings need normalized, or KHR_mesh_quantization', async () => {
    await refused((j) => {
      j.accessors[2].componentType = 5123; // UNSIGNED_SHORT, not normalized
    }, /TEXCOORD_0: accessors\[2\] is UNSIGNED_SHORT, but TEXCOORD_0 must be FLOAT, UNSIGNED_BYTE normalized, UNSIGNED_SHORT normalized \(allowed only with the extension KHR_mesh_quantization/);
    await refused((j) => {
      j.accessors[0].normalized = true; // a FLOAT
    }, /^glTF: accessors\[0\]\.normalized: must not be true for component type 5126/);
  });

  it('one count per primitive; names are semantics or start with "_"', async () => {
    await refused((j) => {
      j.accessors[2].count = 3;
    }, /attributes\.TEXCOORD_0: has 3 elements, but POSITION has 4/);
    await refused((j) => {
      prim(j).attributes.texcoord_0 = 2;
    }, /attributes\.texcoord_0: is not a glTF attribute semantic/);
    const ok = await load((j) => {
      prim(j).attributes._CUSTOM = 2;
    });
    expect(ok.indices.length).toBe(6);
  });
});

describe('every index into every array, features pathwise ignores included', () => {
  it('node.skin, skins, animations, morph targets', async () => {
    await refused((j) => {
      j.nodes[0].skin = 0;
    }, /^glTF: nodes\[0\]\.skin: refers to skins\[0\], but the file has 0$/);
    await refused((j) => {
      j.skins = [{ joints: [0, 5] }];
    }, /^glTF: skins\[0\]\.joints\[1\]: refers to nodes\[5\], but the file has 1$/);
    await refused((j) => {
      j.skins = [{ joints: [0], inverseBindMatrices: 9 }];
    }, /^glTF: skins\[0\]\.inverseBindMatrices: refers to accessors\[9\]/);
    const anim =
      (channel: Json, sampler: Json = { input: 3, output: 0 }): Edit =>
      (j) => {
        j.accessors.push({ bufferView: 0, componentType: 5126, count: 4, type: 'SCALAR' });
        j.animations = [
          { samplers: [{ ...sampler, input: j.accessors.length - 1 }], channels: [channel] },
        ];
      };
    await refused(
      anim({ sampler: 0, target: { node: 3, path: 'translation' } }),
      /^glTF: animations\[0\]\.channels\[0\]\.target\.node: refers to nodes\[3\], but the file has 1$/,
    );
    await refused(
      anim({ sampler: 2, target: { node: 0, path: 'translation' } }),
      /^glTF: animations\[0\]\.channels\[0\]\.sampler: refers to animations\[0\]\.samplers\[2\], but the file has 1$/,
    );
    await refused((j) => {
      anim({ sampler: 0, target: { node: 0, path: 'translation' } })(j, new Uint8Array());
      j.animations[0].samplers[0].output = 40;
    }, /^glTF: animations\[0\]\.samplers\[0\]\.output: refers to accessors\[40\]/);
    await refused((j) => {
      prim(j).targets = [{ POSITION: 12 }];
    }, /^glTF: meshes\[0\]\.primitives\[0\]\.targets\[0\]\.POSITION: refers to accessors\[12\], but the file has 4$/);
    await refused((j) => {
      j.accessors[2].type = 'VEC3';
      j.accessors[2].count = 2;
      prim(j).targets = [{ POSITION: 2 }];
      delete prim(j).attributes.TEXCOORD_0;
    }, /targets\[0\]\.POSITION: has 2 elements, but the primitive's attributes have 4$/);
  });

  it('sparse indices below count and strictly increasing (§3.6.2.3)', async () => {
    // The sparse part reads the index buffer view (UNSIGNED_SHORT 0, 1, 2, 0, 2, 3).
    const sparse = (count: number) => (j: Json) => {
      j.accessors[0].sparse = {
        count,
        indices: { bufferView: 3, componentType: 5123 },
        values: { bufferView: 0 },
      };
    };
    await refused(
      sparse(4),
      /^glTF: accessors\[0\]\.sparse\.indices: element 3 is 0, not greater than the one before \(2\); sparse indices must strictly increase$/,
    );
    await refused((j, bin) => {
      sparse(1)(j);
      const at = j.bufferViews[3].byteOffset as number;
      new DataView(bin.buffer, bin.byteOffset).setUint16(at, 7, true);
    }, /^glTF: accessors\[0\]\.sparse\.indices: element 0 is 7, but the accessor has 4 elements$/);
    const ok = await load(sparse(3));
    expect(ok.indices.length).toBe(6);
  });

  it('a texCoord set the primitive lacks is refused; a set above 1 is noted and ignored', async () => {
    await refused(
      (j) => {
        j.materials[0].pbrMetallicRoughness.baseColorTexture.texCoord = 7;
      },
      /^glTF: meshes\[0\]\.primitives\[0\]\.attributes: has no TEXCOORD_7, which its material's pbrMetallicRoughness\.baseColorTexture reads$/,
      true,
    );
    const model = await load((j) => {
      j.materials[0].pbrMetallicRoughness.baseColorTexture.texCoord = 9;
      prim(j).attributes.TEXCOORD_9 = 2;
    }, true);
    expect(model.warnings.join('\n')).toMatch(
      /baseColorTexture: reads TEXCOORD_9; pathwise reads only sets 0 and 1, so the texture is ignored/,
    );
    expect(imageCount(model.textures)).toBe(0);
  });
});

describe('the rest of issue 27 list 7', () => {
  it('asset.minVersion above 2.0 (§3.2)', async () => {
    await refused((j) => {
      j.asset = { version: '2.1', minVersion: '2.1' };
    }, /^glTF: asset\.minVersion: the file needs glTF "2\.1", and pathwise reads glTF 2\.0/);
    await refused((j) => {
      j.asset.minVersion = '2.1';
    }, /^glTF: asset\.minVersion: "2\.1" is greater than the version "2\.0"$/);
    // A newer minor version without minVersion is meant to load (§3.2).
    const model = await load((j) => {
      j.asset = { version: '2.1' };
    });
    expect(model.warnings).toEqual(['asset.version: "2.1" is read as glTF 2.0']);
  });

  it('a node with both matrix and TRS; duplicate roots; a child listed twice', async () => {
    await refused((j) => {
      j.nodes[0].matrix = [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1];
    }, /^glTF: nodes\[0\]: has both matrix and translation; a node has one or the other/);
    await refused((j) => {
      j.scenes[0].nodes = [0, 0];
    }, /^glTF: scenes\[0\]\.nodes: lists nodes\[0\] twice$/);
    await refused((j) => {
      j.nodes.push({ children: [0, 0] });
      j.scenes[0].nodes = [1];
    }, /^glTF: nodes\[1\]\.children: lists nodes\[0\] twice$/);
  });

  it('an alphaMode other than the three upper-case modes is noted and rendered OPAQUE', async () => {
    const blend = await load((j) => {
      j.materials[0].alphaMode = 'blend';
    }, true);
    expect(blend.warnings).toEqual([
      'materials[0].alphaMode: the string "blend" is not "OPAQUE", "MASK" or "BLEND" (upper case); the material is rendered OPAQUE',
    ]);
    const model = await load((j) => {
      j.materials[0].alphaMode = 'BLEND';
    }, true);
    expect(model.warnings).toEqual([]);
    await refused(
      (j) => {
        j.materials[0].alphaMode = 2;
      },
      /^glTF: materials\[0\]\.alphaMode: must be a string, got 2$/,
      true,
    );
  });

  it('cameras: yfov, znear, aspectRatio, zfar in range; the projection present', async () => {
    const cam =
      (perspective: unknown): Edit =>
      (j) => {
        j.cameras = [{ type: 'perspective', perspective }];
        j.nodes.push({ camera: 0 });
        j.scenes[0].nodes.push(1);
      };
    for (const yfov of [0, -1])
      await refused(
        cam({ yfov, znear: 0.1 }),
        new RegExp(
          `^glTF: cameras\\[0\\]\\.perspective\\.yfov: must be a finite number greater than 0, got ${yfov}$`,
        ),
      );
    await refused(
      cam({ yfov: 1e308, znear: 0.1 }),
      /^glTF: cameras\[0\]\.perspective\.yfov: is out of range: a perspective field of view must be below π \(180°\), got 1e\+308 radians$/,
    );
    await refused(
      cam({ yfov: 0.8, znear: 0 }),
      /^glTF: cameras\[0\]\.perspective\.znear: must be a finite number greater than 0, got 0$/,
    );
    await refused(
      cam({ yfov: 0.8, znear: 0.1, aspectRatio: 0 }),
      /^glTF: cameras\[0\]\.perspective\.aspectRatio: must be a finite number greater than 0, got 0$/,
    );
    await refused(
      cam({ yfov: 0.8, znear: 1, zfar: 0.5 }),
      /^glTF: cameras\[0\]\.perspective\.zfar: must be greater than znear \(1\), got 0\.5$/,
    );
    await refused(
      cam(undefined),
      /^glTF: cameras\[0\]\.perspective: is required for a camera of type "perspective", got nothing$/,
    );
  });

  it('a texture without source is ignored with a warning (was a crash in glTF-Transform)', async () => {
    const model = await load((j) => {
      j.samplers = [{ magFilter: 9729 }];
      j.textures = [{ sampler: 0 }];
    }, true);
    expect(model.warnings).toContain(
      'textures[0]: has no source image; the materials that use it use their factors alone',
    );
    expect(imageCount(model.textures)).toBe(0);
    await refused((j) => {
      j.samplers = [{ magFilter: '9729' }];
    }, /^glTF: samplers\[0\]\.magFilter: must be an integer, got the string "9729"$/);
    await refused((j) => {
      j.samplers = [{ wrapS: 1 }];
    }, /^glTF: samplers\[0\]\.wrapS: must be one of 33071, 33648, 10497, got 1$/);
  });
});

describe('found by the seeded differential fuzz (tests/fuzz/gltf-validator.test.ts)', () => {
  it('a camera type glTF-Transform cannot read is one line, not its TypeError', () =>
    refused((j) => {
      j.cameras = [{ type: 'fisheye', perspective: { yfov: 0.8, znear: 0.1 } }];
      j.nodes.push({ camera: 0 });
      j.scenes[0].nodes.push(1);
    }, /^glTF: cameras\[0\]\.type: the string "fisheye" is not a camera type pathwise reads \("perspective", "orthographic"\)$/));

  it('two vertex accessors sharing a view without byteStride (§3.6.2.1)', () =>
    refused((j) => {
      j.accessors[1].bufferView = 0;
    }, /^glTF: meshes\[0\]\.primitives\[0\]\.attributes\.NORMAL: accessors\[1\] and accessors\[0\] both read bufferViews\[0\], which has no byteStride/));

  it('morph targets: an empty one, weights of the wrong type or number', async () => {
    await refused((j) => {
      prim(j).targets = [{}];
    }, /^glTF: meshes\[0\]\.primitives\[0\]\.targets\[0\]: must name at least one attribute$/);
    await refused((j) => {
      prim(j).targets = [{ NORMAL: 1 }];
      j.meshes[0].weights = ['0'];
    }, /^glTF: meshes\[0\]\.weights: must be an array of finite numbers, got an array of 1 element$/);
    await refused((j) => {
      prim(j).targets = [{ NORMAL: 1 }];
      j.meshes[0].weights = [0, 0];
    }, /^glTF: meshes\[0\]\.weights: has 2 weights for 1 morph targets$/);
  });

  it('a textureInfo that is not an object', () =>
    refused(
      (j) => {
        j.materials[0].pbrMetallicRoughness.baseColorTexture = 3;
      },
      /^glTF: materials\[0\]\.pbrMetallicRoughness\.baseColorTexture: must be an object, got 3$/,
      true,
    ));
});

describe('found by the spec fuzzer', () => {
  it('a texCoord set the primitive lacks is refused even when the texture has no source', async () => {
    await refused((j) => {
      j.textures = [{}];
      j.materials ??= [{}];
      prim(j).material = 0;
      j.materials[0].pbrMetallicRoughness = { baseColorTexture: { index: 0, texCoord: 7 } };
    }, /attributes: has no TEXCOORD_7, which its material's pbrMetallicRoughness\.baseColorTexture reads$/);
  });

  it('POSITION bounds that are missing or do not hold the data: a note, bounds from the vertices', async () => {
    const wrong = await load((j) => {
      j.accessors[0].max = [0.1, 0.1, 0.1];
    });
    expect(wrong.warnings.join('\n')).toMatch(
      /accessors\[0\] \(POSITION\): vertex \d+ has [xyz] = .*, outside the declared min .* and max 0\.1; the bounds are taken from the vertices/,
    );
    const none = await load((j) => {
      delete j.accessors[0].min;
      delete j.accessors[0].max;
    });
    expect(none.warnings.join('\n')).toMatch(/accessors\[0\] \(POSITION\): has no min and max/);
    const right = await load(() => {});
    expect(right.warnings.join('\n')).not.toMatch(/POSITION/);
  });
});
