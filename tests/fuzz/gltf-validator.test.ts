/**
 * Differential test against Khronos's reference validator (npm gltf-validator,
 * 2.0.0-dev.3.10): for each file of the project's glTF corpus and each mutation of
 * issue 27, pathwise's verdict (loads / refuses) agrees with the validator's (no errors
 * / errors), or the case says why they differ, and the test checks that the difference
 * is the one stated: pathwise refuses what the validator only warns about (or cannot
 * see: world space), or pathwise accepts a file with exactly the listed validator errors
 * that it reads soundly anyway. A change on either side that moves a verdict fails here.
 */
import { readFileSync } from 'node:fs';
import { createRequire } from 'node:module';
import { Document } from '@gltf-transform/core';
import { describe, expect, it } from 'vitest';
import { GltfError } from '../../src/core/gltf/errors.ts';
import { loadGltf } from '../../src/core/gltf/load.ts';
import {
  docWith,
  memoryOptions,
  meshPrimitive,
  png,
  quadPrimitive,
  toGlb,
} from '../helpers/gltf.ts';
import { ROOT } from '../helpers/render.ts';
import { quadGlb, quadGltfDataUri } from './gltf-samples.ts';

type Json = Record<string, any>; // eslint-disable-line @typescript-eslint/no-explicit-any

interface Message {
  code: string;
  severity: number; // 0 error, 1 warning, 2 information, 3 hint
  pointer?: string;
  message: string;
}
interface Validator {
  validateBytes(data: Uint8Array, options?: Json): Promise<{ issues: { messages: Message[] } }>;
}
const validator = createRequire(import.meta.url)('gltf-validator') as Validator;

/** How the two verdicts may differ, and why. */
type Difference =
  { pathwise: 'refuses'; why: string } | { pathwise: 'loads'; codes: string[]; why: string };

interface Case {
  name: string;
  bytes: () => Uint8Array | Promise<Uint8Array>;
  /** For a file both refuse: a validator error code that names the same problem. */
  code?: string;
  differs?: Difference;
}

// Reasons shared by several cases.
const WORLD =
  'the validator checks each node alone; pathwise multiplies the transforms and refuses a world space that leaves the double range';

const edit =
  (f: (j: Json, bin: Uint8Array) => void, texture = false): (() => Uint8Array) =>
  () =>
    quadGlb({ texture, edit: f });

/** An animation of one channel, `sampler` and target `node` as given, on a SCALAR time accessor. */
function animate(j: Json, sampler: number, node: number): void {
  j.accessors.push({
    bufferView: 0,
    componentType: 5126,
    count: 4,
    type: 'SCALAR',
    min: [0],
    max: [1],
  });
  j.animations = [
    {
      samplers: [{ input: 4, output: 0 }],
      channels: [{ sampler, target: { node, path: 'translation' } }],
    },
  ];
}

const camera =
  (perspective: Json, translation = [0, 0, 3]) =>
  (j: Json): void => {
    j.cameras = [{ type: 'perspective', perspective }];
    j.nodes.push({ camera: 0, translation });
    j.scenes[0].nodes.push(1);
  };

const corpus: Case[] = [
  { name: 'gltf-samples: quad GLB', bytes: () => quadGlb() },
  { name: 'gltf-samples: textured quad GLB', bytes: () => quadGlb({ texture: true }) },
  { name: 'gltf-samples: quad .gltf with a data: URI buffer', bytes: quadGltfDataUri },
  { name: 'docs/showcase.glb', bytes: () => readFileSync(`${ROOT}docs/showcase.glb`) },
  {
    name: 'helpers/gltf: textured quad (glTF-Transform)',
    bytes: () => {
      const doc = new Document();
      doc.createBuffer();
      const tex = doc
        .createTexture()
        .setImage(png(2, 2, () => [200, 100, 50, 255]))
        .setMimeType('image/png');
      return toGlb(
        docWith(doc, quadPrimitive(doc).setMaterial(doc.createMaterial().setBaseColorTexture(tex))),
      );
    },
  },
  {
    name: 'helpers/gltf: unindexed quad without normals',
    bytes: () => {
      const doc = new Document();
      doc.createBuffer();
      return toGlb(docWith(doc, quadPrimitive(doc, { indexed: false, normals: false })));
    },
  },
  {
    name: 'helpers/gltf: mesh primitive with normals and uv',
    bytes: () => {
      const doc = new Document();
      doc.createBuffer();
      const p = [0, 0, 0, 1, 0, 0, 0, 1, 0];
      return toGlb(
        docWith(
          doc,
          meshPrimitive(doc, p, [0, 1, 2], {
            normals: [0, 0, 1, 0, 0, 1, 0, 0, 1],
            uv: [0, 0, 1, 0, 0, 1],
          }),
        ),
      );
    },
  },
];

