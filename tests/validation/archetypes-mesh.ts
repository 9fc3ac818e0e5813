/**
 * The generator's mesh family (issue 11 §5): scenes with triangle meshes and
 * environment maps, drawn with `generateScene(seed, { family: 'mesh' })`. A family
 * of its own so that the classic scenes (archetypes.ts) keep their random stream,
 * and so their seeds, committed references and coverage, byte for byte.
 *
 * Meshes (meshes.ts) are closed (icosphere, box, torus), open (bowl, tube, height
 * field, disc) or thin (a two-triangle sheet, one triangle, a box squashed to 1e-3
 * of its size); with or without smooth shading normals (the box's point along its
 * diagonals, the sheets' are tilted up to 0.5 rad off the face); placed by a
 * `transform` or baked into the positions; anisotropic, mirrored (winding reversed
 * to keep the front side out, or not: inside out), or with positions 1e3 or 1e-3
 * times their size and a transform that undoes it; inline, or as OBJ / PLY files.
 * Emissive meshes are lights: tiny to large, grazing a floor, next to a receiver,
 * with powers far apart, beside sphere and quad lights. Environment maps
 * (envmaps.ts): constant, gradient, a tiny bright sun; rotated and scaled.
 *
 * Archetypes: mesh-room, mesh-ground, mesh-light (an emissive mesh over a receiver,
 * or grazing a floor and a wall), map-objects (meshes lit by a map alone) and
 * mesh-glass (the camera inside a closed glass mesh).
 */
import {
  compose,
  determinant,
  transformNormals,
  transformPositions,
  trs,
  type Matrix,
} from './affine.ts';
import {
  ENVIRONMENT_MAKERS,
  bounces,
  center,
  environment,
  extent,
  lens,
  lights,
  objects,
  OBJECT_MAKERS,
  pointIn,
  roomCamera,
  type Archetype,
  type EnvironmentMaker,
  type ObjectMaker,
  type Region,
  type Staged,
} from './archetypes.ts';
import type { Feature, MaterialKind, MeshStorage, SceneBuilder } from './builder.ts';
import { makeEnvironmentMap } from './envmaps.ts';
import {
  bowl,
  box,
  disc,
  heightField,
  icosphere,
  meshArea,
  reverseWinding,
  sheet,
  torus,
  triangle,
  tube,
  type LocalMesh,
  type MeshKind,
} from './meshes.ts';
import { add, cross, dot, length, mul, normalize, sub, type Vec3 } from './vec.ts';

/** Environments of the mesh family: the classic ones and three kinds of map. */
export const MAP_ENVIRONMENT_MAKERS: EnvironmentMaker[] = [
  ...ENVIRONMENT_MAKERS.map((m) => ({ ...m, weight: m.weight * 0.4 })),
  { name: 'constant-map', weight: 0.15, make: (b) => map(b, 'constant') },
  { name: 'gradient-map', weight: 0.25, make: (b) => map(b, 'gradient') },
  { name: 'sun-map', weight: 0.25, make: (b) => map(b, 'sun') },
];

function map(b: SceneBuilder, kind: 'constant' | 'gradient' | 'sun') {
  const m = makeEnvironmentMap(b.rng, kind, b.rng.logUniform(0.05, 2));
  b.tag('env-map', `env-map-${kind}`, m.format === 'hdr' ? 'env-map-hdr' : 'env-map-pfm');
  if (m.rotationY !== 0) b.tag('env-map-rotated');
  if (Array.isArray(m.scale)) b.tag('env-map-rgb-scale');
  return m;
}

/** Maps only (the map-objects archetype). */
const MAPS_ONLY = MAP_ENVIRONMENT_MAKERS.filter((m) => m.name.endsWith('-map'));

export interface MeshOptions {
  kind?: MeshKind | 'slab';
  material: string;
  /** World centre and size (half the largest extent). */
  center: Vec3;
  size: number;
  /** Orientation: the local +y axis goes here (default a random direction). */
  up?: Vec3;
  /** Allow a mirroring transform (never for glass: a closed solid must face out). */
  mirror?: boolean;
  /** Shading normals: probability (default 0.5). */
  normals?: number;
  anisotropic?: boolean;
  /** Explicit local scale (instead of size and the random anisotropy). */
  scale?: Vec3;
}

export interface Placed {
  /** World-space positions and the mesh's area. */
  world: number[];
  area: number;
}

