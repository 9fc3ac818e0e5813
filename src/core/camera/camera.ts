import type { CameraDesc } from '../scene/format/types.ts';
import { squareToUniformDiskConcentric, type Vec2Out } from '../sampling/warps.ts';
import type { Ray } from '../geometry/ray.ts';

/**
 * The camera of `pathwise-scene/1`, exactly as the spec frames it:
 * forward = normalize(target − position), right = normalize(forward × up),
 * upImage = right × forward; film point (fx, fy) looks along
 * forward + a·right + b·upImage with a = (2fx/W − 1)·tan(fovY/2)·W/H and
 * b = (1 − 2fy/H)·tan(fovY/2). With an aperture it is a thin lens focused
 * on the plane perpendicular to forward at focusDistance (pbr-book 4e §5.2.3).
 */
export class Camera {
  readonly width: number;
  readonly height: number;
  px = 0;
  py = 0;
  pz = 0;
  fx = 0;
  fy = 0;
  fz = 1;
  rx = 1;
  ry = 0;
  rz = 0;
  ux = 0;
  uy = 1;
  uz = 0;
  /** Film-to-direction scales: a = fx·scaleX − tanX, b = tanY − fy·scaleY. */
  private scaleX = 0;
  private scaleY = 0;
  private tanX = 0;
  private tanY = 0;
  aperture = 0;
  focusDistance = 1;
  private readonly disk: Vec2Out = { x: 0, y: 0 };

  constructor(desc: CameraDesc, width: number, height: number) {
    this.width = width;
    this.height = height;
    this.set(desc);
  }

  set(desc: CameraDesc): void {
    const [px, py, pz] = desc.position;
    let fx = desc.target[0] - px;
    let fy = desc.target[1] - py;
    let fz = desc.target[2] - pz;
    const fl = Math.hypot(fx, fy, fz);
    fx /= fl;
    fy /= fl;
    fz /= fl;
    const [upx, upy, upz] = desc.up;
    let rx = fy * upz - fz * upy;
    let ry = fz * upx - fx * upz;
    let rz = fx * upy - fy * upx;
    const rl = Math.hypot(rx, ry, rz);
    rx /= rl;
    ry /= rl;
    rz /= rl;
    this.px = px;
    this.py = py;
    this.pz = pz;
    this.fx = fx;
    this.fy = fy;
    this.fz = fz;
    this.rx = rx;
    this.ry = ry;
    this.rz = rz;
    this.ux = ry * fz - rz * fy;
    this.uy = rz * fx - rx * fz;
    this.uz = rx * fy - ry * fx;
    const tanHalf = Math.tan((desc.fovY * Math.PI) / 360);
    const aspect = this.width / this.height;
    this.tanX = tanHalf * aspect;
    this.tanY = tanHalf;
    this.scaleX = (2 * tanHalf * aspect) / this.width;
    this.scaleY = (2 * tanHalf) / this.height;
    this.aperture = desc.aperture;
    this.focusDistance = desc.focusDistance;
  }

  /**
   * Primary ray through film point (filmX, filmY) in pixels; (lensU, lensV)
   * pick the point on the lens when the aperture is open. Writes `ray`.
   */
  /**
   * generateRay for pixel (px, py) with the film offset in u[0], u[1] and
   * the lens point in u[lens], u[lens + 1]. The tracer calls this form: no
   * double arguments, which a call V8 does not inline would box on the heap.
   */
  generateRayFromSamples(px: number, py: number, u: Float64Array, lens: number, ray: Ray): void {
    this.generateRay(px + u[0], py + u[1], u[lens], u[lens + 1], ray);
  }

  generateRay(filmX: number, filmY: number, lensU: number, lensV: number, ray: Ray): void {
    const a = filmX * this.scaleX - this.tanX;
    const b = this.tanY - filmY * this.scaleY;
    let dx = this.fx + a * this.rx + b * this.ux;
    let dy = this.fy + a * this.ry + b * this.uy;
    let dz = this.fz + a * this.rz + b * this.uz;
    let ox = this.px;
    let oy = this.py;
    let oz = this.pz;
    if (this.aperture > 0) {
      // The unnormalised direction has unit length along forward, so
      // origin + focusDistance·d lies on the plane of focus.
      const fd = this.focusDistance;
      const focusX = ox + fd * dx;
      const focusY = oy + fd * dy;
      const focusZ = oz + fd * dz;
      squareToUniformDiskConcentric(lensU, lensV, this.disk);
      const lx = this.aperture * this.disk.x;
      const ly = this.aperture * this.disk.y;
      ox += lx * this.rx + ly * this.ux;
      oy += lx * this.ry + ly * this.uy;
      oz += lx * this.rz + ly * this.uz;
      dx = focusX - ox;
      dy = focusY - oy;
      dz = focusZ - oz;
    }
    let squared = dx * dx + dy * dy + dz * dz;
    if (!(squared < Infinity)) {
      // A lens or a focus distance near the double range (aperture 1e308 is finite, so the
      // format allows it): the squares overflow, and 1/√∞ = 0 would make a ray with no
      // direction. Scaled by the largest component first; the usual case keeps its bits.
      const m = Math.max(Math.abs(dx), Math.abs(dy), Math.abs(dz));
      dx /= m;
      dy /= m;
      dz /= m;
      squared = dx * dx + dy * dy + dz * dz;
    }
    const inv = 1 / Math.sqrt(squared);
    ray.ox = ox;
    ray.oy = oy;
    ray.oz = oz;
    ray.dx = dx * inv;
    ray.dy = dy * inv;
    ray.dz = dz * inv;
    ray.tMax = Infinity;
  }
}
