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
 * A hall lit by N small lamps (issue 23's many-light goal): a closed box 20 × 4 × 20 of
 * diffuse walls (a red left, a green right), twenty diffuse and rough metal spheres on
 * the floor, and N small square lamps (side 4–10 cm) on a jittered grid 0.5–2 above the
 * floor, each emitting downward only (a one-sided quad), with a random tint and power
 * spread log-uniformly over two decades (their total fixed, so the exposure does not
 * depend on N). The camera, under the ceiling, looks down at the floor and sees the
 * lamps' dark backs: the image's error is the light sampling's, not that of emitters
 * smaller than a pixel. Each patch of floor is lit mostly by the few lamps above it,
 * which a choice by power alone rarely picks.
 */
export function manyLights(count, seed = 1) {
  let state = seed >>> 0;
  const rand = () => (state = pcgHash(state + 1)) / 4294967296;
  const round = (v) => +v.toFixed(6);
  const W = 20;
  const H = 4;
  const D = 20;
  const shapes = [
    { type: 'quad', corner: [0, 0, 0], u: [0, 0, D], v: [W, 0, 0], material: 'white' },
    { type: 'quad', corner: [0, H, 0], u: [W, 0, 0], v: [0, 0, D], material: 'white' },
    { type: 'quad', corner: [0, 0, D], u: [W, 0, 0], v: [0, H, 0], material: 'white' },
    { type: 'quad', corner: [0, 0, 0], u: [0, H, 0], v: [0, 0, D], material: 'red' },
    { type: 'quad', corner: [W, 0, 0], u: [0, 0, D], v: [0, H, 0], material: 'green' },
    { type: 'quad', corner: [0, 0, 0], u: [W, 0, 0], v: [0, H, 0], material: 'white' },
  ];
  for (let i = 0; i < 20; i++) {
    const r = 0.2 + 0.4 * rand();
    shapes.push({
      type: 'sphere',
      center: [round(1 + (W - 2) * rand()), round(r), round(1 + (D - 2) * rand())],
      radius: round(r),
      material: ['white', 'metal', 'blue'][i % 3],
    });
  }
  const materials = {
    white: { type: 'diffuse', albedo: [0.75, 0.75, 0.75] },
    red: { type: 'diffuse', albedo: [0.7, 0.15, 0.12] },
    green: { type: 'diffuse', albedo: [0.15, 0.6, 0.2] },
    blue: { type: 'diffuse', albedo: [0.15, 0.25, 0.7] },
    metal: { type: 'conductor', color: [0.9, 0.8, 0.6], roughness: 0.3 },
  };
  const side = Math.ceil(Math.sqrt(count));
  const lamps = [];
  let total = 0;
  for (let i = 0; i < count; i++) {
    const s = 0.04 + 0.06 * rand();
    const gx = i % side;
    const gz = Math.floor(i / side);
    const x = 0.5 + ((gx + 0.15 + 0.7 * rand()) * (W - 1)) / side;
    const z = 0.5 + ((gz + 0.15 + 0.7 * rand()) * (D - 1)) / side;
    const y = 0.5 + 1.5 * rand();
    const power = Math.exp(Math.log(100) * rand());
    const tint = Math.floor(rand() * 8);
    total += power;
    lamps.push({ x, y, z, s, power, tint });
  }
  // Total power ~ 400 (radiance × area units), whatever N.
  const scale = 400 / total;
  lamps.forEach((l, i) => {
    const L = (l.power * scale) / (l.s * l.s);
    const name = `lamp${i}`;
    const t = l.tint;
    const c = [0.6 + 0.4 * (t & 1), 0.6 + 0.4 * ((t >> 1) & 1), 0.6 + 0.4 * ((t >> 2) & 1)];
    materials[name] = {
      type: 'diffuse',
      albedo: [0, 0, 0],
      emission: c.map((v) => round(v * L)),
    };
    // cross(u, v) points down (−y): the lamp emits toward the floor only.
    shapes.push({
      type: 'quad',
      corner: [round(l.x - l.s / 2), round(l.y), round(l.z - l.s / 2)],
      u: [round(l.s), 0, 0],
      v: [0, 0, round(l.s)],
      material: name,
    });
  });
  return {
    format: 'pathwise-scene/1',
    name: `a hall lit by ${count} small lamps`,
    camera: { position: [W / 2, 3.6, 1], target: [W / 2, 0, 11], up: [0, 1, 0], fovY: 55 },
    settings: { width: 128, height: 96, maxBounces: 6, spp: 16 },
    materials,
    shapes,
    environment: [0, 0, 0],
  };
}
