/**
 * The BSDF functions with directions as plain arguments, for tests that
 * probe many directions: each call fills one BsdfQuery record and calls the
 * core's record-based `bsdfEval`, `bsdfPdf` and `bsdfSample`.
 */
import * as core from '../../src/core/bsdf/bsdf.ts';
import { BsdfQuery, type BsdfSample, type BsdfValue } from '../../src/core/bsdf/records.ts';

const q = new BsdfQuery();

function directions(wox: number, woy: number, woz: number, wix = 0, wiy = 0, wiz = 1): BsdfQuery {
  q.wox = wox;
  q.woy = woy;
  q.woz = woz;
  q.wix = wix;
  q.wiy = wiy;
  q.wiz = wiz;
  return q;
}

export function bsdfEval(
  materials: Float64Array,
  m: number,
  wox: number,
  woy: number,
  woz: number,
  wix: number,
  wiy: number,
  wiz: number,
  out: BsdfValue,
): void {
  core.bsdfEval(materials, m, directions(wox, woy, woz, wix, wiy, wiz), out);
}

export function bsdfPdf(
  materials: Float64Array,
  m: number,
  wox: number,
  woy: number,
  woz: number,
  wix: number,
  wiy: number,
  wiz: number,
): number {
  return core.bsdfPdf(materials, m, directions(wox, woy, woz, wix, wiy, wiz));
}

export function bsdfSample(
  materials: Float64Array,
  m: number,
  wox: number,
  woy: number,
  woz: number,
  u0: number,
  u1: number,
  u2: number,
  out: BsdfSample,
): boolean {
  const query = directions(wox, woy, woz);
  query.u0 = u0;
  query.u1 = u1;
  query.u2 = u2;
  return core.bsdfSample(materials, m, query, out);
}

/**
 * The shading record the calls above pass to glTF materials (the query's
 * own), for tests to set a glTF material's per-hit parameters.
 */
export function shading(): BsdfQuery['shading'] {
  return q.shading;
}
