/**
 * What the BSDF-only sample bound V of consistency.ts (bsdfSampleBound) takes from a glTF
 * model's material table: its brightest emission, the largest weight one channel of a
 * BSDF sample can carry per bounce, the (n1/n2)² factors of its transmissive solids, and
 * dispersion's channel factor. gltf-weight-bound.test.ts checks the per-bounce weights
 * against every drawer of the glTF family, sample by sample.
 */
import {
  GM_DISPERSION,
  GM_EMISSIVE,
  GM_IOR,
  GM_SHEEN_COLOR,
  GM_SHEEN_ROUGHNESS,
  GM_STRIDE,
  GM_THICKNESS,
  GM_TRANSMISSION,
} from '../../src/core/gltf-material/material-table.ts';

/**
 * A bound on one channel of a glTF BSDF sample's weight f·cos/pdf. The glTF BSDF picks
 * its lobe with probabilities from the *mean* over channels of each lobe's albedo
 * estimate, so one channel of a saturated colour can carry up to 3× the mean; and the
 * estimate is taken at wo only, so a rough lobe's weight may exceed it somewhat. 4 covers
 * both; the suite checks the premise on every scene (the largest sample seen ≤ the bound),
 * so a lobe that breaks it fails loudly rather than weakening the test in silence.
 */
export const GLTF_WEIGHT_BOUND = 4;

/**
 * A bound on one channel of a sample's weight from a glTF material with a sheen of
 * roughness r (KHR_materials_sheen, src/core/bsdf/gltf-layers.ts), where GLTF_WEIGHT_BOUND
 * does not hold. The sheen lobe is picked with probability T(wo)·max3(sheenColor)·Ê(μo)
 * and sampled uniformly over the hemisphere, so its weight is at most
 *   W(r) = sup 2π · D·V(wo, wi)·μi / (max(1, E(μo), E(μi)) · Ê(μo)),
 * the peak-to-mean ratio of the Charlie lobe (the colour over max3 is ≤ 1; a base lobe
 * in the mixture only lowers it: a sum's ratio is at most the larger ratio). It is large
 * for sharp sheens, whose lobe at grazing angles is far from uniform. Maximised on a grid
 * (μo 1/400…1, μi 1/200…1, Δφ 2°): W(0.05) = 27.2, W(0.07) = 24.2, W(0.1) = 21.6,
 * W(0.3) = 6.3, W(0.6) = 2.5, W(1) = 1.8 (decreasing in r); the steps below add a
 * quarter for the grid. Below 0.05 (which the generator does not draw) the albedo table
 * reaches 0 where D·V does not, and no finite bound holds. gltf-weight-bound.test.ts
 * checks every drawer's samples against these.
 */
export function sheenWeightBound(roughness: number): number {
  if (roughness >= 0.6) return GLTF_WEIGHT_BOUND;
  if (roughness >= 0.3) return 8;
  if (roughness >= 0.05) return 34;
  return Infinity;
}

/** One model's share of V (see the file comment). */
export interface GltfSampleFactors {
  /** Largest emissive channel. */
  emission: number;
  /** Largest per-bounce weight of one channel: GLTF_WEIGHT_BOUND or a sheen's bound. */
  weight: number;
  /** Product of max(1, ior²) over transmissive materials, at the largest dispersed index. */
  eta: number;
  /** 3 when a material disperses (a path then carries one channel weighted 3), else 1. */
  channel: number;
}

/** The factors of one model's material table (material-table.ts). */
export function gltfSampleFactors(table: Float64Array): GltfSampleFactors {
  let emission = 0;
  let weight = GLTF_WEIGHT_BOUND;
  let eta = 1;
  let channel = 1;
  for (let o = 0; o < table.length; o += GM_STRIDE) {
    emission = Math.max(
      emission,
      table[o + GM_EMISSIVE],
      table[o + GM_EMISSIVE + 1],
      table[o + GM_EMISSIVE + 2],
    );
    const sheen = Math.max(
      table[o + GM_SHEEN_COLOR],
      table[o + GM_SHEEN_COLOR + 1],
      table[o + GM_SHEEN_COLOR + 2],
    );
    if (sheen > 0) weight = Math.max(weight, sheenWeightBound(table[o + GM_SHEEN_ROUGHNESS]));
    if (!(table[o + GM_TRANSMISSION] > 0)) continue;
    // KHR_materials_dispersion (src/core/bsdf/dispersion.ts): a path keeps one channel,
    // weighted 3, from its first dispersive event on — once per path, whatever the number
    // of dispersive materials — and sees that channel's index, at most ior + h.
    const ior = table[o + GM_IOR];
    const dispersion = table[o + GM_THICKNESS] > 0 ? table[o + GM_DISPERSION] : 0;
    if (dispersion > 0) channel = 3;
    eta *= Math.max(1, (ior + Math.max(0, ior - 1) * 0.025 * dispersion) ** 2);
  }
  return { emission, weight, eta, channel };
}
