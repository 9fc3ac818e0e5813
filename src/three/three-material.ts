/**
 * A three.js material as a glTF 2.0 material: MeshStandardMaterial as metallic–roughness,
 * MeshPhysicalMaterial's layers as the KHR_materials_* extensions pathwise honours
 * (GLTFLoader's mapping, inverted: three.js src/loaders/GLTFLoader.js), MeshBasicMaterial
 * as KHR_materials_unlit and MeshLambertMaterial as a base without specular layer
 * (KHR_materials_specular factor 0, which leaves glTF's diffuse BRDF alone). Everything
 * else a material holds that has no glTF counterpart gets one warning.
 */
import type { Document, Material, Texture } from '@gltf-transform/core';
import {
  KHRMaterialsAnisotropy,
  KHRMaterialsClearcoat,
  KHRMaterialsDispersion,
  KHRMaterialsEmissiveStrength,
  KHRMaterialsIOR,
  KHRMaterialsIridescence,
  KHRMaterialsSheen,
  KHRMaterialsSpecular,
  KHRMaterialsTransmission,
  KHRMaterialsUnlit,
  KHRMaterialsVolume,
} from '@gltf-transform/extensions';
import { colorOf, numberOf, textureOf, type ThreeMaterial } from './three-shapes.ts';
import type { TextureConverter } from './three-texture.ts';

/** What the geometry must know of a material. */
export interface ConvertedMaterial {
  material: Material;
  /** COLOR_0 is multiplied in (`vertexColors`). */
  vertexColors: boolean;
  /** `flatShading`: normals are dropped, so glTF's flat normals apply (§3.7.2.1). */
  flat: boolean;
}

const DOUBLE_SIDE = 2;
const OBJECT_SPACE_NORMAL_MAP = 1;

/** Properties with no glTF counterpart, warned about when set. */
const UNMAPPED: [string, string][] = [
  ['aoMap', 'the path tracer computes occlusion itself'],
  ['lightMap', 'the path tracer computes lighting itself'],
  [
    'envMap',
    'a per-material environment has no glTF counterpart; scene.environment lights everything',
  ],
  ['bumpMap', 'no glTF counterpart'],
  ['displacementMap', 'no glTF counterpart'],
  ['alphaMap', 'no glTF counterpart (opacity comes from map alpha and opacity)'],
];

export class MaterialConverter {
  private readonly made = new Map<string, ConvertedMaterial>();
  private readonly ext: Partial<Record<string, unknown>> = {};

  constructor(
    private readonly doc: Document,
    private readonly textures: TextureConverter,
    private readonly warn: (m: string) => void,
  ) {}

  convert(m: ThreeMaterial | undefined, where: string): ConvertedMaterial {
    const key = m?.uuid ?? '(none)';
    let done = this.made.get(key);
    if (done === undefined) {
      done = this.make(m, `${where} material ${JSON.stringify(m?.name || m?.type || '')}`);
      this.made.set(key, done);
    }
    return done;
  }

  private extension<T>(cls: new (doc: Document) => T & { extensionName: string }): T {
    const name = (cls as unknown as { EXTENSION_NAME: string }).EXTENSION_NAME;
    this.ext[name] ??= this.doc.createExtension(cls as never);
    return this.ext[name] as T;
  }

