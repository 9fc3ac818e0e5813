/**
 * Bakes the project's own environment map, scenes/sky.hdr: a clear sky by the analytic
 * daylight model of Preetham, Shirley and Smits ("A Practical Analytic Model for
 * Daylight", SIGGRAPH 1999: Perez luminance and chromaticity distributions with their
 * turbidity fits), a sun disc, and a plain grey ground below the horizon, as an
 * equirectangular RGBE image in the scene format's convention (row 0 is +y, the left
 * edge looks along −z, u = 0.25 along +x).
 *
 * Licence: the output is made by this script from formulas alone, no third-party
 * data; it is dedicated to the public domain (CC0 1.0), like the script's MIT code.
 *
 *   node scripts/run-ts.mjs scripts/make-sky.ts [out.hdr] [width]
 */
import { writeFileSync } from 'node:fs';
import { encodeHdr } from '../src/core/io/hdr.ts';

const out = process.argv[2] ?? 'scenes/sky.hdr';
const width = Number(process.argv[3] ?? 512);
const height = width / 2;

const TURBIDITY = 2.5;
/** Sun: 40° above the horizon, toward u = 0.3 (between +x and +z). */
const SUN_ELEVATION = (40 * Math.PI) / 180;
const SUN_U = 0.3;
/** An enlarged sun (2° across rather than 0.53°), so that it spans a few texels. */
const SUN_RADIUS = (1 * Math.PI) / 180;
/** Sun radiance relative to the zenith's: its irradiance is then about 4× the sky's. */
const SUN_RADIANCE = 30000;
const GROUND = [0.2, 0.19, 0.17];
const SUPERSAMPLE = 4;

/** Direction of map coordinates (u, v) ∈ [0, 1]²: the inverse of the spec's lookup. */
function direction(u: number, v: number): [number, number, number] {
  const phi = 2 * Math.PI * u;
  const theta = Math.PI * v;
  return [Math.sin(theta) * Math.sin(phi), Math.cos(theta), -Math.sin(theta) * Math.cos(phi)];
}

const T = TURBIDITY;
const thetaS = Math.PI / 2 - SUN_ELEVATION;
const sun = (() => {
  const d = direction(SUN_U, thetaS / Math.PI);
  return d;
})();

type Perez = [number, number, number, number, number];
const perezY: Perez = [
  0.1787 * T - 1.463,
  -0.3554 * T + 0.4275,
  -0.0227 * T + 5.3251,
  0.1206 * T - 2.5771,
  -0.067 * T + 0.3703,
];
const perezX: Perez = [
  -0.0193 * T - 0.2592,
  -0.0665 * T + 0.0008,
  -0.0004 * T + 0.2125,
  -0.0641 * T - 0.8989,
  -0.0033 * T + 0.0452,
];
const perezYc: Perez = [
  -0.0167 * T - 0.2608,
  -0.095 * T + 0.0092,
  -0.0079 * T + 0.2102,
  -0.0441 * T - 1.6537,
  -0.0109 * T + 0.0529,
];

function perez(c: Perez, theta: number, gamma: number): number {
  const [a, b, cc, d, e] = c;
  const cosG = Math.cos(gamma);
  return (
    (1 + a * Math.exp(b / Math.max(Math.cos(theta), 1e-3))) *
    (1 + cc * Math.exp(d * gamma) + e * cosG * cosG)
  );
}

const chi = (4 / 9 - T / 120) * (Math.PI - 2 * thetaS);
const zenithY = (4.0453 * T - 4.971) * Math.tan(chi) - 0.2155 * T + 2.4192;
const t3 = [thetaS ** 3, thetaS ** 2, thetaS, 1];
const dot4 = (a: number[], b: number[]) => a.reduce((s, x, i) => s + x * b[i], 0);
const zenithX =
  T * T * dot4([0.00166, -0.00375, 0.00209, 0], t3) +
  T * dot4([-0.02903, 0.06377, -0.03202, 0.00394], t3) +
  dot4([0.11693, -0.21196, 0.06052, 0.25886], t3);
const zenithYc =
  T * T * dot4([0.00275, -0.0061, 0.00317, 0], t3) +
  T * dot4([-0.04214, 0.0897, -0.04153, 0.00516], t3) +
  dot4([0.15346, -0.26756, 0.0667, 0.26688], t3);

/** Linear Rec.709 radiance of the sky along d (d.y > 0), normalised to a zenith of ~1. */
function sky(d: [number, number, number]): [number, number, number] {
  const theta = Math.acos(Math.min(1, d[1]));
  const cosGamma = d[0] * sun[0] + d[1] * sun[1] + d[2] * sun[2];
  const gamma = Math.acos(Math.max(-1, Math.min(1, cosGamma)));
  const Y = perez(perezY, theta, gamma) / perez(perezY, 0, thetaS);
  const x = (zenithX * perez(perezX, theta, gamma)) / perez(perezX, 0, thetaS);
  const y = (zenithYc * perez(perezYc, theta, gamma)) / perez(perezYc, 0, thetaS);
  const X = (x / y) * Y;
  const Z = ((1 - x - y) / y) * Y;
  return [
    Math.max(0, 3.2406 * X - 1.5372 * Y - 0.4986 * Z),
    Math.max(0, -0.9689 * X + 1.8758 * Y + 0.0415 * Z),
    Math.max(0, 0.0557 * X - 0.204 * Y + 1.057 * Z),
  ];
}

void zenithY; // absolute luminance: the map is normalised to a zenith of ~1 instead

const rgb = new Float32Array(width * height * 3);
const cosSun = Math.cos(SUN_RADIUS);
const sunColour = [1, 0.93, 0.82];
for (let row = 0; row < height; row++) {
  for (let col = 0; col < width; col++) {
    const acc = [0, 0, 0];
    for (let sy = 0; sy < SUPERSAMPLE; sy++) {
      for (let sx = 0; sx < SUPERSAMPLE; sx++) {
        const d = direction(
          (col + (sx + 0.5) / SUPERSAMPLE) / width,
          (row + (sy + 0.5) / SUPERSAMPLE) / height,
        );
        let c: number[];
        if (d[1] <= 0) c = GROUND;
        else if (d[0] * sun[0] + d[1] * sun[1] + d[2] * sun[2] >= cosSun) {
          c = sunColour.map((k) => k * SUN_RADIANCE);
        } else c = sky(d);
        for (let k = 0; k < 3; k++) acc[k] += c[k] / (SUPERSAMPLE * SUPERSAMPLE);
      }
    }
    rgb.set(acc, (row * width + col) * 3);
  }
}
const bytes = encodeHdr(width, height, rgb);
writeFileSync(out, bytes);
process.stdout.write(`wrote ${out}: ${width} × ${height}, ${bytes.length} bytes\n`);
