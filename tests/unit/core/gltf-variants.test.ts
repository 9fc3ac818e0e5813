/**
 * KHR_materials_variants (src/core/gltf/variants.ts): the extension honoured (no
 * "ignored" note, accepted when required), the default materials without a selection,
 * a variant selected by name (mapped primitives change, the others keep their default),
 * an unknown name refused with the file's names, every malformed part refused with its
 * JSON path, and the selection reaching the loader from a scene's gltf shape and from a
 * bare model.
 */
import { createRequire } from 'node:module';
import { describe, expect, it } from 'vitest';
import { loadGltf, type GltfLoadOptions } from '../../../src/core/gltf/load.ts';
import { loadBareModel } from '../../../src/core/scene/load/bare-scene.ts';
import { validateScene } from '../../../src/core/scene/validate/validate.ts';
import { memoryOptions, sceneWithFiles } from '../../helpers/gltf.ts';

const EXT = 'KHR_materials_variants';

/** Khronos's reference validator (npm gltf-validator): its error codes for a file. */
const validator = createRequire(import.meta.url)('gltf-validator') as {
  validateBytes(
    data: Uint8Array,
    options?: Record<string, unknown>,
  ): Promise<{ issues: { messages: { code: string; severity: number }[] } }>;
};
async function validatorErrors(bytes: Uint8Array): Promise<string[]> {
  const report = await validator.validateBytes(bytes, { maxIssues: 50 });
  return report.issues.messages.filter((m) => m.severity === 0).map((m) => m.code);
}

/** One triangle in the z = 0 plane, as a data URI buffer (positions only). */
const TRIANGLE = `data:application/octet-stream;base64,${Buffer.from(
  new Float32Array([0, 0, 0, 1, 0, 0, 0, 1, 0]).buffer,
).toString('base64')}`;

type Json = Record<string, unknown>;

/**
 * A file with two primitives of one triangle each (defaults: materials 0 and 1) and
 * materials 0–3; `variants` at the root, `mappings[i]` on primitive i (undefined: none).
 */
function file(
  variants: unknown,
  mappings: unknown[],
  edit: (json: Json) => void = () => {},
): Uint8Array {
  const prim = (material: number, m: unknown): Json => ({
    attributes: { POSITION: 0 },
    material,
    ...(m !== undefined && { extensions: { [EXT]: { mappings: m } } }),
  });
  const json: Json = {
    asset: { version: '2.0' },
    extensionsUsed: [EXT],
    ...(variants !== undefined && { extensions: { [EXT]: { variants } } }),
    buffers: [{ byteLength: 36, uri: TRIANGLE }],
    bufferViews: [{ buffer: 0, byteLength: 36 }],
    accessors: [
      {
        bufferView: 0,
        componentType: 5126,
        count: 3,
        type: 'VEC3',
        min: [0, 0, 0],
        max: [1, 1, 0],
      },
    ],
    materials: [0.1, 0.2, 0.3, 0.4].map((g) => ({
      pbrMetallicRoughness: { baseColorFactor: [g, g, g, 1] },
    })),
    meshes: [{ primitives: [prim(0, mappings[0]), prim(1, mappings[1])] }],
    nodes: [{ mesh: 0 }],
    scenes: [{ nodes: [0] }],
    scene: 0,
  };
  edit(json);
  return new TextEncoder().encode(JSON.stringify(json));
}

const NAMES = [{ name: 'red' }, { name: 'blue' }, { name: 'green' }];
/** Primitive 0 maps red → 2, blue and green → 3; primitive 1 maps only green → 2. */
const MAPPINGS = [
  [
    { material: 2, variants: [0] },
    { material: 3, variants: [1, 2] },
  ],
  [{ material: 2, variants: [2] }],
];

async function load(bytes: Uint8Array, options: Partial<GltfLoadOptions> = {}) {
  return loadGltf(bytes, 'm.gltf', { ...(await memoryOptions()), ...options });
}

/** The material of each primitive's triangle (one triangle per primitive, in order). */
async function materials(variant?: string | null, bytes = file(NAMES, MAPPINGS)) {
  const model = await load(bytes, { variant });
  return Array.from(model.triangleMaterial);
}

