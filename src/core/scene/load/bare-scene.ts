/**
 * A bare glTF model (a `.glb` or `.gltf` given to the command line, the widget or the
 * demo without a scene file) as a scene of pathwise-scene/1: the model as its one
 * `gltf` shape, a camera from the file's first perspective camera or framing its
 * bounds (framing.ts) at the image's aspect ratio, the studio environment
 * (lights/studio.ts) unless `environment` is 'none', and the format's default settings.
 * The model's punctual lights come with its shape (GltfModel.lights), whatever the
 * environment: a model with one weak lamp still shows in the studio.
 */
import { type BareEnvironment, studioEnvironment } from '../../lights/studio.ts';
import { type LoadStage, type ResolveOptions, type SceneFileReader } from './load.ts';
import { markValidated, SceneError } from '../validate/validate.ts';
import { DEFAULT_SETTINGS, LIMITS, type Scene } from '../format/types.ts';
import { sanitize } from '../../util/message.ts';
import { sceneRangeProblem } from '../validate/extent.ts';
import { frameModel } from './framing.ts';
import { isGlb } from '../../gltf/glb.ts';
import { GLTF_FILE_BYTES, type GltfModel, loadGltf } from '../../gltf/load.ts';
import { decodeImageJs } from '../../texture/decode-js.ts';

export { isModelFileName } from '../../gltf/file-names.ts';

/** Whether bytes are a GLB file (its magic), whatever the name they came with. */
export function isGlbBytes(bytes: Uint8Array): boolean {
  return isGlb(bytes);
}

/**
 * What a user chooses for a bare model, declared once here: the command line
 * (`--environment`, `--variant`), the view's options and the widget's attributes hold
 * one, and pass it whole to the model worker and to loadBareModel.
 */
export interface BareModelChoices {
  /**
   * The environment: the studio (the default), or none, to see only the model's own
   * lights (KHR_lights_punctual, emissive materials). The command line's `--environment`.
   */
  environment?: BareEnvironment;
  /**
   * The model's KHR_materials_variants variant, by name (gltf/variants.ts); absent: its
   * default materials. The command line's `--variant`, the widget's `variant` attribute.
   */
  variant?: string;
}

/** The bare-model choices among a larger set of options (the view's), as one record. */
export function bareChoices(options: BareModelChoices): BareModelChoices {
  return { environment: options.environment, variant: options.variant };
}

export interface BareSceneOptions extends BareModelChoices {
  /** Image size; the format's defaults (512 × 512) when absent. */
  width?: number;
  height?: number;
}

/** The scene of a loaded model (`file`: its name, for the shape and the scene's name). */
export function bareModelScene(
  file: string,
  model: GltfModel,
  options: BareSceneOptions = {},
): Scene {
  const width = options.width ?? DEFAULT_SETTINGS.width;
  const height = options.height ?? DEFAULT_SETTINGS.height;
  const name = file.replace(/[?#].*$/, '').replace(/^.*[\\/]/, '');
  return markValidated({
    format: 'pathwise-scene/1',
    name,
    camera: frameModel(model.bounds, model.cameras, width / height),
    settings: { ...DEFAULT_SETTINGS, width, height },
    materials: {},
    shapes: [
      {
        type: 'gltf',
        file,
        transform: null,
        ...(options.variant !== undefined && { variant: options.variant }),
        data: model,
      },
    ],
    environment: [0, 0, 0],
    environmentMap: options.environment === 'none' ? null : studioEnvironment(),
  });
}

/**
 * Loads the model in `bytes` (the file `file`; its buffers and images are read through
 * `files`, relative to it) and makes its scene. Throws SceneError, whose message the
 * caller prefixes with the file's name as it knows it (a path, a URL).
 */
export async function loadBareModel(
  bytes: Uint8Array,
  file: string,
  files: SceneFileReader | null,
  options: ResolveOptions & BareSceneOptions = {},
): Promise<Scene> {
  const progress = options.onProgress ?? ((_s: LoadStage, _d: number, _t: number) => {});
  if (bytes.length > GLTF_FILE_BYTES) {
    throw new SceneError([
      `the file has ${bytes.length} bytes, more than the limit of ${GLTF_FILE_BYTES}`,
    ]);
  }
  let model: GltfModel;
  try {
    model = await loadGltf(bytes, file, {
      reader: files,
      decodeImage: options.decodeImage ?? decodeImageJs,
      generateTangents: options.generateTangents ?? null,
      decoders: options.decoders,
      sharedTextures: options.sharedTextures,
      maxTriangles: LIMITS.triangles,
      variant: options.variant ?? null,
      onProgress: progress,
    });
  } catch (e) {
    const message = e instanceof Error ? e.message : String(e);
    throw new SceneError([sanitize(message, 400)]);
  }
  const scene = bareModelScene(file, model, options);
  const range = sceneRangeProblem(scene, () => 'the model');
  if (range !== undefined) throw new SceneError([range]);
  return scene;
}
