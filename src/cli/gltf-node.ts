/**
 * What loading glTF needs in Node: files read from disk relative to the
 * scene (bounded), the pure-JS image decoders, and MikkTSpace from the
 * `mikktspace` package (its Node build loads its WebAssembly synchronously).
 */
import { readFile, stat } from 'node:fs/promises';
import { createRequire } from 'node:module';
import path from 'node:path';
import type { GltfLoadOptions } from '../core/gltf/load.ts';
import { createMikkTSpace } from '../core/gltf/mikktspace-wasm.ts';
import type { TangentGenerator } from '../core/gltf/tangents.ts';
import { decodeImageJs } from '../core/texture/decode-js.ts';

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

/** Loader options for a model whose relative paths resolve against `baseDir`. */
export async function nodeGltfOptions(baseDir: string): Promise<GltfLoadOptions> {
  return {
    reader: {
      async read(file: string, maxBytes: number): Promise<Uint8Array> {
        const full = path.resolve(baseDir, file);
        const size = (await stat(full)).size;
        if (size > maxBytes)
          throw new Error(`file is ${size} bytes, over the limit of ${maxBytes}`);
        return new Uint8Array(await readFile(full));
      },
    },
    decodeImage: decodeImageJs,
    generateTangents: await nodeTangentGenerator(),
  };
}
