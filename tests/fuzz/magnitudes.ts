/**
 * Scenes at every magnitude of the double range (issue "scenes at the edges of the
 * double range"): a seeded generator of valid-looking scenes whose shapes have a size of
 * 2^e and sit at ±2^f from the origin, e and f anywhere in [-1074, 1023], for every shape
 * kind: spheres, quads, inline triangles, OBJ and PLY files and glTF models, with
 * transforms. Each case is a scene JSON and the files it names.
 *
 * Written from the format's rules, not from the loaders: a case may be invalid (a sum
 * that overflows, a triangle too small for its position), and then the loader must say
 * so in one line.
 */
import fc from 'fast-check';
import { Document } from '@gltf-transform/core';
import { docWith, meshPrimitive, toGlb } from '../helpers/gltf.ts';

export const KINDS = ['sphere', 'quad', 'triangles', 'obj', 'ply', 'gltf'] as const;
export type Kind = (typeof KINDS)[number];

export interface MagnitudeCase {
  kind: Kind;
  /** Shapes of that kind. */
  count: number;
  /** Size of a shape: 2^sizeExp. */
  sizeExp: number;
  /** Where the shapes are: ±2^offsetExp on each axis, one sign per axis. */
  offsetExp: number;
  signs: [number, number, number];
  /** Mesh and glTF shapes: a scene transform that scales by 2^scaleExp (0: none). */
  scaleExp: number;
  /** Extra spread between shapes: shape k sits k·2^spreadExp further along x. */
  spreadExp: number;
  /** Whether the shapes emit (then they are lights, sampled by area). */
  emissive: boolean;
}

const exponent = fc.integer({ min: -1074, max: 1023 });
// Ordinary exponents too, so a case often mixes a huge and a plain magnitude.
const anyExponent = fc.oneof(exponent, fc.integer({ min: -8, max: 8 }));

export const magnitudeCase: fc.Arbitrary<MagnitudeCase> = fc.record({
  kind: fc.constantFrom(...KINDS),
  count: fc.integer({ min: 1, max: 4 }),
  sizeExp: anyExponent,
  offsetExp: anyExponent,
  signs: fc.tuple(
    fc.constantFrom(-1, 1),
    fc.constantFrom(-1, 1),
    fc.constantFrom(-1, 1),
  ) as fc.Arbitrary<[number, number, number]>,
  scaleExp: fc.oneof(fc.constant(0), fc.integer({ min: -200, max: 200 }), exponent),
  spreadExp: anyExponent,
  emissive: fc.boolean(),
});

/** 2^e as a double (Math.pow is exact for powers of two, subnormals included). */
export function pow2(e: number): number {
  return 2 ** e;
}

/** A tetrahedron of unit size, as a closed triangle mesh. */
const TETRA = {
  positions: [0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1],
  indices: [0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3],
};

function objText(p: number[]): string {
  const lines = [];
  for (let i = 0; i < p.length; i += 3) lines.push(`v ${p[i]} ${p[i + 1]} ${p[i + 2]}`);
  for (let t = 0; t < TETRA.indices.length; t += 3) {
    const [a, b, c] = TETRA.indices.slice(t, t + 3).map((i) => i + 1);
    lines.push(`f ${a} ${b} ${c}`);
  }
  return lines.join('\n') + '\n';
}

function plyBytes(p: number[]): Uint8Array {
  const header =
    'ply\nformat binary_little_endian 1.0\n' +
    `element vertex ${p.length / 3}\nproperty double x\nproperty double y\nproperty double z\n` +
    `element face ${TETRA.indices.length / 3}\nproperty list uchar int vertex_indices\nend_header\n`;
  const head = new TextEncoder().encode(header);
  const body = new DataView(new ArrayBuffer(p.length * 8 + (TETRA.indices.length / 3) * 13));
  let o = 0;
  for (const v of p) {
    body.setFloat64(o, v, true);
    o += 8;
  }
  for (let t = 0; t < TETRA.indices.length; t += 3) {
    body.setUint8(o++, 3);
    for (let k = 0; k < 3; k++) {
      body.setInt32(o, TETRA.indices[t + k], true);
      o += 4;
    }
  }
  const out = new Uint8Array(head.length + body.byteLength);
  out.set(head);
  out.set(new Uint8Array(body.buffer), head.length);
  return out;
}

