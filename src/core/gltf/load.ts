/**
 * Loading a glTF 2.0 file (`.gltf` with its buffers and images, or `.glb`)
 * into what the tracer uses: world-space triangle arrays, a material table
 * and a texture store. glTF-Transform (MIT; @gltf-transform/core and
 * /extensions) parses the document; around it, this module checks the
 * container and the JSON first (validate.ts), reads resources through the
 * injected reader, decodes textures with the injected decoder, and
 * flattens the default scene (flatten.ts). Every failure is one GltfError
 * naming the place in the file; warnings (ignored extensions, skipped
 * primitives, unusable images) are collected, never printed here.
 *
 * Stages, reported through `onProgress`: 'parse' (container, JSON,
 * resources, document), 'textures' (decoding), 'geometry' (flattening and
 * tangents).
 */
import { Document, type JSONDocument } from '@gltf-transform/core';
import {
  EXTMeshGPUInstancing,
  KHRLightsPunctual,
  KHRMaterialsAnisotropy,
  KHRMaterialsClearcoat,
  KHRMaterialsDiffuseTransmission,
  KHRMaterialsDispersion,
  KHRMaterialsEmissiveStrength,
  KHRMaterialsIOR,
  KHRMaterialsIridescence,
  KHRMaterialsPBRSpecularGlossiness,
  KHRMaterialsSheen,
  KHRMaterialsSpecular,
  KHRMaterialsTransmission,
  KHRMaterialsUnlit,
  KHRMaterialsVolume,
  KHRMeshQuantization,
  KHRTextureTransform,
} from '@gltf-transform/extensions';
import { decodeUtf8 } from '../io/utf8.ts';
import { parseJson } from '../io/json.ts';
import { quote } from '../util/message.ts';
import type { ImageDecoder } from '../texture/decoded-image.ts';
import { DEFAULT_TEXTURE_LIMIT_BYTES } from '../texture/texture-store.ts';
import { GltfError, messageOf } from './errors.ts';
import { GLTF_FILE_BYTES } from './file-names.ts';
import { flattenGltf } from './flatten.ts';
import { decodeDataUri, PreloadedIO, resolveUri } from './io.ts';
import { isGlb, parseGlb } from './glb.ts';
import { compileGltfMaterials } from './materials.ts';
import type {
  GltfCamera,
  GltfDecoders,
  GltfFileReader,
  GltfModel,
  TangentGenerator,
} from '../scene/format/gltf-model.ts';
import { decodableExtensions, decodeCompressed, skippedBuffers } from './decode-compressed.ts';
import { decodeGltfTextures } from './textures.ts';
import { fromRowMajor } from './transforms.ts';
import { validateGltfBuffers } from './validate-buffers.ts';
import { checkPrimitiveCounts } from './validate-attributes.ts';
import { validateSparseIndices } from './validate-sparse.ts';
import { positionBoundsNotes } from './validate-bounds.ts';
import { SUPPORTED_REQUIRED, validateGltfJson } from './validate.ts';
import { dropSourcelessTextures } from './sourceless.ts';
import { checkPunctualLights } from './punctual-lights.ts';
import { selectMaterialVariant } from './variants.ts';
import { prepareTextureExtensions, TEXTURE_EXTENSION_NAMES } from './texture-extensions.ts';

/** Extensions whose content is used (everything else is reported as ignored). */
export const HONOURED_EXTENSIONS = new Set([
  'KHR_lights_punctual',
  'KHR_materials_anisotropy',
  'KHR_materials_clearcoat',
  'KHR_materials_diffuse_transmission',
  'KHR_materials_dispersion',
  'KHR_materials_emissive_strength',
  'KHR_materials_ior',
  'KHR_materials_iridescence',
  'KHR_materials_pbrSpecularGlossiness',
  'KHR_materials_sheen',
  'KHR_materials_specular',
  'KHR_materials_transmission',
  'KHR_materials_unlit',
  'KHR_materials_variants',
  'KHR_materials_volume',
  'KHR_mesh_quantization',
  'KHR_texture_transform',
  'EXT_mesh_gpu_instancing',
]);

export { GLTF_FILE_BYTES };

export type GltfStage = 'parse' | 'textures' | 'geometry';