const CLOSED: MeshKind[] = ['icosphere', 'box', 'torus'];

/** Builds the local mesh of a kind. */
function localMesh(b: SceneBuilder, kind: MeshKind | 'slab'): LocalMesh {
  const g = b.rng;
  switch (kind) {
    case 'icosphere':
      return icosphere(g.chance(0.6) ? 1 : 2);
    case 'box':
      return box();
    case 'slab':
      return box();
    case 'torus':
      return torus(g.uniform(0.2, 0.5), g.int(10, 20), g.int(5, 8));
    case 'bowl':
      return bowl(g.int(8, 16), g.int(3, 5));
    case 'tube':
      return tube(g.int(8, 20));
    case 'height-field':
      return heightField(g, g.int(5, 9));
    case 'disc':
      return disc(g.int(6, 20));
    case 'sheet':
      return sheet(g, 0.5);
    case 'triangle':
      return triangle(g, 0.5);
  }
}

/**
 * Places one mesh: local mesh → optional extreme local scale → transform (rotation,
 * scale, optional anisotropy and mirror) → in the file as `transform`, or baked
 * into the positions. Returns its world-space positions (for clearances).
 */
export function placeMesh(b: SceneBuilder, o: MeshOptions): Placed {
  const g = b.rng;
  const kind =
    o.kind ??
    g.weighted<MeshKind | 'slab'>([
      ['icosphere', 0.2],
      ['box', 0.12],
      ['torus', 0.12],
      ['bowl', 0.1],
      ['tube', 0.08],
      ['height-field', 0.1],
      ['disc', 0.06],
      ['sheet', 0.1],
      ['triangle', 0.05],
      ['slab', 0.07],
    ]);
  let mesh = localMesh(b, kind);
  b.tag(mesh.closed ? 'closed-mesh' : 'open-mesh');
  const scale: Vec3 = o.scale ? [...o.scale] : [o.size, o.size, o.size];
  if (kind === 'slab') {
    scale[1] *= g.logUniform(1e-4, 1e-2);
    b.tag('thin-sheet');
  }
  if (kind === 'sheet' || kind === 'triangle') b.tag('thin-sheet');
  if (!o.scale && (o.anisotropic ?? g.chance(0.3))) {
    for (const k of [0, 1, 2]) scale[k] *= g.uniform(0.4, 1);
    b.tag('anisotropic');
  }
  const emissive = b.materials[o.material].emission !== undefined;
  const glass = b.materials[o.material].type === 'dielectric';
  if (glass && mesh.closed) b.tag('glass-mesh');
  let mirrored = false;
  if ((o.mirror ?? true) && !glass && g.chance(0.25)) {
    scale[g.int(0, 2)] *= -1;
    mirrored = true;
    b.tag('mirrored');
    // Mostly the winding is reversed too, so the front side stays outside; an
    // emitter left inside out emits inward, and NEE must find nothing from outside.
    if (g.chance(emissive ? 0.8 : 0.6)) mesh = reverseWinding(mesh);
    else b.tag('mirrored-inside-out');
  }
  const up = o.up ?? g.direction();
  // Rotate local +y onto `up`, then spin about it.
  const axis = cross([0, 1, 0], up);
  const axisLength = length(axis);
  const tilt = Math.atan2(axisLength, up[1]);
  let m: Matrix = trs(o.center, axisLength > 1e-12 ? normalize(axis) : [1, 0, 0], tilt, [1, 1, 1]);
  m = compose(m, trs([0, 0, 0], [0, 1, 0], g.uniform(0, 2 * Math.PI), scale));
  // A mesh light (or any emitter) keeps its geometric normals only: the Mitsuba
  // reference drops an emitter's shading normals, which matters unless it is black.
  const lamp = b.materials[o.material];
  const blackLamp = lamp.type === 'diffuse' && lamp.albedo.every((a) => a === 0);
  const withNormals = (!emissive || blackLamp) && g.chance(o.normals ?? 0.5);
  if (withNormals) b.tag('shading-normals');
  let positions = mesh.positions;
  if (g.chance(0.2)) {
    // Positions 1e3 or 1e-3 times their size, undone by the transform.
    const k = g.chance(0.5) ? 1e3 : 1e-3;
    positions = positions.map((x) => x * k);
    m = compose(m, trs([0, 0, 0], [1, 0, 0], 0, [1 / k, 1 / k, 1 / k]));
    b.tag('transform-scale-extreme');
  }
  const storage = g.weighted<MeshStorage>([
    ['inline', 0.7],
    ['obj', 0.1],
    ['ply-ascii', 0.05],
    ['ply-le', 0.1],
    ['ply-be', 0.05],
  ]);
  if (storage === 'obj') b.tag('mesh-file-obj');
  else if (storage !== 'inline') b.tag('mesh-file-ply');
  const world = transformPositions(m, positions);
  const area = meshArea({ positions: world, indices: mesh.indices });
  const inTransform = storage !== 'inline' || g.chance(0.6);
  b.mesh(
    {
      positions: inTransform ? positions : world,
      // Consecutive triples need no indices (the format's default): leave them out now and then.
      ...(storage === 'inline' && mesh.indices.every((x, k) => x === k) && g.chance(0.5)
        ? {}
        : { indices: mesh.indices }),
      ...(withNormals
        ? { normals: inTransform ? mesh.normals : transformNormals(m, mesh.normals) }
        : {}),
      ...(inTransform ? { transform: m } : {}),
    },
    o.material,
    area,
    storage,
  );
  if (determinant(m) < 0 !== mirrored) throw new Error('mirror bookkeeping');
  return { world, area };
}

