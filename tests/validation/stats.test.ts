/** The distributions behind the validation tests (stats.ts), against tabulated values. */
import { describe, expect, it } from 'vitest';
import {
  logGamma,
  normalQuantileTwoSided,
  normalTwoSided,
  studentTwoSided,
  welch,
} from './stats.ts';

describe('validation statistics', () => {
  it('has ln Γ right', () => {
    expect(logGamma(1)).toBeCloseTo(0, 12);
    expect(logGamma(0.5)).toBeCloseTo(Math.log(Math.sqrt(Math.PI)), 12);
    expect(logGamma(10)).toBeCloseTo(Math.log(362880), 10);
  });

  it('matches Student-t tables (two-sided)', () => {
    // t(0.975; ν) and t(0.9995; ν) from the standard tables.
    expect(studentTwoSided(12.706, 1)).toBeCloseTo(0.05, 4);
    expect(studentTwoSided(2.042, 30)).toBeCloseTo(0.05, 4);
    expect(studentTwoSided(3.646, 30)).toBeCloseTo(0.001, 5);
    expect(studentTwoSided(2.576, 1e6)).toBeCloseTo(0.01, 4);
    expect(studentTwoSided(0, 5)).toBeCloseTo(1, 12);
  });

  it('matches normal tables, and inverts them', () => {
    expect(normalTwoSided(1.959964)).toBeCloseTo(0.05, 6);
    expect(normalTwoSided(5.326724) / 1e-7).toBeCloseTo(1, 4);
    expect(normalQuantileTwoSided(1e-3)).toBeCloseTo(3.290527, 4);
  });

  it('computes Welch’s t and degrees of freedom', () => {
    // Equal variances and dof: ν = 2·df; t = Δ / sqrt(va + vb).
    const w = welch(1, 0.01, 10, 0.7, 0.01, 10);
    expect(w.t).toBeCloseTo(0.3 / Math.sqrt(0.02), 12);
    expect(w.nu).toBeCloseTo(20, 12);
    expect(w.p).toBeCloseTo(studentTwoSided(w.t, 20), 12);
    // A variance known exactly (dof Infinity) leaves the other's dof.
    expect(welch(1, 0.01, 10, 0, 0.01, Infinity).nu).toBeCloseTo(40, 10);
    expect(welch(1, 0, 10, 1, 0, 10).p).toBe(1);
    expect(welch(1, 0, 10, 2, 0, 10).p).toBe(0);
  });
});
