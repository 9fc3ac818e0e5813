/** Reading a scene file on the command line (any subcommand that takes one). */
import { basename, dirname } from 'node:path';
import {
  LIMITS,
  SceneError,
  isModelFileName,
  loadBareModel,
  parseScene,
  resolveSceneFiles,
  type Scene,
} from '../core/index.ts';
import { GLTF_FILE_BYTES } from '../core/gltf/load.ts';
import { sceneSizeProblem } from '../core/scene/load.ts';
import { CliError } from './errors.ts';
import { nodeTangentGenerator } from './gltf-node.ts';
import { ReadLimitError, readBounded, showPath } from './read-bounded.ts';
import { nodeSceneFiles } from './scene-files.ts';

export interface SceneFileOptions {
  /** Image size asked for on the command line: a bare model's camera frames it at this aspect. */
  width?: number;
  height?: number;
}

/**
 * Reads and validates a scene file from any source (file, pipe, device) with the 16 MiB
 * bound on the bytes read, then the mesh, glTF and environment-map files it names
 * (relative to its folder). A `.glb` or `.gltf` is a bare model: it gets a scene of its
 * own (core/gltf/bare-scene.ts). Every problem is a CliError naming the file.
 */
export async function loadSceneFile(path: string, options: SceneFileOptions = {}): Promise<Scene> {
  const model = isModelFileName(path);
  const limit = model ? GLTF_FILE_BYTES : LIMITS.fileBytes;
  let bytes: Uint8Array;
  try {
    bytes = await readBounded(path, limit);
  } catch (e) {
    if (e instanceof ReadLimitError && !model) {
      throw new CliError(`${showPath(path)}: ${sceneSizeProblem(e.size, e.exact)}`);
    }
    throw e;
  }
  try {
    const files = nodeSceneFiles(dirname(path));
    // MikkTSpace's WebAssembly is read only for glTF: a scene of spheres,
    // quads and meshes needs nothing beyond the bundle itself.
    const tangents = async () => ({ generateTangents: await nodeTangentGenerator() });
    if (model) {
      return await loadBareModel(bytes, basename(path), files, {
        ...(await tangents()),
        ...options,
      });
    }
    const scene = parseScene(bytes);
    const gltf = scene.shapes.some((s) => s.type === 'gltf');
    return await resolveSceneFiles(scene, files, gltf ? await tangents() : {});
  } catch (e) {
    if (e instanceof SceneError) throw new CliError(`${showPath(path)}: ${e.message}`);
    throw e;
  }
}
