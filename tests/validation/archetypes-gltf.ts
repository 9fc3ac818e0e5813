/**
 * The generator's glTF family (issue 25): scenes with glTF models whose materials use
 * the metallic–roughness model and its extensions, drawn with
 * `generateScene(seed, { family: 'gltf' })`. A family of its own so the classic and
 * mesh families keep their random streams, seeds and committed references.
 *
 * Two archetypes: gltf-objects (a floor, sphere and quad lights, a constant environment
 * now and then, one to three objects, up to 6 bounces) and gltf-closeup (one object
 * filling the view under an environment map, 1–3 bounces, where the NEE+MIS vs
 * BSDF-only pair has power). The objects are meshes (icosphere, box, torus, disc) written
 * as `.glb` files (gltf-files.ts), each with one material drawn from GLTF_MATERIALS: the
 * core model (metallic–roughness, transmission, ior, specular), clearcoat and sheen,
 * thin-walled and diffuse transmission, volumes with Beer–Lambert absorption and
 * dispersion (closed meshes only), iridescence and anisotropy. Materials without a
 * volume also go on an open disc now and then.
 * The estimator-consistency suite (consistency-d.test.ts) renders them: NEE+MIS must
 * agree with BSDF-only sampling, and Sobol with independent samples, so every lobe's
 * eval, pdf and sample must agree with each other inside a whole renderer (the χ²
 * tests check them one lobe at a time). There are no Mitsuba references for these
 * materials: Mitsuba 3 has no glTF material.
 *
 * A new lobe or material extension joins by adding a drawer to GLTF_MATERIALS with the
 * features it covers; the generator test checks each feature occurs in the suite.
 */
import { trs } from './affine.ts';
import {
  bounces,
  environment,
  extent,
  lens,
  lights,
  pointIn,
  type Archetype,
  type Region,
} from './archetypes.ts';
import { MAP_ENVIRONMENT_MAKERS } from './archetypes-mesh.ts';
import type { GltfFeature, SceneBuilder } from './builder.ts';
import type { GltfMaterialJson, GltfObject } from './gltf-files.ts';
import { drawLayersMaterial } from './gltf-draw-layers.ts';
import { drawSpecMaterial } from './gltf-draw-spec.ts';
import { drawVolumeMaterial } from './gltf-draw-volume.ts';
import { box, disc, icosphere, torus, type LocalMesh } from './meshes.ts';
import type { Rng } from './rng.ts';
import { add, length, sub, type Vec3 } from './vec.ts';

export interface DrawnMaterial {
  material: GltfMaterialJson;
  features: GltfFeature[];
}

/** A way to draw a glTF material, by weight. */
export interface GltfMaterialDrawer {
  name: string;
  weight: number;
  /**
   * Only on closed meshes: a KHR_materials_volume solid needs an inside for its
   * Beer–Lambert path lengths and its refraction in and out (docs/gltf.md).
   */
  closedOnly?: boolean;
  draw(g: Rng): DrawnMaterial;
}

const color = (g: Rng, lo: number, hi: number): Vec3 => [
  g.uniform(lo, hi),
  g.uniform(lo, hi),
  g.uniform(lo, hi),
];

/**
 * The core model: metallic 0, 1 or between; roughness 0 (Dirac lobes) or 0.05…1;
 * KHR_materials_transmission, _ior and _specular now and then.
 */
function drawPlain(g: Rng): DrawnMaterial {
  const features: GltfFeature[] = [];
  const metallic = g.weighted([
    [0, 0.45],
    [1, 0.25],
    [g.uniform(0, 1), 0.3],
  ] as const);
  features.push(metallic > 0.5 ? 'gltf-metal' : 'gltf-dielectric');
  const roughness = g.chance(0.25) ? 0 : g.uniform(0.05, 1);
  features.push(roughness === 0 ? 'gltf-smooth' : 'gltf-rough');
  const extensions: Record<string, unknown> = {};
  if (g.chance(0.35)) {
    extensions.KHR_materials_transmission = { transmissionFactor: g.uniform(0.3, 1) };
    features.push('gltf-transmission');
  }
  if (g.chance(0.4)) {
    extensions.KHR_materials_ior = { ior: g.uniform(1.1, 2.4) };
    features.push('gltf-ior');
  }
  if (g.chance(0.3)) {
    extensions.KHR_materials_specular = {
      specularFactor: g.uniform(0, 1),
      specularColorFactor: color(g, 0.2, 1),
    };
    features.push('gltf-specular');
  }
  return {
    material: {
      pbrMetallicRoughness: {
        baseColorFactor: [...color(g, 0.05, 0.95), 1],
        metallicFactor: metallic,
        roughnessFactor: roughness,
      },
      ...(Object.keys(extensions).length > 0 ? { extensions } : {}),
    },
    features,
  };
}

