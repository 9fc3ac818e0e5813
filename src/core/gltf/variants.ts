/**
 * KHR_materials_variants: a file's named material variants, checked, and one of them
 * selected by name. Per the extension's README (Khronos, ratified):
 * - the root's `extensions.KHR_materials_variants.variants` lists the variants, each with
 *   a required `name`;
 * - a primitive's `extensions.KHR_materials_variants.mappings` lists mappings, each a
 *   required `material` and a required, non-empty list of `variants` (indices into the
 *   root's list) that use it;
 * - with no variant selected a primitive uses its own `material`; with one selected, the
 *   material of the mapping that names it, and its own `material` when none does.
 * The Khronos validator also refuses a variant named by two mappings of one primitive
 * (KHR_MATERIALS_VARIANTS_NON_UNIQUE_VARIANT), as this check does. Variant names need not
 * be unique: selecting a name selects every variant of that name, and a primitive takes
 * the first of its mappings that names one (the README's "first matching mapping").
 *
 * The selection is made on the JSON before glTF-Transform reads it (it does not read the
 * extension): the primitive's `material` is replaced, so everything after (material
 * compilation, flattening, instancing) sees an ordinary file.
 */
import { quote } from '../util/message.ts';
import { textureBindings } from './validate-materials.ts';
import {
  describeValue,
  fail,
  index,
  indexArray,
  isObject,
  list,
  type Json,
} from './validate-values.ts';

export const VARIANTS_EXTENSION = 'KHR_materials_variants';
const ROOT = `extensions.${VARIANTS_EXTENSION}`;
/** Variant names an error lists before it counts the rest. */
const LISTED = 12;

/** One primitive's checked mappings: its JSON, its path and, per mapping, material and variants. */
interface PrimitiveMappings {
  primitive: Json;
  path: string;
  mappings: { material: number; variants: number[] }[];
}

/** The extension object at o.extensions, checked to be an object; undefined when absent. */
function extensionOf(o: Json, path: string): Json | undefined {
  const extensions = o.extensions;
  const ext = isObject(extensions) ? extensions[VARIANTS_EXTENSION] : undefined;
  if (ext === undefined) return undefined;
  if (!isObject(ext)) fail(path, `must be an object, got ${describeValue(ext)}`);
  return ext;
}

/** The root's variant names, checked; empty when the file does not use the extension. */
function variantNames(json: Json): string[] {
  const ext = extensionOf(json, ROOT);
  if (ext === undefined) return [];
  if (ext.variants === undefined) fail(`${ROOT}.variants`, 'is required');
  const variants = list(ext, 'variants', `${ROOT}.variants`);
  if (variants.length === 0) fail(`${ROOT}.variants`, 'must not be empty');
  return variants.map((v, i) => {
    const p = `${ROOT}.variants[${i}].name`;
    if (v.name === undefined) fail(p, 'is required');
    if (typeof v.name !== 'string') fail(p, `must be a string, got ${describeValue(v.name)}`);
    return v.name;
  });
}

/** Every primitive's mappings, checked against the file's materials and `variants` count. */
function primitiveMappings(json: Json, variants: number): PrimitiveMappings[] {
  const materials = list(json, 'materials').length;
  const out: PrimitiveMappings[] = [];
  list(json, 'meshes').forEach((mesh, i) => {
    list(mesh, 'primitives', `meshes[${i}].primitives`).forEach((pr, j) => {
      const path = `meshes[${i}].primitives[${j}]`;
      const ep = `${path}.${ROOT}`;
      const ext = extensionOf(pr, ep);
      if (ext === undefined) return;
      if (ext.mappings === undefined) fail(`${ep}.mappings`, 'is required');
      const mappings = list(ext, 'mappings', `${ep}.mappings`);
      if (mappings.length === 0) fail(`${ep}.mappings`, 'must not be empty');
      const usedBy = new Map<number, number>();
      const checked = mappings.map((m, k) => {
        const mp = `${ep}.mappings[${k}]`;
        const material = index(m, 'material', mp, materials, 'materials');
        if (material === undefined) fail(`${mp}.material`, 'is required');
        if (m.variants === undefined) fail(`${mp}.variants`, 'is required');
        const names = indexArray(m, 'variants', mp, variants, `${ROOT}.variants`);
        if (names.length === 0) fail(`${mp}.variants`, 'must not be empty');
        for (const v of names) {
          const other = usedBy.get(v);
          // The Khronos validator's KHR_MATERIALS_VARIANTS_NON_UNIQUE_VARIANT.
          if (other !== undefined)
            fail(
              `${mp}.variants`,
              `names variant ${v}, which mappings[${other}] of this primitive already maps`,
            );
          usedBy.set(v, k);
        }
        return { material, variants: names };
      });
      out.push({ primitive: pr, path, mappings: checked });
    });
  });
  return out;
}

/**
 * Checks the file's KHR_materials_variants and applies the variant named `name`
 * (null: none, every primitive keeps its `material`) by rewriting the primitives'
 * `material` in `json`. Run after validateGltfJson (indices, meshes and materials are
 * well formed) and before glTF-Transform reads the JSON. Throws GltfError: a malformed
 * extension, or a name the file does not have (the message lists the file's names).
 */
export function selectMaterialVariant(json: Json, name: string | null): void {
  const names = variantNames(json);
  const prims = primitiveMappings(json, names.length);
  // glTF-Transform refuses a required extension it has no reader for; the selection
  // below is all there is to read, so the requirement is met here.
  if (Array.isArray(json.extensionsRequired))
    json.extensionsRequired = json.extensionsRequired.filter((e) => e !== VARIANTS_EXTENSION);
  if (name === null) return;
  if (names.length === 0)
    fail(
      'extensions',
      `the file has no material variants (${VARIANTS_EXTENSION}) to select ${quote(name)} from`,
    );
  const selected = new Set<number>();
  names.forEach((n, i) => n === name && selected.add(i));
  if (selected.size === 0) {
    // One line however many variants the file has: the first LISTED, then a count.
    const listed = names.slice(0, LISTED).map((n) => quote(n));
    if (names.length > LISTED) listed.push(`and ${names.length - LISTED} more`);
    fail(
      `${ROOT}.variants`,
      `has no variant ${quote(name)}; the file's variants are ${listed.join(', ')}`,
    );
  }
  const materials = list(json, 'materials');
  for (const { primitive, path, mappings } of prims) {
    const k = mappings.findIndex((m) => m.variants.some((v) => selected.has(v)));
    if (k < 0) continue;
    const material = mappings[k].material;
    // validateGltfJson checked the TEXCOORD sets of the default material only (§3.9.2:
    // a binding to a set the primitive lacks is invalid); the mapped one needs the same.
    const attributes = primitive.attributes as Json;
    for (const b of textureBindings(materials[material], `materials[${material}]`)) {
      if (attributes[`TEXCOORD_${b.set}`] === undefined)
        fail(
          `${path}.${ROOT}.mappings[${k}].material`,
          `materials[${material}] (variant ${quote(name)}) reads TEXCOORD_${b.set} in ${b.path}, which the primitive lacks`,
        );
    }
    primitive.material = material;
  }
}
