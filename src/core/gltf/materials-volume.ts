/**
 * KHR_materials_volume, KHR_materials_dispersion and
 * KHR_materials_diffuse_transmission into the material table
 * (material-table.ts). What the renderer does with each (docs/gltf.md,
 * "Transmission, volume, dispersion and diffuse transmission"):
 *
 * - volume: `thicknessFactor` > 0 makes the mesh the boundary of a solid
 *   (refraction bends, Beer–Lambert absorption inside); 0, or no extension,
 *   is a thin wall. A path tracer measures the real distance travelled
 *   inside, so `thickness` is only that switch and `thicknessTexture` is not
 *   read: a per-texel decision would let a closed mesh be a solid at one
 *   point and a thin wall at another, and the inside of the mesh would have
 *   no consistent medium.
 * - dispersion: kept as read (20 / Abbe number); used only by volumes.
 * - diffuse transmission: factor, colour and their textures. Its lobe is a
 *   thin Lambertian BTDF; on a volume the light it sends inside is absorbed
 *   like refracted light (the integrator's medium), but the volume does not
 *   scatter (no subsurface scattering), which the loader warns about.
 */
import type { Material, Texture, TextureInfo } from '@gltf-transform/core';
import type { DiffuseTransmission, Dispersion, Volume } from '@gltf-transform/extensions';
import {
  GM_ATTENUATION_COLOR,
  GM_ATTENUATION_DISTANCE,
  GM_DIFFUSE_TRANSMISSION,
  GM_DIFFUSE_TRANSMISSION_COLOR,
  GM_DISPERSION,
  GM_STRIDE,
  GM_THICKNESS,
  GM_TRANSMISSION,
  TEX_DIFFUSE_TRANSMISSION,
  TEX_DIFFUSE_TRANSMISSION_COLOR,
} from '../gltf-material/material-table.ts';

type Bind = (m: number, slot: number, texture: Texture | null, info: TextureInfo | null) => void;

/** Reads the three extensions of material `mat` (index m) into its record; call after transmission. */
export function readVolumeExtensions(
  mat: Material,
  m: number,
  table: Float64Array,
  bind: Bind,
  warn: (message: string) => void,
): void {
  const o = m * GM_STRIDE;
  const where = `materials[${m}].extensions`;
  const volume = mat.getExtension<Volume>('KHR_materials_volume');
  if (volume !== null) {
    const thickness = volume.getThicknessFactor();
    table[o + GM_THICKNESS] = thickness > 0 && Number.isFinite(thickness) ? thickness : 0;
    table.set(volume.getAttenuationColor(), o + GM_ATTENUATION_COLOR);
    const d = volume.getAttenuationDistance();
    // The specification's range is (0, ∞]; anything else is the default, no absorption.
    table[o + GM_ATTENUATION_DISTANCE] = d > 0 ? d : Infinity;
  }
  const dispersion = mat.getExtension<Dispersion>('KHR_materials_dispersion');
  if (dispersion !== null) {
    const v = dispersion.getDispersion();
    table[o + GM_DISPERSION] = v > 0 && Number.isFinite(v) ? v : 0;
    if (v > 0 && !(table[o + GM_THICKNESS] > 0 && table[o + GM_TRANSMISSION] > 0)) {
      // KHR_materials_dispersion: "only applies to volumetric transmission".
      warn(
        `${where}.KHR_materials_dispersion: the material is not a transmissive volume ` +
          `(KHR_materials_transmission and KHR_materials_volume thicknessFactor > 0); ` +
          `dispersion has no effect`,
      );
    }
  }
  const dt = mat.getExtension<DiffuseTransmission>('KHR_materials_diffuse_transmission');
  if (dt !== null) {
    const f = dt.getDiffuseTransmissionFactor();
    table[o + GM_DIFFUSE_TRANSMISSION] = f > 0 ? Math.min(f, 1) : 0;
    table.set(dt.getDiffuseTransmissionColorFactor(), o + GM_DIFFUSE_TRANSMISSION_COLOR);
    bind(
      m,
      TEX_DIFFUSE_TRANSMISSION,
      dt.getDiffuseTransmissionTexture(),
      dt.getDiffuseTransmissionTextureInfo(),
    );
    bind(
      m,
      TEX_DIFFUSE_TRANSMISSION_COLOR,
      dt.getDiffuseTransmissionColorTexture(),
      dt.getDiffuseTransmissionColorTextureInfo(),
    );
    if (f > 0 && table[o + GM_THICKNESS] > 0) {
      warn(
        `${where}.KHR_materials_diffuse_transmission: light that crosses into the volume ` +
          `diffusely is absorbed by it but not scattered inside (subsurface scattering is ` +
          `not modelled)`,
      );
    }
  }
}
