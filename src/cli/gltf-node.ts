/**
 * What loading glTF needs in Node: files read from disk relative to the
 * scene (bounded, kept inside its folder: scene-files.ts), the pure-JS image decoders, MikkTSpace from the
 * `mikktspace` package (its Node build loads its WebAssembly synchronously), and the
 * decoders of compressed meshes (meshoptimizer, draco3dgltf) and textures (libwebp, Basis
 * Universal), each loaded only when a file uses it.
 *
 * The decoder packages are reached at run time (createRequire, or `import()` of a
 * computed name), never by a literal import: esbuild then leaves them out of
 * dist/cli, which keeps its size and the start-up of plain files as they were, and
 * their WebAssembly is read from the installed package (or vendor/basis/) and
 * handed over as bytes or a WebAssembly.Module, so nothing is fetched.
 */
import { readFile } from 'node:fs/promises';
import { createRequire } from 'node:module';
import type { GltfLoadOptions } from '../core/gltf/load.ts';
import type {
  DracoDecoderModule,
  GltfDecoders,
  MeshoptDecoderLike,
  WebpDecoder,
} from '../core/scene/format/gltf-model.ts';
import { createMikkTSpace } from '../core/gltf/mikktspace-wasm.ts';
import type { TangentGenerator } from '../core/gltf/tangents.ts';
import { decodeImageJs } from '../core/texture/decode-js.ts';
import {
  basisKtx2Transcoder,
  type BasisModule,
  type Ktx2ContainerReader,
  type Ktx2Transcoder,
} from '../core/texture/ktx2-transcode.ts';
import { nodeSceneFiles } from './scene-files.ts';
import { vendorFolder } from './vendor-folder.ts';

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
 * The decoders of compressed meshes and textures, as lazy getters. Both packages are reached
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
    webp: nodeWebpDecoder,
    ktx2: nodeKtx2Transcoder,
  };
}

/** An ES module by a name esbuild does not see (so it stays out of the bundle). */
function importAtRunTime<T>(name: string): Promise<T> {
  return import(/* @vite-ignore */ name) as Promise<T>;
}

interface JsquashWebp {
  init(module: WebAssembly.Module): Promise<void>;
  default(buffer: ArrayBuffer): Promise<{ width: number; height: number; data: Uint8ClampedArray }>;
}

let webp: Promise<WebpDecoder> | null = null;

/** libwebp (`@jsquash/webp`, Apache-2.0; libwebp BSD-3-Clause), loaded once. */
export function nodeWebpDecoder(): Promise<WebpDecoder> {
  webp ??= (async () => {
    const require = createRequire(import.meta.url);
    const wasm = await readFile(require.resolve('@jsquash/webp/codec/dec/webp_dec.wasm'));
    const codec = await importAtRunTime<JsquashWebp>('@jsquash/webp/decode.js');
    await codec.init(new WebAssembly.Module(wasm));
    return async (bytes: Uint8Array) => {
      // The codec takes an ArrayBuffer of the image alone.
      const image = await codec.default(bytes.slice().buffer);
      return { width: image.width, height: image.height, data: image.data, channels: 4, depth: 8 };
    };
  })();
  return webp;
}

let ktx2: Promise<Ktx2Transcoder> | null = null;

/**
 * The Basis Universal transcoder (vendor/basis/, Apache-2.0, Binomial LLC; from
 * three.js) and ktx-parse's container reader, loaded once.
 */
export function nodeKtx2Transcoder(): Promise<Ktx2Transcoder> {
  ktx2 ??= (async () => {
    const folder = vendorFolder('basis', 'basis_transcoder.wasm');
    const require = createRequire(import.meta.url);
    const factory = require(folder + 'basis_transcoder.js') as (options: {
      wasmBinary: Uint8Array;
    }) => Promise<BasisModule & { initializeBasis(): void }>;
    const basis = await factory({
      wasmBinary: new Uint8Array(await readFile(folder + 'basis_transcoder.wasm')),
    });
    basis.initializeBasis();
    const { read } = await importAtRunTime<{ read: Ktx2ContainerReader }>('ktx-parse');
    return basisKtx2Transcoder(basis, read);
  })();
  return ktx2;
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
