/**
 * Orthonormal basis around a unit normal, after Duff et al., "Building an
 * Orthonormal Basis, Revisited" (JCGT 2017): branch-free apart from the sign,
 * and exact for every unit input (no near-parallel fallback needed).
 * BSDFs work in this local frame, where the normal is +z.
 */
export class Frame {
  sx = 1;
  sy = 0;
  sz = 0;
  tx = 0;
  ty = 1;
  tz = 0;
  nx = 0;
  ny = 0;
  nz = 1;

  /** Sets the frame around the unit vector (x, y, z). */
  setFromNormal(x: number, y: number, z: number): void {
    this.nx = x;
    this.ny = y;
    this.nz = z;
    this.setFromN();
  }

  /**
   * Sets s and t around the unit normal already in (nx, ny, nz). Hot code
   * writes the normal and calls this: a call V8 does not inline would box
   * three double arguments on the heap.
   */
  setFromN(): void {
    const x = this.nx,
      y = this.ny,
      z = this.nz;
    const sign = z >= 0 ? 1 : -1;
    const a = -1 / (sign + z);
    const b = x * y * a;
    this.sx = 1 + sign * x * x * a;
    this.sy = sign * b;
    this.sz = -sign * x;
    this.tx = b;
    this.ty = sign + y * y * a;
    this.tz = -y;
  }
}
