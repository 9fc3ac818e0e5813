// Scenes of the hard-scene suite (issue 23, deliverable 4) that the native anchor can also
// render (spheres, quads, the three materials, a constant environment), as plain
// pathwise-scene/1 objects:
//
// - caustic: a closed white room lit by one small sphere lamp; a glass ball on the floor
//   focuses it into a caustic. Next-event estimation cannot see the lamp through the glass
//   (a shadow ray stops at it), so the caustic, and the light it throws about the room,
//   come only from BSDF-sampled paths that happen to hit the small lamp: fireflies.
// - window: a closed room lit only through a window by a constant sky. The lit patch of
//   floor and everything it bounces to are reached through the window alone; most
//   directions from inside see walls.
// - dense: a bumpy torus of 1,000,000 triangles (a binary PLY written beside the scene) in a
//   room under a ceiling lamp. The native anchor renders no meshes: Mitsuba alone compares.
//
//   node bench/hard-scenes.mjs caustic /tmp/caustic.json
//   node bench/hard-scenes.mjs dense /tmp/dense/scene.json    (writes /tmp/dense/dense.ply)
import { writeFileSync } from 'node:fs';
import path from 'node:path';

const white = { type: 'diffuse', albedo: [0.73, 0.73, 0.73] };

/** The six inward-facing walls of the box [0, X] × [0, Y] × [0, Z] (quads face +u × v). */
function box(X, Y, Z, material, skip = '') {
  const walls = {
    floor: { corner: [0, 0, 0], u: [0, 0, Z], v: [X, 0, 0] },
    ceiling: { corner: [0, Y, 0], u: [X, 0, 0], v: [0, 0, Z] },
    left: { corner: [0, 0, 0], u: [0, Y, 0], v: [0, 0, Z] },
    right: { corner: [X, 0, 0], u: [0, 0, Z], v: [0, Y, 0] },
    front: { corner: [0, 0, 0], u: [X, 0, 0], v: [0, Y, 0] },
    back: { corner: [0, 0, Z], u: [0, Y, 0], v: [X, 0, 0] },
  };
  return Object.entries(walls)
    .filter(([name]) => !skip.split(',').includes(name))
    .map(([, q]) => ({ type: 'quad', ...q, material }));
}

export function caustic() {
  return {
    format: 'pathwise-scene/1',
    name: 'Caustic through a glass ball (hard-scene suite)',
    camera: { position: [2, 1.6, 0.3], target: [2, 0.5, 2.6], up: [0, 1, 0], fovY: 55 },
    settings: { width: 128, height: 96, maxBounces: 8, spp: 1024 },
    materials: {
      white,
      red: { type: 'diffuse', albedo: [0.63, 0.065, 0.05] },
      glass: { type: 'dielectric', ior: 1.5, color: [1, 1, 1], roughness: 0 },
      lamp: { type: 'diffuse', albedo: [0, 0, 0], emission: [120, 114, 102] },
    },
    shapes: [
      ...box(4, 3, 4, 'white', 'left'),
      { type: 'quad', corner: [0, 0, 0], u: [0, 3, 0], v: [0, 0, 4], material: 'red' },
      { type: 'sphere', center: [2, 0.55, 2.6], radius: 0.55, material: 'glass' },
      { type: 'sphere', center: [2.9, 2.5, 3.3], radius: 0.06, material: 'lamp' },
    ],
  };
}

export function windowRoom() {
  // The window: an opening 1.6 wide and 1.2 high in the right wall (x = 5), 0.9 above
  // the floor; the wall is the four quads around it.
  const [Z0, Z1, Y0, Y1] = [1.7, 3.3, 0.9, 2.1];
  const wall = (z0, z1, y0, y1) => ({
    type: 'quad',
    corner: [5, y0, z0],
    u: [0, 0, z1 - z0],
    v: [0, y1 - y0, 0],
    material: 'white',
  });
  return {
    format: 'pathwise-scene/1',
    name: 'Interior lit through a window by the sky (hard-scene suite)',
    camera: { position: [0.4, 1.5, 0.4], target: [4, 0.8, 3.2], up: [0, 1, 0], fovY: 60 },
    settings: { width: 128, height: 96, maxBounces: 8, spp: 1024 },
    environment: [3, 3.3, 4],
    materials: {
      white,
      wood: { type: 'diffuse', albedo: [0.45, 0.3, 0.18] },
      blue: { type: 'diffuse', albedo: [0.15, 0.25, 0.6] },
    },
    shapes: [
      ...box(5, 2.8, 5, 'white', 'right,floor'),
      { type: 'quad', corner: [0, 0, 0], u: [0, 0, 5], v: [5, 0, 0], material: 'wood' },
      wall(0, 5, 0, Y0),
      wall(0, 5, Y1, 2.8),
      wall(0, Z0, Y0, Y1),
      wall(Z1, 5, Y0, Y1),
      { type: 'sphere', center: [2.2, 0.45, 3.4], radius: 0.45, material: 'blue' },
    ],
  };
}

