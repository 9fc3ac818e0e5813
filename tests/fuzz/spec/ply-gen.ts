/**
 * PLY files written from Greg Turk's PLY description (the "PLY polygon file format", 1994,
 * as kept by Paul Bourke): a header of `element` / `property` lines up to `end_header`,
 * then the elements in order, as ASCII lines or packed binary of either byte order.
 */
import { ByteWriter, ascii, concat } from './bytes.ts';
import { octahedron } from './mesh-data.ts';
import type { Rng } from './rng.ts';
import { meshScene } from './scene-wrap.ts';
import type { Generator, Mutation, Sample } from './types.ts';

type Encoding = 'ascii' | 'binary_little_endian' | 'binary_big_endian';
type Scalar = 'char' | 'uchar' | 'short' | 'ushort' | 'int' | 'uint' | 'float' | 'double';
const ALIASES: Record<string, Scalar> = {
  int8: 'char',
  uint8: 'uchar',
  int16: 'short',
  uint16: 'ushort',
  int32: 'int',
  uint32: 'uint',
  float32: 'float',
  float64: 'double',
};

interface Property {
  name: string;
  type: string;
  /** For a list: the type of its count. */
  countType?: string;
}
interface Element {
  name: string;
  count: number;
  props: Property[];
  rows: number[][][]; // row → property → values (one for a scalar)
}
interface Ply {
  encoding: Encoding;
  comments: string[];
  elements: Element[];
  /** Written in the header instead of the element's true count, if set. */
  countLie?: Map<string, number>;
  endHeader?: string;
}

function scalarOf(t: string): Scalar {
  return (ALIASES[t] ?? t) as Scalar;
}

function writeValue(w: ByteWriter, type: string, v: number, le: boolean): void {
  switch (scalarOf(type)) {
    case 'char':
      return void w.i8(v);
    case 'uchar':
      return void w.u8(v);
    case 'short':
      return void w.i16(v, le);
    case 'ushort':
      return void w.u16(v, le);
    case 'int':
      return void w.i32(v, le);
    case 'uint':
      return void w.u32(v, le);
    case 'float':
      return void w.f32(v, le);
    default:
      return void w.f64(v, le);
  }
}

export function serializePly(p: Ply): Uint8Array {
  const head = ['ply', `format ${p.encoding} 1.0`, ...p.comments.map((c) => `comment ${c}`)];
  for (const e of p.elements) {
    head.push(`element ${e.name} ${p.countLie?.get(e.name) ?? e.count}`);
    for (const pr of e.props) {
      head.push(
        pr.countType
          ? `property list ${pr.countType} ${pr.type} ${pr.name}`
          : `property ${pr.type} ${pr.name}`,
      );
    }
  }
  head.push(p.endHeader ?? 'end_header');
  const header = ascii(head.join('\n') + '\n');
  if (p.encoding === 'ascii') {
    const lines: string[] = [];
    for (const e of p.elements) {
      for (const row of e.rows) {
        lines.push(
          row
            .map((vals, i) => (e.props[i].countType ? [vals.length, ...vals] : vals).join(' '))
            .join(' '),
        );
      }
    }
    return concat([header, ascii(lines.join('\n') + '\n')]);
  }
  const le = p.encoding === 'binary_little_endian';
  const w = new ByteWriter();
  for (const e of p.elements) {
    for (const row of e.rows) {
      row.forEach((vals, i) => {
        const pr = e.props[i];
        if (pr.countType) writeValue(w, pr.countType, vals.length, le);
        for (const v of vals) writeValue(w, pr.type, v, le);
      });
    }
  }
  return concat([header, w.done()]);
}

function buildPly(rng: Rng): Ply {
  const mesh = octahedron(rng);
  const encoding = rng.pick<Encoding>(['ascii', 'binary_little_endian', 'binary_big_endian']);
  const ft = rng.pick(['float', 'double', 'float32']);
  const withNormals = rng.chance(0.5);
  const withColour = rng.chance(0.3);
  const vprops: Property[] = ['x', 'y', 'z'].map((name) => ({ name, type: ft }));
  if (withNormals) vprops.push(...['nx', 'ny', 'nz'].map((name) => ({ name, type: ft })));
  // Other properties are allowed by the format; a reader that uses x y z skips them.
  if (withColour) vprops.push(...['red', 'green', 'blue'].map((name) => ({ name, type: 'uchar' })));
  const vrows = mesh.positions.map((p, i) => {
    const row = p.map((c) => [ft === 'double' ? c : Math.fround(c)]);
    if (withNormals)
      row.push(...mesh.normals[i].map((c) => [ft === 'double' ? c : Math.fround(c)]));
    if (withColour) row.push([200], [100], [50]);
    return row;
  });
  const it = rng.pick(['int', 'uint', 'int32', 'ushort']);
  const ct = rng.pick(['uchar', 'uint8', 'int']);
  const elements: Element[] = [
    { name: 'vertex', count: vrows.length, props: vprops, rows: vrows },
    {
      name: 'face',
      count: mesh.faces.length,
      props: [{ name: rng.pick(['vertex_indices', 'vertex_indices']), type: it, countType: ct }],
      rows: mesh.faces.map((f) => [f]),
    },
  ];
  return { encoding, comments: rng.chance(0.5) ? ['made by spec-fuzz'] : [], elements };
}

