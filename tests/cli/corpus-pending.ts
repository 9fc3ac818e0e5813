/**
 * What the corpus models (tests/corpus/corpus.json) are *currently* expected to say,
 * shared by tests/cli/corpus.test.ts and tests/browser/corpus-widget.test.ts.
 *
 * PENDING lists, per model, every message a render prints today that says something
 * the model uses is ignored or not supported (or the one error that refuses the file).
 * The tests fail when a model prints a message not listed here, and also when a listed
 * message no longer appears: as decoders and extensions land, their entries are
 * removed, until the table is empty and every model renders with nothing ignored.
 * First filled on the branch `corpus` (main at 142dd49, before any issue-25 feature
 * was merged); updated after the meshopt/Draco, punctual-light and clearcoat/sheen/
 * unlit/specular–glossiness merges. What remains waits for the branches texdec (WebP,
 * KTX2), volume, spec (iridescence, anisotropy) and instancing.
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
    'extension "KHR_materials_anisotropy" is not supported; its content is ignored',
    'extension "KHR_materials_volume" is not supported; its content is ignored',
    'extension "KHR_texture_basisu" is not supported; its content is ignored',
    'images[2] (materials[0].baseColorTexture): a KTX2 image is not PNG or JPEG; the texture is ignored',
    'images[1] (materials[0].metallicRoughnessTexture): a KTX2 image is not PNG or JPEG; the texture is ignored',
    'images[0] (materials[0].normalTexture): a KTX2 image is not PNG or JPEG; the texture is ignored',
  ],
  AnisotropyRotationTest: [
    'extension "KHR_materials_anisotropy" is not supported; its content is ignored',
  ],
  AnisotropyStrengthTest: [
    'extension "KHR_materials_anisotropy" is not supported; its content is ignored',
  ],
  AttenuationTest: ['extension "KHR_materials_volume" is not supported; its content is ignored'],
  GlamVelvetSofa: ['extension "KHR_materials_variants" is not supported; its content is ignored'],
  IridescenceSuzanne: [
    'error: glTF: extensionsRequired: the file requires "KHR_materials_iridescence", which pathwise does not support',
  ],
  SimpleInstancing: [
    'extension "EXT_mesh_gpu_instancing" is not supported; its content is ignored',
  ],
  TransmissionRoughnessTest: [
    'extension "KHR_materials_volume" is not supported; its content is ignored',
  ],
  DispersionTest: [
    'extension "KHR_materials_dispersion" is not supported; its content is ignored',
    'extension "KHR_materials_volume" is not supported; its content is ignored',
  ],
  bath_day: [
    'error: glTF: extensionsRequired: the file requires "EXT_texture_webp", which pathwise does not support',
  ],
  minimalistic_modern_bedroom: [
    'accessors[2] (POSITION): vertex 4796 has z = 1.806264877319336, outside the declared min -1.806157112121582 and max 1.806156873703003; the bounds are taken from the vertices',
    'accessors[6] (POSITION): vertex 1099 has x = 0.35703590512275696, outside the declared min -0.3572944104671478 and max 0.3570345640182495; the bounds are taken from the vertices',
    'accessors[10] (POSITION): vertex 14 has z = -0.9893454313278198, outside the declared min -1.0093629360198975 and max -0.9893723130226135; the bounds are taken from the vertices',
    'note: skipped 7 triangles of zero area',
  ],
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
