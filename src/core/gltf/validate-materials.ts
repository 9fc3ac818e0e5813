/**
 * A material's numbers and texture bindings as glTF 2.0 §5.19 ("Material") and the
 * schemas of the extensions pathwise reads bound them (factors in [0, 1]…), and each
 * textureInfo (§5.20) with the TEXCOORD set it reads (KHR_texture_transform's texCoord
 * overrides the textureInfo's).
 */
import {
  bounded,
  boundedArray,
  describeValue,
  fail,
  integer,
  isObject,
  type Json,
} from './validate-values.ts';
import { checkLayerNumbers, layerBindings } from './validate-layers.ts';

/** The numbers of a material and of the extensions pathwise reads, as the glTF schemas bound them. */
export function checkMaterialNumbers(m: Json, p: string): void {
  for (const [o, k, path] of [
    [m, 'pbrMetallicRoughness', p],
    [m, 'extensions', p],
    [m, 'normalTexture', p],
  ] as const) {
    if (o[k] !== undefined && !isObject(o[k]))
      fail(`${path}.${k}`, `must be an object, got ${describeValue(o[k])}`);
  }
  if (isObject(m.extensions)) {
    for (const [name, ext] of Object.entries(m.extensions)) {
      if (!isObject(ext))
        fail(`${p}.extensions.${name}`, `must be an object, got ${describeValue(ext)}`);
    }
  }
  const pbr = m.pbrMetallicRoughness;
  const pp = `${p}.pbrMetallicRoughness`;
  boundedArray(pbr, 'baseColorFactor', pp, 4, 0, 1);
  bounded(pbr, 'metallicFactor', pp, 0, 1);
  bounded(pbr, 'roughnessFactor', pp, 0, 1);
  boundedArray(m, 'emissiveFactor', p, 3, 0, 1);
  bounded(m, 'alphaCutoff', p, 0, Number.MAX_VALUE);
  bounded(m.normalTexture, 'scale', `${p}.normalTexture`, -Number.MAX_VALUE, Number.MAX_VALUE);
  const ext = isObject(m.extensions) ? m.extensions : {};
  const e = (name: string): [unknown, string] => [ext[name], `${p}.extensions.${name}`];
  // Emission is radiance: bounded like every radiance of the scene format.
  const [es, esPath] = e('KHR_materials_emissive_strength');
  bounded(es, 'emissiveStrength', esPath, 0, 1e12);
  const [ior, iorPath] = e('KHR_materials_ior');
  bounded(ior, 'ior', iorPath, 0, 1e6);
  if (isObject(ior) && typeof ior.ior === 'number' && ior.ior > 0 && ior.ior < 1) {
    fail(`${iorPath}.ior`, `must be 0 or at least 1, got ${ior.ior}`);
  }
  const [tr, trPath] = e('KHR_materials_transmission');
  bounded(tr, 'transmissionFactor', trPath, 0, 1);
  const [spec, specPath] = e('KHR_materials_specular');
  bounded(spec, 'specularFactor', specPath, 0, 1);
  boundedArray(spec, 'specularColorFactor', specPath, 3, 0, 1e6);
  checkLayerNumbers(ext, p);
  // KHR_materials_volume, _dispersion, _diffuse_transmission (their schemas; the
  // attenuation distance is exclusive of 0, and a thickness has no upper bound).
  const [vol, volPath] = e('KHR_materials_volume');
  bounded(vol, 'thicknessFactor', volPath, 0, Number.MAX_VALUE);
  bounded(vol, 'attenuationDistance', volPath, Number.MIN_VALUE, Infinity);
  boundedArray(vol, 'attenuationColor', volPath, 3, 0, 1);
  const [disp, dispPath] = e('KHR_materials_dispersion');
  bounded(disp, 'dispersion', dispPath, 0, Number.MAX_VALUE);
  const [dt, dtPath] = e('KHR_materials_diffuse_transmission');
  bounded(dt, 'diffuseTransmissionFactor', dtPath, 0, 1);
  boundedArray(dt, 'diffuseTransmissionColorFactor', dtPath, 3, 0, 1);
  const [ir, irPath] = e('KHR_materials_iridescence');
  bounded(ir, 'iridescenceFactor', irPath, 0, 1);
  bounded(ir, 'iridescenceIor', irPath, 1, 1e6);
  bounded(ir, 'iridescenceThicknessMinimum', irPath, 0, 1e6);
  bounded(ir, 'iridescenceThicknessMaximum', irPath, 0, 1e6);
  const [an, anPath] = e('KHR_materials_anisotropy');
  bounded(an, 'anisotropyStrength', anPath, 0, 1);
  bounded(an, 'anisotropyRotation', anPath, -1e9, 1e9);
  const infos: [unknown, string][] = [
    [isObject(pbr) ? pbr.baseColorTexture : undefined, `${pp}.baseColorTexture`],
    [isObject(pbr) ? pbr.metallicRoughnessTexture : undefined, `${pp}.metallicRoughnessTexture`],
    [m.normalTexture, `${p}.normalTexture`],
    [m.emissiveTexture, `${p}.emissiveTexture`],
  ];
  for (const [info, ip] of infos) {
    const tt =
      isObject(info) && isObject(info.extensions)
        ? info.extensions.KHR_texture_transform
        : undefined;
    if (tt === undefined) continue;
    const tp = `${ip}.extensions.KHR_texture_transform`;
    if (!isObject(tt)) fail(tp, 'must be an object');
    boundedArray(tt, 'offset', tp, 2, -1e9, 1e9);
    boundedArray(tt, 'scale', tp, 2, -1e9, 1e9);
    bounded(tt, 'rotation', tp, -1e9, 1e9);
    integer(tt, 'texCoord', tp, 0, 1 << 16);
  }
}