describe('KHR_materials_variants', () => {
  it('is honoured: no note, and without a selection every primitive keeps its material', async () => {
    const model = await load(file(NAMES, MAPPINGS));
    expect(model.warnings).toEqual([]);
    expect(Array.from(model.triangleMaterial)).toEqual([0, 1]);
    expect(await materials(null)).toEqual([0, 1]);
    // The file is valid by Khronos's validator too (as is the next test's repeated name).
    expect(await validatorErrors(file(NAMES, MAPPINGS))).toEqual([]);
  });

  it('selects a variant by name: mapped primitives change, the others keep their default', async () => {
    expect(await materials('red')).toEqual([2, 1]);
    expect(await materials('blue')).toEqual([3, 1]);
    expect(await materials('green')).toEqual([3, 2]);
  });

  it('is accepted when the file requires it', async () => {
    const bytes = file(NAMES, MAPPINGS, (j) => (j.extensionsRequired = [EXT]));
    expect(await materials(undefined, bytes)).toEqual([0, 1]);
    expect(await materials('red', bytes)).toEqual([2, 1]);
  });

  it('selects every variant of a repeated name, the first matching mapping winning', async () => {
    const bytes = file([{ name: 'a' }, { name: 'b' }, { name: 'b' }], MAPPINGS);
    expect(await materials('b', bytes)).toEqual([3, 2]);
    expect(await validatorErrors(bytes)).toEqual([]);
  });

  it('refuses an unknown name, listing the file’s names', async () => {
    await expect(load(file(NAMES, MAPPINGS), { variant: 'Purple' })).rejects.toThrow(
      `extensions.${EXT}.variants: has no variant "Purple"; the file's variants are "red", "blue", "green"`,
    );
    const many = Array.from({ length: 30 }, (_, i) => ({ name: `v${i}` }));
    await expect(load(file(many, MAPPINGS), { variant: 'v30' })).rejects.toThrow(
      '"v9", "v10", "v11", and 18 more',
    );
    await expect(load(file(undefined, [undefined, undefined]), { variant: 'red' })).rejects.toThrow(
      `extensions: the file has no material variants (${EXT}) to select "red" from`,
    );
  });

  it('refuses a mapped material reading a TEXCOORD set the primitive lacks, when selected', async () => {
    const bytes = file(NAMES, MAPPINGS, (j) => {
      j.textures = [{}];
      (j.materials as Json[])[2].emissiveTexture = { index: 0 };
    });
    expect(await materials(undefined, bytes)).toEqual([0, 1]);
    await expect(load(bytes, { variant: 'red' })).rejects.toThrow(
      `meshes[0].primitives[0].extensions.${EXT}.mappings[0].material: materials[2] (variant "red") ` +
        'reads TEXCOORD_0 in materials[2].emissiveTexture, which the primitive lacks',
    );
  });

  const P = `meshes[0].primitives[0].extensions.${EXT}`;
  const bad: [string, unknown, unknown[], string][] = [
    ['root not an object', 'seven', MAPPINGS, `extensions.${EXT}: must be an object, got 7`],
    ['variants a number', 7, MAPPINGS, `extensions.${EXT}.variants: must be an array, got 7`],
    ['variants missing', 'absent', MAPPINGS, `extensions.${EXT}.variants: is required`],
    ['variants empty', [], MAPPINGS, `extensions.${EXT}.variants: must not be empty`],
    ['variants not an array', {}, MAPPINGS, `extensions.${EXT}.variants: must be an array`],
    [
      'a name missing',
      [{ name: 'a' }, {}],
      MAPPINGS,
      `extensions.${EXT}.variants[1].name: is required`,
    ],
    [
      'a name not a string',
      [{ name: 3 }],
      MAPPINGS,
      `extensions.${EXT}.variants[0].name: must be a string, got 3`,
    ],
    ['mappings missing', NAMES, ['absent'], `${P}.mappings: is required`],
    ['mappings empty', NAMES, [[]], `${P}.mappings: must not be empty`],
    ['a mapping not an object', NAMES, [[5]], `${P}.mappings[0]: must be an object, got 5`],
    ['material missing', NAMES, [[{ variants: [0] }]], `${P}.mappings[0].material: is required`],
    [
      'material out of range',
      NAMES,
      [[{ material: 4, variants: [0] }]],
      `${P}.mappings[0].material: refers to materials[4], but the file has 4`,
    ],
    [
      'variants of a mapping missing',
      NAMES,
      [[{ material: 1 }]],
      `${P}.mappings[0].variants: is required`,
    ],
    [
      'variants of a mapping empty',
      NAMES,
      [[{ material: 1, variants: [] }]],
      `${P}.mappings[0].variants: must not be empty`,
    ],
    [
      'a variant out of range',
      NAMES,
      [[{ material: 1, variants: [0, 3] }]],
      `${P}.mappings[0].variants[1]: refers to extensions.${EXT}.variants[3], but the file has 3`,
    ],
    [
      'a variant index not an integer',
      NAMES,
      [[{ material: 1, variants: ['red'] }]],
      `${P}.mappings[0].variants[0]: must be an integer index into extensions.${EXT}.variants, got the string "red"`,
    ],
    [
      'a variant listed twice in one mapping',
      NAMES,
      [[{ material: 1, variants: [0, 0] }]],
      `${P}.mappings[0].variants: lists extensions.${EXT}.variants[0] twice`,
    ],
    [
      'a variant mapped twice in one primitive',
      NAMES,
      [
        [
          { material: 1, variants: [0, 1] },
          { material: 2, variants: [1] },
        ],
      ],
      `${P}.mappings[1].variants: names variant 1, which mappings[0] of this primitive already maps`,
    ],
    [
      'mappings without root variants',
      undefined,
      [[{ material: 1, variants: [0] }]],
      `${P}.mappings[0].variants[0]: refers to extensions.${EXT}.variants[0], but the file has 0`,
    ],
  ];
  it.each(bad)('refuses %s with its JSON path', async (_what, variants, mappings, message) => {
    const bytes = file(typeof variants === 'string' ? undefined : variants, mappings, (j) => {
      if (variants === 'absent') j.extensions = { [EXT]: {} };
      if (variants === 'seven') j.extensions = { [EXT]: 7 };
      const pr = (j.meshes as Json[])[0].primitives as Json[];
      if (mappings[0] === 'absent') pr[0].extensions = { [EXT]: {} };
    });
    // Refused whether a variant is selected or not: a broken file is broken either way.
    await expect(load(bytes)).rejects.toThrow(message);
    await expect(load(bytes, { variant: 'red' })).rejects.toThrow(message);
    // Each is an error for Khronos's validator as well (checked: schema, reference or
    // KHR_MATERIALS_VARIANTS_NON_UNIQUE_VARIANT), so no valid file is refused here.
    expect(await validatorErrors(bytes)).not.toEqual([]);
  });

  it('reaches the loader from a scene’s gltf shape and from a bare model', async () => {
    const bytes = file(NAMES, MAPPINGS);
    const sceneJson = (shape: Json) => ({
      format: 'pathwise-scene/1',
      camera: { position: [0.5, 0.5, 3], target: [0.5, 0.5, 0], up: [0, 1, 0], fovY: 30 },
      settings: { width: 8, height: 8, maxBounces: 4, spp: 16 },
      materials: {},
      shapes: [{ type: 'gltf', file: 'm.gltf', ...shape }],
      environment: [1, 1, 1],
    });
    const files = new Map([['m.gltf', bytes]]);
    const triangleMaterial = (s: { shapes: unknown[] }) =>
      Array.from(
        (s.shapes[0] as { data: { triangleMaterial: Uint32Array } }).data.triangleMaterial,
      );
    expect(triangleMaterial(await sceneWithFiles(sceneJson({ variant: 'green' }), files))).toEqual([
      3, 2,
    ]);
    expect(triangleMaterial(await sceneWithFiles(sceneJson({}), files))).toEqual([0, 1]);
    await expect(sceneWithFiles(sceneJson({ variant: 'x' }), files)).rejects.toThrow(
      'shapes[0].file "m.gltf": glTF: extensions.KHR_materials_variants.variants: has no variant "x"',
    );
    expect(() => validateScene(sceneJson({ variant: 2 }))).toThrow(
      'shapes[0].variant must be a string, got 2',
    );

    const options = await memoryOptions(files);
    const bare = await loadBareModel(bytes, 'm.gltf', options.reader, { variant: 'blue' });
    expect(triangleMaterial(bare)).toEqual([3, 1]);
    expect(bare.shapes[0]).toMatchObject({ type: 'gltf', variant: 'blue' });
    const plain = await loadBareModel(bytes, 'm.gltf', options.reader);
    expect(triangleMaterial(plain)).toEqual([0, 1]);
    expect('variant' in plain.shapes[0]).toBe(false);
  });
});