/** Mesh objects of random kind and material, clear of the eye (a classic object now and then). */
export const MESH_OBJECT_MAKERS: ObjectMaker[] = [
  ...OBJECT_MAKERS.map((m) => ({ ...m, weight: m.weight * 0.25 })),
  {
    name: 'mesh',
    weight: 0.75,
    make: (b, r, avoid) => {
      const size = extent(r) * b.rng.logUniform(0.04, 0.2);
      const c = pointIn(b, r);
      // Every kind reaches at most √3 of its size from its centre: keep the eye out of it.
      if (length(sub(c, avoid)) < size * 3) return;
      placeMesh(b, { material: b.material(), center: c, size });
    },
  },
];

/**
 * Emissive meshes of very different size and power, as lights() places spheres and
 * quads: radiance set so diffuse surfaces near them read about `brightness`; every
 * one after the first 1e-3…1 of that. A closed mesh (icosphere, box, torus) or a
 * sheet or disc facing down or towards the region's middle; a quarter next to the
 * floor (an icosphere at d/r 1.01…1.5, a sheet 1e-3…0.1 of its size above).
 */
export function meshLights(
  b: SceneBuilder,
  r: Region,
  floorY: number,
  count: number,
  avoid: Vec3,
): void {
  const g = b.rng;
  const size0 = extent(r);
  for (let i = 0; i < count; i++) {
    const brightness = g.logUniform(0.2, 2) * (i === 0 ? 1 : g.logUniform(1e-3, 1));
    const cls = g.weighted([
      ['tiny', 0.15],
      ['small', 0.35],
      ['medium', 0.3],
      ['large', 0.2],
    ] as const);
    const rel = {
      tiny: [1e-3, 1e-2],
      small: [1e-2, 0.05],
      medium: [0.05, 0.15],
      large: [0.15, 0.4],
    }[cls];
    const size = size0 * g.logUniform(rel[0], rel[1]);
    const tags: Feature[] = [];
    if (cls === 'tiny') tags.push('emissive-mesh-tiny', 'tiny-light');
    if (cls === 'large') tags.push('emissive-mesh-large', 'large-light');
    const near = g.chance(0.25);
    const p = pointIn(b, r);
    const distance = Math.max(size * 2, p[1] - floorY, size0 * 0.3);
    const closed = g.chance(0.5);
    if (closed) {
      // An icosphere is inscribed in its sphere: d/r measured to the sphere.
      const kind = near ? 'icosphere' : g.pick(CLOSED);
      const radius = size / 2;
      if (near) {
        p[1] = floorY + radius * (1 + g.logUniform(0.01, 0.5));
        tags.push('emissive-mesh-near-receiver', 'light-near-receiver');
      }
      if (length(sub(p, avoid)) < radius * 3) continue;
      const d = near ? p[1] - floorY : distance;
      const radiance = Math.min(1e9, (brightness * (d / radius) ** 2) / 0.5);
      const material = b.emitter(radiance);
      placeMesh(b, { kind, material, center: p, size: radius, mirror: !near });
      b.tag(...tags);
    } else {
      const n: Vec3 = g.chance(0.6)
        ? normalize([g.uniform(-0.3, 0.3), -1, g.uniform(-0.3, 0.3)])
        : normalize(sub(center(r), p));
      if (near && n[1] < -0.9) {
        // The sheet's lowest corner (≤ √2 · size from its centre) 1e-3…0.1 of its size above the floor.
        p[1] = floorY + size * (Math.SQRT2 * Math.sqrt(1 - n[1] * n[1]) + g.logUniform(1e-3, 0.1));
        tags.push('emissive-mesh-near-receiver', 'light-near-receiver');
      }
      if (length(sub(p, avoid)) < size * 3) continue;
      const area = 4 * size * size;
      const d = near ? size : distance;
      const radiance = Math.min(1e9, (brightness * Math.PI * d * d) / (0.5 * area));
      const material = b.emitter(radiance);
      placeMesh(b, {
        kind: g.pick(['sheet', 'disc', 'triangle'] as const),
        material,
        center: p,
        size,
        up: n,
        anisotropic: false,
        mirror: false,
      });
      b.tag(...tags);
    }
  }
}

