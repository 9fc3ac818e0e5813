/**
 * glTF cases: the model of gltf-doc.ts in one of the three containers, and mutations from
 * the rules of the glTF 2.0 specification. Those marked `invalid` break a rule the
 * specification states with MUST (the attribute table of §3.7.2.1, index ranges of §5, the
 * accessor bounds of §3.6.2.4, the camera ranges of §5.12, the GLB layout of §4.4) or the
 * project's rule that a model's files stay in its folder (issue 27, deliverable 5).
 */
import { ByteWriter } from './bytes.ts';
import { FLOAT, UNSIGNED_INT, buildModel, type Json, type Model } from './gltf-doc.ts';
import { glbEdits } from './glb-edits.ts';
import { COMPRESSED_EDITS } from './gltf-compressed-gen.ts';
import { modelSample, type ModelEdit } from './gltf-host.ts';
import { mutateJson } from './mutate.ts';
import type { Rng } from './rng.ts';
import type { Generator, Sample } from './types.ts';

type J = Json;
const j = (name: string, f: (json: J, rng: Rng) => void, invalid = false): ModelEdit => ({
  name: `gltf:${name}`,
  invalid,
  edit: (m, rng) => void f(m.json, rng),
});
const prim = (json: J) => json.meshes[0].primitives[0];
const acc = (json: J, attr: string) =>
  json.accessors[attr === 'indices' ? prim(json).indices : prim(json).attributes[attr]];

/** A float written into the geometry buffer at accessor `a`'s element `i`, component `c`. */
function poke(m: Model, a: number, i: number, c: number, v: number): void {
  const view = m.json.bufferViews[m.json.accessors[a].bufferView];
  new DataView(m.bin.buffer, m.bin.byteOffset).setFloat32(
    view.byteOffset + (i * 3 + c) * 4,
    v,
    true,
  );
}

/**
 * §3.6.2.3 sparse accessors: `indices` (strictly increasing, each < count) and values
 * appended to the buffer, replacing those POSITION elements.
 */
function sparse(name: string, indices: number[], invalid: boolean): ModelEdit {
  return {
    name: `gltf:${name}`,
    invalid,
    edit: (m) => {
      const w = new ByteWriter().bytes(m.bin);
      const iOff = w.length;
      for (const i of indices) w.u32(i, true);
      const vOff = w.length;
      for (let k = 0; k < indices.length * 3; k++) w.f32(0.4, true);
      m.bin = w.done();
      const g = m.json;
      g.bufferViews.push({ buffer: 0, byteOffset: iOff, byteLength: vOff - iOff });
      g.bufferViews.push({ buffer: 0, byteOffset: vOff, byteLength: m.bin.length - vOff });
      g.buffers[0].byteLength = m.bin.length;
      const n = g.bufferViews.length;
      acc(g, 'POSITION').sparse = {
        count: indices.length,
        indices: { bufferView: n - 2, componentType: UNSIGNED_INT },
        values: { bufferView: n - 1 },
      };
      acc(g, 'POSITION').max = [0.5, 0.5, 0.5];
    },
  };
}

/** §5.12 camera.perspective: yfov, znear and aspectRatio > 0 (and a camera node in view). */
function camera(name: string, values: number[], invalid: boolean): ModelEdit {
  return j(
    name,
    (g, r) => {
      const p: J = { yfov: 0.8, znear: 0.1, aspectRatio: 1 };
      p[r.pick(['yfov', 'znear', 'aspectRatio'])] = r.pick(values);
      g.cameras = [{ type: 'perspective', perspective: p }];
      g.nodes.push({ camera: 0, translation: [0, 0, 3] });
      g.scenes[0].nodes.push(g.nodes.length - 1);
    },
    invalid,
  );
}

