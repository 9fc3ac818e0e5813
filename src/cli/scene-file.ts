/** Reading a scene file on the command line (any subcommand that takes one). */
import { dirname } from 'node:path';
import { LIMITS, SceneError, parseScene, resolveSceneFiles, type Scene } from '../core/index.ts';
import { sceneSizeProblem } from '../core/scene/load.ts';
import { CliError } from './errors.ts';
import { ReadLimitError, readBounded, showPath } from './read-bounded.ts';
import { nodeSceneFiles } from './scene-files.ts';

/**
 * Reads and validates a scene file from any source (file, pipe, device) with the 16 MiB
 * bound on the bytes read, then the mesh and environment-map files it names (relative to
 * its folder). Every problem is a CliError naming the file.
 */
export async function loadSceneFile(path: string): Promise<Scene> {
  let bytes: Uint8Array;
  try {
    bytes = await readBounded(path, LIMITS.fileBytes);
  } catch (e) {
    if (e instanceof ReadLimitError) {
      throw new CliError(`${showPath(path)}: ${sceneSizeProblem(e.size, e.exact)}`);
    }
    throw e;
  }
  try {
    return await resolveSceneFiles(parseScene(bytes), nodeSceneFiles(dirname(path)));
  } catch (e) {
    if (e instanceof SceneError) throw new CliError(`${showPath(path)}: ${e.message}`);
    throw e;
  }
}
