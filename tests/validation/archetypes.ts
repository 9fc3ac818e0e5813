/**
 * Scene archetypes of the generator, each built in its own unit frame
 * (y up, sizes ~1–10) into a SceneBuilder; generate.ts then maps the
 * whole scene by a random similarity (scale 1e-4…1e4, rotation,
 * translation). The archetypes are the situations of issue 8:
 * - room: a box of inward quads (one wall may be missing), camera inside;
 * - ground: objects on a ground quad or a ground sphere (radius up to
 *   1e5), camera outside;
 * - glass: either of those with the camera inside a glass sphere or box;
 * - sphere-over-receiver: a sphere light over a quad, a small sphere or a
 *   huge sphere, with d/r from 100 down to 1.01 (the first two
 *   cases);
 * - grazing: a thin quad light tilted 1e-4…0.1 rad off a floor, facing
 *   down, lighting a back wall at grazing angles; the camera sees the wall
 *   or looks along the light's plane (the third case).
 */
import type { CameraJson, EnvironmentJson, SceneBuilder } from './builder.ts';
import { add, cross, dot, length, mul, normalize, perpendicular, sub, type Vec3 } from './vec.ts';

/** What an archetype leaves besides the shapes: the camera and the bounce limit. */
export interface Staged {
  camera: CameraJson;
  maxBounces: number;
}

export interface Archetype {
  name: string;
  weight: number;
  build(b: SceneBuilder): Staged;
}

/** An axis-aligned region where objects and lights may go. */
export interface Region {
  lo: Vec3;
  hi: Vec3;
}

export const center = (r: Region): Vec3 => mul(add(r.lo, r.hi), 0.5);
export const extent = (r: Region): number => length(sub(r.hi, r.lo));

export function pointIn(b: SceneBuilder, r: Region): Vec3 {
  const g = b.rng;
  return [g.uniform(r.lo[0], r.hi[0]), g.uniform(r.lo[1], r.hi[1]), g.uniform(r.lo[2], r.hi[2])];
}

/** A way to fill a scene's `environment`, drawn by weight. */
export interface EnvironmentMaker {
  name: string;
  weight: number;
  make(b: SceneBuilder): EnvironmentJson;
}

/**
 * Environments of the classic family. Frozen: an entry added here changes the
 * random stream, and so every classic scene; a new kind (an environment map)
 * goes into the mesh family's list (archetypes-mesh.ts).
 */
export const ENVIRONMENT_MAKERS: EnvironmentMaker[] = [
  { name: 'none', weight: 0.4, make: () => null },
  {
    name: 'constant',
    weight: 0.6,
    make: (b) => {
      const level = b.rng.logUniform(0.01, 2);
      const tint = b.color(0.4, 1);
      return [level * tint[0], level * tint[1], level * tint[2]];
    },
  },
];

export function environment(
  b: SceneBuilder,
  weightOfNone = 0.4,
  makers: EnvironmentMaker[] = ENVIRONMENT_MAKERS,
): void {
  const maker = b.rng.weighted(
    makers.map((m) => [m, m.name === 'none' ? weightOfNone : m.weight] as const),
  );
  b.environment = maker.make(b);
  b.tag(b.environment === null ? 'no-environment' : 'environment');
}

/** A way to place one object in a region, clear of the point `avoid` (the eye), drawn by weight. */
export interface ObjectMaker {
  name: string;
  weight: number;
  make(b: SceneBuilder, r: Region, avoid: Vec3): void;
}

/**
 * Objects of the classic family: random material. Frozen, like
 * ENVIRONMENT_MAKERS: new shape kinds (triangle meshes) go into the mesh
 * family's list (archetypes-mesh.ts).
 */
