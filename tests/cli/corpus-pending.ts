/**
 * What the corpus models (tests/corpus/corpus.json) are *currently* expected to say,
 * shared by tests/cli/corpus.test.ts and tests/browser/corpus-widget.test.ts.
 *
 * PENDING lists, per model, every message a render prints today that says something
 * the model uses is ignored or not supported (or the one error that refuses the file).
 * The tests fail when a model prints a message not listed here, and also when a listed
 * message no longer appears: as decoders and extensions land, their entries are
 * removed, until the table is empty and every model renders with nothing ignored.
 * Filled from the run of `node scripts/corpus.mjs` on the branch `corpus` (main at
 * 142dd49, before any issue-25 feature was merged).
 */

/** A note that a still image rightly ignores: the rest pose of an animated model. */
export const REST_POSE = /rendered in its rest pose$/;

const ignored = (ext: string) => `extension "${ext}" is not supported; its content is ignored`;
const requires = (ext: string) =>
  `error: glTF: extensionsRequired: the file requires "${ext}", which pathwise does not support`;
const ktx2 = (image: number, slot: string) =>
  `images[${image}] (materials[0].${slot}): a KTX2 image is not PNG or JPEG; the texture is ignored`;

export const PENDING: Record<string, string[]> = {
  'AnisotropyBarnLamp-KTX2': [
    ignored('KHR_materials_anisotropy'),
    ignored('KHR_materials_clearcoat'),
    ignored('KHR_materials_volume'),
    ignored('KHR_texture_basisu'),
    ktx2(2, 'baseColorTexture'),
    ktx2(1, 'metallicRoughnessTexture'),
    ktx2(0, 'normalTexture'),
  ],
  AnisotropyRotationTest: [ignored('KHR_materials_anisotropy')],
  AnisotropyStrengthTest: [ignored('KHR_materials_anisotropy')],
  AttenuationTest: [ignored('KHR_materials_volume')],
  'Box-Draco': [requires('KHR_draco_mesh_compression')],
  'CesiumMan-Draco': [requires('KHR_draco_mesh_compression')],
  'CesiumMilkTruck-Draco': [requires('KHR_draco_mesh_compression')],
  ClearCoatCarPaint: [requires('KHR_materials_clearcoat')],
  ClearCoatTest: [ignored('KHR_materials_clearcoat')],
  GlamVelvetSofa: [
    ignored('KHR_materials_sheen'),
    ignored('KHR_materials_variants'),
    ignored('KHR_lights_punctual'),
  ],
  IridescenceSuzanne: [requires('KHR_materials_iridescence')],
  LightsPunctualLamp: [ignored('KHR_lights_punctual')],
  'MorphPrimitivesTest-Draco': [requires('KHR_draco_mesh_compression')],
  'RiggedFigure-Draco': [requires('KHR_draco_mesh_compression')],
  'RiggedSimple-Draco': [requires('KHR_draco_mesh_compression')],
  SimpleInstancing: [ignored('EXT_mesh_gpu_instancing')],
  TextureTransformMultiTest: [ignored('KHR_materials_unlit'), ignored('KHR_materials_clearcoat')],
  TransmissionRoughnessTest: [ignored('KHR_materials_volume')],
  UnlitTest: [requires('KHR_materials_unlit')],
  BoxMeshopt: [requires('EXT_meshopt_compression')],
  'BoxTextured-SpecGloss': [ignored('KHR_materials_pbrSpecularGlossiness')],
  DracoSparseMesh: [requires('KHR_draco_mesh_compression')],
  pirate: [requires('EXT_meshopt_compression')],
  DispersionTest: [ignored('KHR_materials_dispersion'), ignored('KHR_materials_volume')],
  bath_day: [requires('EXT_texture_webp')],
  minimalistic_modern_bedroom: [requires('KHR_draco_mesh_compression')],
};

/**
 * The pathwise CLI's standard error as messages: without "pathwise: ", without the
 * "note: shapes[i] (FILE): " of a note, and with the model's path of an error replaced
 * by "error:". Rest-pose notes are dropped (they are not ignored extensions).
 */
export function cliMessages(stderr: string, path: string): string[] {
  const out: string[] = [];
  for (const line of stderr.split('\n')) {
    if (!line.startsWith('pathwise: ')) continue;
    let m = line.slice('pathwise: '.length);
    const note = /^note: shapes\[\d+\] \([^)]*\): (.*)$/.exec(m);
    if (note) m = note[1];
    else if (m.startsWith(`${path}: `)) m = `error: ${m.slice(path.length + 2)}`;
    if (!REST_POSE.test(m)) out.push(m);
  }
  return out;
}

/** The widget's warning messages (and error) in the same form. */
export function widgetMessages(warnings: string[], error: string | null): string[] {
  const out = warnings
    .map((m) => m.replace(/^shapes\[\d+\] \([^)]*\): /, ''))
    .filter((m) => !REST_POSE.test(m));
  // The widget's error names the file first ("Box.gltf: glTF: …").
  if (error) out.push(`error: ${error.replace(/^[^:]*: /, '')}`);
  return out;
}

/** Messages not listed, and listed ones that no longer appear. */
export function pendingDiff(name: string, messages: string[]) {
  const expected = PENDING[name] ?? [];
  return {
    unexpected: messages.filter((m) => !expected.includes(m)),
    gone: expected.filter((m) => !messages.includes(m)),
  };
}