/** Tags several lights and a power ratio ≥ 1000 over every emitter placed (powers ≈ L · area). */
/** Places mesh objects until the scene has a mesh (a try fails when it lands next to the eye). */
function atLeastOneMesh(b: SceneBuilder, r: Region, avoid: Vec3): void {
  const mesh = MESH_OBJECT_MAKERS.filter((m) => m.name === 'mesh');
  for (let tries = 0; tries < 16 && !b.shapes.some((s) => s.type === 'mesh'); tries++) {
    objects(b, r, 1, avoid, mesh);
  }
}

function tagPowers(b: SceneBuilder): void {
  const powers = b.lights.map(
    (l) => l.emission * l.size * l.size * (l.kind === 'sphere' ? 4 * Math.PI : 1),
  );
  if (powers.length > 1) {
    b.tag('multiple-lights');
    if (Math.max(...powers) >= 1000 * Math.min(...powers)) b.tag('power-ratio-1000');
  }
}

/** A room of quads, or one inward-facing box mesh (a face sometimes missing). */
function buildMeshRoom(b: SceneBuilder): Staged {
  const g = b.rng;
  const W = g.uniform(2, 6);
  const H = g.uniform(2, 4);
  const D = g.uniform(2, 6);
  const wall = b.material(g.chance(0.85) ? 'diffuse' : 'conductor');
  let open = false;
  if (g.chance(0.5)) {
    const room = reverseWinding(box());
    // Drop one face's two triangles now and then (the box's faces are 2 triangles each, in order).
    const face = g.chance(0.4) ? g.int(0, 5) : -1;
    open = face >= 0;
    const indices = room.indices.filter((_, k) => Math.floor(k / 6) !== face);
    const m = trs([W / 2, H / 2, D / 2], [0, 1, 0], 0, [W / 2, H / 2, D / 2]);
    b.mesh(
      { positions: transformPositions(m, room.positions), indices },
      wall,
      2 * (W * H + H * D + W * D),
    );
    b.tag('closed-mesh');
  } else {
    const skip = g.chance(0.4) ? [g.pick(['front', 'ceiling', 'left'])] : [];
    open = skip.length > 0;
    b.box([0, 0, 0], [W, H, D], wall, false, skip);
  }
  environment(b, open ? 0.3 : 0.7, MAP_ENVIRONMENT_MAKERS);
  const eye: Vec3 = [g.uniform(0.2, 0.8) * W, g.uniform(0.2, 0.8) * H, g.uniform(0.05, 0.12) * D];
  const region: Region = { lo: [0.1 * W, 0, 0.2 * D], hi: [0.9 * W, 0.85 * H, 0.9 * D] };
  meshLights(b, region, 0, g.int(1, 2), eye);
  if (g.chance(0.5)) lights(b, region, 0, g.int(1, 2), eye);
  // Every light may have landed too near the eye: then a mesh light until one stays.
  for (let tries = 0; b.lights.length === 0 && tries < 8; tries++) meshLights(b, region, 0, 1, eye);
  tagPowers(b);
  objects(
    b,
    { lo: [0.15 * W, 0, 0.25 * D], hi: [0.85 * W, 0.5 * H, 0.85 * D] },
    g.int(1, 4),
    eye,
    MESH_OBJECT_MAKERS,
  );
  atLeastOneMesh(b, { lo: [0.15 * W, 0, 0.25 * D], hi: [0.85 * W, 0.5 * H, 0.85 * D] }, eye);
  return { camera: roomCamera(b, eye, W, H, D), maxBounces: bounces(b, 0, 12) };
}

