// A pathwise-scene/1 file rebuilt as a three.js scene, for the peer benchmark
// (three-gpu-pathtracer renders it). Only what the benchmark's scenes use is
// mapped: quads and spheres with diffuse materials (emission included) and the
// pinhole camera. Anything else throws, so a scene that cannot be reproduced
// is never measured silently different.
import {
  BufferGeometry,
  Color,
  DoubleSide,
  Float32BufferAttribute,
  LinearSRGBColorSpace,
  Mesh,
  MeshStandardMaterial,
  PerspectiveCamera,
  RectAreaLight,
  Scene,
  SphereGeometry,
} from 'three';

/** Two triangles of the parallelogram corner + s·u + t·v, wound so the normal is u × v (the file's front). */
function quadGeometry({ corner: c, u, v }) {
  const p = (s, t) => [0, 1, 2].map((k) => c[k] + s * u[k] + t * v[k]);
  const positions = [p(0, 0), p(1, 0), p(1, 1), p(0, 0), p(1, 1), p(0, 1)].flat();
  const g = new BufferGeometry();
  g.setAttribute('position', new Float32BufferAttribute(positions, 3));
  g.computeVertexNormals();
  return g;
}

/**
 * Diffuse albedo becomes a white-specular-free standard material (roughness 1,
 * metalness 0). Emission (radiance) becomes emissive × emissiveIntensity:
 * three-gpu-pathtracer adds `emissiveIntensity * emissive` as radiance where a
 * path hits the surface (get_surface_record_function.glsl.js), so the colour is
 * the emission over its largest component and the intensity that component.
 * Colours are given as linear sRGB, the file's space and three's working space.
 */
function standardMaterial(def, name) {
  if (def.type !== 'diffuse') {
    throw new Error(`material ${name}: type ${def.type} is not mapped by the peer benchmark`);
  }
  const m = new MeshStandardMaterial({ roughness: 1, metalness: 0, side: DoubleSide });
  m.color = new Color().setRGB(...def.albedo, LinearSRGBColorSpace);
  if (def.emission && Math.max(...def.emission) > 0) {
    const peak = Math.max(...def.emission);
    m.emissive = new Color().setRGB(...def.emission.map((e) => e / peak), LinearSRGBColorSpace);
    m.emissiveIntensity = peak;
  }
  return m;
}

/**
 * An emissive, axis-aligned, downward-facing quad as a RectAreaLight of the
 * same radiance (three-gpu-pathtracer adds color × intensity as radiance and
 * samples it by next-event estimation with MIS). Its limits, which make this
 * a different scene: camera rays do not see area lights (the ceiling shows
 * instead), and it emits from one side only, as the quad does.
 */
function rectLight(shape, def) {
  const { corner: c, u, v } = shape;
  const down = u[1] === 0 && v[1] === 0 && u[2] * v[0] - u[0] * v[2] < 0;
  if (!down || u[2] !== 0 || v[0] !== 0) {
    throw new Error('only a downward quad with u along x and v along z becomes a RectAreaLight');
  }
  const peak = Math.max(...def.emission);
  const light = new RectAreaLight(0xffffff, peak, u[0], v[2]);
  light.color.setRGB(...def.emission.map((e) => e / peak), LinearSRGBColorSpace);
  light.position.set(c[0] + u[0] / 2, c[1], c[2] + v[2] / 2);
  // Local −z (the lit side) turned to −y; local x (width) stays x, local y (height) becomes −z.
  light.rotation.set(-Math.PI / 2, 0, 0);
  return light;
}

/**
 * The scene and camera at width × height; `summary` lists what was built.
 * options.emitters: 'emissive' (default; emissive triangles, reached only by
 * BSDF sampling) or 'rect-area-light' (see rectLight).
 */
export function threeSceneFromPathwise(json, width, height, options = {}) {
  const emitters = options.emitters ?? 'emissive';
  const summary = { meshes: 0, emissiveMeshes: 0, rectAreaLights: 0, emitters };
  if (json.environment) throw new Error('environment is not mapped by the peer benchmark');
  if (json.lights?.length) throw new Error('lights are not mapped by the peer benchmark');
  const materials = {};
  for (const [name, def] of Object.entries(json.materials)) {
    materials[name] = standardMaterial(def, name);
  }
  const scene = new Scene();
  // A black background, not null: three-gpu-pathtracer then accumulates with
  // float blending straight into its target (backgroundAlpha 1), and rays that
  // leave the open front of the box see black, as in pathwise.
  scene.background = new Color(0, 0, 0);
  for (const shape of json.shapes) {
    const def = json.materials[shape.material];
    const emits = def.emission && Math.max(...def.emission) > 0;
    if (emits && emitters === 'rect-area-light') {
      scene.add(rectLight(shape, def));
      summary.rectAreaLights++;
      continue;
    }
    let geometry;
    if (shape.type === 'quad') geometry = quadGeometry(shape);
    else if (shape.type === 'sphere') {
      geometry = new SphereGeometry(shape.radius, 96, 48);
      geometry.translate(...shape.center);
    } else throw new Error(`shape type ${shape.type} is not mapped by the peer benchmark`);
    scene.add(new Mesh(geometry, materials[shape.material]));
    summary.meshes++;
    if (emits) summary.emissiveMeshes++;
  }
  const cam = json.camera;
  if (cam.aperture) throw new Error('a thin-lens camera is not mapped by the peer benchmark');
  const camera = new PerspectiveCamera(cam.fovY, width / height, 0.1, 1e5);
  camera.position.set(...cam.position);
  camera.up.set(...(cam.up ?? [0, 1, 0]));
  camera.lookAt(...cam.target);
  camera.updateMatrixWorld();
  scene.updateMatrixWorld(true);
  return { scene, camera, summary };
}
