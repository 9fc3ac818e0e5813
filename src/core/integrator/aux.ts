/**
 * Auxiliary outputs for denoising: the first-hit albedo and shading normal of one
 * sample, as Open Image Denoise defines its `albedo` and `normal` feature images
 * (OIDN documentation, "RT" filter): per-sample values in [0, 1] and [-1, 1] that the
 * film averages over the same samples as the radiance (film.ts, addSampleAux).
 *
 * - The camera ray is the sample's own (same sampler dimensions as trace-path.ts), and
 *   glTF alpha (stochastic opacity) is decided with the path's own random numbers, so
 *   the aux image sees what the radiance sees.
 * - Perfect specular surfaces (a smooth conductor, a scene dielectric) are followed,
 *   as OIDN recommends: the path's own BSDF sample picks reflection or refraction (its
 *   lobe number), the albedo is multiplied by that sample's weight (the Fresnel colour
 *   of a mirror, the tint of glass) and taken at the first non-delta hit; averaged over
 *   samples this is OIDN's "Fresnel blend of the reflected and transmitted albedos".
 *   At most AUX_DELTA_LIMIT such events are followed.
 * - Albedo of a non-delta hit: the diffuse colour; a rough conductor's specular colour
 *   (reflectivity at normal incidence); a glTF material's layer sum (gltfAlbedo); plus
 *   emission, clamped to [0, 1] per channel (a light is 1, an unlit surface its colour).
 * - A ray that leaves the scene: the environment's radiance clamped to [0, 1] (0 where
 *   there is none), times the throughput of the delta chain; normal 0 when the camera
 *   ray itself escapes (OIDN's "no surface"), else the last delta surface's normal.
 * - The normal: world-space shading normal (vertex-interpolated, normal-mapped on
 *   glTF), turned towards the side the ray arrives from.
 *
 * Not in the hot loop: PathTracer calls this only for films that carry aux planes, so
 * renders without them run the unchanged trace.
 */
import { bsdfSample } from '../bsdf/bsdf.ts';
import {
  MATERIAL_CONDUCTOR,
  MATERIAL_DIFFUSE,
  MATERIAL_GLTF,
  MATERIAL_STRIDE,
  M_COLOR,
  M_DELTA,
  M_EMISSION,
  M_EMISSIVE,
  M_GEOMETRIC_SIDE,
  M_TYPE,
} from '../bsdf/materials.ts';
import { SHAPE_SPHERE, SHAPE_TRIANGLE } from '../geometry/ray.ts';
import { OFFSET_SCALE, QUAD_STRIDE, Q_NORMAL, SPHERE_STRIDE } from '../geometry/shapes.ts';
import { intersectScene } from '../accel/trace.ts';
import {
  DIM_ALPHA,
  DIM_ALPHA_EXTRA,
  DIM_ALPHA_STRIDE,
  DIM_BOUNCE,
  DIM_BSDF,
  DIM_BSDF_LOBE,
  DIM_FILM,
  DIM_LENS,
  DIM_PER_BOUNCE,
  DIM_ROULETTE,
} from '../sampling/sampler.ts';
import { completeTriangleHit } from './triangle-surface.ts';
import { MAX_ALPHA_CROSSINGS, gltfRow, shadeGltfHit } from './gltf-surface.ts';
import type { PathTracer } from './path-tracer.ts';
import { AuxSample, clamp01, finish, gltfAlbedo } from './aux-albedo.ts';

export { AuxSample, gltfAlbedo };

/** Perfect specular scattering events followed before the albedo is taken as it stands. */
export const AUX_DELTA_LIMIT = 8;

/**
 * The albedo and normal of sample `sampleIndex` of pixel (px, py) into `out`.
 * PathTracer's `traceAux` (set on the prototype in path-tracer.ts). `started`: the
 * sampler is already at this pixel sample (trace of the same sample just ran; fill is a
 * pure function of the state startPixelSample sets), which saves the Sobol set-up.
 */