const mutations: Case[] = [
  // Finding 5: values of the wrong type.
  { name: '"scene": "0"', bytes: edit((j) => (j.scene = '0')), code: 'TYPE_MISMATCH' },
  {
    name: '"bufferView": [0]',
    bytes: edit((j) => (j.accessors[0].bufferView = [0])),
    code: 'TYPE_MISMATCH',
  },
  // Finding 3: attributes that do not fit their semantic.
  {
    name: 'POSITION as VEC2',
    bytes: edit((j) => {
      j.accessors[0].type = 'VEC2';
      delete j.accessors[0].min;
      delete j.accessors[0].max;
    }),
    code: 'MESH_PRIMITIVE_ATTRIBUTES_ACCESSOR_INVALID_FORMAT',
  },
  {
    name: 'POSITION as UNSIGNED_INT',
    bytes: edit((j) => (j.accessors[0].componentType = 5125)),
    code: 'MESH_PRIMITIVE_ATTRIBUTES_ACCESSOR_INVALID_FORMAT',
  },
  {
    name: 'NORMAL as VEC4',
    bytes: edit((j) => {
      j.accessors[1].type = 'VEC4';
      j.accessors[1].count = 3;
    }),
    code: 'MESH_PRIMITIVE_ATTRIBUTES_ACCESSOR_INVALID_FORMAT',
  },
  {
    name: 'TEXCOORD_0 as VEC3',
    bytes: edit((j) => {
      j.accessors[2].type = 'VEC3';
      j.accessors[2].count = 2;
    }),
    code: 'MESH_PRIMITIVE_ATTRIBUTES_ACCESSOR_INVALID_FORMAT',
  },
  {
    name: 'TANGENT as VEC3',
    bytes: edit((j) => (j.meshes[0].primitives[0].attributes.TANGENT = 1)),
    code: 'MESH_PRIMITIVE_ATTRIBUTES_ACCESSOR_INVALID_FORMAT',
  },
  {
    name: 'FLOAT normalized',
    bytes: edit((j) => (j.accessors[0].normalized = true)),
    code: 'ACCESSOR_NORMALIZED_INVALID',
  },
  {
    name: 'unequal attribute counts',
    bytes: edit((j) => (j.accessors[2].count = 3)),
    code: 'MESH_PRIMITIVE_UNEQUAL_ACCESSOR_COUNT',
  },
  {
    name: 'sparse indices not increasing',
    bytes: edit((j) => {
      j.accessors[0].sparse = {
        count: 4,
        indices: { bufferView: 3, componentType: 5123 },
        values: { bufferView: 0 },
      };
    }),
    code: 'ACCESSOR_SPARSE_INDICES_NON_INCREASING',
  },
  {
    name: 'sparse index >= count',
    bytes: edit((j, bin) => {
      j.accessors[0].sparse = {
        count: 1,
        indices: { bufferView: 3, componentType: 5123 },
        values: { bufferView: 0 },
      };
      new DataView(bin.buffer, bin.byteOffset).setUint16(j.bufferViews[3].byteOffset, 7, true);
    }),
    code: 'ACCESSOR_SPARSE_INDEX_OOB',
  },
  // Finding 7: indices of features pathwise ignores, and the rest of the list.
  {
    name: 'node.skin out of range',
    bytes: edit((j) => (j.nodes[0].skin = 0)),
    code: 'UNRESOLVED_REFERENCE',
  },
  {
    name: 'skin joint out of range',
    bytes: edit((j) => (j.skins = [{ joints: [0, 5] }])),
    code: 'UNRESOLVED_REFERENCE',
  },
  {
    name: 'animation channel target out of range',
    bytes: edit((j) => animate(j, 0, 3)),
    code: 'UNRESOLVED_REFERENCE',
  },
  {
    name: 'animation channel sampler out of range',
    bytes: edit((j) => animate(j, 2, 0)),
    code: 'UNRESOLVED_REFERENCE',
  },
  {
    name: 'morph target accessor out of range',
    bytes: edit((j) => (j.meshes[0].primitives[0].targets = [{ POSITION: 12 }])),
    code: 'UNRESOLVED_REFERENCE',
  },
  {
    name: 'texCoord 7 the primitive lacks',
    bytes: edit((j) => (j.materials[0].pbrMetallicRoughness.baseColorTexture.texCoord = 7), true),
    code: 'MESH_PRIMITIVE_TOO_FEW_TEXCOORDS',
  },
  {
    name: 'minVersion 2.1',
    bytes: edit((j) => (j.asset = { version: '2.1', minVersion: '2.1' })),
    differs: {
      pathwise: 'refuses',
      why: 'the validator only warns on an unknown minor version (UNKNOWN_ASSET_MINOR_VERSION); §3.2 says a loader that does not support minVersion must not load the file, and pathwise reads 2.0',
    },
  },
  {
    name: 'matrix and TRS',
    bytes: edit((j) => (j.nodes[0].matrix = [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1])),
    code: 'NODE_MATRIX_TRS',
  },
  {
    name: 'duplicate scene roots',
    bytes: edit((j) => (j.scenes[0].nodes = [0, 0])),
    code: 'DUPLICATE_ELEMENTS',
  },
  {
    name: 'a child listed twice',
    bytes: edit((j) => {
      j.nodes.push({ children: [0, 0] });
      j.scenes[0].nodes = [1];
    }),
    code: 'DUPLICATE_ELEMENTS',
  },
  // The schema's alphaMode is an open enum: the validator warns (VALUE_NOT_IN_LIST), pathwise notes it.
  {
    name: 'alphaMode "blend"',
    bytes: edit((j) => (j.materials[0].alphaMode = 'blend'), true),
  },

  {
    name: 'camera znear 0',
    bytes: edit(camera({ yfov: 0.8, znear: 0 })),
    code: 'VALUE_NOT_IN_RANGE',
  },
  {
    name: 'camera aspectRatio 0',
    bytes: edit(camera({ yfov: 0.8, znear: 0.1, aspectRatio: 0 })),
    code: 'VALUE_NOT_IN_RANGE',
  },
  {
    name: 'camera yfov 0',
    bytes: edit(camera({ yfov: 0, znear: 0.1 })),
    code: 'VALUE_NOT_IN_RANGE',
  },
  {
    name: 'camera yfov -1',
    bytes: edit(camera({ yfov: -1, znear: 0.1 })),
    code: 'VALUE_NOT_IN_RANGE',
  },
  {
    name: 'camera yfov 1e308',
    bytes: edit(camera({ yfov: 1e308, znear: 0.1 })),
    differs: {
      pathwise: 'refuses',
      why: 'the validator only warns (CAMERA_YFOV_GEQUAL_PI); a perspective projection of 180° or more has no image plane to frame a model with',
    },
  },
  {
    name: 'camera without perspective',
    bytes: edit((j) => camera(undefined as unknown as Json)(j)),
    code: 'UNDEFINED_PROPERTY',
  },
  // Finding 2, 3, 5: finite numbers whose products are not.
  {
    name: 'node at 1e308',
    bytes: edit((j) => (j.nodes[0].translation = [1e308, 0, 0])),
    differs: { pathwise: 'refuses', why: WORLD },
  },
  {
    name: 'translation 1.7e308 under a parent scaled by 10',
    bytes: edit((j) => {
      j.nodes[0].translation = [1.7e308, 0, 0];
      j.nodes.push({ scale: [10, 10, 10], children: [0] });
      j.scenes[0].nodes = [1];
    }),
    differs: { pathwise: 'refuses', why: WORLD },
  },
  {
    name: 'matrix diag(1e308)',
    bytes: edit((j) => {
      delete j.nodes[0].translation;
      j.nodes[0].matrix = [1e308, 0, 0, 0, 0, 1e308, 0, 0, 0, 0, 1e308, 0, 0, 0, 0, 1];
    }),
    // The validator cannot decompose it (its products overflow); pathwise finds the
    // triangles' area overflowing in world space.
    code: 'NODE_MATRIX_NON_TRS',
  },
  // Validator errors pathwise reads soundly.
  {
    name: 'a sheared matrix',
    bytes: edit((j) => {
      delete j.nodes[0].translation;
      j.nodes[0].matrix = [1, 0, 0, 0, 0.5, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1];
    }),
    differs: {
      pathwise: 'loads',
      codes: ['NODE_MATRIX_NON_TRS'],
      why: 'glTF asks for TRS-decomposable matrices so that animation can replace their parts; pathwise does not animate and applies any finite affine matrix as written (normals by the inverse transpose)',
    },
  },
  {
    name: 'a rotation that is not unit length',
    bytes: edit((j) => (j.nodes[0].rotation = [0, 0, 0, 0.5])),
    code: 'ROTATION_NON_UNIT',
  },
  {
    // Both load it: pathwise normalises a quaternion within 1e-2 of unit length.
    name: 'a rotation 1e-3 off unit length',
    bytes: edit((j) => (j.nodes[0].rotation = [0.0447, 0, 0, 1])),
  },
  {
    name: 'POSITION without min and max',
    bytes: edit((j) => {
      delete j.accessors[0].min;
      delete j.accessors[0].max;
    }),
    differs: {
      pathwise: 'loads',
      codes: ['MESH_PRIMITIVE_POSITION_ACCESSOR_WITHOUT_BOUNDS'],
      why: 'pathwise computes the bounds from the positions it reads and never trusts min/max',
    },
  },

  // Accepted by both.
  { name: 'a camera node at 1e308', bytes: edit(camera({ yfov: 0.8, znear: 0.1 }, [0, 0, 1e308])) },
  { name: 'alphaMode "BLEND"', bytes: edit((j) => (j.materials[0].alphaMode = 'BLEND'), true) },
  { name: 'a 2.1 file without minVersion', bytes: edit((j) => (j.asset = { version: '2.1' })) },
  {
    name: 'a texture without source',
    bytes: edit((j) => {
      j.samplers = [{ magFilter: 9729 }];
      j.textures = [{ sampler: 0 }];
    }, true),
  },
];

