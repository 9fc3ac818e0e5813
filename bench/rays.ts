/**
 * Ray queries alone, without shading: rays made once from a scene (camera rays, bounce
 * rays leaving each hit in a random direction of the outer hemisphere, shadow rays from
 * each hit to a random point of the Cornell light), then replayed through
 * `intersectScene` (camera, bounce) and `occluded` (shadow), repeatedly; prints the
 * median nanoseconds per ray of process CPU time per kind, and a digest of the answers
 * (equal digests: the same hits, distances bit for bit).
 *   node scripts/run-ts.mjs bench/rays.ts SCENE [N REPS ACCEL]
 * SCENE: a scene file, or @million / @bunny (bench/mesh-scenes.ts).
 */
import { Camera, compileScene } from '../src/core/index.ts';
import { Hit, Ray, SHAPE_QUAD, SHAPE_SPHERE } from '../src/core/geometry/ray.ts';
import { intersectScene, occluded } from '../src/core/accel/trace.ts';
import { Q_NORMAL, QUAD_STRIDE, SPHERE_STRIDE } from '../src/core/geometry/shapes.ts';
import { loadBenchScene } from './mesh-scenes.ts';

const [file = '@million', nArg = '100000', repsArg = '7', accel] = process.argv.slice(2);
const scene = loadBenchScene(file);
const compiled = compileScene(scene, {
  bvh: accel === 'bvh' ? true : accel === 'list' ? false : undefined,
});
const n = Number(nArg);
const reps = Number(repsArg);
let state = 12345;
const rand = (): number => (state = (Math.imul(state, 1664525) + 1013904223) >>> 0) / 4294967296;

/** Closest-hit rays (camera then bounce, interleaved as made) and shadow rays: o, d, tMax. */
const closest = new Float64Array(n * 7);
const shadow = new Float64Array(n * 7);
let nc = 0;
let ns = 0;
const camera = new Camera(scene.camera, 256, 256);
const ray = new Ray();
const hit = new Hit();
// The light: the largest emitter's box is not known here; aim at the scene's centre
// region above (y of the camera target plus a half extent), good for the Cornell scenes.
const lightY = 548.7;
function normalAt(px: number, py: number, pz: number, out: number[]): void {
  if (hit.kind === SHAPE_SPHERE) {
    const s = compiled.spheres;
    const o = hit.index * SPHERE_STRIDE;
    const x = px - s[o],
      y = py - s[o + 1],
      z = pz - s[o + 2];
    const l = Math.hypot(x, y, z);
    out[0] = x / l;
    out[1] = y / l;
    out[2] = z / l;
  } else if (hit.kind === SHAPE_QUAD) {
    const o = hit.index * QUAD_STRIDE + Q_NORMAL;
    out[0] = compiled.quads[o];
    out[1] = compiled.quads[o + 1];
    out[2] = compiled.quads[o + 2];
  } else {
    const p = compiled.triPositions;
    const ix = compiled.triIndices;
    const a = ix[3 * hit.index] * 3,
      b = ix[3 * hit.index + 1] * 3,
      c = ix[3 * hit.index + 2] * 3;
    const e1 = [p[b] - p[a], p[b + 1] - p[a + 1], p[b + 2] - p[a + 2]];
    const e2 = [p[c] - p[a], p[c + 1] - p[a + 1], p[c + 2] - p[a + 2]];
    const x = e1[1] * e2[2] - e1[2] * e2[1],
      y = e1[2] * e2[0] - e1[0] * e2[2],
      z = e1[0] * e2[1] - e1[1] * e2[0];
    const l = Math.hypot(x, y, z);
    out[0] = x / l;
    out[1] = y / l;
    out[2] = z / l;
  }
}
const nrm = [0, 0, 0];
while (nc < n || ns < n) {
  camera.generateRay(256 * rand(), 256 * rand(), 0.5, 0.5, ray);
  for (let depth = 0; depth < 4; depth++) {
    if (nc < n) closest.set([ray.ox, ray.oy, ray.oz, ray.dx, ray.dy, ray.dz, ray.tMax], 7 * nc++);
    if (!intersectScene(compiled, ray, hit)) break;
    const px = ray.ox + hit.t * ray.dx,
      py = ray.oy + hit.t * ray.dy,
      pz = ray.oz + hit.t * ray.dz;
    normalAt(px, py, pz, nrm);
    if (nrm[0] * ray.dx + nrm[1] * ray.dy + nrm[2] * ray.dz > 0) {
      nrm[0] = -nrm[0];
      nrm[1] = -nrm[1];
      nrm[2] = -nrm[2];
    }
    const eps = 1e-7 * (Math.abs(px) + Math.abs(py) + Math.abs(pz) + 1);
    const ox = px + eps * nrm[0],
      oy = py + eps * nrm[1],
      oz = pz + eps * nrm[2];
    if (ns < n) {
      const lx = 213 + 130 * rand() - ox,
        ly = lightY - 1e-3 - oy,
        lz = 227 + 105 * rand() - oz;
      const len = Math.hypot(lx, ly, lz);
      shadow.set([ox, oy, oz, lx / len, ly / len, lz / len, len * (1 - 1e-9)], ns * 7);
      ns++;
    }
    // A random direction in the outer hemisphere.
    let dx, dy, dz;
    do {
      dx = 2 * rand() - 1;
      dy = 2 * rand() - 1;
      dz = 2 * rand() - 1;
    } while (dx * dx + dy * dy + dz * dz > 1 || dx * dx + dy * dy + dz * dz < 1e-6);
    if (dx * nrm[0] + dy * nrm[1] + dz * nrm[2] < 0) {
      dx = -dx;
      dy = -dy;
      dz = -dz;
    }
    const l = Math.hypot(dx, dy, dz);
    ray.ox = ox;
    ray.oy = oy;
    ray.oz = oz;
    ray.dx = dx / l;
    ray.dy = dy / l;
    ray.dz = dz / l;
    ray.tMax = Infinity;
  }
}

