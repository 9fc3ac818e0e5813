/**
 * EXT_texture_webp and KHR_texture_basisu on the glTF JSON, before it is validated:
 * each names, in `textures[i].extensions.<name>.source`, an image in a format a
 * core glTF reader may lack (WebP; KTX2 with Basis Universal data), and the texture's
 * own `source`, when present, is the fallback (PNG or JPEG) for such readers.
 *
 * With the platform's decoder (GltfDecoders), the extension's image replaces the
 * fallback here, and glTF-Transform's class for it is registered (its `preread` makes
 * the same swap, unconditionally: registered without a decoder, it would throw the
 * fallback away). Without one, the fallback stays, with one warning per texture; a
 * texture that has none loses its image (sourceless.ts, with the reason); a file that
 * lists the extension in `extensionsRequired` is refused with one error.
 */
import { EXTTextureWebP, KHRTextureBasisu } from '@gltf-transform/extensions';
import type { GltfDecoders } from '../scene/format/gltf-model.ts';
import { quote } from '../util/message.ts';
import { GltfError } from './errors.ts';
import { describeValue, indexValue, isObject, list } from './validate-values.ts';

/** In the order they are applied: where a texture has both, the WebP image wins. */
const EXTENSIONS = [
  {
    name: 'KHR_texture_basisu',
    format: 'KTX2 (Basis Universal)',
    decoder: 'ktx2',
    ext: KHRTextureBasisu,
  },
  { name: 'EXT_texture_webp', format: 'WebP', decoder: 'webp', ext: EXTTextureWebP },
] as const;

export const TEXTURE_EXTENSION_NAMES: ReadonlySet<string> = new Set(EXTENSIONS.map((e) => e.name));

export interface TextureExtensionPlan {
  /** The extensions this platform decodes (they may be required). */
  honoured: Set<string>;
  /** glTF-Transform's classes for those that the file uses. */
  classes: (typeof KHRTextureBasisu | typeof EXTTextureWebP)[];
  /** Why a texture is left without an image: texture index → reason. */
  reasons: Map<number, string>;
}

/**
 * Swaps in the extensions' images the platform can decode, and says what it cannot.
 * Throws GltfError for a required extension without a decoder and for an extension
 * whose `source` is no image index.
 */
export function prepareTextureExtensions(
  json: unknown,
  decoders: GltfDecoders | undefined,
  warn: (message: string) => void,
): TextureExtensionPlan {
  const plan: TextureExtensionPlan = { honoured: new Set(), classes: [], reasons: new Map() };
  for (const e of EXTENSIONS) if (decoders?.[e.decoder] !== undefined) plan.honoured.add(e.name);
  if (!isObject(json)) return plan; // validate.ts says what is wrong
  const required = Array.isArray(json.extensionsRequired) ? json.extensionsRequired : [];
  const used = Array.isArray(json.extensionsUsed) ? json.extensionsUsed : [];
  for (const e of EXTENSIONS) {
    if (required.includes(e.name) && !plan.honoured.has(e.name))
      throw new GltfError(
        `extensionsRequired: the file requires ${quote(e.name)}, and this platform has no ` +
          `${e.format} decoder`,
      );
    if (plan.honoured.has(e.name) && (used.includes(e.name) || required.includes(e.name)))
      plan.classes.push(e.ext);
  }
  const images = list(json, 'images').length;
  list(json, 'textures').forEach((t, i) => {
    if (!isObject(t.extensions)) return;
    let swapped = false;
    for (const e of EXTENSIONS) {
      const x = t.extensions[e.name];
      if (x === undefined) continue;
      const path = `textures[${i}].extensions.${e.name}`;
      if (!isObject(x)) throw new GltfError(`${path}: must be an object, got ${describeValue(x)}`);
      if (x.source === undefined) throw new GltfError(`${path}.source: is required`);
      const source = indexValue(x.source, `${path}.source`, images, 'images');
      if (plan.honoured.has(e.name)) {
        t.source = source;
        swapped = true;
        plan.reasons.delete(i);
      } else if (swapped) {
        continue;
      } else if (t.source !== undefined) {
        warn(
          `textures[${i}]: its ${e.format} image (${e.name}) needs a decoder this platform ` +
            `lacks; its fallback source is used`,
        );
      } else {
        plan.reasons.set(
          i,
          `its ${e.format} image (${e.name}) needs a decoder this platform lacks, and it has ` +
            `no fallback source`,
        );
      }
    }
  });
  return plan;
}