export const OBJECT_MAKERS: ObjectMaker[] = [
  {
    name: 'sphere',
    weight: 0.5,
    make: (b, r, avoid) => {
      const radius = extent(r) * b.rng.logUniform(0.03, 0.25);
      const c = pointIn(b, r);
      if (length(sub(c, avoid)) > radius * 1.2) b.sphere(c, radius, b.material());
    },
  },
  {
    name: 'panel',
    weight: 0.25,
    make: (b, r, avoid) => {
      const size = extent(r) * b.rng.logUniform(0.05, 0.4);
      const n = b.rng.direction();
      const u = mul(perpendicular(n), size);
      const v = mul(normalize(cross(n, u)), size * b.rng.uniform(0.3, 1));
      const corner = pointIn(b, r);
      if (Math.abs(dot(sub(avoid, corner), n)) > 1e-3 * size)
        b.quad(corner, u, v, b.material(b.rng.chance(0.7) ? 'diffuse' : 'conductor'));
    },
  },
  {
    name: 'box',
    weight: 0.25,
    make: (b, r, avoid) => {
      const lo = pointIn(b, r);
      const s = extent(r) * b.rng.logUniform(0.05, 0.25);
      const hi: Vec3 = [
        lo[0] + s * b.rng.uniform(0.5, 1.5),
        lo[1] + s,
        lo[2] + s * b.rng.uniform(0.5, 1.5),
      ];
      const inside = avoid.every((x, i) => x >= lo[i] - s * 0.1 && x <= hi[i] + s * 0.1);
      if (!inside) b.box(lo, hi, b.material(), true);
    },
  },
];

export function objects(
  b: SceneBuilder,
  r: Region,
  count: number,
  avoid: Vec3,
  makers: ObjectMaker[] = OBJECT_MAKERS,
): void {
  for (let i = 0; i < count; i++) {
    b.rng.weighted(makers.map((m) => [m, m.weight] as const)).make(b, r, avoid);
  }
}

/**
 * Emitters of very different size and power. Each is given the radiance
 * that makes the diffuse surfaces near it read about `brightness`, so a
 * tiny light is very bright; every light after the first gets 1e-3…1 of
 * that. A quarter sit next to a receiver (d/r 1.01…1.5, or a quad light
 * 1e-3…0.1 of its size above the floor).
 */
export function lights(
  b: SceneBuilder,
  r: Region,
  floorY: number,
  count: number,
  avoid: Vec3,
): void {
  const g = b.rng;
  const size0 = extent(r);
  const powers: number[] = [];
  for (let i = 0; i < count; i++) {
    const brightness = g.logUniform(0.2, 2) * (i === 0 ? 1 : g.logUniform(1e-3, 1));
    const cls = g.weighted([
      ['tiny', 0.15],
      ['small', 0.35],
      ['medium', 0.35],
      ['large', 0.15],
    ] as const);
    const rel = {
      tiny: [1e-3, 1e-2],
      small: [1e-2, 0.05],
      medium: [0.05, 0.15],
      large: [0.15, 0.4],
    }[cls];
    const size = size0 * g.logUniform(rel[0], rel[1]);
    if (cls === 'tiny') b.tag('tiny-light');
    if (cls === 'large') b.tag('large-light');
    const near = g.chance(0.25);
    const p = pointIn(b, r);
    const distance = Math.max(size * 2, p[1] - floorY, size0 * 0.3);
    if (g.chance(0.55)) {
      const radius = size / 2;
      if (near) {
        p[1] = floorY + radius * (1 + g.logUniform(0.01, 0.5));
        b.tag('light-near-receiver');
      }
      if (length(sub(p, avoid)) < radius * 1.5) continue;
      const d = near ? p[1] - floorY : distance;
      const radiance = Math.min(1e9, (brightness * (d / radius) ** 2) / 0.5);
      b.sphere(p, radius, b.emitter(radiance));
      powers.push(radiance * radius * radius * 4 * Math.PI);
    } else {
      // Facing down (a ceiling lamp) or towards the middle of the region.
      const n: Vec3 = g.chance(0.6)
        ? normalize([g.uniform(-0.3, 0.3), -1, g.uniform(-0.3, 0.3)])
        : normalize(sub(center(r), p));
      const aspect = g.logUniform(0.2, 5);
      const eu = perpendicular(n);
      const ev = cross(n, eu);
      const u = mul(eu, size * Math.sqrt(aspect));
      const v = mul(ev, size / Math.sqrt(aspect));
      // cross(u, v) = size² n: the front side faces along n.
      const c = sub(p, mul(add(u, v), 0.5));
      if (near && n[1] < -0.9) {
        const h = size * g.logUniform(1e-3, 0.1);
        const lift = floorY + h - Math.min(c[1], c[1] + u[1], c[1] + v[1], c[1] + u[1] + v[1]);
        c[1] += lift;
        b.tag('light-near-receiver');
      }
      const area = size * size;
      const d = near ? size : distance;
      const radiance = Math.min(1e9, (brightness * Math.PI * d * d) / (0.5 * area));
      b.quad(c, u, v, b.emitter(radiance));
      powers.push(radiance * area);
    }
  }
  if (powers.length > 1) {
    b.tag('multiple-lights');
    if (Math.max(...powers) >= 1000 * Math.min(...powers)) b.tag('power-ratio-1000');
  }
}

