/**
 * Textures without an image: glTF 2.0 §5.29 makes a texture's `source`
 * optional ("When undefined, an extension or other mechanism SHOULD supply
 * an alternate texture source"). pathwise reads images through `source`
 * only, and glTF-Transform fails deep inside (reading a texture that it never
 * made) on a material that binds such a texture; so each binding of a
 * sourceless texture is removed from the JSON before glTF-Transform reads it,
 * with one warning per texture: its materials use their factors alone.
 */
import { isObject, type Json } from './validate-values.ts';

/** The textureInfo objects of a material, with the object and key that hold each. */
function bindings(m: Json): [Json, string][] {
  const out: [Json, string][] = [];
  const at = (o: unknown, key: string): void => {
    if (isObject(o) && isObject(o[key])) out.push([o, key]);
  };
  at(m.pbrMetallicRoughness, 'baseColorTexture');
  at(m.pbrMetallicRoughness, 'metallicRoughnessTexture');
  for (const k of ['normalTexture', 'emissiveTexture', 'occlusionTexture']) at(m, k);
  const ext = isObject(m.extensions) ? m.extensions : {};
  at(ext.KHR_materials_transmission, 'transmissionTexture');
  at(ext.KHR_materials_specular, 'specularTexture');
  at(ext.KHR_materials_specular, 'specularColorTexture');
  at(ext.KHR_materials_volume, 'thicknessTexture');
  at(ext.KHR_materials_diffuse_transmission, 'diffuseTransmissionTexture');
  at(ext.KHR_materials_diffuse_transmission, 'diffuseTransmissionColorTexture');
  return out;
}

/**
 * Removes the bindings of the textures `sourceless` from the (validated) JSON's materials;
 * `reasons` says why a texture has no image, where it is known (texture-extensions.ts).
 */
export function dropSourcelessTextures(
  json: Json,
  sourceless: number[],
  warn: (message: string) => void,
  reasons: ReadonlyMap<number, string> = new Map(),
): void {
  if (sourceless.length === 0) return;
  const set = new Set(sourceless);
  const materials = (json.materials as Json[] | undefined) ?? [];
  const used = new Set<number>();
  for (const m of materials) {
    for (const [holder, key] of bindings(m)) {
      const t = (holder[key] as Json).index as number;
      if (set.has(t)) {
        used.add(t);
        delete holder[key];
      }
    }
  }
  for (const t of [...used].sort((a, b) => a - b))
    warn(
      `textures[${t}]: ${reasons.get(t) ?? 'has no source image'}; the materials that use it ` +
        `use their factors alone`,
    );
}