export interface GltfLoadOptions {
  /** Reads external buffers and images; null when the file may name none (a GLB). */
  reader: GltfFileReader | null;
  /** Decodes PNG/JPEG bytes (decode-js.ts in Node, createImageBitmap in the browser). */
  decodeImage: ImageDecoder;
  /** MikkTSpace, for normal-mapped primitives without TANGENT; null ignores such normal maps. */
  generateTangents?: TangentGenerator | null;
  /** Decoders of compressed meshes and textures, each called only when the file uses its extension. */
  decoders?: GltfDecoders;
  /** Row-major affine 4×4 of the scene shape, applied on top of the node transforms. */
  transform?: number[] | null;
  textureLimitBytes?: number;
  /** Put the texels in a SharedArrayBuffer (when the platform has one). */
  sharedTextures?: boolean;
  /**
   * Triangles the file may instance, when fewer than the file limit remain (a scene's
   * other meshes count against the scene's limit); checked from the accessor counts,
   * before any geometry is read.
   */
  maxTriangles?: number;
  /**
   * The KHR_materials_variants variant to render, by name (variants.ts); absent or null:
   * every primitive's default material. A name the file lacks is an error.
   */
  variant?: string | null;
  onProgress?: (stage: GltfStage, done: number, total: number) => void;
}

export type { GltfCamera, GltfDecoders, GltfModel };

const EXTENSIONS = [
  EXTMeshGPUInstancing,
  KHRLightsPunctual,
  KHRMaterialsAnisotropy,
  KHRMaterialsClearcoat,
  KHRMaterialsDiffuseTransmission,
  KHRMaterialsDispersion,
  KHRMaterialsEmissiveStrength,
  KHRMaterialsIOR,
  KHRMaterialsIridescence,
  KHRMaterialsPBRSpecularGlossiness,
  KHRMaterialsSheen,
  KHRMaterialsSpecular,
  KHRMaterialsTransmission,
  KHRMaterialsUnlit,
  KHRMaterialsVolume,
  KHRMeshQuantization,
  KHRTextureTransform,
];

/** Silences glTF-Transform's console logger: its findings are ours to report. */
const QUIET_LOGGER = { debug() {}, info() {}, warn() {}, error() {} };

/**
 * Loads the glTF or GLB `bytes` of the file at `path` (the reader's path,
 * used to resolve the file's relative URIs). Throws GltfError.
 */
export async function loadGltf(
  bytes: Uint8Array,
  path: string,
  options: GltfLoadOptions,
): Promise<GltfModel> {
  const progress = options.onProgress ?? (() => {});
  const warnings: string[] = [];
  const warn = (m: string): void => {
    if (warnings.length < 100) warnings.push(m);
    else if (warnings.length === 100) warnings.push('(further warnings omitted)');
  };
  progress('parse', 0, 1);
  let jsonBytes = bytes;
  let bin: Uint8Array | null = null;
  if (isGlb(bytes)) ({ json: jsonBytes, bin } = parseGlb(bytes));
  let json: Record<string, unknown>;
  try {
    json = parseJson(decodeUtf8(jsonBytes)) as Record<string, unknown>;
  } catch (e) {
    throw new GltfError(`JSON: ${messageOf(e)}`);
  }
  const decodable = decodableExtensions(options.decoders);
  const textureExtensions = prepareTextureExtensions(json, options.decoders, warn);
  for (const name of textureExtensions.honoured) decodable.add(name);
  const summary = validateGltfJson(json, decodable);
  if (options.maxTriangles !== undefined && summary.triangles > options.maxTriangles) {
    throw new GltfError(
      `scene: instances ${summary.triangles} triangles, more than the ${options.maxTriangles} ` +
        `left of the scene's limit`,
    );
  }
  for (const note of summary.notes) warn(note);
  checkPunctualLights(json);
  selectMaterialVariant(json, options.variant ?? null);
  const asset = json.asset as Record<string, unknown>;
  if (asset.version !== '2.0') {
    // §3.2: a 2.x file whose minVersion (checked above) is at most 2.0 is meant to load
    // in a 2.0 reader; glTF-Transform refuses any version but "2.0", so it is told 2.0.
    warn(`asset.version: ${quote(asset.version as string)} is read as glTF 2.0`);
    json.asset = { ...asset, version: '2.0' };
  }
  dropSourcelessTextures(json, summary.sourceless, warn, textureExtensions.reasons);
  for (const name of (json.extensionsUsed as unknown[] | undefined) ?? []) {
    // WebP and KTX2 without a decoder are said per texture (texture-extensions.ts).
    if (
      typeof name === 'string' &&
      !HONOURED_EXTENSIONS.has(name) &&
      !decodable.has(name) &&
      !TEXTURE_EXTENSION_NAMES.has(name)
    ) {
      warn(`extension ${quote(name)} is not supported; its content is ignored`);
    }
  }

  const count = (key: string): number => ((json[key] as unknown[] | undefined) ?? []).length;
  if (count('animations') > 0)
    warn(`${count('animations')} animation(s) ignored: the model is rendered in its rest pose`);
  if (count('skins') > 0)
    warn(`${count('skins')} skin(s) ignored: the model is rendered in its rest pose`);
  const meshes = (json.meshes as Record<string, unknown>[] | undefined) ?? [];
  if (
    meshes.some((m) =>
      (m.primitives as Record<string, unknown>[]).some((p) => p.targets !== undefined),
    )
  ) {
    warn('morph targets ignored: the model is rendered in its rest pose');
  }

  // Resources: the GLB chunk, data URIs, files beside the model.
  const resources: Record<string, Uint8Array> = {};
  const buffers = (json.buffers as Record<string, unknown>[] | undefined) ?? [];
  const data: Uint8Array[] = [];
  const skipped = skippedBuffers(json, decodable);
  for (let i = 0; i < buffers.length; i++) {
    const b = buffers[i];
    const where = `buffers[${i}]`;
    let bytes: Uint8Array;
    if (skipped.has(i)) {
      bytes = new Uint8Array(0); // a meshopt fallback buffer: its views are decoded
    } else if (b.uri === undefined) {
      if (i !== 0 || bin === null)
        throw new GltfError(`${where}: has no uri and the file has no GLB binary chunk`);
      bytes = bin;
      resources['@glb.bin'] = bin;
    } else {
      bytes = await readResource(
        b.uri as string,
        path,
        where,
        (b.byteLength as number) + 4096,
        options,
      );
      resources[b.uri as string] = bytes;
    }
    data.push(bytes);
  }
  const bufferBytes = await decodeCompressed(
    json,
    data,
    resources,
    bytes.length,
    skipped,
    options.decoders,
  );
  validateGltfBuffers(json, bufferBytes);
  checkPrimitiveCounts(json);
  validateSparseIndices(json, data);
  for (const note of positionBoundsNotes(json, data)) warn(note);
  const images = (json.images as Record<string, unknown>[] | undefined) ?? [];
  for (let i = 0; i < images.length; i++) {
    const uri = images[i].uri;
    if (typeof uri === 'string' && !(uri in resources)) {
      resources[uri] = await readResource(uri, path, `images[${i}]`, GLTF_FILE_BYTES, options);
    }
  }

  let doc: Document;
  try {
    const io = new PreloadedIO()
      .setLogger(QUIET_LOGGER)
      .registerExtensions([...EXTENSIONS, ...textureExtensions.classes]);
    doc = await io.readJSON({ json, resources } as unknown as JSONDocument);
  } catch (e) {
    if (e instanceof GltfError) throw e;
    throw new GltfError(`document: ${messageOf(e)}`);
  }
  progress('parse', 1, 1);

  try {
    return await build(doc, json, summary.scene, options, warnings, warn, progress);
  } catch (e) {
    // The last guard of the decoder contract: whatever the checks above
    // missed surfaces as one glTF error, never as a TypeError.
    if (e instanceof GltfError) throw e;
    throw new GltfError(`document: ${messageOf(e)}`);
  }
}