export function lens(b: SceneBuilder, camera: CameraJson): CameraJson {
  if (!b.rng.chance(0.25)) return camera;
  const d = length(sub(camera.target, camera.position));
  b.tag('aperture');
  return {
    ...camera,
    aperture: d * b.rng.logUniform(0.002, 0.05),
    focusDistance: d * b.rng.uniform(0.5, 1.5),
  };
}

/**
 * The camera of a room W × H × D with its eye at `eye` (tagged camera-in-room): aimed at
 * a random point of the back half, a random field of view, now and then a lens. The
 * random numbers are drawn in the same order wherever it is called.
 */
export function roomCamera(
  b: SceneBuilder,
  eye: Vec3,
  W: number,
  H: number,
  D: number,
): CameraJson {
  b.tag('camera-in-room');
  return lens(b, {
    position: eye,
    target: pointIn(b, { lo: [0.2 * W, 0, 0.5 * D], hi: [0.8 * W, 0.7 * H, D] }),
    up: [0, 1, 0],
    fovY: b.rng.uniform(30, 80),
  });
}

export function bounces(b: SceneBuilder, lo: number, hi: number): number {
  const n = b.rng.int(lo, hi);
  if (n === 0) b.tag('bounces-0');
  if (n === 12) b.tag('bounces-12');
  return n;
}

const room: Archetype = {
  name: 'room',
  weight: 0.3,
  build: (b) => buildRoom(b),
};

function buildRoom(b: SceneBuilder): Staged {
  const g = b.rng;
  const W = g.uniform(2, 6);
  const H = g.uniform(2, 4);
  const D = g.uniform(2, 6);
  const open = g.chance(0.4) ? [g.pick(['front', 'ceiling', 'left'])] : [];
  const wall = b.material(g.chance(0.85) ? 'diffuse' : 'conductor');
  b.box([0, 0, 0], [W, H, D], wall, false, open);
  if (g.chance(0.3)) b.quad([0, 0, D * 0.999], [0, H, 0], [W, 0, 0], b.material('diffuse'));
  environment(b, open.length > 0 ? 0.4 : 0.7);
  const eye: Vec3 = [g.uniform(0.2, 0.8) * W, g.uniform(0.2, 0.8) * H, g.uniform(0.05, 0.12) * D];
  const region: Region = { lo: [0.1 * W, 0, 0.2 * D], hi: [0.9 * W, 0.85 * H, 0.9 * D] };
  lights(b, region, 0, g.int(1, 3), eye);
  objects(b, { lo: [0.15 * W, 0, 0.25 * D], hi: [0.85 * W, 0.5 * H, 0.85 * D] }, g.int(1, 4), eye);
  return { camera: roomCamera(b, eye, W, H, D), maxBounces: bounces(b, 0, 12) };
}

const ground: Archetype = {
  name: 'ground',
  weight: 0.3,
  build: (b) => buildGround(b),
};

