/**
 * The numbers and texture bindings of the layer extensions pathwise reads
 * (KHR_materials_clearcoat, KHR_materials_sheen, KHR_materials_pbrSpecularGlossiness),
 * bounded as their schemas bound them; for validate-materials.ts.
 */
import { bounded, boundedArray, isObject, type Json } from './validate-values.ts';

/** Refuses a layer extension's factor outside its schema's range, naming its JSON path. */
export function checkLayerNumbers(ext: Json, p: string): void {
  const cc = ext.KHR_materials_clearcoat;
  const ccp = `${p}.extensions.KHR_materials_clearcoat`;
  bounded(cc, 'clearcoatFactor', ccp, 0, 1);
  bounded(cc, 'clearcoatRoughnessFactor', ccp, 0, 1);
  if (isObject(cc)) {
    const nt = cc.clearcoatNormalTexture;
    bounded(nt, 'scale', `${ccp}.clearcoatNormalTexture`, -Number.MAX_VALUE, Number.MAX_VALUE);
  }
  const sh = ext.KHR_materials_sheen;
  const shp = `${p}.extensions.KHR_materials_sheen`;
  boundedArray(sh, 'sheenColorFactor', shp, 3, 0, 1);
  bounded(sh, 'sheenRoughnessFactor', shp, 0, 1);
  const sg = ext.KHR_materials_pbrSpecularGlossiness;
  const sgp = `${p}.extensions.KHR_materials_pbrSpecularGlossiness`;
  boundedArray(sg, 'diffuseFactor', sgp, 4, 0, 1);
  boundedArray(sg, 'specularFactor', sgp, 3, 0, 1);
  bounded(sg, 'glossinessFactor', sgp, 0, 1);
}

/** Lists the layer extensions' textureInfos with `add` (validate-materials.ts's). */
export function layerBindings(ext: Json, p: string, add: (o: unknown, path: string) => void): void {
  const slots: [string, string[]][] = [
    [
      'KHR_materials_clearcoat',
      ['clearcoatTexture', 'clearcoatRoughnessTexture', 'clearcoatNormalTexture'],
    ],
    ['KHR_materials_sheen', ['sheenColorTexture', 'sheenRoughnessTexture']],
    ['KHR_materials_pbrSpecularGlossiness', ['diffuseTexture', 'specularGlossinessTexture']],
  ];
  for (const [name, keys] of slots) {
    const e = ext[name];
    if (!isObject(e)) continue;
    for (const k of keys) add(e[k], `${p}.extensions.${name}.${k}`);
  }
}