function replay(rays: Float64Array, any: boolean): { ns: number; digest: number } {
  const c0 = process.cpuUsage();
  let digest = 0;
  for (let i = 0; i < n; i++) {
    const o = i * 7;
    ray.ox = rays[o];
    ray.oy = rays[o + 1];
    ray.oz = rays[o + 2];
    ray.dx = rays[o + 3];
    ray.dy = rays[o + 4];
    ray.dz = rays[o + 5];
    ray.tMax = rays[o + 6];
    if (any) {
      if (occluded(compiled, ray)) digest = (Math.imul(digest, 31) + i) | 0;
    } else if (intersectScene(compiled, ray, hit)) {
      digest = (Math.imul(digest, 31) + hit.index * 4 + hit.kind + ((hit.t * 1e6) | 0)) | 0;
    }
  }
  const c = process.cpuUsage(c0);
  return { ns: ((c.user + c.system) * 1000) / n, digest: digest >>> 0 };
}

const closestNs: number[] = [];
const shadowNs: number[] = [];
let digestC = 0;
let digestS = 0;
for (let r = 0; r <= reps; r++) {
  const a = replay(closest, false);
  const b = replay(shadow, true);
  digestC = a.digest;
  digestS = b.digest;
  if (r > 0) {
    closestNs.push(a.ns);
    shadowNs.push(b.ns);
  }
}
const median = (xs: number[]): number => [...xs].sort((a, b) => a - b)[xs.length >> 1];
process.stdout.write(
  JSON.stringify({
    scene: file,
    rays: n,
    closest_ns: +median(closestNs).toFixed(1),
    shadow_ns: +median(shadowNs).toFixed(1),
    digest: `${digestC.toString(16)}-${digestS.toString(16)}`,
  }) + '\n',
);