function buildGround(b: SceneBuilder): Staged {
  const g = b.rng;
  const floor = b.material(g.chance(0.85) ? 'diffuse' : 'conductor');
  if (g.chance(0.5)) {
    const R = g.chance(0.3) ? 1e5 : g.logUniform(10, 1e5);
    b.sphere([0, -R, 0], R, floor);
    b.tag('ground-sphere');
    if (R >= 1e3) b.tag('huge-receiver');
    if (R === 1e5) b.tag('ground-sphere-1e5');
  } else {
    const S = g.logUniform(20, 2000);
    b.quad([-S / 2, 0, -S / 2], [0, 0, S], [S, 0, 0], floor);
    if (S >= 500) b.tag('huge-receiver');
  }
  environment(b, 0.35);
  const region: Region = { lo: [-2, 0, -2], hi: [2, 2, 2] };
  const elevation = g.uniform(3, 60) * (Math.PI / 180);
  const azimuth = g.uniform(0, 2 * Math.PI);
  const dist = g.uniform(5, 12);
  const eye: Vec3 = [
    dist * Math.cos(elevation) * Math.sin(azimuth),
    dist * Math.sin(elevation) + 0.2,
    dist * Math.cos(elevation) * Math.cos(azimuth),
  ];
  lights(b, { lo: [-3, 0, -3], hi: [3, 4, 3] }, 0, g.int(1, 3), eye);
  objects(b, region, g.int(1, 5), eye);
  b.tag('camera-outside');
  return {
    camera: lens(b, {
      position: eye,
      target: add(center(region), [g.uniform(-1, 1), g.uniform(-0.8, 0), g.uniform(-1, 1)]),
      up: [0, 1, 0],
      fovY: g.uniform(20, 70),
    }),
    maxBounces: bounces(b, 0, 12),
  };
}

/** Room or ground, then a glass sphere or box around the camera, clear of everything else. */
const glass: Archetype = {
  name: 'glass',
  weight: 0.12,
  build: (b) => {
    const staged = b.rng.chance(0.5) ? buildRoom(b) : buildGround(b);
    const eye = staged.camera.position;
    let clearance = Infinity;
    for (const s of b.shapes) {
      clearance = Math.min(
        clearance,
        s.type === 'sphere'
          ? length(sub(s.center, eye)) - s.radius
          : s.type === 'quad'
            ? Math.abs(dot(sub(eye, s.corner), normalize(cross(s.u, s.v))))
            : Infinity, // the classic family has no meshes
      );
    }
    const size = clearance * b.rng.uniform(0.2, 0.6);
    const glassMaterial = b.material('dielectric');
    if (b.rng.chance(0.6)) {
      b.sphere(add(eye, mul(b.rng.direction(), size * 0.4)), size, glassMaterial);
    } else {
      const off = mul(b.rng.direction(), size * 0.3);
      b.box(
        sub(add(eye, off), [size, size, size]),
        add(add(eye, off), [size, size, size]),
        glassMaterial,
        true,
      );
    }
    b.tag('camera-in-glass');
    return staged;
  },
};

