/**
 * The generator's punctual family (issue 25): glTF models under KHR_lights_punctual
 * lights, drawn with `generateScene(seed, { family: 'punctual' })`, for
 * consistency-e.test.ts. A delta light cannot be hit, so it cannot join the BSDF-only
 * comparison of the other families; these scenes check it two other ways (punctual.ts):
 * Sobol against independent samples, and each point light against a tiny emissive
 * sphere standing in for it.
 *
 * Each scene: a diffuse floor, a constant environment now and then, one to three glTF
 * objects with materials of GLTF_MATERIALS (archetypes-gltf.ts) and one to three
 * punctual lights (gltf-draw-lights.ts), the first a point light. The sphere stand-in
 * asks three things of the scene, which the builder ensures:
 * - no Dirac lobe anywhere (withoutDeltaLobes): a point light seen through a mirror or
 *   smooth glass is lost to a path tracer (no vertex can connect to it), the sphere is
 *   not; so the floor is diffuse and every glTF roughness is at least MIN_ROUGHNESS;
 * - point lights outside the camera's view (the sphere would be seen, the point not);
 * - point lights clear of every surface by at least CLEARANCE, so the sphere's angular
 *   radius seen from any receiver is at most POINT_SPHERE_RADIUS / CLEARANCE.
 * There is no other emitter: area lights would only add noise to both renders alike.
 */
import { trs } from './affine.ts';
import {
  bounces,
  environment,
  extent,
  pointIn,
  type Archetype,
  type Region,
} from './archetypes.ts';
import { GLTF_MATERIALS, drawGltfMesh } from './archetypes-gltf.ts';
import type { PunctualLightJson, SceneBuilder } from './builder.ts';
import { drawPunctualLight, type PunctualType } from './gltf-draw-lights.ts';
import type { GltfMaterialJson } from './gltf-files.ts';
import { add, cross, dot, length, normalize, sub, type Vec3 } from './vec.ts';

/** Smallest glTF roughness: α = 0.04, a lobe ~0.02 rad wide, 200× the sphere's radius. */
export const MIN_ROUGHNESS = 0.2;
/** Least distance from a point light to any surface, in the archetype's unit frame. */
export const CLEARANCE = 0.5;
/** Radius of the sphere standing in for a point light, in the unit frame. */
export const POINT_SPHERE_RADIUS = 1e-4;

/**
 * The material with every Dirac lobe made rough: base and coat roughness at least
 * MIN_ROUGHNESS, and a transmissive index at least 1.33 (index-matched rough
 * transmission, ior 1, passes light straight through: a Dirac lobe whatever the
 * roughness).
 */
export function withoutDeltaLobes(material: GltfMaterialJson): GltfMaterialJson {
  const m = structuredClone(material) as GltfMaterialJson & {
    pbrMetallicRoughness: { roughnessFactor: number };
    extensions?: Record<string, Record<string, number>>;
  };
  const pbr = m.pbrMetallicRoughness;
  pbr.roughnessFactor = Math.max(MIN_ROUGHNESS, pbr.roughnessFactor);
  const ext = m.extensions ?? {};
  const coat = ext.KHR_materials_clearcoat;
  if (coat !== undefined)
    coat.clearcoatRoughnessFactor = Math.max(MIN_ROUGHNESS, coat.clearcoatRoughnessFactor ?? 0);
  if (ext.KHR_materials_ior !== undefined)
    ext.KHR_materials_ior.ior = Math.max(1.33, ext.KHR_materials_ior.ior);
  return m;
}

interface Placed {
  center: Vec3;
  /** Radius of a ball holding the object (a box's corner is √3 from its centre). */
  reach: number;
}

/** Whether `p` is inside the camera's view, with a margin for the pixel filter and the lens. */
function inView(p: Vec3, eye: Vec3, target: Vec3, fovY: number, aspect: number): boolean {
  const f = normalize(sub(target, eye));
  const r = normalize(cross(f, [0, 1, 0]));
  const u = cross(r, f);
  const v = sub(p, eye);
  const z = dot(v, f);
  if (z <= 0) return false;
  const t = Math.tan(((fovY / 2) * Math.PI) / 180) * 1.25;
  return Math.abs(dot(v, u)) < t * z && Math.abs(dot(v, r)) < t * aspect * z;
}

