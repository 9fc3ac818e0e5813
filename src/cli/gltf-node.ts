/**
 * What loading glTF needs in Node: files read from disk relative to the
 * scene (bounded, kept inside its folder: scene-files.ts), the pure-JS image decoders, MikkTSpace from the
 * `mikktspace` package (its Node build loads its WebAssembly synchronously), and the
 * decoders of compressed meshes (meshoptimizer, draco3dgltf), loaded only when a file
 * uses them.
 */
import { readFile } from 'node:fs/promises';
import { createRequire } from 'node:module';
import type { GltfDecoders, GltfLoadOptions } from '../core/gltf/load.ts';
import type { DracoDecoderModule, MeshoptDecoderLike } from '../core/scene/format/gltf-model.ts';
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

let meshopt: Promise<MeshoptDecoderLike> | null = null;
let draco: Promise<DracoDecoderModule> | null = null;

/**
 * The decoders of compressed meshes, as lazy getters. Both packages are reached
 * through `createRequire` at run time, never bundled by esbuild: the CLI bundle stays
 * as it was, and neither module is evaluated (meshopt instantiates its WebAssembly on
 * import) unless a file needs it. Draco's Emscripten glue cannot be bundled at all
 * (its `require("fs")` fails in an ES module bundle), and its WebAssembly is read here
 * and handed over, as MikkTSpace's is.
 */
export function nodeGltfDecoders(): GltfDecoders {
  return {
    meshopt() {
      meshopt ??= (async () => {
        const require = createRequire(import.meta.url);
        // The CommonJS build exports the decoder itself (module.exports = MeshoptDecoder).
        const MeshoptDecoder = require('meshoptimizer/decoder.cjs') as MeshoptDecoderLike;
        await MeshoptDecoder.ready;
        return MeshoptDecoder;
      })();
      return meshopt;
    },
    draco() {
      draco ??= (async () => {
        const require = createRequire(import.meta.url);
        const create = require('draco3dgltf/draco_decoder_gltf_nodejs.js') as (options: {
          wasmBinary: Uint8Array;
        }) => Promise<DracoDecoderModule>;
        const wasm = await readFile(require.resolve('draco3dgltf/draco_decoder_gltf.wasm'));
        return create({ wasmBinary: new Uint8Array(wasm) });
      })();
      return draco;
    },
  };
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
    decoders: nodeGltfDecoders(),
  };
}
