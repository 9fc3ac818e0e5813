/**
 * The thin-film Fresnel of KHR_materials_iridescence (src/core/bsdf/thin-film.ts):
 * reductions (no film: the base's Schlick Fresnel), bounds over a parameter grid,
 * and spot values against a direct transcription of the extension README's /
 * glTF Sample Viewer's GLSL `evalIridescence` (written out here independently,
 * per component, with its 1e-5 floor and no upper clamp), with the one change
 * thin-film.ts documents: the air → film interface's exact Fresnel for
 * Schlick's.
 */
import { describe, expect, it } from 'vitest';
import { fresnelDielectric } from '../../../../src/core/bsdf/fresnel.ts';
import { ThinFilm, thinFilmFresnel } from '../../../../src/core/bsdf/thin-film.ts';

const t = new ThinFilm();

function film(cos: number, eta: number, d: number, f0: [number, number, number]): number[] {
  t.cos = cos;
  t.eta = eta;
  t.thickness = d;
  [t.f0r, t.f0g, t.f0b] = f0;
  thinFilmFresnel(t);
  return [t.r, t.g, t.b];
}

const schlick = (f0: number, c: number): number => f0 + (1 - f0) * (1 - c) ** 5;

/** The README's evalIridescence, transcribed line by line (outside index 1). */
function reference(cos1: number, eta2In: number, d: number, baseF0: number[]): number[] {
  const sq = (x: number): number => x * x;
  const smooth = (x: number): number => {
    const s = Math.min(Math.max(x / 0.03, 0), 1);
    return s * s * (3 - 2 * s);
  };
  const eta2 = 1 + (eta2In - 1) * smooth(d);
  const sin2 = sq(1 / eta2) * (1 - sq(cos1));
  const cos2sq = 1 - sin2;
  if (cos2sq < 0) return [1, 1, 1];
  const cos2 = Math.sqrt(cos2sq);
  const R12 = fresnelDielectric(cos1, eta2);
  const T121 = 1 - R12;
  const phi12 = eta2 < 1 ? Math.PI : 0;
  const phi21 = Math.PI - phi12;
  const baseIor = baseF0.map((f) => {
    const s = Math.sqrt(Math.min(Math.max(f, 0), 0.9999));
    return (1 + s) / (1 - s);
  });
  const R23 = baseIor.map((n) => schlick(sq((n - eta2) / (n + eta2)), cos2));
  const phi23 = baseIor.map((n) => (n < eta2 ? Math.PI : 0));
  const OPD = 2 * eta2 * d * cos2;
  const phi = phi23.map((p) => phi21 + p);
  const R123 = R23.map((r) => Math.min(Math.max(R12 * r, 1e-5), 0.9999));
  const r123 = R123.map(Math.sqrt);
  const Rs = R23.map((r, k) => (sq(T121) * r) / (1 - R123[k]));
  const I = Rs.map((rs) => R12 + rs);
  const Cm = Rs.map((rs) => rs - T121);
  const sens = (opd: number, shift: number[]): number[] => {
    const phase = 2 * Math.PI * opd * 1e-9;
    const val = [5.4856e-13, 4.4201e-13, 5.2481e-13];
    const pos = [1.681e6, 1.7953e6, 2.2084e6];
    const v = [4.3278e9, 9.3046e9, 6.6121e9];
    const xyz = [0, 1, 2].map(
      (k) =>
        val[k] *
        Math.sqrt(2 * Math.PI * v[k]) *
        Math.cos(pos[k] * phase + shift[k]) *
        Math.exp(-sq(phase) * v[k]),
    );
    xyz[0] +=
      9.747e-14 *
      Math.sqrt(2 * Math.PI * 4.5282e9) *
      Math.cos(2.2399e6 * phase + shift[0]) *
      Math.exp(-4.5282e9 * sq(phase));
    const [X, Y, Z] = xyz.map((x) => x / 1.0685e-7);
    return [
      3.2404542 * X - 1.5371385 * Y - 0.4985314 * Z,
      -0.969266 * X + 1.8760108 * Y + 0.041556 * Z,
      0.0556434 * X - 0.2040259 * Y + 1.0572252 * Z,
    ];
  };
  for (let m = 1; m <= 2; m++) {
    for (let k = 0; k < 3; k++) Cm[k] *= r123[k];
    const S = sens(
      m * OPD,
      phi.map((p) => m * p),
    );
    for (let k = 0; k < 3; k++) I[k] += Cm[k] * 2 * S[k];
  }
  return I.map((x) => Math.max(x, 0));
}

