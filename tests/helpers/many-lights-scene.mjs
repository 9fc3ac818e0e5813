// The many-light scene of issue 23 (a room lit by N small emitters), shared by the
// benchmark (bench/many-lights.ts, through bench/scenes.mjs) and the reference test
// (tests/validation/many-lights.test.ts), so both read the very same scene.
// Deterministic for a given (count, seed).

/** PCG hash (the same permutation as src/core/rng/pcg.ts), for placement only. */
function pcgHash(input) {
  const state = (Math.imul(input, 747796405) + 2891336453) | 0;
  const word = Math.imul((state >>> ((state >>> 28) + 4)) ^ state, 277803737);
  return ((word >>> 22) ^ word) >>> 0;
}

/**
 * A room lit by N small emitters (issue 23's many-light goal): a closed box of
 * diffuse walls (a red left, a green right), three diffuse spheres and a rough metal
 * one on the floor, and N emissive spheres of radius 0.003–0.008: three quarters in a
 * band under the ceiling, a quarter floating through the room, with a random tint
 * and power spread log-uniformly over two decades (their total fixed, so the
 * exposure does not depend on N). Nothing else emits.
 */
export function manyLights(count, seed = 1) {
  let state = seed >>> 0;
  const rand = () => (state = pcgHash(state + 1)) / 4294967296;
  const round = (v) => +v.toFixed(6);
  const W = 4;
  const H = 3;
  const D = 4;
  const shapes = [
    { type: 'quad', corner: [0, 0, 0], u: [0, 0, D], v: [W, 0, 0], material: 'white' },
    { type: 'quad', corner: [0, H, 0], u: [W, 0, 0], v: [0, 0, D], material: 'white' },
    { type: 'quad', corner: [0, 0, D], u: [W, 0, 0], v: [0, H, 0], material: 'white' },
    { type: 'quad', corner: [0, 0, 0], u: [0, H, 0], v: [0, 0, D], material: 'red' },
    { type: 'quad', corner: [W, 0, 0], u: [0, 0, D], v: [0, H, 0], material: 'green' },
    { type: 'quad', corner: [0, 0, 0], u: [W, 0, 0], v: [0, H, 0], material: 'white' },
    { type: 'sphere', center: [1.1, 0.5, 2.6], radius: 0.5, material: 'white' },
    { type: 'sphere', center: [2.9, 0.4, 2.2], radius: 0.4, material: 'metal' },
    { type: 'sphere', center: [2.0, 0.3, 1.4], radius: 0.3, material: 'blue' },
    { type: 'sphere', center: [3.2, 0.25, 3.3], radius: 0.25, material: 'white' },
  ];
  const materials = {
    white: { type: 'diffuse', albedo: [0.75, 0.75, 0.75] },
    red: { type: 'diffuse', albedo: [0.7, 0.15, 0.12] },
    green: { type: 'diffuse', albedo: [0.15, 0.6, 0.2] },
    blue: { type: 'diffuse', albedo: [0.15, 0.25, 0.7] },
    metal: { type: 'conductor', color: [0.9, 0.8, 0.6], roughness: 0.3 },
  };
  // Eight tints; each light's radiance is its power over its area.
  const tints = 8;
  const powers = [];
  const lights = [];
  for (let i = 0; i < count; i++) {
    const r = 0.003 + 0.005 * rand();
    const band = rand() < 0.75;
    const x = 0.1 + (W - 0.2) * rand();
    const y = band ? H - 0.1 - 0.5 * rand() : 0.8 + (H - 1.5) * rand();
    const z = 0.2 + (D - 0.3) * rand();
    const power = Math.exp(Math.log(100) * rand());
    const tint = Math.floor(rand() * tints);
    powers.push(power);
    lights.push({ center: [x, y, z], r, power, tint });
  }
  const total = powers.reduce((a, b) => a + b, 0);
  // Total power ~ 40 (in radiance × area units), whatever N.
  const scale = 40 / total;
  lights.forEach((l, i) => {
    const L = (l.power * scale) / (4 * Math.PI * l.r * l.r);
    const name = `lamp${i}`;
    const t = l.tint;
    const c = [0.6 + 0.4 * (t & 1), 0.6 + 0.4 * ((t >> 1) & 1), 0.6 + 0.4 * ((t >> 2) & 1)];
    materials[name] = {
      type: 'diffuse',
      albedo: [0, 0, 0],
      emission: c.map((v) => round(v * L)),
    };
    shapes.push({
      type: 'sphere',
      center: l.center.map(round),
      radius: round(l.r),
      material: name,
    });
  });
  return {
    format: 'pathwise-scene/1',
    name: `a room lit by ${count} small emitters`,
    camera: { position: [2, 1.5, 0.05], target: [2, 1.2, 4], up: [0, 1, 0], fovY: 62 },
    settings: { width: 128, height: 96, maxBounces: 6, spp: 16 },
    materials,
    shapes,
    environment: [0, 0, 0],
  };
}