/**
 * A torus of major radius R and minor radius r around the y axis, its tube bumped by a few
 * sines, as a binary little-endian PLY of nu × nv quads split in two: 2·nu·nv triangles,
 * none degenerate (a torus has no poles), facing outward.
 */
function bumpyTorusPly(nu, nv, R, r) {
  const vertices = nu * nv;
  const header =
    `ply\nformat binary_little_endian 1.0\nelement vertex ${vertices}\n` +
    `property float x\nproperty float y\nproperty float z\n` +
    `element face ${2 * vertices}\nproperty list uchar uint vertex_indices\nend_header\n`;
  const head = Buffer.from(header, 'ascii');
  const body = Buffer.alloc(12 * vertices + 13 * 2 * vertices);
  let at = 0;
  for (let i = 0; i < nu; i++) {
    const u = (2 * Math.PI * i) / nu;
    for (let j = 0; j < nv; j++) {
      const v = (2 * Math.PI * j) / nv;
      const rr =
        r * (1 + 0.08 * Math.sin(13 * u) * Math.sin(7 * v) + 0.03 * Math.sin(57 * u + 3 * v));
      const ring = R + rr * Math.cos(v);
      body.writeFloatLE(ring * Math.cos(u), at);
      body.writeFloatLE(rr * Math.sin(v), at + 4);
      body.writeFloatLE(ring * Math.sin(u), at + 8);
      at += 12;
    }
  }
  const id = (i, j) => (i % nu) * nv + (j % nv);
  const face = (a, b, c) => {
    body.writeUInt8(3, at);
    body.writeUInt32LE(a, at + 1);
    body.writeUInt32LE(b, at + 5);
    body.writeUInt32LE(c, at + 9);
    at += 13;
  };
  for (let i = 0; i < nu; i++) {
    for (let j = 0; j < nv; j++) {
      face(id(i, j), id(i, j + 1), id(i + 1, j + 1));
      face(id(i, j), id(i + 1, j + 1), id(i + 1, j));
    }
  }
  return Buffer.concat([head, body]);
}

const C20 = Math.cos((20 * Math.PI) / 180);
const S20 = Math.sin((20 * Math.PI) / 180);

/** The dense scene; its mesh is written to dir/dense.ply. */
export function dense(dir) {
  writeFileSync(path.join(dir, 'dense.ply'), bumpyTorusPly(1000, 500, 1, 0.35));
  return {
    format: 'pathwise-scene/1',
    name: 'A torus of 1,000,000 triangles (hard-scene suite)',
    camera: { position: [2, 2.2, -1.2], target: [2, 0.5, 2], up: [0, 1, 0], fovY: 50 },
    settings: { width: 128, height: 96, maxBounces: 8, spp: 1024 },
    materials: {
      white,
      clay: { type: 'diffuse', albedo: [0.8, 0.45, 0.3] },
      lamp: { type: 'diffuse', albedo: [0, 0, 0], emission: [12, 11.5, 10.5] },
    },
    shapes: [
      ...box(4, 3, 4, 'white', 'front'),
      { type: 'quad', corner: [1.5, 2.99, 1.5], u: [1, 0, 0], v: [0, 0, 1], material: 'lamp' },
      {
        type: 'mesh',
        file: 'dense.ply',
        material: 'clay',
        // Tilted 20° about x, centred at (2, 0.95, 2).
        transform: [1, 0, 0, 2, 0, C20, -S20, 0.95, 0, S20, C20, 2, 0, 0, 0, 1],
      },
    ],
  };
}

export const HARD_SCENES = { caustic, window: windowRoom, dense };

if (process.argv[1] && import.meta.url.endsWith(process.argv[1].split('/').pop())) {
  const make = HARD_SCENES[process.argv[2]];
  const out = process.argv[3];
  if (!make || (process.argv[2] === 'dense' && !out)) {
    throw new Error(`usage: node bench/hard-scenes.mjs ${Object.keys(HARD_SCENES)} [OUT.json]`);
  }
  const text = JSON.stringify(make(out ? path.dirname(out) : '.'), null, 2) + '\n';
  if (out) writeFileSync(out, text);
  else process.stdout.write(text);
}
