/**
 * A three.js texture as a glTF texture: its texels re-encoded as PNG (three holds them
 * decoded, so the file's own bytes are gone), in the colour encoding the glTF slot
 * expects (§3.9.6: colour slots sRGB, data slots linear), with its sampler, UV set and
 * `offset`/`repeat`/`rotation` as KHR_texture_transform.
 */
import type { Document, Texture, TextureInfo } from '@gltf-transform/core';
import { KHRTextureTransform } from '@gltf-transform/extensions';
import { zlibSync } from 'fflate';
import { encodePng } from '../core/io/png.ts';
import { srgbEncode } from '../core/io/tonemap.ts';
import { srgbToLinear } from '../core/texture/srgb.ts';
import { readTexels } from './three-pixels.ts';
import type { ThreeTexture } from './three-shapes.ts';

/** How a slot reads its texture: colour (sRGB-encoded 8-bit) or data (linear 8-bit). */
export type SlotEncoding = 'srgb' | 'linear';

/** three's wrap and filter constants (src/constants.js) to glTF's (GL enums, §5.26). */
const WRAP: Record<number, number> = { 1000: 10497, 1001: 33071, 1002: 33648 };
const FILTER: Record<number, number> = {
  1003: 9728,
  1004: 9984,
  1005: 9986,
  1006: 9729,
  1007: 9985,
  1008: 9987,
};

type Wrap = Parameters<TextureInfo['setWrapS']>[0];

export class TextureConverter {
  private readonly made = new Map<string, Texture | null>();
  private transforms: KHRTextureTransform | null = null;

  constructor(
    private readonly doc: Document,
    private readonly warn: (m: string) => void,
  ) {}

  /**
   * Sets `tex` in a glTF slot: `set` attaches the glTF texture and returns the slot's
   * TextureInfo. `flipGreen` inverts the green channel (a normal map whose three
   * normalScale.y has the other sign than glTF's convention implies).
   */
  apply(
    tex: ThreeTexture | null,
    where: string,
    encoding: SlotEncoding,
    set: (t: Texture) => TextureInfo | null,
    flipGreen = false,
  ): void {
    if (tex === null) return;
    const texture = this.texture(tex, where, encoding, flipGreen);
    if (texture === null) return;
    const info = set(texture);
    if (info === null) return;
    const channel = tex.channel ?? 0;
    if (channel > 1) {
      this.warn(`${where}: uv${channel} is not read; the texture uses uv`);
    } else info.setTexCoord(channel);
    info.setWrapS((WRAP[tex.wrapS] ?? 10497) as Wrap).setWrapT((WRAP[tex.wrapT] ?? 10497) as Wrap);
    if (FILTER[tex.magFilter] === 9728 || FILTER[tex.magFilter] === 9729) {
      info.setMagFilter(FILTER[tex.magFilter] as 9728 | 9729);
    }
    if (FILTER[tex.minFilter] !== undefined) info.setMinFilter(FILTER[tex.minFilter] as 9728);
    this.transform(tex, where, info);
  }

  private texture(
    tex: ThreeTexture,
    where: string,
    encoding: SlotEncoding,
    flipGreen: boolean,
  ): Texture | null {
    const key = `${tex.uuid}/${encoding}/${flipGreen}`;
    const known = this.made.get(key);
    if (known !== undefined) return known;
    let texture: Texture | null = null;
    if (tex.isCubeTexture || tex.isCompressedTexture || tex.isRenderTargetTexture) {
      this.warn(`${where}: a cube, compressed or render-target texture is not read; ignored`);
    } else {
      try {
        const png = cachedPng(tex, `${encoding}/${flipGreen}`, () =>
          encodeTexels(tex, encoding, flipGreen),
        );
        texture = this.doc
          .createTexture(tex.name || tex.uuid)
          .setImage(png)
          .setMimeType('image/png');
      } catch (e) {
        this.warn(
          `${where}: ${e instanceof Error ? e.message : String(e)}; the texture is ignored`,
        );
      }
    }
    this.made.set(key, texture);
    return texture;
  }