/** A ground (quad, sphere, mesh sheet or height field), mesh objects, maps, few lights. */
function buildMeshGround(b: SceneBuilder, onlyMaps: boolean): Staged {
  const g = b.rng;
  const floor = b.material(g.chance(0.85) ? 'diffuse' : 'conductor');
  const ground = g.weighted([
    ['none', onlyMaps ? 0.3 : 0],
    ['quad', 0.25],
    ['sphere', 0.25],
    ['sheet', 0.3],
    ['height-field', 0.2],
  ] as const);
  if (ground === 'quad') {
    const S = g.logUniform(20, 2000);
    b.quad([-S / 2, 0, -S / 2], [0, 0, S], [S, 0, 0], floor);
    if (S >= 500) b.tag('huge-receiver');
  } else if (ground === 'sphere') {
    const R = g.chance(0.3) ? 1e5 : g.logUniform(10, 1e5);
    b.sphere([0, -R, 0], R, floor);
    b.tag('ground-sphere');
    if (R >= 1e3) b.tag('huge-receiver');
    if (R === 1e5) b.tag('ground-sphere-1e5');
  } else if (ground !== 'none') {
    // A ground mesh 20…2000 across; a height field's bumps (≤ 0.9 of its y scale) stay below y = 0.
    const S = g.logUniform(20, 2000);
    placeMesh(b, groundMesh(ground, floor, S));
    if (S >= 500) b.tag('huge-receiver');
  }
  environment(b, onlyMaps ? 0 : 0.15, onlyMaps ? MAPS_ONLY : MAP_ENVIRONMENT_MAKERS);
  const region: Region = { lo: [-2, 0, -2], hi: [2, 2, 2] };
  const elevation = g.uniform(3, 60) * (Math.PI / 180);
  const azimuth = g.uniform(0, 2 * Math.PI);
  const dist = g.uniform(5, 12);
  const eye: Vec3 = [
    dist * Math.cos(elevation) * Math.sin(azimuth),
    dist * Math.sin(elevation) + 0.2,
    dist * Math.cos(elevation) * Math.cos(azimuth),
  ];
  const hasMap = b.environment !== null && !Array.isArray(b.environment);
  if (onlyMaps) {
    b.tag('env-map-only');
  } else {
    const count = g.int(hasMap ? 0 : 1, 2);
    meshLights(b, { lo: [-3, 0, -3], hi: [3, 4, 3] }, 0, count, eye);
    if (g.chance(0.3)) lights(b, { lo: [-3, 0, -3], hi: [3, 4, 3] }, 0, 1, eye);
    tagPowers(b);
    if (count === 0 && b.lights.length === 0) b.tag('env-map-only');
  }
  const makers = onlyMaps
    ? MESH_OBJECT_MAKERS.map((m) => (m.name === 'mesh' ? { ...m, weight: 2 } : m))
    : MESH_OBJECT_MAKERS;
  objects(b, region, g.int(1, 4), eye, makers);
  atLeastOneMesh(b, region, eye);
  b.tag('camera-outside');
  return {
    camera: lens(b, {
      position: eye,
      target: add(center(region), [g.uniform(-1, 1), g.uniform(-0.8, 0), g.uniform(-1, 1)]),
      up: [0, 1, 0],
      fovY: g.uniform(20, 70),
    }),
    maxBounces: bounces(b, onlyMaps ? 1 : 0, 12),
  };
}

const meshRoom: Archetype = { name: 'mesh-room', weight: 0.25, build: buildMeshRoom };
const meshGround: Archetype = {
  name: 'mesh-ground',
  weight: 0.22,
  build: (b) => buildMeshGround(b, false),
};
const mapObjects: Archetype = {
  name: 'map-objects',
  weight: 0.18,
  build: (b) => buildMeshGround(b, true),
};