  private make(m: ThreeMaterial | undefined, where: string): ConvertedMaterial {
    const mat = this.doc.createMaterial(m?.name ?? '');
    const out: ConvertedMaterial = { material: mat, vertexColors: false, flat: false };
    if (m === undefined) return out;
    const o = m as Record<string, unknown>;
    const tx = this.textures;
    out.vertexColors = o.vertexColors === true;
    out.flat = o.flatShading === true;
    mat.setDoubleSided(o.side === DOUBLE_SIDE);
    const color = colorOf(o, 'color') ?? [1, 1, 1];
    const opacity = numberOf(o, 'opacity', 1);
    mat.setBaseColorFactor([color[0], color[1], color[2], opacity]);
    tx.apply(textureOf(o, 'map'), `${where}.map`, 'srgb', (t) =>
      mat.setBaseColorTexture(t).getBaseColorTextureInfo(),
    );
    const alphaTest = numberOf(o, 'alphaTest', 0);
    if (alphaTest > 0) mat.setAlphaMode('MASK').setAlphaCutoff(alphaTest);
    // pathwise's BLEND is stochastic (a path passes with probability 1 − α), which is
    // what three's alphaHash draws too.
    else if (o.transparent === true || o.alphaHash === true) mat.setAlphaMode('BLEND');
    if (o.wireframe === true) this.warn(`${where}: wireframe is not drawn; the surfaces are`);

    if (m.isMeshBasicMaterial) {
      mat.setExtension('KHR_materials_unlit', this.extension(KHRMaterialsUnlit).createUnlit());
      return out;
    }
    if (!m.isMeshStandardMaterial && !m.isMeshLambertMaterial && !m.isMeshPhongMaterial) {
      this.warn(
        `${where}: ${m.type ?? 'this material'} has no glTF counterpart; a white diffuse is used`,
      );
      mat.setBaseColorFactor([1, 1, 1, 1]).setMetallicFactor(0).setRoughnessFactor(1);
      return out;
    }
    for (const [key, why] of UNMAPPED) {
      if (textureOf(o, key) !== null) this.warn(`${where}: ${key} ignored: ${why}`);
    }
    this.emission(o, mat, where);
    this.normal(o, mat, where);
    if (!m.isMeshStandardMaterial) {
      if (m.isMeshPhongMaterial) {
        this.warn(
          `${where}: MeshPhongMaterial's specular highlight is not mapped; rendered as Lambertian`,
        );
      }
      // Lambert: glTF's base without its dielectric specular layer is Lambertian.
      mat.setMetallicFactor(0).setRoughnessFactor(1);
      mat.setExtension(
        'KHR_materials_specular',
        this.extension(KHRMaterialsSpecular).createSpecular().setSpecularFactor(0),
      );
      return out;
    }
    mat
      .setMetallicFactor(numberOf(o, 'metalness', 0))
      .setRoughnessFactor(numberOf(o, 'roughness', 1));
    this.metallicRoughness(o, mat, where);
    if (m.isMeshPhysicalMaterial) this.physical(o, mat, where);
    return out;
  }

  private emission(o: Record<string, unknown>, mat: Material, where: string): void {
    const e = colorOf(o, 'emissive') ?? [0, 0, 0];
    let strength = numberOf(o, 'emissiveIntensity', 1);
    // glTF's emissiveFactor is at most 1 per channel; the rest goes to emissive_strength.
    const peak = Math.max(e[0], e[1], e[2]);
    const factor = peak > 1 ? e.map((v) => v / peak) : e;
    if (peak > 1) strength *= peak;
    mat.setEmissiveFactor([factor[0], factor[1], factor[2]]);
    this.textures.apply(textureOf(o, 'emissiveMap'), `${where}.emissiveMap`, 'srgb', (t) =>
      mat.setEmissiveTexture(t).getEmissiveTextureInfo(),
    );
    if (strength !== 1 && peak > 0) {
      const ext = this.extension(KHRMaterialsEmissiveStrength);
      mat.setExtension(
        'KHR_materials_emissive_strength',
        ext.createEmissiveStrength().setEmissiveStrength(strength),
      );
    }
  }

  private normal(o: Record<string, unknown>, mat: Material, where: string): void {
    const map = textureOf(o, 'normalMap');
    if (map === null) return;
    if (o.normalMapType === OBJECT_SPACE_NORMAL_MAP) {
      this.warn(`${where}.normalMap: object-space normal maps are not supported; ignored`);
      return;
    }
    const scale = (o.normalScale as { x: number; y: number } | undefined) ?? { x: 1, y: 1 };
    if (Math.abs(Math.abs(scale.x) - Math.abs(scale.y)) > 1e-6 * Math.abs(scale.x)) {
      this.warn(`${where}.normalScale: x and y differ; glTF has one scale, x is used`);
    }
    // y's sign is three's convention for the texture's orientation (GLTFLoader negates it
    // for flipY-false maps on meshes without tangents); glTF's scale is x's.
    mat.setNormalScale(scale.x);
    this.textures.apply(map, `${where}.normalMap`, 'linear', (t) =>
      mat.setNormalTexture(t).getNormalTextureInfo(),
    );
  }