  /**
   * three applies `offset`, `repeat`, `rotation` about `center` (Matrix3.setUvTransform);
   * GLTFLoader maps KHR_texture_transform's offset, rotation and scale onto the first
   * three with `center` 0, and this is its inverse. A non-zero `center` folds into the
   * offset (the translation column of three's matrix); with non-uniform `repeat` and a
   * rotation three scales after rotating where glTF scales first, which no glTF transform
   * reproduces: said in a warning.
   */
  private transform(tex: ThreeTexture, where: string, info: TextureInfo): void {
    const { offset, repeat, center, rotation } = tex;
    const identity =
      offset.x === 0 && offset.y === 0 && repeat.x === 1 && repeat.y === 1 && rotation === 0;
    if (identity) return;
    const c = Math.cos(rotation);
    const s = Math.sin(rotation);
    const tx = -repeat.x * (c * center.x + s * center.y) + center.x + offset.x;
    const ty = -repeat.y * (-s * center.x + c * center.y) + center.y + offset.y;
    if (repeat.x !== repeat.y && Math.abs(s * c) > 1e-12) {
      this.warn(
        `${where}: rotation with a non-uniform repeat scales after rotating in three, ` +
          'before in glTF; the texture is placed as glTF reads it',
      );
    }
    this.transforms ??= this.doc.createExtension(KHRTextureTransform);
    info.setExtension(
      'KHR_texture_transform',
      this.transforms
        .createTransform()
        .setOffset([tx, ty])
        .setRotation(rotation)
        .setScale([repeat.x, repeat.y]),
    );
  }
}

/**
 * PNGs already made, per texture object and encoding, while the texture's `version`
 * (which three bumps on `needsUpdate`) stays: converting a scene again after a change
 * (the widget's threeChanged()) re-encodes only the textures that changed.
 */
const pngs = new WeakMap<object, Map<string, { version: unknown; png: Uint8Array }>>();

function cachedPng(tex: ThreeTexture, key: string, make: () => Uint8Array): Uint8Array {
  let byKey = pngs.get(tex);
  if (byKey === undefined) pngs.set(tex, (byKey = new Map()));
  const version = (tex as { version?: unknown }).version;
  const known = byKey.get(key);
  if (known !== undefined && known.version === version && version !== undefined) return known.png;
  const png = make();
  byKey.set(key, { version, png });
  return png;
}

/**
 * The texels as an RGBA8 PNG in the slot's encoding. three decodes a texture whose
 * `colorSpace` is 'srgb' before use and reads any other as linear; the PNG holds what the
 * slot expects so that pathwise reads the same values.
 */
function encodeTexels(tex: ThreeTexture, encoding: SlotEncoding, flipGreen: boolean): Uint8Array {
  const t = readTexels(tex);
  const srgbSource = tex.colorSpace === 'srgb';
  const out = new Uint8ClampedArray(t.width * t.height * 4);
  const lut = new Uint8ClampedArray(256);
  for (let v = 0; v < 256; v++) {
    const x = v / 255;
    const linear = srgbSource ? srgbToLinear(x) : x;
    lut[v] = Math.round((encoding === 'srgb' ? srgbEncode(linear) : linear) * 255);
  }
  const n = t.width * t.height;
  for (let i = 0; i < n * 4; i++) {
    const alpha = (i & 3) === 3;
    const v = t.rgba[i];
    if (t.float) {
      const x = Math.min(1, Math.max(0, v));
      out[i] = Math.round((alpha || encoding !== 'srgb' ? x : srgbEncode(x)) * 255);
    } else {
      out[i] = alpha ? v : lut[v];
    }
    if (flipGreen && (i & 3) === 1) out[i] = 255 - out[i];
  }
  return encodePng(t.width, t.height, out, (raw) => zlibSync(raw, { level: 1 }));
}
