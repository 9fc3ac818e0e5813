/**
 * The hot loop of unidirectional path tracing (Kajiya 1986; pbr-book 4e
 * §13.4): one sample of one pixel, traced from the camera to its end. Two
 * estimators share the loop:
 * - 'nee-mis': next-event estimation on every emitter combined with BSDF
 *   sampling by multiple importance sampling with the power heuristic
 *   (Veach & Guibas 1995; pbr-book 4e §13.4 "PathIntegrator");
 * - 'bsdf': BSDF sampling only, paths score emission where they land —
 *   the estimator of the original WebGL demos, kept for comparison.
 *
 * `maxBounces` = B keeps exactly the light reaching the eye over paths with
 * at most B scattering events. Russian roulette starts after the third
 * bounce (pbr-book 3e §14.5.5); it changes noise, not the expected value.
 *
 * The loop allocates nothing: rays, hits and BSDF records are the tracer's
 * fields, created once, and the scene is read from typed arrays copied into
 * locals.
 *
 * Why one long function: V8 inlines calls into it only while its cumulative
 * inlining budget (920 bytes of bytecode) lasts, and a call it does not
 * inline boxes its double arguments. The common cases (the diffuse BSDF,
 * quad lights, the shading frame) are therefore written out here, with the
 * generic calls (bsdf.ts, lights.ts) for every other kind; cutting the loop
 * into helpers would turn them back into calls (docs/performance.md).
 * PathTracer (path-tracer.ts) owns the state and runs the loop per pixel.
 */