export const GLTF_EDITS: ModelEdit[] = [
  ...COMPRESSED_EDITS,
  // §3.7.2.1: POSITION is VEC3 float (or, with KHR_mesh_quantization, which is not used here, normalized ints).
  {
    ...j('position-vec2', (g) => void (acc(g, 'POSITION').type = 'VEC2'), true),
    expect: /VEC|type|component/,
  },
  {
    ...j('position-uint', (g) => void (acc(g, 'POSITION').componentType = UNSIGNED_INT), true),
    expect: /VEC|type|component|FLOAT/,
  },
  {
    ...j('normal-vec4', (g) => void (acc(g, 'NORMAL').type = 'VEC4'), true),
    expect: /VEC|type|component/,
  },
  {
    ...j('texcoord-vec3', (g) => void (acc(g, 'TEXCOORD_0').type = 'VEC3'), true),
    expect: /VEC|type|component/,
  },
  {
    ...j(
      'tangent-vec3',
      (g) => void (prim(g).attributes.TANGENT = prim(g).attributes.NORMAL),
      true,
    ),
    expect: /VEC|type|component/,
  },
  j('indices-float', (g) => void (acc(g, 'indices').componentType = FLOAT), true),
  j('indices-vec3', (g) => void (acc(g, 'indices').type = 'VEC3'), true),
  {
    ...j('attribute-counts-differ', (g) => void (acc(g, 'NORMAL').count = 23), true),
    expect: /count/,
  },
  j(
    'count-huge',
    (g, r) =>
      void (acc(g, r.pick(['POSITION', 'NORMAL', 'indices'])).count = r.pick([
        1e9,
        2 ** 31,
        2 ** 53,
      ])),
    true,
  ),
  j('count-zero', (g) => void (acc(g, 'POSITION').count = 0), true),
  j('accessor-offset-past-view', (g) => void (acc(g, 'POSITION').byteOffset = 4096), true),
  j(
    'view-past-buffer',
    (g, r) => void (g.bufferViews[r.int(4)].byteLength = r.pick([1e9, 2 ** 32, 100000])),
    true,
  ),
  j('view-offset-huge', (g) => void (g.bufferViews[0].byteOffset = 2 ** 40), true),
  j('buffer-length-lie', (g) => void (g.buffers[0].byteLength = 2 ** 31), true),
  j('stride-too-small', (g) => void (g.bufferViews[0].byteStride = 4), true),
  // pathwise takes bounds from the vertices: wrong ones are honestly ignored, with a note.
  {
    ...j('position-min-max-wrong', (g) => void (acc(g, 'POSITION').max = [0.1, 0.1, 0.1])),
    expect: /outside the declared/,
  },
  // §5: every index into an array is in range.
  j('node-mesh-out-of-range', (g) => void (g.nodes[1].mesh = 7), true),
  j('node-skin-out-of-range', (g) => void (g.nodes[1].skin = 3), true),
  j('node-camera-out-of-range', (g) => void (g.nodes[1].camera = 4), true),
  j('child-out-of-range', (g) => void g.nodes[0].children.push(99), true),
  j('child-cycle', (g) => void (g.nodes[1].children = [0]), true),
  j(
    'node-two-parents',
    (g) => {
      g.nodes.push({ children: [1] });
      g.scenes[0].nodes.push(g.nodes.length - 1);
    },
    true,
  ),
  j('scene-root-twice', (g) => void g.scenes[0].nodes.push(0), true),
  j('scene-out-of-range', (g) => void (g.scene = 5), true),
  { ...j('scene-index-string', (g) => void (g.scene = '0'), true), expect: /string|integer/ },
  {
    ...j('bufferview-array', (g) => void (acc(g, 'POSITION').bufferView = [0]), true),
    expect: /array|integer/,
  },
  j('material-out-of-range', (g) => void (prim(g).material = 9), true),
  j(
    'texture-source-out-of-range',
    (g) => {
      g.textures ??= [{}];
      g.materials[0].pbrMetallicRoughness.baseColorTexture ??= { index: 0 };
      g.textures[0].source = 12;
    },
    true,
  ),
  j('texture-without-source', (g) => {
    g.textures = [{ sampler: 0 }];
    g.samplers ??= [{}];
    g.materials[0].pbrMetallicRoughness.baseColorTexture = { index: 0 };
  }),
  j(
    'sampler-out-of-range',
    (g) => {
      g.textures ??= [{}];
      g.materials[0].pbrMetallicRoughness.baseColorTexture ??= { index: 0 };
      g.textures[0].sampler = 5;
    },
    true,
  ),
  j(
    'texcoord-set-missing',
    (g, r) => {
      g.textures ??= [{}];
      g.materials[0].pbrMetallicRoughness.baseColorTexture = {
        index: 0,
        texCoord: r.pick([1, 7, 9]),
      };
    },
    true,
  ),
  j(
    'skin-joint-out-of-range',
    (g) => {
      g.skins = [{ joints: [42] }];
      g.nodes[1].skin = 0;
    },
    true,
  ),
  j(
    'animation-out-of-range',
    (g, r) => {
      g.animations = [
        {
          channels: [
            { sampler: r.pick([0, 3]), target: { node: r.pick([1, 40]), path: 'translation' } },
          ],
          samplers: [{ input: r.pick([2, 77]), output: 0 }],
        },
      ];
    },
    true,
  ),
  j('morph-target-out-of-range', (g) => void (prim(g).targets = [{ POSITION: 50 }]), true),
  sparse('sparse-valid', [1, 3], false),
  sparse('sparse-not-increasing', [3, 1], true),
  sparse('sparse-index-past-count', [2, 30], true),
  // §3.5.3: matrix or TRS, not both; §5.12: camera ranges.
  j(
    'matrix-and-trs',
    (g) => void (g.nodes[1].matrix = [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]),
    true,
  ),
  {
    ...j('matrix-diag-1e308', (g) => {
      delete g.nodes[1].translation;
      delete g.nodes[1].scale;
      g.nodes[1].matrix = [1e308, 0, 0, 0, 0, 1e308, 0, 0, 0, 0, 1e308, 0, 0, 0, 0, 1];
    }),
    expect: /finite|range|overflow|matrix/,
  },
  j(
    'translation-1e308',
    (g, r) => void (g.nodes[r.int(2)].translation = [1e308, r.pick([0, -1e308]), 0]),
  ),
  j('translation-overflow-under-scale', (g) => {
    g.nodes[0].scale = [10, 10, 10];
    g.nodes[1].translation = [1.7e308, 0, 0];
  }),
  j('rotation-not-unit', (g) => void (g.nodes[0].rotation = [0, 0, 0, 0]), true),
  j('scale-zero', (g) => void (g.nodes[1].scale = [0, 0, 0])),
  j('camera-far', (g) => {
    g.cameras = [{ type: 'perspective', perspective: { yfov: 0.8, znear: 0.1 } }];
    g.nodes.push({ camera: 0, translation: [0, 0, 1e308] });
    g.scenes[0].nodes.push(g.nodes.length - 1);
  }),
  camera('camera-bad-value', [0, -1], true),
  camera('camera-huge-value', [1e308], false),
  j(
    'camera-without-perspective',
    (g) => {
      g.cameras = [{ type: 'perspective' }];
      g.nodes.push({ camera: 0, translation: [0, 0, 3] });
      g.scenes[0].nodes.push(g.nodes.length - 1);
    },
    true,
  ),
  j('version-3', (g) => void (g.asset.version = '3.0'), true),
  j('min-version-2.1', (g) => void (g.asset.minVersion = '2.1'), true),
  j('no-asset', (g) => void delete g.asset, true),
  // The schema leaves alphaMode open (any string; the validator warns): a note, rendered OPAQUE.
  {
    ...j('alpha-mode-lowercase', (g) => void (g.materials[0].alphaMode = 'blend')),
    expect: /alphaMode/,
  },
  j('extension-required-unknown', (g) => {
    g.extensionsUsed = ['EXT_spec_fuzz'];
    g.extensionsRequired = ['EXT_spec_fuzz'];
  }),
  j(
    'extension-required-not-used',
    (g) => void (g.extensionsRequired = ['KHR_materials_unlit']),
    true,
  ),
  j('mode-points', (g) => void (prim(g).mode = 0)),
  j('mode-invalid', (g) => void (prim(g).mode = 9), true),
  // URIs (§3.6.1.1: relative paths resolve against the .gltf; the project keeps them inside).
  {
    ...j('uri-escapes-folder', (g) => void (g.buffers[0].uri = '../../outside.bin'), true),
    expect: /beside|outside|folder|\.\./,
  },
  {
    ...j(
      'uri-etc-passwd',
      (g) => void (g.buffers[0].uri = '../../../../../../../../../../etc/passwd'),
      true,
    ),
    expect: /beside|outside|folder|\.\./,
  },
  j('uri-absolute', (g) => void (g.buffers[0].uri = '/etc/passwd'), true),
  j('uri-url', (g) => void (g.buffers[0].uri = 'https://example.invalid/model.bin'), true),
  j('uri-missing-file', (g) => void (g.buffers[0].uri = 'nowhere.bin'), true),
  j(
    'uri-bad-data',
    (g) => void (g.buffers[0].uri = 'data:application/octet-stream;base64,@@@not base64'),
    true,
  ),
  {
    ...j(
      'image-escapes-folder',
      (g) => {
        g.textures = [{ source: 0 }];
        g.images = [{ uri: '../../outside.png' }];
        g.materials[0].pbrMetallicRoughness.baseColorTexture = { index: 0 };
      },
      true,
    ),
    expect: /beside|outside|folder|\.\./,
  },
  j('image-not-an-image', (g) => {
    g.textures = [{ source: 0 }];
    g.images = [{ uri: 'data:image/png;base64,aGVsbG8gd29ybGQ=' }];
    g.materials[0].pbrMetallicRoughness.baseColorTexture = { index: 0 };
  }),
  {
    name: 'gltf:position-non-finite',
    edit: (m, rng) => poke(m, 0, rng.int(24), rng.int(3), rng.pick([NaN, Infinity, -Infinity])),
  },
  {
    name: 'gltf:position-huge',
    edit: (m, rng) => poke(m, 0, rng.int(24), rng.int(3), rng.pick([3e38, -3e38])),
  },
  {
    name: 'gltf:normal-zero',
    edit: (m) => [0, 1, 2].forEach((c) => poke(m, 1, 0, c, 0)),
  },
  {
    name: 'gltf:index-out-of-range',
    invalid: true,
    edit: (m) => {
      const a = m.json.accessors[m.json.meshes[0].primitives[0].indices];
      const v = m.json.bufferViews[a.bufferView];
      const size = { 5121: 1, 5123: 2, 5125: 4 }[a.componentType as 5121] ?? 4;
      const d = new DataView(m.bin.buffer, m.bin.byteOffset);
      if (size === 1) d.setUint8(v.byteOffset + 4, 200);
      else if (size === 2) d.setUint16(v.byteOffset + 8, 60000, true);
      else d.setUint32(v.byteOffset + 16, 4e9, true);
    },
  },
  { name: 'gltf:json-random', edit: (m, rng) => void (m.json = mutateJson(m.json, rng).json as J) },
  {
    name: 'gltf:json-random-2',
    edit: (m, rng) => void (m.json = mutateJson(mutateJson(m.json, rng).json, rng).json as J),
  },
];

export const gltfGenerator: Generator = {
  format: 'gltf',
  generate(rng: Rng): Sample {
    const model = buildModel(rng);
    return modelSample(rng, model, [...GLTF_EDITS, ...glbEdits()], '');
  },
};