/** The base's tags: metal or dielectric, smooth (Dirac lobes) or rough. */
function baseFeatures(m: GltfMaterialJson): GltfFeature[] {
  const pbr = m.pbrMetallicRoughness as { metallicFactor: number; roughnessFactor: number };
  return [
    pbr.metallicFactor > 0.5 ? 'gltf-metal' : 'gltf-dielectric',
    pbr.roughnessFactor === 0 ? 'gltf-smooth' : 'gltf-rough',
  ];
}

/** KHR_materials_clearcoat and KHR_materials_sheen over a base (gltf-draw-layers.ts). */
function drawLayers(g: Rng): DrawnMaterial {
  const layers = drawLayersMaterial(g);
  const { KHR_materials_clearcoat: coat, KHR_materials_sheen: sheen } = layers.extensions;
  const material: GltfMaterialJson = { ...layers };
  const features = baseFeatures(material);
  // A zero coat or a black sheen is the reduction to the base: drawn, but not tagged.
  if (coat.clearcoatFactor > 0) features.push('gltf-clearcoat');
  if (Math.max(...sheen.sheenColorFactor) > 0) features.push('gltf-sheen');
  return { material, features };
}

/** Transmission without a volume: thin-walled glass or diffuse transmission (gltf-draw-volume.ts). */
function drawThinWalled(g: Rng): DrawnMaterial {
  const { kind, ...material } = drawVolumeMaterial(
    g,
    g.pick(['thin glass', 'diffuse transmission'] as const),
  );
  const features = baseFeatures(material);
  features.push(kind === 'thin glass' ? 'gltf-thin-glass' : 'gltf-diffuse-transmission');
  if ((material.extensions as Record<string, unknown>).KHR_materials_transmission)
    features.push('gltf-transmission');
  return { material, features };
}

/** A KHR_materials_volume solid, dispersive now and then (gltf-draw-volume.ts): closed meshes only. */
function drawVolume(g: Rng): DrawnMaterial {
  const { kind, ...material } = drawVolumeMaterial(
    g,
    g.pick(['volume', 'dispersive volume'] as const),
  );
  const ext = material.extensions as { KHR_materials_volume: { attenuationDistance?: number } };
  const features = baseFeatures(material);
  features.push('gltf-transmission', 'gltf-volume');
  if (ext.KHR_materials_volume.attenuationDistance !== undefined) features.push('gltf-attenuation');
  if (kind === 'dispersive volume') features.push('gltf-dispersion');
  return { material, features };
}

/** KHR_materials_iridescence and/or KHR_materials_anisotropy (gltf-draw-spec.ts). */
function drawSpec(g: Rng): DrawnMaterial {
  const { material } = drawSpecMaterial(g);
  const ext = material.extensions as Record<string, unknown>;
  const features = baseFeatures(material);
  // encodeGlb writes TEXCOORD_0 and TANGENT, which anisotropy needs.
  if (ext.KHR_materials_anisotropy) features.push('gltf-anisotropy');
  if (ext.KHR_materials_iridescence) features.push('gltf-iridescence');
  return { material, features };
}

/**
 * Every drawer; a material extension's lobes join here (see the file comment). The
 * weights give the core model and the two-lobe clearcoat–sheen drawer about a quarter
 * of the objects each, and each other extension drawer about a seventh, so the suite's
 * seeds see every feature (generator.test.ts checks).
 */
export const GLTF_MATERIALS: GltfMaterialDrawer[] = [
  { name: 'metallic-roughness', weight: 2, draw: drawPlain },
  { name: 'clearcoat-sheen', weight: 2, draw: drawLayers },
  { name: 'thin-walled', weight: 1, draw: drawThinWalled },
  { name: 'volume', weight: 1, closedOnly: true, draw: drawVolume },
  { name: 'iridescence-anisotropy', weight: 1, draw: drawSpec },
];

/**
 * The meshes a glTF object may be: closed ones (icosphere, box, torus), which bound a
 * volume, and for materials without one now and then an open disc (a thin wall seen
 * from both sides).
 */
export function drawGltfMesh(g: Rng, closedOnly: boolean): LocalMesh {
  return g.weighted([
    [icosphere(2), 0.45],
    [box(), 0.2],
    [torus(0.35, 24, 12), 0.2],
    [disc(16), closedOnly ? 0 : 0.15],
  ] as const);
}

const MAPS_ONLY = MAP_ENVIRONMENT_MAKERS.filter((m) => m.name.endsWith('-map'));