/** An emissive mesh over a receiver's normal, or a mesh sheet light grazing a floor and a wall. */
const meshLight: Archetype = {
  name: 'mesh-light',
  weight: 0.2,
  build: (b) => {
    const g = b.rng;
    if (g.chance(0.35)) return grazingMeshLight(b);
    const r = g.logUniform(0.01, 1);
    const dOverR = 1 + g.logUniform(0.01, 99);
    const d = dOverR * r;
    const receiver = g.weighted([
      ['quad', 0.25],
      ['sheet', 0.25],
      ['height-field', 0.15],
      ['huge-sphere', 0.35],
    ] as const);
    const albedo = b.material('diffuse');
    if (receiver === 'quad') {
      const S = d * g.logUniform(4, 400);
      b.quad([-S / 2, 0, -S / 2], [0, 0, S], [S, 0, 0], albedo);
      if (S >= 1e3 * r) b.tag('huge-receiver');
    } else if (receiver === 'huge-sphere') {
      const R = g.pick([1e3, 1e4, 1e5, g.logUniform(1e3, 1e5)]);
      b.sphere([0, -R, 0], R, albedo);
      b.tag('ground-sphere', 'huge-receiver');
      if (R === 1e5) b.tag('ground-sphere-1e5');
    } else {
      const S = d * g.logUniform(4, 400);
      placeMesh(b, groundMesh(receiver, albedo, S));
      if (S >= 1e3 * r) b.tag('huge-receiver');
    }
    if (dOverR < 1.5) b.tag('light-near-receiver', 'emissive-mesh-near-receiver');
    if (r < 0.03) b.tag('tiny-light', 'emissive-mesh-tiny');
    const radiance = g.logUniform(1, 100) * Math.min(1e4, dOverR * dOverR);
    placeMesh(b, {
      kind: 'icosphere',
      material: b.emitter(radiance),
      center: [0, d, 0],
      size: r,
      mirror: false,
      anisotropic: false,
    });
    if (g.chance(0.3)) {
      const s = g.logUniform(0.1, 1) * r;
      placeMesh(b, {
        material: b.material(),
        center: [g.uniform(2, 4) * d, s, g.uniform(-2, 2) * d],
        size: s,
      });
    }
    environment(b, 0.7, MAP_ENVIRONMENT_MAKERS);
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

/** The grazing archetype with the light a mesh: a strip of triangles tilted 1e-4…0.1 rad. */
function grazingMeshLight(b: SceneBuilder): Staged {
  const g = b.rng;
  const S = 8;
  const floorKind: MaterialKind = g.chance(0.8) ? 'diffuse' : 'conductor';
  if (g.chance(0.5)) {
    b.quad([-S / 2, 0, -S / 2], [0, 0, S], [S, 0, 0], b.material(floorKind));
  } else {
    placeMesh(b, {
      kind: 'sheet',
      material: b.material(floorKind),
      center: [0, 0, 0],
      size: S / 2,
      up: [0, 1, 0],
      anisotropic: false,
      normals: 0.3,
    });
  }
  const zw = 2;
  b.quad([-S / 2, 0, zw], [S, 0, 0], [0, S / 2, 0], b.material('diffuse'));
  const w = g.uniform(1, 3);
  const depth = g.uniform(0.3, 1.5);
  const h = g.uniform(0.05, 0.6);
  const tilt = g.logUniform(1e-4, 0.1);
  const z0 = zw - depth - g.uniform(0.05, 1);
  // A strip of n quads across its width, two triangles each, facing down and tilted
  // towards the wall as in the classic grazing archetype: normal (0, −cos, sin).
  const n = g.int(1, 4);
  const positions: number[] = [];
  const indices: number[] = [];
  const v: Vec3 = [0, depth * Math.sin(tilt), depth * Math.cos(tilt)];
  for (let k = 0; k <= n; k++) {
    const x = -w / 2 + (w * k) / n;
    positions.push(x, h, z0, ...add([x, h, z0], v));
  }
  for (let k = 0; k < n; k++) {
    const a = 2 * k;
    // cross(+x, v) points along (0, −cos, sin): corners (a, a+2, a+3) and (a, a+3, a+1).
    indices.push(a, a + 2, a + 3, a, a + 3, a + 1);
  }
  const lamp = b.emitter(g.logUniform(2, 50));
  b.mesh({ positions, indices }, lamp, w * depth);
  b.tag('emissive-mesh-grazing', 'grazing', 'open-mesh');
  if (g.chance(0.3)) {
    placeMesh(b, { material: b.material(), center: [g.uniform(-1, 1), 0.3, zw - 0.6], size: 0.3 });
  }
  environment(b, 0.75, MAP_ENVIRONMENT_MAKERS);
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
}

/** Room or ground of the family, then a closed glass mesh around the camera. */
const meshGlass: Archetype = {
  name: 'mesh-glass',
  weight: 0.15,
  build: (b) => {
    const g = b.rng;
    const staged = g.chance(0.5) ? buildMeshRoom(b) : buildMeshGround(b, g.chance(0.3));
    const eye = staged.camera.position;
    let clearance = Infinity;
    for (const s of b.shapes) {
      if (s.type === 'sphere')
        clearance = Math.min(clearance, length(sub(s.center, eye)) - s.radius);
      else if (s.type === 'quad') {
        const n = normalize(cross(s.u, s.v));
        clearance = Math.min(
          clearance,
          Math.abs(sub(eye, s.corner).reduce((a, x, i) => a + x * n[i], 0)),
        );
      }
    }
    clearance = Math.min(clearance, meshClearance(b, eye));
    // A box reaches √3 of its size from its centre, which is 0.2 of it off the eye.
    const size = clearance * g.uniform(0.2, 0.45);
    const kind = g.pick(['icosphere', 'box'] as const);
    placeMesh(b, {
      kind,
      material: b.material('dielectric'),
      center: add(eye, mul(g.direction(), size * 0.2)),
      size,
      normals: 0.3,
      anisotropic: false,
    });
    b.tag('camera-in-glass', 'camera-in-glass-mesh', 'glass-mesh');
    // Leaving the glass is a bounce: at least two, or the image is black.
    if (staged.maxBounces < 2) {
      b.features.delete('bounces-0');
      return { ...staged, maxBounces: bounces(b, 2, 12) };
    }
    return staged;
  },
};

/** Distance from p to the nearest triangle of the meshes placed so far. */
function meshClearance(b: SceneBuilder, p: Vec3): number {
  let best = Infinity;
  for (const s of b.shapes) {
    if (s.type !== 'mesh') continue;
    const w = s.transform ? transformPositions(s.transform, s.positions!) : s.positions!;
    const ix = s.indices ?? w.map((_, i) => i).filter((i) => i < w.length / 3);
    const at = (i: number): Vec3 => [w[3 * i], w[3 * i + 1], w[3 * i + 2]];
    for (let t = 0; t < ix.length; t += 3) {
      best = Math.min(best, pointTriangleDistance(p, at(ix[t]), at(ix[t + 1]), at(ix[t + 2])));
    }
  }
  return best;
}

/** Distance from p to triangle abc (closest point by Voronoi regions; Ericson 2005, §5.1.5). */
export function pointTriangleDistance(p: Vec3, a: Vec3, b: Vec3, c: Vec3): number {
  const ab = sub(b, a);
  const ac = sub(c, a);
  const ap = sub(p, a);
  const d1 = dot(ab, ap);
  const d2 = dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) return length(ap);
  const bp = sub(p, b);
  const d3 = dot(ab, bp);
  const d4 = dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return length(bp);
  const vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return length(sub(p, add(a, mul(ab, d1 / (d1 - d3)))));
  const cp = sub(p, c);
  const d5 = dot(ab, cp);
  const d6 = dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return length(cp);
  const vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return length(sub(p, add(a, mul(ac, d2 / (d2 - d6)))));
  const va = d3 * d6 - d5 * d4;
  if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0) {
    const w = (d4 - d3) / (d4 - d3 + (d5 - d6));
    return length(sub(p, add(b, mul(sub(c, b), w))));
  }
  const denom = 1 / (va + vb + vc);
  const q = add(a, add(mul(ab, vb * denom), mul(ac, vc * denom)));
  return length(sub(p, q));
}

/**
 * A ground or receiver mesh S across, facing up, its top at y = 0: a sheet, or a
 * height field squashed to 0.1 of its width (bumps ≤ 0.09 of its size, all below 0).
 */
function groundMesh(kind: 'sheet' | 'height-field', material: string, S: number): MeshOptions {
  const h = S / 2;
  return kind === 'sheet'
    ? { kind, material, center: [0, 0, 0], size: h, up: [0, 1, 0], anisotropic: false }
    : { kind, material, center: [0, -0.1 * h, 0], size: h, up: [0, 1, 0], scale: [h, 0.1 * h, h] };
}

export const MESH_ARCHETYPES: Archetype[] = [
  meshRoom,
  meshGround,
  meshLight,
  mapObjects,
  meshGlass,
];
