/**
 * Decodes the textures the materials use into one TextureStore: every
 * image's size is read from its header first and the whole store checked
 * against the memory limit before any decoder is loaded or anything is
 * allocated; then each image is decoded (PNG and JPEG by the injected
 * decoder, WebP and KTX2 by the injected lazy decoders) and written once,
 * with sRGB → linear for colour textures. An image that cannot be used (a
 * format this platform has no decoder for) is dropped with a warning: its
 * materials fall back to their factors.
 *
 * KTX2 mip chains: the largest level that fits the texture memory left is
 * used (a level is a quarter of the one above), with a warning when it is not
 * level 0; so a scene over the limit by its KTX2 textures still loads.
 */
import { B_IMAGE } from '../gltf-material/material-table.ts';
import type { TextureRequest } from './materials.ts';
import type { GltfDecoders, WebpDecoder } from '../scene/format/gltf-model.ts';
import type { DecodedImage, ImageDecoder } from '../texture/decoded-image.ts';
import { writeDecodedImage } from '../texture/decoded-image.ts';
import { imageDecodeError, libraryMessage } from '../texture/image-error.ts';
import {
  checkImageBytes,
  notPngOrJpeg,
  otherImageFormat,
  readImageInfo,
  sniffTextureType,
  type TextureImageType,
} from '../texture/image-header.ts';
import { readKtx2Info } from '../texture/ktx2-header.ts';
import {
  EMPTY_TEXTURES,
  TEXEL_BYTES,
  TextureLayout,
  type TextureStore,
} from '../texture/texture-store.ts';
import { GltfError, messageOf } from './errors.ts';

interface Usable {
  request: TextureRequest;
  bytes: Uint8Array;
  mime: TextureImageType;
  /** The KTX2 level used (0 otherwise). */
  level: number;
}

const FORMAT: Record<string, string> = { 'image/webp': 'WebP', 'image/ktx2': 'KTX2' };

export async function decodeGltfTextures(
  requests: TextureRequest[],
  table: Float64Array,
  decode: ImageDecoder,
  decoders: GltfDecoders | undefined,
  limitBytes: number,
  shared: boolean,
  warn: (message: string) => void,
  progress: (done: number, total: number) => void,
): Promise<TextureStore> {
  const layout = new TextureLayout(limitBytes);
  const usable: Usable[] = [];
  const add = (width: number, height: number, what: string): void => {
    try {
      layout.add(width, height, what);
    } catch (e) {
      throw new GltfError(messageOf(e));
    }
  };
  for (const r of requests) {
    const what = `images[${r.imageIndex}] (${r.firstUse})`;
    const bytes = r.texture.getImage();
    if (bytes === null || bytes.length === 0) {
      warn(`${what}: has no image data; the texture is ignored`);
      continue;
    }
    const declared = r.texture.getMimeType();
    const mime = sniffTextureType(bytes);
    // WebP or KTX2 (by their bytes, or declared so) where this platform cannot decode
    // them: ignored, said once per image.
    const compressed =
      mime ?? (declared === 'image/webp' || declared === 'image/ktx2' ? declared : null);
    if (compressed === 'image/webp' || compressed === 'image/ktx2') {
      if ((compressed === 'image/webp' ? decoders?.webp : decoders?.ktx2) === undefined) {
        warn(
          `${what}: ${compressed} needs a ${FORMAT[compressed]} decoder, which this platform ` +
            `lacks; the texture is ignored`,
        );
        continue;
      }
    }
    if (mime === null) {
      // Another image format (GIF, AVIF) is honestly ignored; bytes that are no
      // image at all, though declared PNG, JPEG, WebP or KTX2, are a damaged file.
      const other = compressed === null ? otherImageFormat(bytes, declared) : null;
      if (other === null) throw new GltfError(`${what}: ${notPngOrJpeg(bytes, declared)}`);
      warn(`${what}: ${other} is not PNG, JPEG, WebP or KTX2; the texture is ignored`);
      continue;
    }
    let info;
    try {
      info = readImageInfo(bytes, what);
    } catch (e) {
      throw new GltfError(messageOf(e));
    }
    let level = 0;
    if (mime === 'image/ktx2') level = addKtx2Level(layout, bytes, what, warn);
    else add(info.width, info.height, what);
    // The declared size against the bytes present, before the store is allocated
    // (the headers of WebP and KTX2 were checked in full by readImageInfo).
    if (mime === 'image/png' || mime === 'image/jpeg') {
      try {
        checkImageBytes(bytes, limitBytes / TEXEL_BYTES);
      } catch (e) {
        throw new GltfError(`${what}: ${imageDecodeError(e).message}`);
      }
    }
    usable.push({ request: r, bytes, mime, level });
  }
  if (usable.length === 0) return EMPTY_TEXTURES;
  // Every size has passed the budget: only now are the decoders this file needs loaded.
  const webp = await loadDecoder(usable, 'image/webp', decoders?.webp);
  const ktx2 = await loadDecoder(usable, 'image/ktx2', decoders?.ktx2);
  const store = layout.allocate(shared);
  for (let i = 0; i < usable.length; i++) {
    const { request, bytes, mime, level } = usable[i];
    const what = `images[${request.imageIndex}] (${request.firstUse})`;
    progress(i, usable.length);
    let img: DecodedImage;
    try {
      if (mime === 'image/webp') img = await decodeWebp(webp!, bytes);
      else if (mime === 'image/ktx2') img = await ktx2!(bytes, level);
      else img = await decode(bytes, mime, limitBytes / TEXEL_BYTES);
    } catch (e) {
      throw new GltfError(`${what}: ${messageOf(e)}`);
    }
    try {
      writeDecodedImage(store, i, img, request.srgb, what);
    } catch (e) {
      throw new GltfError(messageOf(e));
    }
    for (const b of request.bindings) table[b + B_IMAGE] = i;
  }
  progress(usable.length, usable.length);
  return store;
}

