/**
 * What loading glTF needs in Node: files read from disk relative to the
 * scene (bounded), the pure-JS image decoders, and MikkTSpace from the
 * `mikktspace` package (its Node build loads its WebAssembly synchronously).
 */
import { readFile, stat } from 'node:fs/promises';
import { createRequire } from 'node:module';
import path from 'node:path';
import type { GltfLoadOptions } from '../core/gltf/load.ts';
import type { TangentGenerator } from '../core/gltf/tangents.ts';
import { decodeImageJs } from '../core/texture/decode-js.ts';

let mikktspace: TangentGenerator | null = null;

/** MikkTSpace (the reference C implementation compiled to WebAssembly, by glTF-Transform's author). */
export function nodeTangentGenerator(): TangentGenerator {
  if (mikktspace === null) {
    const require = createRequire(import.meta.url);
    mikktspace = (require('mikktspace') as { generateTangents: TangentGenerator }).generateTangents;
  }
  return mikktspace;
}

/** Loader options for a model whose relative paths resolve against `baseDir`. */
export function nodeGltfOptions(baseDir: string): GltfLoadOptions {
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
    generateTangents: nodeTangentGenerator(),
  };
}
