/// <reference path="./draco-glue.d.ts" />
/**
 * What loading glTF needs in the browser (page or worker): images decoded by
 * the platform's createImageBitmap (no colour-space conversion, no
 * premultiplication, so the texels are the file's sRGB codes that the core
 * converts to linear once), WebP included, MikkTSpace's WebAssembly fetched from the
 * bundle's assets, and the Basis Universal transcoder (ktx2-browser.ts), loaded only
 * when a file has a KTX2 texture.
 */
import mikktspaceWasmUrl from 'mikktspace/dist/module/mikktspace_module_bg.wasm?url';
// Deep imports: these are the browser host's own tools, not part of the core's public
// entries (whose published declarations a consumer compiles).
import { createMikkTSpace } from '../../src/core/gltf/mikktspace-wasm.ts';
import type {
  DracoDecoderModule,
  GltfDecoders,
  MeshoptDecoderLike,
  TangentGenerator,
} from '../../src/core/scene/format/gltf-model.ts';
import { DEFAULT_MAX_TEXELS, type DecodedImage } from '../../src/core/texture/decoded-image.ts';
import { imageDecodeError, libraryMessage } from '../../src/core/texture/image-error.ts';
import { notPngOrJpeg, sniffImageType } from '../../src/core/texture/image-header.ts';
import { checkJpeg } from '../../src/core/texture/jpeg-check.ts';
import { checkPng } from '../../src/core/texture/png-check.ts';
import type { ResolveOptions } from '../../src/core/index.ts';
import { decodeImageJs } from '../../src/core/texture/decode-js.ts';

/**
 * Decodes PNG or JPEG bytes to RGBA8; falls back to the pure-JS decoders where the
 * platform cannot. The same checks as in Node run first (png-check.ts: chunks, the
 * declared size against the bytes and the budget, the image data inflated under a hard
 * limit; jpeg-check.ts: segments and the frame size against the bytes), so that a
 * lying header or a deflate bomb fails here with the same message as in the CLI
 * instead of reaching the browser's decoder; its own failures read the same way.
 */
export async function decodeImageBrowser(
  bytes: Uint8Array,
  mimeType: string,
  maxTexels = DEFAULT_MAX_TEXELS,
): Promise<DecodedImage> {
  const type = sniffImageType(bytes);
  if (type === null) throw new Error(notPngOrJpeg(bytes, mimeType));
  if (typeof createImageBitmap !== 'function' || typeof OffscreenCanvas !== 'function') {
    return decodeImageJs(bytes, mimeType, maxTexels);
  }
  try {
    if (type === 'image/png') checkPng(bytes, maxTexels);
    else checkJpeg(bytes, maxTexels);
  } catch (e) {
    throw imageDecodeError(e);
  }
  const pixels = await bitmapPixels(bytes, type, type === 'image/png' ? 'PNG' : 'JPEG');
  return pixels ?? decodeImageJs(bytes, mimeType, maxTexels);
}

/**
 * The RGBA8 texels of an image the browser decodes; null where there is no 2D context.
 * Failures read "cannot decode <format>: the browser could not decode it (…)".
 */
async function bitmapPixels(
  bytes: Uint8Array,
  type: string,
  format: string,
): Promise<DecodedImage | null> {
  const blob = new Blob([bytes as Uint8Array<ArrayBuffer>], { type });
  let bitmap: ImageBitmap;
  try {
    bitmap = await createImageBitmap(blob, {
      colorSpaceConversion: 'none',
      premultiplyAlpha: 'none',
    });
  } catch (e) {
    throw new Error(
      `cannot decode ${format}: the browser could not decode it (${libraryMessage(e)})`,
    );
  }
  try {
    const canvas = new OffscreenCanvas(bitmap.width, bitmap.height);
    const ctx = canvas.getContext('2d', { willReadFrequently: true });
    if (ctx === null) return null;
    ctx.drawImage(bitmap, 0, 0);
    const data = ctx.getImageData(0, 0, bitmap.width, bitmap.height).data;
    return { width: bitmap.width, height: bitmap.height, data, channels: 4, depth: 8 };
  } finally {
    bitmap.close();
  }
}