  private metallicRoughness(o: Record<string, unknown>, mat: Material, where: string): void {
    const rough = textureOf(o, 'roughnessMap');
    const metal = textureOf(o, 'metalnessMap');
    // three reads roughness from G and metalness from B, as glTF's one texture does; two
    // different textures (or one alone) cannot both be kept in one glTF texture.
    const tex = rough ?? metal;
    if (tex === null) return;
    if (rough !== null && metal !== null && rough !== metal) {
      this.warn(
        `${where}: roughnessMap and metalnessMap differ; glTF has one texture, roughnessMap's is used for both`,
      );
    } else if (metal === null && numberOf(o, 'metalness', 0) !== 0) {
      this.warn(
        `${where}: roughnessMap without metalnessMap: its blue channel scales metalness too`,
      );
    } else if (rough === null && numberOf(o, 'roughness', 1) !== 0) {
      this.warn(
        `${where}: metalnessMap without roughnessMap: its green channel scales roughness too`,
      );
    }
    this.textures.apply(tex, `${where}.${rough ? 'roughnessMap' : 'metalnessMap'}`, 'linear', (t) =>
      mat.setMetallicRoughnessTexture(t).getMetallicRoughnessTextureInfo(),
    );
  }

  private physical(o: Record<string, unknown>, mat: Material, where: string): void {
    const tx = this.textures;
    const t = (key: string) => textureOf(o, key);
    const w = (key: string) => `${where}.${key}`;
    const n = (key: string, fallback: number) => numberOf(o, key, fallback);

    const ior = n('ior', 1.5);
    if (ior !== 1.5)
      mat.setExtension(
        'KHR_materials_ior',
        this.extension(KHRMaterialsIOR).createIOR().setIOR(ior),
      );

    const specular = n('specularIntensity', 1);
    const specularColor = colorOf(o, 'specularColor') ?? [1, 1, 1];
    if (
      specular !== 1 ||
      specularColor.some((v) => v !== 1) ||
      t('specularIntensityMap') ||
      t('specularColorMap')
    ) {
      const s = this.extension(KHRMaterialsSpecular).createSpecular();
      s.setSpecularFactor(specular).setSpecularColorFactor(specularColor);
      tx.apply(t('specularIntensityMap'), w('specularIntensityMap'), 'linear', (x) =>
        s.setSpecularTexture(x).getSpecularTextureInfo(),
      );
      tx.apply(t('specularColorMap'), w('specularColorMap'), 'srgb', (x) =>
        s.setSpecularColorTexture(x).getSpecularColorTextureInfo(),
      );
      mat.setExtension('KHR_materials_specular', s);
    }

    if (n('clearcoat', 0) > 0) {
      const c = this.extension(KHRMaterialsClearcoat).createClearcoat();
      c.setClearcoatFactor(n('clearcoat', 0)).setClearcoatRoughnessFactor(
        n('clearcoatRoughness', 0),
      );
      tx.apply(t('clearcoatMap'), w('clearcoatMap'), 'linear', (x) =>
        c.setClearcoatTexture(x).getClearcoatTextureInfo(),
      );
      tx.apply(t('clearcoatRoughnessMap'), w('clearcoatRoughnessMap'), 'linear', (x) =>
        c.setClearcoatRoughnessTexture(x).getClearcoatRoughnessTextureInfo(),
      );
      const normal = t('clearcoatNormalMap');
      if (normal !== null) {
        const scale = (o.clearcoatNormalScale as { x: number } | undefined)?.x ?? 1;
        c.setClearcoatNormalScale(scale);
        tx.apply(normal, w('clearcoatNormalMap'), 'linear', (x) =>
          c.setClearcoatNormalTexture(x).getClearcoatNormalTextureInfo(),
        );
      }
      mat.setExtension('KHR_materials_clearcoat', c);
    }

    if (n('sheen', 0) > 0) {
      // three's `sheen` weights sheenColor; glTF has the product only (GLTFLoader sets sheen 1).
      const weight = n('sheen', 0);
      const sc = colorOf(o, 'sheenColor') ?? [0, 0, 0];
      const s = this.extension(KHRMaterialsSheen).createSheen();
      s.setSheenColorFactor([sc[0] * weight, sc[1] * weight, sc[2] * weight]);
      s.setSheenRoughnessFactor(n('sheenRoughness', 1));
      tx.apply(t('sheenColorMap'), w('sheenColorMap'), 'srgb', (x) =>
        s.setSheenColorTexture(x).getSheenColorTextureInfo(),
      );
      tx.apply(t('sheenRoughnessMap'), w('sheenRoughnessMap'), 'linear', (x) =>
        s.setSheenRoughnessTexture(x).getSheenRoughnessTextureInfo(),
      );
      mat.setExtension('KHR_materials_sheen', s);
    }

    if (n('transmission', 0) > 0) {
      const tr = this.extension(KHRMaterialsTransmission).createTransmission();
      tr.setTransmissionFactor(n('transmission', 0));
      tx.apply(t('transmissionMap'), w('transmissionMap'), 'linear', (x) =>
        tr.setTransmissionTexture(x).getTransmissionTextureInfo(),
      );
      mat.setExtension('KHR_materials_transmission', tr);
    }

    const thickness = n('thickness', 0);
    const distance = n('attenuationDistance', Infinity);
    if (thickness > 0 || t('thicknessMap')) {
      const v = this.extension(KHRMaterialsVolume).createVolume();
      v.setThicknessFactor(thickness).setAttenuationColor(
        colorOf(o, 'attenuationColor') ?? [1, 1, 1],
      );
      if (Number.isFinite(distance) && distance > 0) v.setAttenuationDistance(distance);
      tx.apply(t('thicknessMap'), w('thicknessMap'), 'linear', (x) =>
        v.setThicknessTexture(x).getThicknessTextureInfo(),
      );
      mat.setExtension('KHR_materials_volume', v);
    } else if (Number.isFinite(distance)) {
      this.warn(
        `${where}: attenuationDistance without thickness is a thin wall in glTF; no absorption`,
      );
    }

    if (n('iridescence', 0) > 0) {
      const range = (o.iridescenceThicknessRange as number[] | undefined) ?? [100, 400];
      const i = this.extension(KHRMaterialsIridescence).createIridescence();
      i.setIridescenceFactor(n('iridescence', 0)).setIridescenceIOR(n('iridescenceIOR', 1.3));
      i.setIridescenceThicknessMinimum(range[0]).setIridescenceThicknessMaximum(range[1]);
      tx.apply(t('iridescenceMap'), w('iridescenceMap'), 'linear', (x) =>
        i.setIridescenceTexture(x).getIridescenceTextureInfo(),
      );
      tx.apply(t('iridescenceThicknessMap'), w('iridescenceThicknessMap'), 'linear', (x) =>
        i.setIridescenceThicknessTexture(x).getIridescenceThicknessTextureInfo(),
      );
      mat.setExtension('KHR_materials_iridescence', i);
    }

    if (n('anisotropy', 0) > 0) {
      const a = this.extension(KHRMaterialsAnisotropy).createAnisotropy();
      a.setAnisotropyStrength(n('anisotropy', 0)).setAnisotropyRotation(n('anisotropyRotation', 0));
      tx.apply(t('anisotropyMap'), w('anisotropyMap'), 'linear', (x) =>
        a.setAnisotropyTexture(x).getAnisotropyTextureInfo(),
      );
      mat.setExtension('KHR_materials_anisotropy', a);
    }

    if (n('dispersion', 0) > 0) {
      const d = this.extension(KHRMaterialsDispersion)
        .createDispersion()
        .setDispersion(n('dispersion', 0));
      mat.setExtension('KHR_materials_dispersion', d);
    }
  }
}

export type { Texture };