async function pathwiseLoads(bytes: Uint8Array): Promise<boolean> {
  try {
    await loadGltf(bytes, 'case.glb', await memoryOptions());
    return true;
  } catch (e) {
    if (!(e instanceof GltfError)) throw e;
    return false;
  }
}

async function validatorErrors(bytes: Uint8Array): Promise<string[]> {
  const report = await validator.validateBytes(bytes, { maxIssues: 50 });
  return report.issues.messages.filter((m) => m.severity === 0).map((m) => m.code);
}

describe('pathwise and the Khronos glTF validator agree, or say why not', () => {
  for (const c of [...corpus, ...mutations]) {
    it(c.name, async () => {
      const bytes = await c.bytes();
      const loads = await pathwiseLoads(bytes);
      const errors = await validatorErrors(bytes);
      const verdicts = { loads, errors };
      if (c.differs === undefined) {
        expect(verdicts).toEqual({ loads: errors.length === 0, errors });
        if (c.code !== undefined) expect(errors).toContain(c.code);
      } else if (c.differs.pathwise === 'refuses') {
        expect(verdicts).toEqual({ loads: false, errors: [] });
      } else {
        expect(loads).toBe(true);
        expect(errors.length).toBeGreaterThan(0);
        for (const e of errors) expect(c.differs.codes).toContain(e);
      }
    });
  }
});