function buildPunctual(b: SceneBuilder): ReturnType<Archetype['build']> {
  const g = b.rng;
  const S = 40;
  b.quad([-S / 2, 0, -S / 2], [0, 0, S], [S, 0, 0], b.material('diffuse'));
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
  const target = add(
    [0, 0.8, 0],
    [g.uniform(-0.5, 0.5), g.uniform(-0.3, 0.3), g.uniform(-0.5, 0.5)],
  );
  const fovY = g.uniform(25, 60);
  const placed: Placed[] = [];
  const count = g.int(1, 3);
  for (let i = 0; i < count || placed.length === 0; i++) {
    const size = extent(region) * g.uniform(0.08, 0.18);
    const c: Vec3 = i < count ? pointIn(b, region) : [0, 0, 0];
    c[1] = Math.max(c[1], size * 1.2);
    if (length(sub(c, eye)) < size * 3) continue;
    const drawer = g.weighted(GLTF_MATERIALS.map((d) => [d, d.weight] as const));
    const drawn = drawer.draw(g);
    const mesh = drawGltfMesh(g, drawer.closedOnly === true);
    // Roughened: no 'gltf-smooth' here.
    const features = drawn.features.map((f) => (f === 'gltf-smooth' ? 'gltf-rough' : f));
    b.tag('gltf', ...features, ...(mesh.closed ? [] : (['gltf-open-mesh'] as const)));
    b.gltf({
      mesh,
      material: withoutDeltaLobes(drawn.material),
      transform: trs(c, g.direction(), g.uniform(0, 2 * Math.PI), [size, size, size]),
    });
    placed.push({ center: c, reach: size * Math.sqrt(3) });
  }
  // Lights aimed at an object, the first a point light. A point light that lands too
  // near a surface or in view is drawn again, each time farther off (up to 40 times),
  // else left out; the first then goes 3 units above the eye, out of view (the view
  // axis is at most 50° below the horizontal, half the field at most 30°).
  const lightCount = g.int(1, 3);
  const clear = (p: Vec3): boolean =>
    p[1] >= CLEARANCE &&
    placed.every((o) => length(sub(p, o.center)) - o.reach >= CLEARANCE) &&
    !inView(p, eye, target, fovY, 32 / 24);
  for (let i = 0; i < lightCount; i++) {
    const types: PunctualType[] = i === 0 ? ['point'] : ['point', 'spot', 'directional'];
    let done = false;
    for (let attempt = 0; attempt < 40 && !done; attempt++) {
      const aim = g.pick(placed).center;
      const light = drawPunctualLight(g, aim, 2.5 + 0.25 * attempt, types);
      const p = light.scene.position as Vec3 | undefined;
      if (light.gltf.type === 'point' && !clear(p!)) continue;
      b.punctualLights.push(light.scene as unknown as PunctualLightJson);
      b.tag(`punctual-${light.gltf.type}`);
      done = true;
    }
    if (!done && i === 0) {
      const p = add(eye, [0, 3, 0]);
      if (!clear(p)) throw new Error('no place for the point light');
      const color: Vec3 = [g.uniform(0.3, 1), g.uniform(0.3, 1), g.uniform(0.3, 1)];
      // Irradiance about 1 at the objects, like drawPunctualLight's.
      const d = length(sub(p, target));
      b.punctualLights.push({ type: 'point', position: p, intensity: d * d, color });
      b.tag('punctual-point');
    }
  }
  b.tag('camera-outside');
  return {
    camera: { position: eye, target, up: [0, 1, 0], fovY },
    maxBounces: bounces(b, 1, 6),
  };
}

export const PUNCTUAL_ARCHETYPES: Archetype[] = [
  { name: 'punctual-objects', weight: 1, build: buildPunctual },
];
