/**
 * The files a scene names (mesh `.obj` / `.ply`, environment `.hdr` / `.pfm`), read
 * through an injected `SceneFileReader` so the core needs neither `fs` nor the DOM: the
 * command line reads paths relative to the scene file, the browser fetches URLs relative
 * to the scene's URL or takes files dropped together with the scene.
 *
 * Every failure becomes one SceneError naming the shape (or `environment`), the file and,
 * inside the file, the line or element. Limits are checked before anything is allocated
 * for them: the reader refuses a file over its byte limit, the parsers count triangles
 * and check image sizes before they allocate.
 */
import { buildMeshData } from '../../geometry/mesh-data.ts';
import { GLTF_FILE_BYTES, type GltfStage, loadGltf } from '../../gltf/load.ts';
import type { GltfDecoders, TangentGenerator } from '../format/gltf-model.ts';
import { decodeImageJs } from '../../texture/decode-js.ts';
import type { ImageDecoder } from '../../texture/decoded-image.ts';
import { decodeHdr } from '../../io/hdr.ts';
import { parseObj } from '../../io/obj.ts';
import { decodePfm } from '../../io/pfm.ts';
import { parsePly } from '../../io/ply.ts';
import { envMapFileKind } from '../validate/environment-desc.ts';
import { sceneRangeProblem } from '../validate/extent.ts';
import { sanitize } from '../../util/message.ts';
import { checkTexelRadiance } from '../validate/radiance.ts';
import { SceneError, markValidated, parseScene } from '../validate/validate.ts';
import { meshFileKind } from '../validate/mesh-desc.ts';
import { sceneNeedsFiles } from '../validate/needs-files.ts';
import {
  LIMITS,
  type EnvironmentImage,
  type EnvironmentMapDesc,
  type Scene,
} from '../format/types.ts';
import { describe } from '../validate/validate-helpers.ts';

export interface SceneFileReader {
  /**
   * The bytes of `path`, as written in the scene (relative to the scene file). Rejects,
   * without reading it whole, a file longer than `maxBytes`, and any file it cannot
   * read, with an Error whose message says why in one line (the caller adds the path).
   */
  read(path: string, maxBytes: number): Promise<Uint8Array>;
  /** Folders beyond the scene's whose files a glTF model may name (GltfFileReader). */
  readonly allowedFolders?: readonly string[];
}

/**
 * Stages of loading a scene, for progress reports: reading files, parsing a glTF,
 * decoding its textures, flattening its geometry; `compile` (the BVH) follows in the
 * caller (compile.ts).
 */
export type LoadStage = 'read' | GltfStage | 'compile';

/** What loading glTF models needs from the platform, and where progress goes. */
export interface ResolveOptions {
  /** PNG/JPEG decoder; default the pure-JavaScript one (decode-js.ts). */
  decodeImage?: ImageDecoder;
  /** MikkTSpace for normal-mapped primitives without tangents; without it such normal maps are ignored (with a warning). */
  generateTangents?: TangentGenerator | null;
  /** Lazy decoders of compressed glTF data (meshopt, Draco, WebP, KTX2), each loaded only when a model uses it; without one, such data is not read. */
  decoders?: GltfDecoders;
  /** Texels in a SharedArrayBuffer where the platform has one. */
  sharedTextures?: boolean;
  onProgress?: (stage: LoadStage, done: number, total: number) => void;
}

export { sceneNeedsFiles };

/** Parses a scene and reads every file it names. Throws SceneError. */
export async function loadScene(
  text: string,
  files: SceneFileReader | null,
  options: ResolveOptions = {},
): Promise<Scene> {
  return resolveSceneFiles(parseScene(text), files, options);
}

/**
 * A copy of `scene` with every mesh file and environment map read and decoded. A scene
 * that names no files comes back as it is. Throws SceneError.
 */