/** The first two cases, generalised: a sphere light over a receiver's normal. */
const sphereOverReceiver: Archetype = {
  name: 'sphere-over-receiver',
  weight: 0.16,
  build: (b) => {
    const g = b.rng;
    const r = g.logUniform(0.01, 1);
    const dOverR = 1 + g.logUniform(0.01, 99);
    const d = dOverR * r;
    const receiver = g.weighted([
      ['quad', 0.4],
      ['small-sphere', 0.25],
      ['huge-sphere', 0.35],
    ] as const);
    const albedo = b.material('diffuse');
    if (receiver === 'quad') {
      const S = d * g.logUniform(4, 400);
      b.quad([-S / 2, 0, -S / 2], [0, 0, S], [S, 0, 0], albedo);
      if (S >= 1e3 * r) b.tag('huge-receiver');
    } else {
      const R =
        receiver === 'huge-sphere'
          ? g.pick([1e3, 1e4, 1e5, g.logUniform(1e3, 1e5)])
          : d * g.logUniform(0.3, 3);
      b.sphere([0, -R, 0], R, albedo);
      b.tag('ground-sphere');
      if (receiver === 'huge-sphere') b.tag('huge-receiver');
      if (R === 1e5) b.tag('ground-sphere-1e5');
    }
    if (dOverR < 1.5) b.tag('light-near-receiver');
    if (r < 0.03) b.tag('tiny-light');
    const radiance = g.logUniform(1, 100) * Math.min(1e4, dOverR * dOverR);
    b.sphere([0, d, 0], r, b.emitter(radiance));
    if (g.chance(0.25)) {
      const s = g.logUniform(0.1, 1) * r;
      b.sphere([g.uniform(2, 4) * d, s, g.uniform(-2, 2) * d], s, b.material());
    }
    environment(b, 0.7);
    // Seen from far enough off the normal that the light does not hide the foot point.
    const hidden = Math.asin(1 / dOverR);
    const theta = g.uniform(Math.min(hidden + 0.05, 1.5), 1.53);
    const phi = g.uniform(0, 2 * Math.PI);
    const dist = d * g.uniform(3, 10);
    const eye: Vec3 = [
      dist * Math.sin(theta) * Math.cos(phi),
      dist * Math.cos(theta),
      dist * Math.sin(theta) * Math.sin(phi),
    ];
    b.tag('camera-outside');
    if (theta > 1.45) b.tag('grazing');
    return {
      camera: lens(b, {
        position: eye,
        target: [g.uniform(-0.3, 0.3) * d, 0, g.uniform(-0.3, 0.3) * d],
        up: [0, 1, 0],
        fovY: g.uniform(5, 60),
      }),
      maxBounces: bounces(b, 1, 4),
    };
  },
};

/** The third case, generalised: a thin quad light nearly edge-on to floor and wall. */
const grazing: Archetype = {
  name: 'grazing',
  weight: 0.12,
  build: (b) => {
    const g = b.rng;
    const S = 8;
    b.quad(
      [-S / 2, 0, -S / 2],
      [0, 0, S],
      [S, 0, 0],
      b.material(g.chance(0.8) ? 'diffuse' : 'conductor'),
    );
    const zw = 2;
    b.quad([-S / 2, 0, zw], [S, 0, 0], [0, S / 2, 0], b.material('diffuse'));
    const w = g.uniform(1, 3);
    const depth = g.uniform(0.3, 1.5);
    const h = g.uniform(0.05, 0.6);
    const tilt = g.logUniform(1e-4, 0.1);
    const z0 = zw - depth - g.uniform(0.05, 1);
    // Facing down, tilted towards the wall: cross(u, v) = (0, -cos, sin)·w·depth,
    // so the wall below the light's plane sees its emitting side edge-on.
    const u: Vec3 = [w, 0, 0];
    const v: Vec3 = [0, depth * Math.sin(tilt), depth * Math.cos(tilt)];
    const c: Vec3 = [-w / 2, h, z0];
    b.quad(c, u, v, b.emitter(g.logUniform(2, 50)));
    if (g.chance(0.3)) b.sphere([g.uniform(-1, 1), 0.3, zw - 0.6], 0.3, b.material());
    environment(b, 0.75);
    b.tag('grazing');
    b.tag('camera-outside');
    const edgeOn = g.chance(0.4);
    const eye: Vec3 = edgeOn
      ? [g.uniform(-0.5, 0.5), h + g.uniform(-0.02, 0.02), z0 - g.uniform(2, 5)]
      : [g.uniform(-1, 1), g.uniform(0.2, 1.5), zw - g.uniform(3, 6)];
    return {
      camera: lens(b, {
        position: eye,
        target: edgeOn ? [0, h, zw] : [0, h * g.uniform(0.2, 1), zw],
        up: [0, 1, 0],
        fovY: g.uniform(10, 50),
      }),
      maxBounces: bounces(b, 1, 4),
    };
  },
};

export const ARCHETYPES: Archetype[] = [room, ground, glass, sphereOverReceiver, grazing];