/** One glTF object of a drawn material at `c`, `size` across (a random rotation). */
function placeGltfObject(b: SceneBuilder, c: Vec3, size: number): void {
  const g = b.rng;
  const drawer = g.weighted(GLTF_MATERIALS.map((d) => [d, d.weight] as const));
  const drawn = drawer.draw(g);
  const mesh = drawGltfMesh(g, drawer.closedOnly === true);
  if (drawer.closedOnly === true && !mesh.closed) throw new Error(`${drawer.name} on an open mesh`);
  b.tag('gltf', ...drawn.features, ...(mesh.closed ? [] : (['gltf-open-mesh'] as const)));
  b.gltf({
    mesh,
    material: drawn.material,
    transform: trs(c, g.direction(), g.uniform(0, 2 * Math.PI), [size, size, size]),
  });
}

/**
 * One glTF object filling most of the view, lit by an environment map alone (no
 * emitter in view), 1–3 bounces: the material's own lobes make most of the image, and the
 * BSDF-only bound V (a product over the bounces) stays small enough for the NEE+MIS vs
 * BSDF-only pair to have power on it. The objects archetype, with up to six bounces
 * between several small objects, has almost none on that pair (docs/validation.md).
 */
function buildGltfCloseup(b: SceneBuilder): ReturnType<Archetype['build']> {
  const g = b.rng;
  const S = 40;
  b.quad([-S / 2, 0, -S / 2], [0, 0, S], [S, 0, 0], b.material('diffuse'));
  // A map, not a constant: only a map is a light that next-event estimation samples, so
  // under a constant alone NEE+MIS would be BSDF-only and the pair would test nothing.
  environment(b, 0, MAPS_ONLY);
  const size = g.uniform(0.6, 1);
  const c: Vec3 = [0, size * 1.3, 0];
  const elevation = g.uniform(5, 60) * (Math.PI / 180);
  const azimuth = g.uniform(0, 2 * Math.PI);
  const dist = size * g.uniform(3, 5);
  const eye: Vec3 = [
    c[0] + dist * Math.cos(elevation) * Math.sin(azimuth),
    c[1] + dist * Math.sin(elevation),
    c[2] + dist * Math.cos(elevation) * Math.cos(azimuth),
  ];
  placeGltfObject(b, c, size);
  b.tag('camera-outside');
  // The object (≤ √3·size across from its centre) fills about two thirds of the height.
  const fovY = (2 * Math.atan((size * g.uniform(1.4, 2)) / dist) * 180) / Math.PI;
  return {
    camera: { position: eye, target: c, up: [0, 1, 0], fovY },
    maxBounces: bounces(b, 1, 3),
  };
}

function buildGltfObjects(b: SceneBuilder): ReturnType<Archetype['build']> {
  const g = b.rng;
  const floor = b.material(g.chance(0.8) ? 'diffuse' : 'conductor');
  const S = 40;
  b.quad([-S / 2, 0, -S / 2], [0, 0, S], [S, 0, 0], floor);
  environment(b, 0.5);
  const region: Region = { lo: [-2, 0, -2], hi: [2, 2, 2] };
  const elevation = g.uniform(5, 50) * (Math.PI / 180);
  const azimuth = g.uniform(0, 2 * Math.PI);
  const dist = g.uniform(5, 10);
  const eye: Vec3 = [
    dist * Math.cos(elevation) * Math.sin(azimuth),
    dist * Math.sin(elevation) + 0.2,
    dist * Math.cos(elevation) * Math.cos(azimuth),
  ];
  const hasEnv = b.environment !== null;
  lights(b, { lo: [-3, 0.5, -3], hi: [3, 4, 3] }, 0, g.int(hasEnv ? 0 : 1, 2), eye);
  const count = g.int(1, 3);
  let placed = 0;
  for (let i = 0; i < count || placed === 0; i++) {
    const size = extent(region) * g.uniform(0.08, 0.18);
    // After `count` tries, the middle of the region (the eye is at least 5 away).
    const c: Vec3 = i < count ? pointIn(b, region) : [0, 0, 0];
    c[1] = Math.max(c[1], size * 1.2);
    if (length(sub(c, eye)) < size * 3) continue;
    placed++;
    placeGltfObject(b, c, size);
  }
  b.tag('camera-outside');
  return {
    camera: lens(b, {
      position: eye,
      target: add([0, 0.8, 0], [g.uniform(-0.5, 0.5), g.uniform(-0.3, 0.3), g.uniform(-0.5, 0.5)]),
      up: [0, 1, 0],
      fovY: g.uniform(25, 60),
    }),
    maxBounces: bounces(b, 1, 6),
  };
}

export const GLTF_ARCHETYPES: Archetype[] = [
  { name: 'gltf-objects', weight: 1, build: buildGltfObjects },
  { name: 'gltf-closeup', weight: 1, build: buildGltfCloseup },
];