export async function resolveSceneFiles(
  scene: Scene,
  files: SceneFileReader | null,
  options: ResolveOptions = {},
): Promise<Scene> {
  if (!sceneNeedsFiles(scene)) return scene;
  const progress = options.onProgress ?? (() => {});
  const shapes = scene.shapes.slice();
  let triangles = 0;
  for (const s of shapes) {
    if ((s.type === 'mesh' || s.type === 'gltf') && s.data !== null)
      triangles += s.data.indices.length / 3 + s.data.skipped;
  }
  for (let i = 0; i < shapes.length; i++) {
    const shape = shapes[i];
    if (shape.type === 'gltf' && shape.data === null) {
      const where = `shapes[${i}].file ${describe(shape.file)}`;
      progress('read', 0, 1);
      const bytes = await readFile(files, shape.file, GLTF_FILE_BYTES, where);
      progress('read', 1, 1);
      let data;
      try {
        data = await loadGltf(bytes, shape.file, {
          reader: files,
          decodeImage: options.decodeImage ?? decodeImageJs,
          generateTangents: options.generateTangents ?? null,
          decoders: options.decoders,
          transform: shape.transform,
          variant: shape.variant ?? null,
          sharedTextures: options.sharedTextures,
          maxTriangles: LIMITS.triangles - triangles,
          onProgress: progress,
        });
      } catch (e) {
        throw new SceneError([`${where}: ${oneLine(e)}`]);
      }
      triangles += data.indices.length / 3 + data.skipped;
      shapes[i] = { ...shape, data };
      continue;
    }
    if (shape.type !== 'mesh' || shape.data !== null) continue;
    const file = shape.file!;
    const where = `shapes[${i}].file ${describe(file)}`;
    progress('read', 0, 1);
    const bytes = await readFile(files, file, LIMITS.meshFileBytes, where);
    progress('read', 1, 1);
    const limits = {
      maxTriangles: LIMITS.triangles - triangles,
      sceneTriangles: LIMITS.triangles,
    };
    const data = decode(where, () => {
      const raw = meshFileKind(file) === 'ply' ? parsePly(bytes, limits) : parseObj(bytes, limits);
      return buildMeshData(raw, shape.transform);
    });
    triangles += data.indices.length / 3 + data.skipped;
    shapes[i] = { ...shape, data };
  }
  let environmentMap = scene.environmentMap ?? null;
  if (environmentMap !== null && environmentMap.image === null) {
    const map = environmentMap;
    const where = `environment.file ${describe(map.file)}`;
    progress('read', 0, 1);
    const bytes = await readFile(files, map.file, envMapByteLimit(map.file), where);
    const image = decodeEnvironmentImage(bytes, map, where);
    environmentMap = { ...map, image };
  }
  const loaded: Scene = { ...scene, shapes, environmentMap };
  const range = sceneRangeProblem(loaded);
  if (range !== undefined) throw new SceneError([range]);
  return markValidated(loaded);
}

/**
 * The largest file an environment map within the size limit can be: a flat HDR (4 bytes
 * per texel) or a colour PFM (12), plus room for a header.
 */
function envMapByteLimit(file: string): number {
  const texels = LIMITS.envMapWidth * LIMITS.envMapHeight;
  return (envMapFileKind(file) === 'pfm' ? 12 : 4) * texels + (1 << 16);
}

async function readFile(
  files: SceneFileReader | null,
  path: string,
  maxBytes: number,
  where: string,
): Promise<Uint8Array> {
  if (files === null) {
    throw new SceneError([
      `${where}: this scene names files, but it was given without a way to read them ` +
        '(load it from a file or URL, or drop its files together with it)',
    ]);
  }
  try {
    return await files.read(path, maxBytes);
  } catch (e) {
    throw new SceneError([`${where}: ${oneLine(e)}`]);
  }
}

function decode<T>(where: string, f: () => T): T {
  try {
    return f();
  } catch (e) {
    // Format and mesh problems are expected; anything else (say, memory) is reported
    // the same way rather than escaping as a crash.
    if (e instanceof SceneError) throw e;
    throw new SceneError([`${where}: ${oneLine(e)}`]);
  }
}

/** The message of an error from a reader or decoder, as one printable line. */
function oneLine(e: unknown): string {
  return sanitize(e instanceof Error ? e.message : String(e), 400);
}

/**
 * Decodes an environment map and checks every texel (radiance.ts): finite, non-negative,
 * and at most the radiance bound once multiplied by the map's scale. Throws SceneError.
 */
export function decodeEnvironmentImage(
  bytes: Uint8Array,
  map: Pick<EnvironmentMapDesc, 'file' | 'scale'>,
  where: string,
): EnvironmentImage {
  const limits = { maxWidth: LIMITS.envMapWidth, maxHeight: LIMITS.envMapHeight };
  const image = decode(where, () =>
    envMapFileKind(map.file) === 'pfm'
      ? decodePfm(bytes, { ...limits, allowNonFinite: true })
      : decodeHdr(bytes, limits),
  );
  const problems: string[] = [];
  if (!checkTexelRadiance(image.rgb, image.width, map.scale, where, problems)) {
    throw new SceneError(problems);
  }
  return image;
}
