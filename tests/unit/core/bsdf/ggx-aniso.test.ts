/**
 * Anisotropic GGX (src/core/bsdf/ggx-aniso.ts), the warp in threes: the
 * visible-normal sampler, its density, and the checks that tie them —
 * ∫ D(m) cosθm dm = 1 and ∫ D_wo(m) dm = 1 by quadrature, χ² of the sampler
 * against the density, and the isotropic reduction against ggx.ts.
 * Fixed seeds; the χ² tests reject at 1% overall (Šidák-corrected).
 */
import { describe, expect, it } from 'vitest';
import { ggxD, ggxG1 } from '../../../../src/core/bsdf/ggx.ts';
import {
  AnisoQuery,
  ggxDAniso,
  ggxG1Aniso,
  ggxSampleVisibleNormalAniso,
  ggxVisibleNormalPdfAniso,
} from '../../../../src/core/bsdf/ggx-aniso.ts';
import { hashToUnit, sampleKey } from '../../../../src/core/rng/pcg.ts';
import { chi2Test } from '../../../helpers/chi2.ts';
import { gaussLegendre, HemisphereGrid } from '../../../helpers/hemisphere-grid.ts';

const ROUGHNESS: [number, number][] = [
  [0.5, 0.5],
  [0.8, 0.1],
  [0.05, 0.6],
  [1, 0.02],
  [0.3, 0.9],
];
const VIEWS: [number, number][] = [
  [0, 0],
  [50, 0.4],
  [80, 2.1],
];

function dir(thetaDeg: number, phi: number): [number, number, number] {
  const t = (thetaDeg * Math.PI) / 180;
  return [Math.sin(t) * Math.cos(phi), Math.sin(t) * Math.sin(phi), Math.cos(t)];
}

/** ∫ over the hemisphere by Gauss–Legendre in (cosθ, φ), with extra nodes near the pole. */
function hemisphere(f: (x: number, y: number, z: number) => number): number {
  const gl = gaussLegendre(64);
  let sum = 0;
  // cosθ in [0, 1] split at 0.9 and 0.99 (the lobes of small α sit at the pole).
  for (const [a, b] of [
    [0, 0.9],
    [0.9, 0.99],
    [0.99, 0.9999],
    [0.9999, 1],
  ]) {
    for (let i = 0; i < 64; i++) {
      const z = a + ((b - a) * (gl.x[i] + 1)) / 2;
      const s = Math.sqrt(Math.max(0, 1 - z * z));
      // φ in 16 pieces: an elongated lobe varies fast in φ.
      for (let k = 0; k < 16; k++) {
        for (let j = 0; j < 64; j++) {
          const p = (Math.PI / 8) * (k + (gl.x[j] + 1) / 2);
          sum +=
            gl.w[i] *
            gl.w[j] *
            ((b - a) / 2) *
            (Math.PI / 16) *
            f(s * Math.cos(p), s * Math.sin(p), z);
        }
      }
    }
  }
  return sum;
}

describe('anisotropic GGX', () => {
  it('D is normalised: ∫ D(m) cosθm dm = 1', () => {
    for (const [ax, ay] of ROUGHNESS) {
      if (Math.min(ax, ay) < 0.05) continue; // too narrow for the fixed quadrature
      expect(hemisphere((x, y, z) => ggxDAniso(x, y, z, ax, ay) * z)).toBeCloseTo(1, 3);
    }
  });

  it('the visible-normal density integrates to 1 for every view', () => {
    for (const [ax, ay] of ROUGHNESS) {
      if (Math.min(ax, ay) < 0.05) continue;
      for (const [t, p] of VIEWS) {
        const [wx, wy, wz] = dir(t, p);
        const mass = hemisphere((x, y, z) => ggxVisibleNormalPdfAniso(wx, wy, wz, x, y, z, ax, ay));
        expect(mass, `α (${ax}, ${ay}), view ${t}°`).toBeCloseTo(1, 3);
      }
    }
  });

  it('reduces to the isotropic D and G1 of ggx.ts when α_x = α_y', () => {
    for (const a of [0.01, 0.2, 0.7, 1]) {
      for (const [t, p] of [...VIEWS, [89, 5] as [number, number]]) {
        const [x, y, z] = dir(t, p);
        const d = ggxD(z, a);
        expect(Math.abs(ggxDAniso(x, y, z, a, a) - d)).toBeLessThan(1e-11 * d);
        expect(ggxG1Aniso(x, y, z, a, a)).toBeCloseTo(ggxG1(z, a), 12);
      }
    }
  });

  const cases = ROUGHNESS.flatMap(([ax, ay]) => VIEWS.map((v) => ({ ax, ay, v })));
  const ALPHA = 1 - Math.pow(1 - 0.01, 1 / cases.length);
  const N = 100_000;
  cases.forEach(({ ax, ay, v }, index) => {
    it(`χ² of the sampler against its density: α (${ax}, ${ay}), view ${v[0]}°`, () => {
      const [wx, wy, wz] = dir(v[0], v[1]);
      const grid = HemisphereGrid.around(0, 0, Math.max(ax, ay));
      // A ridge narrower than a cell needs more quadrature nodes per cell.
      const expected = grid.integrate(
        (x, y, z) => ggxVisibleNormalPdfAniso(wx, wy, wz, x, y, z, ax, ay),
        Math.min(ax, ay) < 0.05 ? 40 : 8,
      );
      let mass = 0;
      for (let i = 0; i < grid.below; i++) mass += expected[i];
      for (let i = 0; i < grid.below; i++) expected[i] *= N;
      expected[grid.failed] = N * Math.max(0, 1 - mass);
      const observed = new Float64Array(grid.nCells);
      const q = new AnisoQuery();
      const m = { x: 0, y: 0, z: 1 };
      q.wx = wx;
      q.wy = wy;
      q.wz = wz;
      q.ax = ax;
      q.ay = ay;
      for (let i = 0; i < N; i++) {
        const key = sampleKey(4100 + index, i, 0);
        q.u0 = hashToUnit(key, 0);
        q.u1 = hashToUnit(key, 1);
        ggxSampleVisibleNormalAniso(q, m);
        observed[grid.cellOf(m.x, m.y, m.z)]++;
      }
      const r = chi2Test(observed, expected);
      expect(r.impossible).toBeNull();
      expect(r.dof).toBeGreaterThan(50);
      expect(r.pValue, `χ² ${r.stat.toFixed(1)} on ${r.dof}`).toBeGreaterThan(ALPHA);
    });
  });

  it('has power: the sampler for (0.5, 0.2) is rejected against the density of (0.5, 0.25)', () => {
    const [wx, wy, wz] = dir(50, 0.4);
    const grid = HemisphereGrid.around(0, 0, 0.5);
    const expected = grid.integrate((x, y, z) =>
      ggxVisibleNormalPdfAniso(wx, wy, wz, x, y, z, 0.5, 0.25),
    );
    const n = 100_000;
    for (let i = 0; i < grid.below; i++) expected[i] *= n;
    const observed = new Float64Array(grid.nCells);
    const q = new AnisoQuery();
    const m = { x: 0, y: 0, z: 1 };
    Object.assign(q, { wx, wy, wz, ax: 0.5, ay: 0.2 });
    for (let i = 0; i < n; i++) {
      const key = sampleKey(4999, i, 0);
      q.u0 = hashToUnit(key, 0);
      q.u1 = hashToUnit(key, 1);
      ggxSampleVisibleNormalAniso(q, m);
      observed[grid.cellOf(m.x, m.y, m.z)]++;
    }
    expect(chi2Test(observed, expected).pValue).toBeLessThan(1e-6);
  });
});