/**
 * WebP (EXT_texture_webp) by the browser's own decoder; the core checked the header's
 * size against the texture budget before this is called.
 */
async function decodeWebpBrowser(bytes: Uint8Array): Promise<DecodedImage> {
  const pixels = await bitmapPixels(bytes, 'image/webp', 'WebP');
  if (pixels === null) throw new Error('cannot decode WebP: no 2D canvas in this browser');
  return pixels;
}

/**
 * What the loader takes from the browser, on the page and in the scene worker alike:
 * the platform's image decoder, MikkTSpace, texels in shared memory when the workers
 * share it, and the caller's progress.
 */
export async function browserGltfPlatform(
  sharedTextures: boolean,
  onProgress: ResolveOptions['onProgress'],
): Promise<ResolveOptions> {
  return {
    decodeImage: decodeImageBrowser,
    // Without it, normal maps of primitives that have no tangents are ignored with a
    // warning (the loader says so) rather than failing the whole model.
    generateTangents: await browserTangentGenerator().catch(() => null),
    decoders: browserGltfDecoders(),
    sharedTextures,
    onProgress,
  };
}

let mikktspace: Promise<TangentGenerator> | null = null;

/** MikkTSpace, loaded once per page or worker. */
export function browserTangentGenerator(): Promise<TangentGenerator> {
  mikktspace ??= fetch(mikktspaceWasmUrl)
    .then((r) => {
      if (!r.ok) throw new Error(`cannot load MikkTSpace (${r.status} ${r.statusText})`);
      return r.arrayBuffer();
    })
    .then((b) => createMikkTSpace(new Uint8Array(b)));
  return mikktspace;
}

let meshopt: Promise<MeshoptDecoderLike> | null = null;
let draco: Promise<DracoDecoderModule> | null = null;

/**
 * The decoders of compressed meshes, loaded once per page or worker and only when a
 * model uses them: meshopt through a dynamic import (a chunk of its own: its module
 * instantiates its WebAssembly on import, which a static import would do on every
 * page), Draco's Emscripten glue likewise, with its WebAssembly fetched from the
 * bundle's assets and handed over (as MikkTSpace's is), so the glue never looks for it.
 */
export function browserGltfDecoders(): GltfDecoders {
  return {
    meshopt() {
      meshopt ??= import('meshoptimizer/decoder').then(async ({ MeshoptDecoder }) => {
        await MeshoptDecoder.ready;
        return MeshoptDecoder as MeshoptDecoderLike;
      });
      return meshopt;
    },
    draco() {
      draco ??= Promise.all([
        import('draco3dgltf/draco_decoder_gltf_nodejs.js'),
        import('./draco-wasm.ts')
          .then(({ default: url }) => fetch(url))
          .then((r) => {
            if (!r.ok)
              throw new Error(`cannot load the Draco decoder (${r.status} ${r.statusText})`);
            return r.arrayBuffer();
          }),
      ]).then(([glue, wasm]) => {
        const create = (glue.default ?? glue) as DracoFactory;
        return create({ wasmBinary: new Uint8Array(wasm) });
      });
      return draco;
    },
    webp: async () => {
      if (typeof createImageBitmap !== 'function' || typeof OffscreenCanvas !== 'function')
        throw new Error('this browser has no createImageBitmap and OffscreenCanvas');
      return decodeWebpBrowser;
    },
    // A chunk of its own: the library build inlines the transcoder's 0.6 MB as base64,
    // which is then fetched only for a file with a KTX2 texture.
    ktx2: async () => (await import('./ktx2-browser.ts')).browserKtx2Transcoder(),
  };
}

type DracoFactory = (options: { wasmBinary: Uint8Array }) => Promise<DracoDecoderModule>;