/**
 * Seeded random mutations of a file that uses every feature the check covers (a
 * textured quad with a camera, a morph target, mesh weights, an animation of them and
 * a sampler; the validator reports no error on it): one to three values replaced by
 * values of the kinds glTF uses (indices, enums, component types, numbers at the ends
 * of the double range, wrong JSON types) or removed.
 */
function richQuad(mutate: (j: Json) => void): Uint8Array {
  return quadGlb({
    texture: true,
    edit: (j: Json) => {
      camera({ yfov: 0.8, znear: 0.1 })(j);
      j.accessors[1].min = [0, 0, 1];
      j.accessors[1].max = [0, 0, 1];
      j.meshes[0].primitives[0].targets = [{ POSITION: 1 }];
      j.meshes[0].weights = [0];
      // Animation data in a view of its own (over the position bytes 0, 1: increasing).
      j.bufferViews.push({ buffer: 0, byteOffset: 8, byteLength: 8 });
      const v = j.bufferViews.length - 1;
      j.accessors.push({
        bufferView: v,
        componentType: 5126,
        count: 2,
        type: 'SCALAR',
        min: [0],
        max: [1],
      });
      j.accessors.push({ bufferView: v, componentType: 5126, count: 2, type: 'SCALAR' });
      j.animations = [
        {
          samplers: [{ input: 4, output: 5 }],
          channels: [{ sampler: 0, target: { node: 0, path: 'weights' } }],
        },
      ];
      j.samplers = [{ magFilter: 9729, wrapS: 33071 }];
      j.textures[0].sampler = 0;
      mutate(j);
    },
  });
}

