/**
 * Images as glTF textures (issue 27, findings 1 and 5): the declared size is checked
 * against the bytes before the texture store is allocated, decode failures read
 * "cannot decode PNG: …", and bytes that are no image name their first bytes instead
 * of "image/png is not PNG or JPEG".
 */
import { Document } from '@gltf-transform/core';
import { describe, expect, it } from 'vitest';
import type { ImageDecoder } from '../../../src/core/texture/decoded-image.ts';
import { decodeImageJs } from '../../../src/core/texture/decode-js.ts';
import { docWith, loadGlb, quadPrimitive } from '../../helpers/gltf.ts';
import { jpegImage, jpegWithSize, pngImage } from '../../fuzz/image-samples.ts';

function texturedDoc(image: Uint8Array, mimeType: string): Document {
  const doc = new Document();
  doc.createBuffer();
  const tex = doc.createTexture().setImage(image).setMimeType(mimeType);
  docWith(doc, quadPrimitive(doc).setMaterial(doc.createMaterial().setBaseColorTexture(tex)));
  return doc;
}

const WHAT = 'glTF: images[0] (materials[0].baseColorTexture)';

describe('glTF textures: checked against their bytes', () => {
  it('bytes declared image/png that are no image: an error naming what they are', async () => {
    const html = Uint8Array.from('<!DOCTYPE html>', (c) => c.charCodeAt(0));
    await expect(loadGlb(texturedDoc(html, 'image/png'))).rejects.toThrow(
      `${WHAT}: not a PNG or JPEG image (it starts with 3c 21 44 4f 43 54 59 50 …, "<!DOCTYP"; its mimeType says image/png)`,
    );
  });

  it('a WebP where no WebP decoder is given: honestly ignored with a note', async () => {
    const webp = Uint8Array.from('RIFF\0\0\0\0WEBPVP8 ', (c) => c.charCodeAt(0));
    const m = await loadGlb(texturedDoc(webp, 'image/png'));
    expect(m.warnings).toContain(
      'images[0] (materials[0].baseColorTexture): image/webp needs a WebP decoder, which this platform lacks; the texture is ignored',
    );
  });

  it('a lying JPEG fails before the store is allocated or the decoder runs', async () => {
    let decoded = 0;
    const counting: ImageDecoder = (bytes, mime, max) => {
      decoded++;
      return decodeImageJs(bytes, mime, max);
    };
    const lying = jpegWithSize(jpegImage(16, 8), 16384, 8192);
    await expect(
      loadGlb(texturedDoc(lying, 'image/jpeg'), { decodeImage: counting }),
    ).rejects.toThrow(
      `${WHAT}: cannot decode JPEG: the frame header claims 16384×8192 but the file has only ` +
        `${lying.length} bytes (at least 1572864 needed)`,
    );
    expect(decoded).toBe(0);
  });

  it('a valid PNG still loads', async () => {
    const m = await loadGlb(texturedDoc(pngImage(2, 2), 'image/png'));
    expect(m.textures.info.length).toBe(3);
  });
});