function mutations(p: Ply): Mutation[] {
  const file = (q: Ply) => ({ 'mesh.ply': serializePly(q) });
  const edit = (name: string, f: (q: Ply, rng: Rng) => void, invalid = false): Mutation => ({
    name,
    invalid,
    apply: (rng) => {
      const q = structuredClone(p);
      f(q, rng);
      return file(q);
    },
  });
  const vertex = (q: Ply) => q.elements[0];
  const face = (q: Ply) => q.elements[1];
  return [
    edit('ply:vertex-count-huge', (q, r) => {
      q.countLie = new Map([['vertex', r.pick([2 ** 31 - 1, 2 ** 32 - 1, 1e9, 1e15])]]);
    }),
    edit('ply:vertex-count-short', (q) => {
      q.countLie = new Map([['vertex', 3]]);
    }),
    edit('ply:vertex-count-long', (q) => {
      q.countLie = new Map([['vertex', vertex(q).count + 1]]);
    }),
    edit('ply:face-count-huge', (q, r) => {
      q.countLie = new Map([['face', r.pick([2 ** 31 - 1, 1e12, 4294967295])]]);
    }),
    edit('ply:count-negative', (q) => {
      q.countLie = new Map([['vertex', -6]]);
    }),
    edit(
      'ply:index-out-of-range',
      (q, r) => {
        face(q).rows[r.int(face(q).rows.length)][0][r.int(3)] = r.pick([6, 1000, 2 ** 31 - 1]);
      },
      true,
    ),
    edit(
      'ply:index-negative',
      (q) => {
        face(q).props[0].type = 'int';
        face(q).rows[0][0][1] = -1;
      },
      true,
    ),
    edit('ply:list-count-zero', (q) => {
      face(q).rows[2][0] = [];
    }),
    edit('ply:list-count-255', (q) => {
      face(q).props[0].countType = 'uchar';
      face(q).rows[0][0] = Array.from({ length: 255 }, (_, i) => i % 6);
    }),
    edit('ply:nan-coordinate', (q, r) => {
      for (const pr of vertex(q).props.slice(0, 3)) pr.type = 'float';
      vertex(q).rows[r.int(6)][r.int(3)] = [r.pick([NaN, Infinity, -Infinity])];
    }),
    edit('ply:huge-coordinate', (q, r) => {
      for (const pr of vertex(q).props.slice(0, 3)) pr.type = 'double';
      vertex(q).rows[r.int(6)][r.int(3)] = [r.pick([1e308, -1.7e308, 3e38])];
    }),
    edit('ply:zero-normal', (q) => {
      if (vertex(q).props.length < 6) return;
      vertex(q).rows[0][3] = [0];
      vertex(q).rows[0][4] = [0];
      vertex(q).rows[0][5] = [0];
    }),
    edit('ply:unknown-type', (q) => {
      vertex(q).props[0].type = 'float128';
    }),
    edit('ply:no-z', (q) => {
      vertex(q).props.splice(2, 1);
      for (const row of vertex(q).rows) row.splice(2, 1);
    }),
    edit('ply:bad-format-line', (q) => {
      (q as { encoding: string }).encoding = 'binary_middle_endian';
    }),
    edit('ply:no-end-header', (q) => {
      q.endHeader = 'end_headr';
    }),
    edit('ply:no-face-element', (q) => {
      q.elements.pop();
    }),
    edit('ply:elements-swapped', (q) => {
      q.elements.reverse();
    }),
    edit('ply:float-index', (q) => {
      face(q).props[0].type = 'float';
    }),
    edit('ply:huge-comment', (q) => {
      q.comments.push('x'.repeat(200_000));
    }),
    {
      // An ASCII face line with one index more than its count (issue 27, item 7).
      name: 'ply:ascii-extra-token',
      invalid: true,
      // The error must name the face whose line is too long, not a later one the shift broke.
      expect: /face 0\b/,
      apply: () => {
        const q = structuredClone(p);
        q.encoding = 'ascii';
        const text = new TextDecoder().decode(serializePly(q));
        const lines = text.split('\n');
        const firstFace = lines.indexOf('end_header') + 1 + vertex(q).count;
        lines[firstFace] += ' 5';
        return { 'mesh.ply': ascii(lines.join('\n')) };
      },
    },
    {
      name: 'ply:truncated-body',
      apply: (rng) => {
        const b = serializePly(p);
        const head = new TextDecoder('latin1').decode(b).indexOf('end_header') + 11;
        return { 'mesh.ply': b.slice(0, rng.range(head, b.length - 1)) };
      },
    },
    {
      name: 'ply:trailing-garbage',
      apply: (rng) => ({
        'mesh.ply': concat([serializePly(p), new Uint8Array(rng.range(1, 64)).fill(0x41)]),
      }),
    },
  ];
}

export const plyGenerator: Generator = {
  format: 'ply',
  generate(rng: Rng): Sample {
    const p = buildPly(rng);
    return {
      variant: p.encoding,
      files: { 'mesh.ply': serializePly(p), 'scene.json': meshScene('mesh.ply') },
      target: 'mesh.ply',
      args: ['render', 'scene.json'],
      lit: true,
      mutations: mutations(p),
    };
  },
};