/**
 * Checks a KTX2 header and adds its largest level that fits the texture memory left
 * to `layout`; returns that level. A level that does not fit is a warning when a
 * smaller one does, and the level 0 error when none does.
 */
function addKtx2Level(
  layout: TextureLayout,
  bytes: Uint8Array,
  what: string,
  warn: (message: string) => void,
): number {
  let levels;
  try {
    levels = readKtx2Info(bytes).levels;
  } catch (e) {
    throw new GltfError(`${what}: ${imageDecodeError(e).message}`);
  }
  let first: unknown = null;
  for (let i = 0; i < levels.length; i++) {
    try {
      layout.add(levels[i].width, levels[i].height, what);
    } catch (e) {
      first ??= e;
      continue;
    }
    if (i > 0)
      warn(
        `${what}: KTX2 level 0 (${levels[0].width}×${levels[0].height}) does not fit the texture ` +
          `memory limit; level ${i} (${levels[i].width}×${levels[i].height}) is used`,
      );
    return i;
  }
  throw new GltfError(messageOf(first));
}

/** The decoder of `mime` when an image needs it; its failure to load names that image. */
async function loadDecoder<T>(
  usable: Usable[],
  mime: TextureImageType,
  getter: (() => Promise<T>) | undefined,
): Promise<T | null> {
  const first = usable.find((u) => u.mime === mime);
  if (first === undefined || getter === undefined) return null;
  try {
    return await getter();
  } catch (e) {
    const what = `images[${first.request.imageIndex}] (${first.request.firstUse})`;
    throw new GltfError(`${what}: cannot load the ${FORMAT[mime]} decoder: ${libraryMessage(e)}`);
  }
}

async function decodeWebp(webp: WebpDecoder, bytes: Uint8Array): Promise<DecodedImage> {
  try {
    return await webp(bytes);
  } catch (e) {
    throw new Error(
      `cannot decode WebP: the decoder stopped (${libraryMessage(e)}): damaged or truncated data`,
    );
  }
}