const POOL: unknown[] = [
  undefined,
  null,
  '0',
  [0],
  {},
  true,
  -1,
  0,
  1,
  2,
  3,
  7,
  0.5,
  1e308,
  -1e308,
  5e-324,
  5120,
  5121,
  5123,
  5125,
  5126,
  9729,
  33071,
  'VEC2',
  'VEC4',
  'SCALAR',
  'MAT4',
  'BLEND',
  'perspective',
  'weights',
  'translation',
  [0, 0, 0, 0.5],
  [1e308, 0, 0],
  [1, 2],
];

function mulberry32(seed: number): () => number {
  return () => {
    seed = (seed + 0x6d2b79f5) | 0;
    let t = Math.imul(seed ^ (seed >>> 15), 1 | seed);
    t = (t + Math.imul(t ^ (t >>> 7), 61 | t)) ^ t;
    return ((t ^ (t >>> 14)) >>> 0) / 4294967296;
  };
}

/** Every JSON path of `o`. */
function jsonPaths(o: unknown, at: (string | number)[] = [], out: (string | number)[][] = []) {
  if (typeof o === 'object' && o !== null) {
    for (const [k, v] of Object.entries(o)) {
      const p = [...at, Array.isArray(o) ? Number(k) : k];
      out.push(p);
      jsonPaths(v, p, out);
    }
  }
  return out;
}

/**
 * Validator errors pathwise loads through, each with the reason and the JSON pointers
 * it applies to. Anything else the validator calls an error, pathwise must refuse.
 */
const TOLERATED: { codes: string[]; pointer: RegExp; why: string }[] = [
  {
    codes: ['UNSATISFIED_DEPENDENCY'],
    pointer: /^\/images\/\d+\/bufferView$/,
    why: 'an image in a buffer view needs a mimeType (§5.18); pathwise identifies an image by its bytes, not by mimeType',
  },
  {
    codes: ['*'],
    pointer: /^\/animations\//,
    why: 'animations are not played (rest pose): their indices and input accessors are checked, their outputs and data are not',
  },
  {
    codes: ['*'],
    pointer: /^\/accessors\/\d+\/(min|max)(\/\d+)?$/,
    why: 'pathwise never reads accessor.min/max: bounds come from the data it reads',
  },
  {
    codes: [
      'ACCESSOR_MIN_MISMATCH',
      'ACCESSOR_MAX_MISMATCH',
      'ACCESSOR_ELEMENT_OUT_OF_MIN_BOUND',
      'ACCESSOR_ELEMENT_OUT_OF_MAX_BOUND',
      'MESH_PRIMITIVE_POSITION_ACCESSOR_WITHOUT_BOUNDS',
      'ANIMATION_SAMPLER_INPUT_ACCESSOR_WITHOUT_BOUNDS',
    ],
    pointer: /./,
    why: 'pathwise never reads accessor.min/max: bounds come from the data it reads',
  },
  {
    codes: ['*'],
    pointer: /^\/images\/\d+\/mimeType$/,
    why: 'pathwise identifies an image by its bytes (PNG or JPEG signature), not by mimeType',
  },
  {
    codes: ['TEXTURE_INVALID_IMAGE_MIME_TYPE', 'IMAGE_MIME_TYPE_INVALID'],
    pointer: /./,
    why: 'pathwise identifies an image by its bytes (PNG or JPEG signature), not by mimeType',
  },
  {
    codes: ['BUFFER_VIEW_TARGET_OVERRIDE'],
    pointer: /./,
    why: 'a buffer view used both as vertex data and as an image: pathwise reads each use by itself (such image bytes are not an image, and the texture is dropped with a warning)',
  },
  {
    codes: ['ROTATION_NON_UNIT', 'NODE_MATRIX_NON_TRS'],
    pointer: /./,
    why: 'pathwise normalises rotations and applies any finite affine matrix as written; it does not animate',
  },
  {
    codes: [
      'ACCESSOR_ANIMATION_INPUT_NON_INCREASING',
      'ACCESSOR_ANIMATION_INPUT_NEGATIVE',
      'ANIMATION_SAMPLER_OUTPUT_ACCESSOR_INVALID_COUNT',
      'ANIMATION_SAMPLER_OUTPUT_ACCESSOR_INVALID_FORMAT',
      'ANIMATION_CHANNEL_TARGET_NODE_WEIGHTS_NO_MORPHS',
      'ANIMATION_DUPLICATE_TARGETS',
      'MESH_INVALID_WEIGHTS_COUNT',
      'NODE_WEIGHTS_INVALID',
    ],
    pointer: /./,
    why: 'animations and morph weights are not read (rest pose); their indices and accessor types are checked, their data is not',
  },
];