export function traceAux(
  this: PathTracer,
  px: number,
  py: number,
  sampleIndex: number,
  out: AuxSample,
  started = false,
): void {
  const scene = this.scene;
  const materials = scene.materials;
  const spheres = scene.spheres;
  const quads = scene.quads;
  const gltf = scene.gltf;
  const sampler = this.sampler;
  const ray = this.ray;
  const hit = this.hit;
  const bq = this.bq;
  const bs = this.bs;
  const sp = bq.shading;
  const u = this.u;
  const aperture = this.camera.aperture > 0;
  if (!started) sampler.startPixelSample(py * this.width + px, sampleIndex, aperture);
  sampler.fillRange(DIM_FILM, 0, aperture ? DIM_LENS + 2 - DIM_FILM : DIM_LENS - DIM_FILM, u);
  this.camera.generateRayFromSamples(px, py, u, DIM_LENS - DIM_FILM, ray);
  // Throughput of the delta chain so far.
  let tr = 1,
    tg = 1,
    tb = 1;
  let onx = 0,
    ony = 0,
    onz = 0;
  let crossings = 0;
  for (let depth = 0; ; depth++) {
    if (!intersectScene(scene, ray, hit)) {
      let er = 0,
        eg = 0,
        eb = 0;
      const env = scene.envMap;
      if (env !== null) {
        const es = this.es;
        env.eval(ray.dx, ray.dy, ray.dz, es);
        er = es.r;
        eg = es.g;
        eb = es.b;
      } else if (scene.hasEnvironment) {
        er = scene.envR;
        eg = scene.envG;
        eb = scene.envB;
      }
      finish(out, tr * clamp01(er), tg * clamp01(eg), tb * clamp01(eb), onx, ony, onz);
      return;
    }
    const t = hit.t;
    let x = ray.ox + t * ray.dx;
    let y = ray.oy + t * ray.dy;
    let z = ray.oz + t * ray.dz;
    let nx: number, ny: number, nz: number;
    let snx: number, sny: number, snz: number;
    let m: number;
    let shapeScale: number;
    let isGltf = false;
    const index = hit.index;
    if (hit.kind === SHAPE_SPHERE) {
      const o = index * SPHERE_STRIDE;
      const r = spheres[o + 3];
      nx = (x - spheres[o]) / r;
      ny = (y - spheres[o + 1]) / r;
      nz = (z - spheres[o + 2]) / r;
      const inv = 1 / Math.sqrt(nx * nx + ny * ny + nz * nz);
      nx *= inv;
      ny *= inv;
      nz *= inv;
      x = spheres[o] + r * nx;
      y = spheres[o + 1] + r * ny;
      z = spheres[o + 2] + r * nz;
      snx = nx;
      sny = ny;
      snz = nz;
      m = scene.sphereMaterial[index];
      shapeScale = scene.sphereScale[index];
    } else if (hit.kind === SHAPE_TRIANGLE) {
      const ts = this.ts;
      completeTriangleHit(scene, hit, ts);
      x = ts.x;
      y = ts.y;
      z = ts.z;
      nx = ts.nx;
      ny = ts.ny;
      nz = ts.nz;
      m = ts.material;
      shapeScale = ts.scale;
      if (gltf !== null && materials[m * MATERIAL_STRIDE + M_TYPE] === MATERIAL_GLTF) {
        shadeGltfHit(scene, gltf, index, hit.b1, hit.b2, gltfRow(materials, m), ts, sp, this.gw);
        if (sp.opacity < 1 && crossings < MAX_ALPHA_CROSSINGS) {
          // The path's own decision (trace-path.ts): the same dimension, the same number.
          const au = this.au;
          sampler.fill(
            crossings === 0
              ? DIM_BOUNCE + depth * DIM_PER_BOUNCE + DIM_ALPHA
              : DIM_ALPHA_EXTRA + depth * DIM_ALPHA_STRIDE + crossings,
            1,
            au,
          );
          if (au[0] >= sp.opacity) {
            crossings++;
            const lift =
              (ray.dx * nx + ray.dy * ny + ray.dz * nz >= 0 ? 1 : -1) *
              Math.max(Math.abs(x), Math.abs(y), Math.abs(z), shapeScale) *
              OFFSET_SCALE;
            ray.ox = x + nx * lift;
            ray.oy = y + ny * lift;
            ray.oz = z + nz * lift;
            depth--;
            continue;
          }
        }
        isGltf = true;
      }
      snx = ts.snx;
      sny = ts.sny;
      snz = ts.snz;
    } else {
      const o = index * QUAD_STRIDE;
      nx = quads[o + Q_NORMAL];
      ny = quads[o + Q_NORMAL + 1];
      nz = quads[o + Q_NORMAL + 2];
      snx = nx;
      sny = ny;
      snz = nz;
      m = scene.quadMaterial[index];
      shapeScale = scene.quadScale[index];
    }
    // The shading normal on the side the ray comes from.
    const facing = snx * ray.dx + sny * ray.dy + snz * ray.dz > 0 ? -1 : 1;
    onx = facing * snx;
    ony = facing * sny;
    onz = facing * snz;
    const mo = m * MATERIAL_STRIDE;
    const mtype = materials[mo + M_TYPE];
    const front = nx * ray.dx + ny * ray.dy + nz * ray.dz < 0;
    if (
      mtype !== MATERIAL_GLTF &&
      materials[mo + M_DELTA] !== 0 &&
      depth < AUX_DELTA_LIMIT &&
      !(materials[mo + M_EMISSIVE] !== 0 && front)
    ) {
      // A perfect specular surface: follow the path's own choice of lobe.
      let sx = snx,
        sy = sny,
        sz = snz;
      if (materials[mo + M_GEOMETRIC_SIDE] === 0 && facing < 0) {
        sx = -snx;
        sy = -sny;
        sz = -snz;
      }
      const fsign = sz >= 0 ? 1 : -1;
      const fa = -1 / (fsign + sz);
      const fb = sx * sy * fa;
      const fsx = 1 + fsign * sx * sx * fa;
      const fsy = fsign * fb;
      const fsz = -fsign * sx;
      const ftx = fb;
      const fty = fsign + sy * sy * fa;
      const ftz = -sy;
      const wox = -ray.dx,
        woy = -ray.dy,
        woz = -ray.dz;
      bq.wox = wox * fsx + woy * fsy + woz * fsz;
      bq.woy = wox * ftx + woy * fty + woz * ftz;
      bq.woz = wox * sx + woy * sy + woz * sz;
      sampler.fillRange(DIM_BOUNCE + depth * DIM_PER_BOUNCE, DIM_BSDF, DIM_ROULETTE, u);
      bq.u0 = u[DIM_BSDF];
      bq.u1 = u[DIM_BSDF + 1];
      bq.u2 = u[DIM_BSDF_LOBE];
      if (!bsdfSample(materials, m, bq, bs)) {
        finish(out, 0, 0, 0, onx, ony, onz);
        return;
      }
      // The albedo's factor is the surface's colour, not the radiance weight: etaScale
      // undoes refraction's 1/η² (radiance compression), which is no reflectance.
      tr *= bs.weightR * bs.etaScale;
      tg *= bs.weightG * bs.etaScale;
      tb *= bs.weightB * bs.etaScale;
      const wix = bs.wx * fsx + bs.wy * ftx + bs.wz * sx;
      const wiy = bs.wx * fsy + bs.wy * fty + bs.wz * sy;
      const wiz = bs.wx * fsz + bs.wy * ftz + bs.wz * sz;
      const scale = Math.max(Math.abs(x), Math.abs(y), Math.abs(z), shapeScale) * OFFSET_SCALE;
      const side = wix * nx + wiy * ny + wiz * nz >= 0 ? scale : -scale;
      ray.ox = x + nx * side;
      ray.oy = y + ny * side;
      ray.oz = z + nz * side;
      const inv = 1 / Math.sqrt(wix * wix + wiy * wiy + wiz * wiz);
      ray.dx = wix * inv;
      ray.dy = wiy * inv;
      ray.dz = wiz * inv;
      ray.tMax = Infinity;
      crossings = 0;
      continue;
    }
    let ar: number, ag: number, ab: number;
    if (isGltf) {
      gltfAlbedo(sp, out);
      ar = out.ar;
      ag = out.ag;
      ab = out.ab;
      if (front) {
        ar += sp.emR;
        ag += sp.emG;
        ab += sp.emB;
      }
    } else {
      // Diffuse: its albedo; conductor: its specular colour; a dielectric past the
      // chain's limit: its tint. All are M_COLOR.
      ar = materials[mo + M_COLOR];
      ag = materials[mo + M_COLOR + 1];
      ab = materials[mo + M_COLOR + 2];
      if (mtype !== MATERIAL_DIFFUSE && mtype !== MATERIAL_CONDUCTOR && depth >= AUX_DELTA_LIMIT) {
        ar = 1;
        ag = 1;
        ab = 1;
      }
      if (materials[mo + M_EMISSIVE] !== 0 && front) {
        ar += materials[mo + M_EMISSION];
        ag += materials[mo + M_EMISSION + 1];
        ab += materials[mo + M_EMISSION + 2];
      }
    }
    finish(out, tr * clamp01(ar), tg * clamp01(ag), tb * clamp01(ab), onx, ony, onz);
    return;
  }
}