import { bsdfEval, bsdfSample } from '../bsdf/bsdf.ts';
import { dispersedIor, dispersionChannel } from '../bsdf/dispersion.ts';
import {
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
import {
  LIGHT_ENVIRONMENT,
  LIGHT_POINT,
  SHAPE_QUAD,
  SHAPE_SPHERE,
  SHAPE_TRIANGLE,
} from '../geometry/ray.ts';
import {
  OFFSET_SCALE,
  QUAD_STRIDE,
  Q_AREA,
  Q_CORNER,
  Q_NORMAL,
  Q_PLANE,
  Q_U,
  Q_V,
  SPHERE_STRIDE,
} from '../geometry/shapes.ts';
import { intersectScene, occluded } from '../accel/trace.ts';
import { SPHERE_HUGE, SPHERE_TINY } from '../geometry/intersect.ts';
import { sampleLight } from '../lights/lights.ts';
import { LIGHT_SPLIT } from '../lights/light-bvh.ts';
import { hashToUnit, sampleKey } from '../rng/pcg.ts';
import { environmentLightPdf, lightPdf } from '../lights/light-pdf.ts';
import { completeTriangleHit } from './triangle-surface.ts';
import { anisotropyToLocal } from '../gltf-material/anisotropy-frame.ts';
import {
  MAX_ALPHA_CROSSINGS,
  gltfLightEmission,
  gltfRow,
  shadeGltfHit,
  shadowTransmittance,
} from './gltf-surface.ts';
import {
  DIM_ALPHA,
  DIM_ALPHA_EXTRA,
  DIM_ALPHA_STRIDE,
  DIM_BOUNCE,
  DIM_BSDF,
  DIM_BSDF_LOBE,
  DIM_FILM,
  DIM_LENS,
  DIM_LIGHT_CHOICE,
  DIM_LIGHT_POINT,
  DIM_PER_BOUNCE,
  DIM_ROULETTE,
} from '../sampling/sampler.ts';
import type { PathTracer, RenderStats } from './path-tracer.ts';

const INV_PI = 1 / Math.PI;
const PI_OVER_4 = Math.PI / 4;
const PI_OVER_2 = Math.PI / 2;

/**
 * A split light sample's shadow ray is traced for sure when its unoccluded contribution is
 * at least this share of the vertex's strongest, and else by Russian roulette (below).
 */
const SHADOW_RR = 0.25;
/** Salts the seed of the roulette's key, apart from the sampler's (shadowRouletteKey). */
const SHADOW_RR_SALT = 0x2c1b3c6d;

/**
 * The key of a path's shadow-ray roulette: light j at depth d decides with
 * hashToUnit(key, d · LIGHT_SPLIT + j). Its own key, the seed salted: the sampler hashes
 * sampleKey(seed, …) into the dimensions it does not stratify (sampler.ts), so that key
 * would hand the roulette a number the light choice or point also used, and bias it
 * (tests/statistical/shadow-roulette.test.ts).
 */
export function shadowRouletteKey(seed: number, pixelIndex: number, sampleIndex: number): number {
  return sampleKey(seed ^ SHADOW_RR_SALT, pixelIndex, sampleIndex);
}

/**
 * Numbers per pending light sample: the shadow ray's origin, direction and length, and
 * what it adds.
 */
export const NEE_RECORD = 10;

/** Russian roulette begins once a path has scattered this many times. */
const ROULETTE_DEPTH = 3;

/** The R2 sequence's step (Roberts 2018): 1/g and 1/g² for the plastic number g. */
const R2_A0 = 0.7548776662466927;
const R2_A1 = 0.5698402909980532;

/**
 * Traces sample `sampleIndex` of pixel (px, py); the radiance lands in
 * this.lr, this.lg, this.lb. PathTracer's `trace` method (path-tracer.ts
 * sets it on the prototype): a method, not a function of the tracer, so
 * that its code and the call in renderRow stay those V8 was measured with —
 * as a plain function V8 compiled renderRow earlier, inlined the film's
 * addRadiance there with only half of its addFixed calls, and Cornell
 * lost ~2 %.
 */
export function trace(
  this: PathTracer,
  px: number,
  py: number,
  sampleIndex: number,
  stats: RenderStats,
): void {
  const scene = this.scene;
  const materials = scene.materials;
  const spheres = scene.spheres;
  const quads = scene.quads;
  const lights = scene.lights;
  // The light BVH when it chooses among the lights, null for the choice by power.
  const lightBvh = this.lightBvh;
  const sampler = this.sampler;
  const ray = this.ray;
  const hit = this.hit;
  const bs = this.bs;
  const fv = this.fv;
  const nee = this.estimator === 'nee-mis' && lights !== null;
  const maxBounces = this.maxBounces;
  const lightSplit = this.lightSplit;
  // glTF: null in scenes without glTF shapes, which then never take its branches.
  const gltf = scene.gltf;
  const alphaShadows = gltf !== null && gltf.hasAlpha;
  const sp = this.bq.shading;

  const u = this.u;
  const aperture = this.camera.aperture > 0;
  sampler.startPixelSample(py * this.width + px, sampleIndex, aperture);
  // Film and lens dimensions are adjacent: one fill draws both pairs (the
  // lens pair only with an aperture).
  sampler.fillRange(DIM_FILM, 0, aperture ? DIM_LENS + 2 - DIM_FILM : DIM_LENS - DIM_FILM, u);
  const lens = DIM_LENS - DIM_FILM;
  this.camera.generateRayFromSamples(px, py, u, lens, ray);
  let segments = 1;
  let lr = 0,
    lg = 0,
    lb = 0;
  let br = 1,
    bg = 1,
    bb = 1;
  let etaScale = 1;
  // The camera ray counts as "specular": emission it finds is not light-sampled.
  let specular = true;
  let prevPdf = 0;
  let prevX = 0,
    prevY = 0,
    prevZ = 0;
  // The previous vertex's normal: the light BVH's choice there depended on it.
  let prevNx = 0,
    prevNy = 0,
    prevNz = 0;
  // Alpha surfaces the current segment passed through (see gltf-surface.ts).
  let crossings = 0;
  // KHR_materials_volume: the absorbing solid the path is inside, if any — σa
  // per channel, set by refraction into a glTF volume and cleared by
  // refraction out of one (one medium: nested volumes are not tracked).
  let inMedium = false;
  let sar = 0,
    sag = 0,
    sab = 0;
  // KHR_materials_dispersion: the one colour channel the path carries, once chosen (dispersion.ts).
  let channel = -1;
  // The key of the shadow rays' roulette (below), hashed when first needed.
  let pathKey = -1;

  for (let depth = 0; ; depth++) {
    if (!intersectScene(scene, ray, hit)) {
      const env = scene.envMap;
      if (env !== null) {
        const es = this.es;
        env.eval(ray.dx, ray.dy, ray.dz, es);
        let w = 1;
        if (nee && !specular) {
          const pl = environmentLightPdf(lights!, lightBvh, ray.dx, ray.dy, ray.dz);
          w = (prevPdf * prevPdf) / (prevPdf * prevPdf + pl * pl);
        }
        lr += br * es.r * w;
        lg += bg * es.g * w;
        lb += bb * es.b * w;
      } else if (scene.hasEnvironment) {
        // The constant environment: no light sampling, no lookup.
        lr += br * scene.envR;
        lg += bg * scene.envG;
        lb += bb * scene.envB;
      }
      break;
    }
    const t = hit.t;
    const index = hit.index;
    if (inMedium) {
      // Beer–Lambert over the segment (rays have unit direction): T = exp(−σa·t),
      // pbr-book 4e §11.2. A path that leaves an open mesh without a hit is not absorbed.
      br *= Math.exp(-sar * t);
      bg *= Math.exp(-sag * t);
      bb *= Math.exp(-sab * t);
    }
    let x = ray.ox + t * ray.dx;
    let y = ray.oy + t * ray.dy;
    let z = ray.oz + t * ray.dz;
    let nx: number, ny: number, nz: number;
    // Shading normal: the geometric one except on meshes with vertex normals.
    let snx = 0,
      sny = 0,
      snz = 0;
    let m: number;
    let light: number;
    let shapeScale: number;
    // The hit's material is glTF: its parameters are in sp (this.bq.shading).
    let isGltf = false;
    if (hit.kind === SHAPE_SPHERE) {
      const o = index * SPHERE_STRIDE;
      const cx = spheres[o],
        cy = spheres[o + 1],
        cz = spheres[o + 2],
        r = spheres[o + 3];
      // Re-project the hit point onto the sphere: removes the error that
      // accumulated along a long ray (pbr-book 4e §6.8.5).
      nx = x - cx;
      ny = y - cy;
      nz = z - cz;
      if (!(r < SPHERE_HUGE && r > SPHERE_TINY)) {
        // Beyond 2^±400 the squares below would over- or underflow: to unit scale first.
        nx /= r;
        ny /= r;
        nz /= r;
      }
      const inv = 1 / Math.sqrt(nx * nx + ny * ny + nz * nz);
      nx *= inv;
      ny *= inv;
      nz *= inv;
      x = cx + r * nx;
      y = cy + r * ny;
      z = cz + r * nz;
      m = scene.sphereMaterial[index];
      light = scene.sphereLight[index];
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
      snx = ts.snx;
      sny = ts.sny;
      snz = ts.snz;
      m = ts.material;
      light = ts.light;
      shapeScale = ts.scale;
      if (gltf !== null && materials[m * MATERIAL_STRIDE + M_TYPE] === MATERIAL_GLTF) {
        shadeGltfHit(scene, gltf, index, hit.b1, hit.b2, gltfRow(materials, m), ts, sp, this.gw);
        if (sp.opacity < 1 && crossings < MAX_ALPHA_CROSSINGS) {
          // Stochastic opacity: the surface is there with probability `opacity`.
          const au = this.au;
          sampler.fill(
            crossings === 0
              ? DIM_BOUNCE + depth * DIM_PER_BOUNCE + DIM_ALPHA
              : DIM_ALPHA_EXTRA + depth * DIM_ALPHA_STRIDE + crossings,
            1,
            au,
          );
          if (au[0] >= sp.opacity) {
            // Not there: the same ray goes on from the far side. No scattering
            // event, so the depth stays (the loop's increment is undone).
            crossings++;
            const lift =
              (ray.dx * nx + ray.dy * ny + ray.dz * nz >= 0 ? 1 : -1) *
              Math.max(Math.abs(x), Math.abs(y), Math.abs(z), shapeScale) *
              OFFSET_SCALE;
            ray.ox = x + nx * lift;
            ray.oy = y + ny * lift;
            ray.oz = z + nz * lift;
            segments++;
            depth--;
            continue;
          }
        }
        isGltf = true;
        snx = ts.snx;
        sny = ts.sny;
        snz = ts.snz;
      }
    } else {
      const o = index * QUAD_STRIDE;
      nx = quads[o + Q_NORMAL];
      ny = quads[o + Q_NORMAL + 1];
      nz = quads[o + Q_NORMAL + 2];
      // Re-project onto the plane for the same reason.
      const off = nx * x + ny * y + nz * z - quads[o + Q_PLANE];
      x -= off * nx;
      y -= off * ny;
      z -= off * nz;
      m = scene.quadMaterial[index];
      light = scene.quadLight[index];
      shapeScale = scene.quadScale[index];
    }
    if (hit.kind !== SHAPE_TRIANGLE) {
      snx = nx;
      sny = ny;
      snz = nz;
    }
    const mo = m * MATERIAL_STRIDE;
    const wox = -ray.dx,
      woy = -ray.dy,
      woz = -ray.dz;
    const cosO = nx * wox + ny * woy + nz * woz;

    // Emission, front side only.
    if (materials[mo + M_EMISSIVE] !== 0 && cosO > 0) {
      let w = 1;
      // An emitter that is no light (an unlit glTF surface) is never light-sampled: weight 1.
      if (nee && !specular && light >= 0) {
        // Past alpha surfaces the light is farther than this last segment.
        const d = crossings === 0 ? t : Math.hypot(x - prevX, y - prevY, z - prevZ);
        // lightPdf's quad case written out: the call, not inlined, boxed
        // its five double arguments and its result on the heap.
        const pl =
          lightBvh === null && lights!.kind[light] === SHAPE_QUAD
            ? (lights!.prob[light] * d * d) /
              (quads[lights!.shape[light] * QUAD_STRIDE + Q_AREA] * cosO)
            : lightPdf(
                lights!,
                lightBvh,
                spheres,
                quads,
                light,
                index,
                prevX,
                prevY,
                prevZ,
                prevNx,
                prevNy,
                prevNz,
                d,
                cosO,
                lightSplit,
              );
        w = (prevPdf * prevPdf) / (prevPdf * prevPdf + pl * pl);
      }
      if (isGltf) {
        lr += br * sp.emR * w;
        lg += bg * sp.emG * w;
        lb += bb * sp.emB * w;
      } else {
        lr += br * materials[mo + M_EMISSION] * w;
        lg += bg * materials[mo + M_EMISSION + 1] * w;
        lb += bb * materials[mo + M_EMISSION + 2] * w;
      }
    }
    if (depth >= maxBounces) break;

    // Shading frame: glass needs the outward normal to know inside from
    // outside; every other surface scatters on both sides, so its frame
    // faces wo. With vertex normals the shading normal decides both, as in
    // Mitsuba 3 (the geometric normal still decides emission and offsets):
    // wo behind the shading normal flips it (Mitsuba's 'twosided' mirrors wi
    // in the shading frame), even where wo is in front of the geometric one.
    let sx = snx,
      sy = sny,
      sz = snz;
    // Glass (and transmissive glTF) keeps its outward normal: M_GEOMETRIC_SIDE.
    const geometricSide = materials[mo + M_GEOMETRIC_SIDE] !== 0;
    if (!geometricSide && snx * wox + sny * woy + snz * woz < 0) {
      sx = -snx;
      sy = -sny;
      sz = -snz;
    }
    // The tangents of the frame around s, in locals (Frame.setFromN written
    // out: the call was not inlined once trace's inlining budget was spent).
    const fsign = sz >= 0 ? 1 : -1;
    const fa = -1 / (fsign + sz);
    const fb = sx * sy * fa;
    const fsx = 1 + fsign * sx * sx * fa;
    const fsy = fsign * fb;
    const fsz = -fsign * sx;
    const ftx = fb;
    const fty = fsign + sy * sy * fa;
    const ftz = -sy;
    // KHR_materials_anisotropy: its direction on this frame's tangents.
    if (isGltf && sp.anisotropy > 0)
      anisotropyToLocal(this.gw.anisotropy, fsx, fsy, fsz, ftx, fty, ftz, sp);
    const bq = this.bq;
    if (isGltf && sp.clearcoat > 0) {
      // The coat normal (world space, gltf-surface.ts) into this frame; it flips with
      // the frame. Unmapped, it is the shading normal: exactly +z.
      const cx = sp.ccnx,
        cy = sp.ccny,
        cz = sp.ccnz;
      if (cx === snx && cy === sny && cz === snz) {
        sp.ccnx = 0;
        sp.ccny = 0;
        sp.ccnz = 1;
      } else {
        const cl = cx * sx + cy * sy + cz * sz;
        const k = cl < 0 ? -1 : 1;
        sp.ccnx = k * (cx * fsx + cy * fsy + cz * fsz);
        sp.ccny = k * (cx * ftx + cy * fty + cz * ftz);
        sp.ccnz = k * cl;
      }
    }
    const lwox = wox * fsx + woy * fsy + woz * fsz;
    const lwoy = wox * ftx + woy * fty + woz * ftz;
    const lwoz = wox * sx + woy * sy + woz * sz;
    const mtype = materials[mo + M_TYPE];
    // The diffuse case below reads only lwoz: the BSDF calls take the rest.
    if (mtype !== MATERIAL_DIFFUSE) {
      bq.wox = lwox;
      bq.woy = lwoy;
      bq.woz = lwoz;
    }
    const scale = Math.max(Math.abs(x), Math.abs(y), Math.abs(z), shapeScale) * OFFSET_SCALE;
    // Only the numbers this bounce reads: the light's when it samples one
    // (the choice only among several lights), the roulette number from the
    // bounce where roulette starts. Dimensions by role: light choice, light
    // point, BSDF direction, lobe, roulette (sampler.ts).
    const sampleLights = nee && materials[mo + M_DELTA] === 0;
    sampler.fillRange(
      DIM_BOUNCE + depth * DIM_PER_BOUNCE,
      sampleLights
        ? lightBvh !== null || lights!.count > 1
          ? DIM_LIGHT_CHOICE
          : DIM_LIGHT_POINT
        : DIM_BSDF,
      depth + 1 >= ROULETTE_DEPTH ? DIM_ROULETTE + 1 : DIM_ROULETTE,
      u,
    );
    if (isGltf && sp.dispersion > 0) {
      if (channel < 0) {
        // Keep one channel, chosen with probability ⅓, weighted 3 (dispersion.ts);
        // the lobe number is rescaled so the BSDF still gets a uniform one.
        channel = dispersionChannel(u[DIM_BSDF_LOBE]);
        u[DIM_BSDF_LOBE] = u[DIM_BSDF_LOBE] * 3 - channel;
        br = channel === 0 ? br * 3 : 0;
        bg = channel === 1 ? bg * 3 : 0;
        bb = channel === 2 ? bb * 3 : 0;
      }
      sp.ior = dispersedIor(sp.ior, sp.dispersion, channel);
    }

    // Next-event estimation.
    if (sampleLights) {
      const ls = this.ls;
      // The choice: by the light BVH at this point, up to lightSplit lights from the
      // subtrees of its cut (light-bvh.ts chooseSplit), or one light by power. Each
      // light is chosen with probability pick, and each adds its own estimate.
      let chosen = 1;
      let lp = -1;
      if (lightBvh === null) lp = lights!.choose(u[DIM_LIGHT_CHOICE]);
      else {
        lightBvh.setPoint(x, y, z, nx, ny, nz);
        chosen = lightBvh.chooseSplit(u[DIM_LIGHT_CHOICE], lightSplit);
      }
      let pending = 0;
      let strongest = 0;
      for (let c = 0; c < chosen; c++) {
        let l: number;
        if (lightBvh === null) {
          l = lp;
          ls.pick = lights!.prob[l];
          ls.triangle = -1;
        } else {
          l = lightBvh.chosenLight[c];
          ls.pick = lightBvh.chosenPick[c];
          ls.triangle = lightBvh.chosenTriangle[c];
        }
        // Each further light's point from the same numbers rotated (Cranley–Patterson
        // rotation by the R2 sequence's step): still uniform, so each sample unbiased.
        let lu0 = u[DIM_LIGHT_POINT],
          lu1 = u[DIM_LIGHT_POINT + 1];
        if (c > 0) {
          lu0 += c * R2_A0;
          lu1 += c * R2_A1;
          lu0 -= Math.floor(lu0);
          lu1 -= Math.floor(lu1);
        }
        // The sampled direction, the shadow ray's far end and the density.
        let sampled = false;
        let wix = 0,
          wiy = 0,
          wiz = 0;
        let lpx = 0,
          lpy = 0,
          lpz = 0;
        let lpdf = 0;
        let infinite = false;
        // A punctual light (lights/punctual.ts): no BSDF-sampled ray finds it, so its
        // sample's MIS weight is 1 (pbr-book 4e §13.4: pdf_bsdf counts as 0).
        let delta = false;
        if (lights!.kind[l] === SHAPE_QUAD) {
          // sampleLight's quad case (and finishAreaSample) written out,
          // the same arithmetic: the call was not inlined.
          const o = lights!.shape[l] * QUAD_STRIDE;
          const u0 = lu0,
            u1 = lu1;
          const qx = quads[o + Q_CORNER] + u0 * quads[o + Q_U] + u1 * quads[o + Q_V];
          const qy = quads[o + Q_CORNER + 1] + u0 * quads[o + Q_U + 1] + u1 * quads[o + Q_V + 1];
          const qz = quads[o + Q_CORNER + 2] + u0 * quads[o + Q_U + 2] + u1 * quads[o + Q_V + 2];
          const qnx = quads[o + Q_NORMAL],
            qny = quads[o + Q_NORMAL + 1],
            qnz = quads[o + Q_NORMAL + 2];
          wix = qx - x;
          wiy = qy - y;
          wiz = qz - z;
          const d2 = wix * wix + wiy * wiy + wiz * wiz;
          if (d2 > 0) {
            const dist = Math.sqrt(d2);
            wix /= dist;
            wiy /= dist;
            wiz /= dist;
            const cosLight = -(qnx * wix + qny * wiy + qnz * wiz);
            if (cosLight > 0) {
              const lift = lights!.offset[l];
              lpx = qx + lift * qnx;
              lpy = qy + lift * qny;
              lpz = qz + lift * qnz;
              lpdf = (ls.pick * d2) / (quads[o + Q_AREA] * cosLight);
              sampled = lpdf < Infinity;
            }
          }
        } else {
          ls.refX = x;
          ls.refY = y;
          ls.refZ = z;
          ls.u0 = lu0;
          ls.u1 = lu1;
          if (sampleLight(lights!, spheres, quads, l, ls)) {
            sampled = true;
            wix = ls.wx;
            wiy = ls.wy;
            wiz = ls.wz;
            lpx = ls.px;
            lpy = ls.py;
            lpz = ls.pz;
            lpdf = ls.pdf;
            infinite = ls.distance === Infinity;
            delta = lights!.kind[l] >= LIGHT_POINT;
          }
        }
        if (sampled) {
          const lwiz = wix * sx + wiy * sy + wiz * sz;
          // A frame facing wo sees light only above it; a transmissive glTF surface
          // (geometric side) reflects below it too when the path is inside.
          if (geometricSide ? lwiz !== 0 : lwiz > 0) {
            let fr: number, fg: number, fb: number, pb: number;
            if (mtype === MATERIAL_DIFFUSE) {
              // diffuseEval written out (diffuse.ts).
              if (lwoz <= 0 || lwiz <= 0) {
                fr = 0;
                fg = 0;
                fb = 0;
                pb = 0;
              } else {
                fr = materials[mo + M_COLOR] * INV_PI;
                fg = materials[mo + M_COLOR + 1] * INV_PI;
                fb = materials[mo + M_COLOR + 2] * INV_PI;
                pb = lwiz * INV_PI;
              }
            } else {
              bq.wix = wix * fsx + wiy * fsy + wiz * fsz;
              bq.wiy = wix * ftx + wiy * fty + wiz * ftz;
              bq.wiz = lwiz;
              bsdfEval(materials, m, bq, fv);
              fr = fv.r;
              fg = fv.g;
              fb = fv.b;
              pb = fv.pdf;
            }
            if (fr !== 0 || fg !== 0 || fb !== 0) {
              // Both ends lifted off their surfaces (see lights.ts): the
              // segment between them crosses neither. The origin leaves by
              // the geometric side wi is on.
              const lift = wix * nx + wiy * ny + wiz * nz >= 0 ? scale : -scale;
              const ox = x + nx * lift;
              const oy = y + ny * lift;
              const oz = z + nz * lift;
              let len = Infinity;
              let sdx = wix,
                sdy = wiy,
                sdz = wiz;
              if (!infinite) {
                const ex = lpx - ox;
                const ey = lpy - oy;
                const ez = lpz - oz;
                len = Math.sqrt(ex * ex + ey * ey + ez * ez);
                sdx = ex / len;
                sdy = ey / len;
                sdz = ez / len;
              }
              // One light sample: its ray is traced now, and an occluded one stops here,
              // before its emission is looked up (a texture, for glTF). Several (splitting):
              // the rays wait for the roulette below, which needs what each would add.
              let visible = 1;
              if (chosen === 1) {
                const sr = this.shadowRay;
                sr.ox = ox;
                sr.oy = oy;
                sr.oz = oz;
                sr.dx = sdx;
                sr.dy = sdy;
                sr.dz = sdz;
                sr.tMax = len;
                segments++;
                visible =
                  len > 0
                    ? alphaShadows
                      ? shadowTransmittance(scene, gltf!, sr, this.gw)
                      : occluded(scene, sr)
                        ? 0
                        : 1
                    : 0;
                if (!(visible > 0)) continue;
              }
              let er: number, eg: number, eb: number;
              // Not a shape (the environment, a punctual light): sampleLight wrote what arrives.
              if (lights!.kind[l] >= LIGHT_ENVIRONMENT) {
                er = ls.r;
                eg = ls.g;
                eb = ls.b;
              } else {
                const lmi = lights!.material[l];
                const lm = lmi * MATERIAL_STRIDE;
                if (materials[lm + M_TYPE] === MATERIAL_GLTF) {
                  // Emission varies over the mesh: looked up at the sampled point.
                  const gw = this.gw;
                  gltfLightEmission(
                    scene,
                    gltf!,
                    ls.triangle,
                    ls.b1,
                    ls.b2,
                    gltfRow(materials, lmi),
                    gw,
                  );
                  er = gw.emission.r;
                  eg = gw.emission.g;
                  eb = gw.emission.b;
                } else {
                  er = materials[lm + M_EMISSION];
                  eg = materials[lm + M_EMISSION + 1];
                  eb = materials[lm + M_EMISSION + 2];
                }
              }
              const pl = lpdf;
              const w = (pl / (pl * pl + (delta ? 0 : pb * pb))) * Math.abs(lwiz);
              if (inMedium && !infinite) {
                // The shadow ray runs inside the absorbing solid too.
                er *= Math.exp(-sar * len);
                eg *= Math.exp(-sag * len);
                eb *= Math.exp(-sab * len);
              }
              // What this light adds if nothing is in the way.
              const cr = br * fr * er * w,
                cg = bg * fg * eg * w,
                cb = bb * fb * eb * w;
              if (chosen === 1) {
                lr += cr * visible;
                lg += cg * visible;
                lb += cb * visible;
              } else {
                const o = pending * NEE_RECORD;
                const rec = this.neeRecords;
                rec[o] = ox;
                rec[o + 1] = oy;
                rec[o + 2] = oz;
                rec[o + 3] = sdx;
                rec[o + 4] = sdy;
                rec[o + 5] = sdz;
                rec[o + 6] = len;
                rec[o + 7] = cr;
                rec[o + 8] = cg;
                rec[o + 9] = cb;
                const c = cr + cg + cb;
                if (c > strongest) strongest = c;
                pending++;
              }
            }
          }
        }
      }
      if (pending > 0) {
        // Russian roulette on the shadow rays of the weak lights (pbr-book 4e §14.1.5 on
        // roulette; here per light sample, as Conty Estevez and Kulla's splitting leaves
        // many whose unoccluded contribution is a small share of the vertex's): a light
        // whose contribution c is under SHADOW_RR times the strongest's traces its ray
        // with probability q = c / (SHADOW_RR · strongest) and counts 1/q times. The
        // number that decides is hashed from the salted seed, pixel, sample, depth and
        // light, so it is independent of everything q depends on and the same in every
        // worker layout.
        const rec = this.neeRecords;
        const floor = SHADOW_RR * strongest;
        for (let j = 0; j < pending; j++) {
          const o = j * NEE_RECORD;
          const c = rec[o + 7] + rec[o + 8] + rec[o + 9];
          let inv = 1;
          if (c < floor) {
            const q = c / floor;
            if (pathKey === -1) {
              pathKey = shadowRouletteKey(sampler.seed, py * this.width + px, sampleIndex);
            }
            if (!(hashToUnit(pathKey, depth * LIGHT_SPLIT + j) < q)) continue;
            inv = 1 / q;
          }
          const sr = this.shadowRay;
          sr.ox = rec[o];
          sr.oy = rec[o + 1];
          sr.oz = rec[o + 2];
          sr.dx = rec[o + 3];
          sr.dy = rec[o + 4];
          sr.dz = rec[o + 5];
          const len = rec[o + 6];
          sr.tMax = len;
          segments++;
          const visible =
            len > 0
              ? alphaShadows
                ? shadowTransmittance(scene, gltf!, sr, this.gw)
                : occluded(scene, sr)
                  ? 0
                  : 1
              : 0;
          if (visible > 0) {
            const v = visible * inv;
            lr += rec[o + 7] * v;
            lg += rec[o + 8] * v;
            lb += rec[o + 9] * v;
          }
        }
      }
    }

    // Continue the path by sampling the BSDF.
    let bwx: number, bwy: number, bwz: number;
    if (mtype === MATERIAL_DIFFUSE) {
      // diffuseSample written out (diffuse.ts; the concentric map and
      // Malley's method of warps.ts): the same arithmetic, no calls.
      if (lwoz <= 0) break;
      const ox = 2 * u[DIM_BSDF] - 1;
      const oy = 2 * u[DIM_BSDF + 1] - 1;
      if (ox === 0 && oy === 0) {
        bwx = 0;
        bwy = 0;
      } else {
        let r: number, theta: number;
        if (Math.abs(ox) > Math.abs(oy)) {
          r = ox;
          theta = PI_OVER_4 * (oy / ox);
        } else {
          r = oy;
          theta = PI_OVER_2 - PI_OVER_4 * (ox / oy);
        }
        bwx = r * Math.cos(theta);
        bwy = r * Math.sin(theta);
      }
      bwz = Math.sqrt(Math.max(0, 1 - bwx * bwx - bwy * bwy));
      if (bwz <= 0) break;
      br *= materials[mo + M_COLOR];
      bg *= materials[mo + M_COLOR + 1];
      bb *= materials[mo + M_COLOR + 2];
      if (br === 0 && bg === 0 && bb === 0) break;
      specular = false;
      prevPdf = bwz * INV_PI;
    } else {
      bq.u0 = u[DIM_BSDF];
      bq.u1 = u[DIM_BSDF + 1];
      bq.u2 = u[DIM_BSDF_LOBE];
      if (!bsdfSample(materials, m, bq, bs)) break;
      br *= bs.weightR;
      bg *= bs.weightG;
      bb *= bs.weightB;
      if (br === 0 && bg === 0 && bb === 0) break;
      etaScale *= bs.etaScale;
      bwx = bs.wx;
      bwy = bs.wy;
      bwz = bs.wz;
      specular = bs.isDelta;
      prevPdf = bs.pdf;
    }
    const wix = bwx * fsx + bwy * ftx + bwz * sx;
    const wiy = bwx * fsy + bwy * fty + bwz * sy;
    const wiz = bwx * fsz + bwy * ftz + bwz * sz;
    prevX = x;
    prevY = y;
    prevZ = z;
    prevNx = nx;
    prevNy = ny;
    prevNz = nz;

    if (depth + 1 >= ROULETTE_DEPTH) {
      // Survival in proportion to throughput; etaScale undoes the (n1/n2)²
      // of refraction so a path inside glass is not killed for it.
      const rr = Math.max(br, bg, bb) * etaScale;
      if (rr < 1) {
        const q = Math.max(0.05, 1 - rr);
        if (u[DIM_ROULETTE] < q) break;
        const inv = 1 / (1 - q);
        br *= inv;
        bg *= inv;
        bb *= inv;
      }
    }

    // Spawn the next ray from the side of the surface it leaves by.
    const side = wix * nx + wiy * ny + wiz * nz >= 0 ? scale : -scale;
    if (isGltf && geometricSide && sp.thickness > 0 && side < 0 !== cosO < 0) {
      // Refraction through a glTF volume's boundary: in by the back of the
      // geometric normal, out by its front. Reflections keep the medium.
      inMedium = side < 0 && sp.sigmaAR + sp.sigmaAG + sp.sigmaAB > 0;
      sar = sp.sigmaAR;
      sag = sp.sigmaAG;
      sab = sp.sigmaAB;
    }
    ray.ox = x + nx * side;
    ray.oy = y + ny * side;
    ray.oz = z + nz * side;
    // Renormalise: keeps long specular chains at unit length.
    const inv = 1 / Math.sqrt(wix * wix + wiy * wiy + wiz * wiz);
    ray.dx = wix * inv;
    ray.dy = wiy * inv;
    ray.dz = wiz * inv;
    ray.tMax = Infinity;
    segments++;
    crossings = 0;
  }
  stats.paths++;
  stats.segments += segments;
  this.lr = lr;
  this.lg = lg;
  this.lb = lb;
}