function tolerated(m: Message): boolean {
  return TOLERATED.some(
    (t) => (t.codes.includes('*') || t.codes.includes(m.code)) && t.pointer.test(m.pointer ?? ''),
  );
}

/** pathwise's own refusals of files the validator passes (messages, and why). */
const PATHWISE_ONLY: { message: RegExp; why: string }[] = [
  {
    message: /^glTF: cameras\[\d+\]\.type: .* is not a camera type pathwise reads/,
    why: 'the schema leaves camera types open (the validator warns); glTF-Transform, which parses the document, reads any other type as orthographic and fails',
  },
  {
    message: /NORMAL: vertex \d+ has a zero-length normal$/,
    why: 'NORMAL must be unit length (§3.7.2.1); the validator does not look at the values of an accessor without a bufferView (all zeros)',
  },
  {
    message: /^glTF: samplers\[\d+\]\.wrap[ST]: must be one of/,
    why: 'the schema leaves wrap modes open (the validator warns, VALUE_NOT_IN_LIST); pathwise must apply the mode, so it must know it',
  },
  { message: /^glTF: nodes\[\d+\]: (its world|all \d+ triangles|triangle \d+)/, why: WORLD },
  {
    message: /yfov: is out of range/,
    why: 'a perspective projection of 180° or more frames nothing',
  },
  {
    message: /: (not a PNG or JPEG image|cannot decode (PNG|JPEG))/,
    why: 'an image a material uses must decode (else the texture would render as garbage or nothing); the validator reports bytes it cannot recognise only as a warning (IMAGE_UNRECOGNIZED_FORMAT)',
  },
];

describe('seeded mutations: pathwise and the validator agree, or the difference is a listed one', () => {
  it('the base file is valid for both', async () => {
    const bytes = richQuad(() => {});
    expect(await validatorErrors(bytes)).toEqual([]);
    expect(await pathwiseLoads(bytes)).toBe(true);
  });

  it('300 mutations', async () => {
    const random = mulberry32(27);
    const pick = <T>(a: T[]): T => a[Math.floor(random() * a.length)];
    const problems: string[] = [];
    const counts = { agree: 0, tolerated: 0, pathwiseOnly: 0, validatorCrash: 0 };
    for (let i = 0; i < 300; i++) {
      const log: string[] = [];
      const bytes = richQuad((j) => {
        const paths = jsonPaths(j).filter((p) => p[0] !== 'buffers');
        const n = 1 + Math.floor(random() * 3);
        for (let k = 0; k < n; k++) {
          const p = pick(paths);
          let o = j;
          for (const s of p.slice(0, -1)) o = o?.[s];
          if (typeof o !== 'object' || o === null) continue;
          const v = pick(POOL);
          log.push(`${p.join('.')} = ${JSON.stringify(v) ?? 'removed'}`);
          if (v === undefined) delete o[p[p.length - 1]];
          else o[p[p.length - 1]] = v;
        }
      });
      let message = '';
      try {
        await loadGltf(bytes, 'case.glb', await memoryOptions());
      } catch (e) {
        if (!(e instanceof GltfError)) throw e;
        message = e.message;
      }
      let messages: Message[];
      try {
        messages = (await validator.validateBytes(bytes, { maxIssues: 50 })).issues.messages;
      } catch {
        // The validator itself throws on some (a Dart NoSuchMethodError); pathwise only
        // had to end in a load or one GltfError, which the try above required.
        counts.validatorCrash++;
        continue;
      }
      const errors = messages.filter((m) => m.severity === 0);
      const loads = message === '';
      if (loads === (errors.length === 0)) counts.agree++;
      else if (loads && errors.every(tolerated)) counts.tolerated++;
      else if (!loads && PATHWISE_ONLY.some((d) => d.message.test(message))) counts.pathwiseOnly++;
      else
        problems.push(
          `${log.join('; ')}: pathwise ${loads ? 'loads' : `refuses (${message})`}, validator ${JSON.stringify(errors.map((e) => [e.code, e.pointer]))}`,
        );
    }
    expect(problems.slice(0, 5)).toEqual([]);
    expect(counts.agree).toBeGreaterThan(150);
  });
});