/** A row-major 4×4 that scales by s and translates by t. */
function scaleTranslate(s: number, t: number[]): number[] {
  return [s, 0, 0, t[0], 0, s, 0, t[1], 0, 0, s, t[2], 0, 0, 0, 1];
}

export interface GeneratedScene {
  json: Record<string, unknown>;
  files: Map<string, Uint8Array>;
}

/** The scene of a case: its shapes, a camera looking at the first, and their files. */
export async function magnitudeScene(c: MagnitudeCase): Promise<GeneratedScene> {
  const size = pow2(c.sizeExp);
  const offset = c.signs.map((s) => s * pow2(c.offsetExp));
  const spread = pow2(c.spreadExp);
  const files = new Map<string, Uint8Array>();
  const material = c.emissive ? 'm' : 'd';
  const shapes: Record<string, unknown>[] = [];
  for (let k = 0; k < c.count; k++) {
    const at = [offset[0] + k * spread, offset[1], offset[2]];
    const scaled = c.scaleExp !== 0 && c.kind !== 'sphere' && c.kind !== 'quad';
    // A scene transform scales the file's own coordinates: the points before it are
    // smaller by its scale, so the shape ends up the same size at the same place.
    const s = scaled ? pow2(c.scaleExp) : 1;
    const local = (x: number) => x / s;
    switch (c.kind) {
      case 'sphere':
        shapes.push({ type: 'sphere', center: at, radius: size / 2, material });
        break;
      case 'quad':
        shapes.push({
          type: 'quad',
          corner: at,
          u: [size, 0, 0],
          v: [0, size, 0],
          material,
        });
        break;
      default: {
        // The vertices around the origin, placed by the transform's translation.
        const positions = TETRA.positions.map((x) => local(x * size));
        const transform = scaleTranslate(s, at);
        if (c.kind === 'triangles') {
          shapes.push({ type: 'mesh', positions, indices: TETRA.indices, transform, material });
        } else if (c.kind === 'obj') {
          files.set(`m${k}.obj`, new TextEncoder().encode(objText(positions)));
          shapes.push({ type: 'mesh', file: `m${k}.obj`, transform, material });
        } else if (c.kind === 'ply') {
          files.set(`m${k}.ply`, plyBytes(positions));
          shapes.push({ type: 'mesh', file: `m${k}.ply`, transform, material });
        } else {
          // glTF stores positions in float32: the unit tetrahedron, with the size in the
          // node's scale (a double in the JSON) and the scene's transform on top.
          const doc = new Document();
          doc.createBuffer();
          const prim = meshPrimitive(doc, TETRA.positions, TETRA.indices);
          docWith(doc, prim);
          const node = doc.getRoot().listNodes()[0];
          node.setScale([local(size), local(size), local(size)]);
          files.set(`m${k}.glb`, await toGlb(doc));
          shapes.push({ type: 'gltf', file: `m${k}.glb`, transform });
        }
      }
    }
  }
  // The camera looks at the first shape from 3 sizes away, along −z.
  const target = [offset[0] + size / 2, offset[1] + size / 2, offset[2] + size / 2];
  const position = [target[0], target[1], target[2] - 3 * size];
  const json = {
    format: 'pathwise-scene/1',
    camera: { position, target, up: [0, 1, 0], fovY: 50 },
    settings: { width: 16, height: 16, maxBounces: 3, spp: 1 },
    environment: [0.5, 0.5, 0.5],
    materials: {
      m: { type: 'diffuse', albedo: [0.7, 0.7, 0.7], emission: [0.2, 0.2, 0.2] },
      d: { type: 'diffuse', albedo: [0.7, 0.7, 0.7] },
    },
    shapes,
  };
  return { json, files };
}