const COSINES = [0, 0.05, 0.2, 0.5, 0.8, 1];
const F0S: [number, number, number][] = [
  [0.04, 0.04, 0.04],
  [0.9, 0.6, 0.3],
  [0.02, 0.5, 0.99],
  [0, 0, 0],
];

describe('thin-film Fresnel', () => {
  it('a film of thickness 0 is no film: the base Fresnel (Schlick) to rounding', () => {
    for (const c of COSINES) {
      for (const f0 of F0S) {
        for (const eta of [1.3, 2, 1.01]) {
          const r = film(c, eta, 0, f0);
          // F0 → index → F0 round-trips up to rounding; F0 near 1 is clamped at 0.9999.
          for (let k = 0; k < 3; k++) expect(r[k]).toBeCloseTo(schlick(f0[k], c), 12);
        }
      }
    }
  });

  it('over glass (a base given by its index), no film is the exact Fresnel of the glass', () => {
    for (const c of COSINES) {
      for (const ior of [1.33, 1.5, 2.4]) {
        for (const [eta, d] of [
          [1.3, 0],
          [1, 400],
        ]) {
          t.cos = c;
          t.eta = eta;
          t.thickness = d;
          t.baseIor = ior;
          thinFilmFresnel(t);
          t.baseIor = 0;
          const fd = fresnelDielectric(c, ior);
          for (const x of [t.r, t.g, t.b]) expect(x).toBeCloseTo(fd, 12);
        }
      }
    }
  });

  it('a film of the outside medium’s index (1) is no film', () => {
    for (const c of COSINES) {
      for (const f0 of F0S) {
        for (const d of [50, 400, 1200]) {
          const r = film(c, 1, d, f0);
          for (let k = 0; k < 3; k++) expect(r[k]).toBeCloseTo(schlick(f0[k], c), 12);
        }
      }
    }
  });

  it('matches the README / Sample Viewer evalIridescence where neither clamp acts', () => {
    let compared = 0;
    for (const c of [0.1, 0.3, 0.6, 0.9, 1]) {
      for (const eta of [1.3, 1.8]) {
        for (const d of [100, 250, 400, 800]) {
          for (const f0 of [
            [0.9, 0.6, 0.3],
            [0.25, 0.25, 0.25],
          ] as [number, number, number][]) {
            const ref = reference(c, eta, d, f0);
            if (ref.some((x) => x <= 0 || x >= 1)) continue;
            const r = film(c, eta, d, f0);
            for (let k = 0; k < 3; k++) expect(r[k]).toBeCloseTo(ref[k], 12);
            compared++;
          }
        }
      }
    }
    expect(compared).toBeGreaterThan(50);
  });

  it('interferes: a 400 nm film of index 1.3 over F0 0.04 is coloured and angle-dependent', () => {
    const a = film(1, 1.3, 400, [0.04, 0.04, 0.04]);
    const b = film(0.5, 1.3, 400, [0.04, 0.04, 0.04]);
    expect(Math.max(...a) - Math.min(...a)).toBeGreaterThan(0.01);
    expect(Math.abs(a[0] - b[0]) + Math.abs(a[1] - b[1]) + Math.abs(a[2] - b[2])).toBeGreaterThan(
      0.01,
    );
  });

  it('stays finite and in [0, 1] per channel over a grid of cosθ × thickness × η × F0', () => {
    const bad: string[] = [];
    for (const c of [...COSINES, 1e-9, 0.999999]) {
      for (const d of [0, 1e-3, 0.02, 10, 100, 333, 400, 1000, 1e4, 1e6]) {
        for (const eta of [1, 1.0001, 1.3, 1.5, 2.5, 10, 1e6]) {
          for (const f0 of [...F0S, [1, 1, 1] as [number, number, number]]) {
            for (const x of film(c, eta, d, f0)) {
              if (!(x >= 0 && x <= 1)) bad.push(`${x} at cos ${c}, d ${d}, η ${eta}, F0 ${f0}`);
            }
          }
        }
      }
    }
    expect(bad).toEqual([]);
  });
});