/** The texture bindings of a material: JSON path and the TEXCOORD set each reads. */
export function textureBindings(m: Json, p: string): { path: string; set: number; info: Json }[] {
  const out: { path: string; set: number; info: Json }[] = [];
  const add = (o: unknown, path: string): void => {
    if (o === undefined) return;
    // A textureInfo that is not an object is listed for validate.ts to refuse.
    if (!isObject(o)) return void out.push({ path, set: 0, info: o as Json });
    let set = typeof o.texCoord === 'number' ? o.texCoord : 0;
    const tt = isObject(o.extensions) ? o.extensions.KHR_texture_transform : undefined;
    // KHR_texture_transform's texCoord overrides the textureInfo's.
    if (isObject(tt) && typeof tt.texCoord === 'number') set = tt.texCoord;
    out.push({ path, set, info: o });
  };
  const pbr = isObject(m.pbrMetallicRoughness) ? m.pbrMetallicRoughness : {};
  add(pbr.baseColorTexture, `${p}.pbrMetallicRoughness.baseColorTexture`);
  add(pbr.metallicRoughnessTexture, `${p}.pbrMetallicRoughness.metallicRoughnessTexture`);
  for (const k of ['normalTexture', 'emissiveTexture', 'occlusionTexture']) add(m[k], `${p}.${k}`);
  const ext = isObject(m.extensions) ? m.extensions : {};
  const tr = ext.KHR_materials_transmission;
  if (isObject(tr))
    add(tr.transmissionTexture, `${p}.extensions.KHR_materials_transmission.transmissionTexture`);
  const sp = ext.KHR_materials_specular;
  if (isObject(sp)) {
    add(sp.specularTexture, `${p}.extensions.KHR_materials_specular.specularTexture`);
    add(sp.specularColorTexture, `${p}.extensions.KHR_materials_specular.specularColorTexture`);
  }
  layerBindings(ext, p, add);
  const vol = ext.KHR_materials_volume;
  if (isObject(vol))
    add(vol.thicknessTexture, `${p}.extensions.KHR_materials_volume.thicknessTexture`);
  const dt = ext.KHR_materials_diffuse_transmission;
  if (isObject(dt)) {
    const dp = `${p}.extensions.KHR_materials_diffuse_transmission`;
    add(dt.diffuseTransmissionTexture, `${dp}.diffuseTransmissionTexture`);
    add(dt.diffuseTransmissionColorTexture, `${dp}.diffuseTransmissionColorTexture`);
  }
  const ir = ext.KHR_materials_iridescence;
  if (isObject(ir)) {
    const ip = `${p}.extensions.KHR_materials_iridescence`;
    add(ir.iridescenceTexture, `${ip}.iridescenceTexture`);
    add(ir.iridescenceThicknessTexture, `${ip}.iridescenceThicknessTexture`);
  }
  const an = ext.KHR_materials_anisotropy;
  if (isObject(an))
    add(an.anisotropyTexture, `${p}.extensions.KHR_materials_anisotropy.anisotropyTexture`);
  return out;
}
