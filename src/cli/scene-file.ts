/** Reading a scene file on the command line (any subcommand that takes one). */
import { basename, dirname } from 'node:path';
// Only what every scene needs is imported statically: the glTF loader (glTF-Transform,
// image decoders, MikkTSpace; most of the command line's code) is imported when a scene
// names a model, so a scene of spheres and quads starts without compiling it.
import { GLTF_FILE_BYTES, isModelFileName } from '../core/gltf/file-names.ts';
import { SceneError, parseScene, sceneSizeProblem } from '../core/scene/validate/validate.ts';
import { sceneNeedsFiles } from '../core/scene/validate/needs-files.ts';
import { LIMITS, type Scene } from '../core/scene/format/types.ts';
import { CliError } from './errors.ts';
import { ReadLimitError, readBounded, showPath } from './read-bounded.ts';
import { nodeSceneFiles } from './scene-files.ts';
import { testStage } from './test-stages.ts';
import type { BareModelChoices } from '../core/scene/load/bare-scene.ts';

export interface SceneFileOptions {
  /** Image size asked for on the command line: a bare model's camera frames it at this aspect. */
  width?: number;
  height?: number;
  /** Folders beyond the scene's whose files may be read (`--allow-read`; scene-files.ts). */
  allowRead?: readonly string[];
  /**
   * A bare model's choices (`--environment`, `--variant`); a scene file sets its own
   * environment and names a variant per shape, so it refuses them.
   */
  bare?: BareModelChoices;
}

/**
 * Reads and validates a scene file from any source (file, pipe, device) with the 16 MiB
 * bound on the bytes read, then the mesh, glTF and environment-map files it names
 * (relative to its folder, and inside it or an `allowRead` folder). A `.glb` or `.gltf` is a bare model: it gets a scene of its
 * own (core/scene/load/bare-scene.ts). Every problem is a CliError naming the file.
 */
export async function loadSceneFile(path: string, options: SceneFileOptions = {}): Promise<Scene> {
  const model = isModelFileName(path);
  const limit = model ? GLTF_FILE_BYTES : LIMITS.fileBytes;
  let bytes: Uint8Array;
  try {
    testStage('read');
    bytes = await readBounded(path, limit);
  } catch (e) {
    if (e instanceof ReadLimitError && !model) {
      throw new CliError(`${showPath(path)}: ${sceneSizeProblem(e.size, e.exact)}`);
    }
    throw e;
  }
  try {
    const files = nodeSceneFiles(dirname(path), { allowRead: options.allowRead });
    // MikkTSpace's WebAssembly is read only for glTF: a scene of spheres,
    // quads and meshes needs nothing beyond the bundle itself.
    const tangents = async () => {
      const { nodeGltfDecoders, nodeTangentGenerator } = await import('./gltf-node.ts');
      return { generateTangents: await nodeTangentGenerator(), decoders: nodeGltfDecoders() };
    };
    if (model) {
      testStage('load');
      const { loadBareModel } = await import('../core/scene/load/bare-scene.ts');
      return await loadBareModel(bytes, basename(path), files, {
        ...(await tangents()),
        width: options.width,
        height: options.height,
        ...options.bare,
      });
    }
    if (options.bare?.environment !== undefined) {
      throw new CliError(
        `${showPath(path)}: --environment applies to a glTF model; a scene file sets its own environment`,
      );
    }
    if (options.bare?.variant !== undefined) {
      throw new CliError(
        `${showPath(path)}: --variant applies to a glTF model; in a scene file, a gltf shape names its own variant`,
      );
    }
    testStage('parse');
    const scene = parseScene(bytes);
    if (!sceneNeedsFiles(scene)) return scene;
    testStage('load');
    const { resolveSceneFiles } = await import('../core/scene/load/load.ts');
    const gltf = scene.shapes.some((s) => s.type === 'gltf');
    return await resolveSceneFiles(scene, files, gltf ? await tangents() : {});
  } catch (e) {
    if (e instanceof SceneError) throw new CliError(`${showPath(path)}: ${e.message}`);
    throw e;
  }
}
