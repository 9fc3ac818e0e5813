/**
 * What loading glTF needs in Node: files read from disk relative to the
 * scene (bounded, kept inside its folder: scene-files.ts), the pure-JS image decoders, and MikkTSpace from the
 * `mikktspace` package (its Node build loads its WebAssembly synchronously).
 */
import { readFile } from 'node:fs/promises';
import { createRequire } from 'node:module';
import type { GltfLoadOptions } from '../core/gltf/load.ts';
import { createMikkTSpace } from '../core/gltf/mikktspace-wasm.ts';
import type { TangentGenerator } from '../core/gltf/tangents.ts';
import { decodeImageJs } from '../core/texture/decode-js.ts';
import { nodeSceneFiles } from './scene-files.ts';

let mikktspace: Promise<TangentGenerator> | null = null;

/**
 * MikkTSpace: the `mikktspace` package's WebAssembly (the reference C
 * implementation) through the core's own loader, as in the browser.
 */
export function nodeTangentGenerator(): Promise<TangentGenerator> {
  if (mikktspace === null) {
    const require = createRequire(import.meta.url);
    const file = require.resolve('mikktspace/dist/module/mikktspace_module_bg.wasm');
    mikktspace = readFile(file).then((b) => createMikkTSpace(new Uint8Array(b)));
  }
  return mikktspace;
}

/**
 * Loader options for a model whose relative paths resolve against `baseDir`, read as
 * the command line reads a scene's files: inside that folder (or `allowRead`), bounded.
 */
export async function nodeGltfOptions(
  baseDir: string,
  allowRead: readonly string[] = [],
): Promise<GltfLoadOptions> {
  return {
    reader: nodeSceneFiles(baseDir, { allowRead }),
    decodeImage: decodeImageJs,
    generateTangents: await nodeTangentGenerator(),
  };
}