async function build(
  doc: Document,
  json: Record<string, unknown>,
  scene: number,
  options: GltfLoadOptions,
  warnings: string[],
  warn: (m: string) => void,
  progress: (stage: GltfStage, done: number, total: number) => void,
): Promise<GltfModel> {
  const root = doc.getRoot();
  const { table, defaultMaterial, requests } = compileGltfMaterials(
    root.listMaterials(),
    root.listTextures(),
    warn,
  );
  const textures = await decodeGltfTextures(
    requests,
    table,
    options.decodeImage,
    options.decoders,
    options.textureLimitBytes ?? DEFAULT_TEXTURE_LIMIT_BYTES,
    options.sharedTextures ?? false,
    warn,
    (done, total) => progress('textures', done, total),
  );

  progress('geometry', 0, 1);
  if (scene < 0) warn('the file has no scene; nothing to render');
  const geometry = flattenGltf(
    doc,
    json,
    scene,
    table,
    defaultMaterial,
    options.transform ? fromRowMajor(options.transform) : null,
    options.generateTangents ?? null,
    warn,
  );
  progress('geometry', 1, 1);
  return { ...geometry, materials: table, textures, warnings };
}

async function readResource(
  uri: string,
  path: string,
  where: string,
  maxBytes: number,
  options: GltfLoadOptions,
): Promise<Uint8Array> {
  if (uri.startsWith('data:')) return decodeDataUri(uri, `${where}.uri`);
  const file = resolveUri(path, uri, `${where}.uri`, options.reader?.allowedFolders);
  if (options.reader === null) {
    throw new GltfError(
      `${where}.uri: names the file ${quote(file)}, but no way to read files beside the model was given`,
    );
  }
  try {
    return await options.reader.read(file, Math.min(maxBytes, GLTF_FILE_BYTES));
  } catch (e) {
    throw new GltfError(`${where}.uri: cannot read ${quote(file)}: ${messageOf(e)}`);
  }
}
