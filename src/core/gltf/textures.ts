/**
 * Decodes the textures the materials use into one TextureStore: every
 * image's size is read from its header first and the whole store checked
 * against the memory limit before anything is decoded or allocated; then
 * each image is decoded (by the injected decoder) and written once, with
 * sRGB → linear for colour textures. An image that cannot be used (a format
 * the decoder lacks, such as WebP or KTX2 in Node) is dropped with a
 * warning: its materials fall back to their factors.
 */
import { B_IMAGE } from '../gltf-material/material-table.ts';
import type { TextureRequest } from './materials.ts';
import type { ImageDecoder } from '../texture/decoded-image.ts';
import { writeDecodedImage } from '../texture/decoded-image.ts';
import { imageDecodeError } from '../texture/image-error.ts';
import {
  checkImageBytes,
  notPngOrJpeg,
  otherImageFormat,
  readImageInfo,
  sniffImageType,
} from '../texture/image-header.ts';
import {
  EMPTY_TEXTURES,
  TEXEL_BYTES,
  TextureLayout,
  type TextureStore,
} from '../texture/texture-store.ts';
import { GltfError, messageOf } from './errors.ts';

export async function decodeGltfTextures(
  requests: TextureRequest[],
  table: Float64Array,
  decode: ImageDecoder,
  limitBytes: number,
  shared: boolean,
  warn: (message: string) => void,
  progress: (done: number, total: number) => void,
): Promise<TextureStore> {
  const layout = new TextureLayout(limitBytes);
  const usable: { request: TextureRequest; bytes: Uint8Array; mime: string }[] = [];
  for (const r of requests) {
    const what = `images[${r.imageIndex}] (${r.firstUse})`;
    const bytes = r.texture.getImage();
    if (bytes === null || bytes.length === 0) {
      warn(`${what}: has no image data; the texture is ignored`);
      continue;
    }
    const mime = sniffImageType(bytes);
    if (mime === null) {
      // Another image format (WebP, KTX2) is honestly ignored; bytes that are no
      // image at all, though declared PNG or JPEG, are a damaged file.
      const other = otherImageFormat(bytes, r.texture.getMimeType());
      if (other === null) {
        throw new GltfError(`${what}: ${notPngOrJpeg(bytes, r.texture.getMimeType())}`);
      }
      warn(`${what}: ${other} is not PNG or JPEG; the texture is ignored`);
      continue;
    }
    let info;
    try {
      info = readImageInfo(bytes, what);
    } catch (e) {
      throw new GltfError(messageOf(e));
    }
    try {
      layout.add(info.width, info.height, what);
    } catch (e) {
      throw new GltfError(messageOf(e));
    }
    // The declared size against the bytes present, before the store is allocated.
    try {
      checkImageBytes(bytes, limitBytes / TEXEL_BYTES);
    } catch (e) {
      throw new GltfError(`${what}: ${imageDecodeError(e).message}`);
    }
    usable.push({ request: r, bytes, mime });
  }
  if (usable.length === 0) return EMPTY_TEXTURES;
  const store = layout.allocate(shared);
  for (let i = 0; i < usable.length; i++) {
    const { request, bytes, mime } = usable[i];
    const what = `images[${request.imageIndex}] (${request.firstUse})`;
    progress(i, usable.length);
    let img;
    try {
      img = await decode(bytes, mime, limitBytes / TEXEL_BYTES);
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
