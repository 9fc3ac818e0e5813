/**
 * Normal mapping at a hit (glTF 2.0 §3.9.3 "normalTexture"): the texture's
 * tangent-space normal (ShadingParams.nx, ny, nz, already scaled and
 * normalised by fillGltfShading) is taken to world space by the TBN frame
 * of the interpolated shading normal N, the interpolated tangent T
 * (Gram–Schmidt against N) and the bitangent B = (N × T) · w. Allocation-free.
 *
 * A degenerate frame (no tangent at the vertices, T parallel to N) leaves
 * the normal unperturbed, and so does a result that would face away from
 * the geometric normal's side: the perturbed normal is flipped back into
 * that hemisphere's closure, the usual guard against black fringes (pbr-book
 * 4e §10.5.3 "Normal Mapping" clamps to the geometric hemisphere as well).
 */
import type { Vec3Out } from '../sampling/warps.ts';

/**
 * Writes the world-space normal-mapped shading normal to `out`. (nx, ny, nz):
 * the unit shading normal; (tx, ty, tz, tw): the interpolated tangent and its
 * handedness; (mx, my, mz): the tangent-space normal from the map; (gx, gy,
 * gz): the geometric normal, on whose side the shading normal must stay.
 * Returns false (and writes N) when the frame is degenerate.
 */
export function applyNormalMap(
  nx: number,
  ny: number,
  nz: number,
  tx: number,
  ty: number,
  tz: number,
  tw: number,
  mx: number,
  my: number,
  mz: number,
  gx: number,
  gy: number,
  gz: number,
  out: Vec3Out,
): boolean {
  out.x = nx;
  out.y = ny;
  out.z = nz;
  // T orthogonalised against N.
  const d = tx * nx + ty * ny + tz * nz;
  let ux = tx - d * nx;
  let uy = ty - d * ny;
  let uz = tz - d * nz;
  const ul = Math.sqrt(ux * ux + uy * uy + uz * uz);
  if (!(ul > 1e-12) || tw === 0) return false;
  ux /= ul;
  uy /= ul;
  uz /= ul;
  const s = tw < 0 ? -1 : 1;
  const bx = s * (ny * uz - nz * uy);
  const by = s * (nz * ux - nx * uz);
  const bz = s * (nx * uy - ny * ux);
  let px = mx * ux + my * bx + mz * nx;
  let py = mx * uy + my * by + mz * ny;
  let pz = mx * uz + my * bz + mz * nz;
  // Keep it on the geometric normal's side of the surface (N is, by construction).
  const sideN = nx * gx + ny * gy + nz * gz >= 0 ? 1 : -1;
  const g = (px * gx + py * gy + pz * gz) * sideN;
  if (g < 1e-4) {
    const k = (1e-4 - g) * sideN;
    px += k * gx;
    py += k * gy;
    pz += k * gz;
  }
  const pl = Math.sqrt(px * px + py * py + pz * pz);
  if (!(pl > 0)) return false;
  out.x = px / pl;
  out.y = py / pl;
  out.z = pz / pl;
  return true;
}
