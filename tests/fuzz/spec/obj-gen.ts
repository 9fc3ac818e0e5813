/**
 * Wavefront OBJ written from the "Object Files (.obj)" appendix B1 of the Advanced
 * Visualizer manual: `v x y z [w]`, `vt`, `vn`, and `f` with `v`, `v/vt`, `v//vn` or
 * `v/vt/vn` references, 1-based or negative (relative to the end so far); other statements
 * (`o`, `g`, `s`, `usemtl`, `mtllib`) are legal and, for a renderer of geometry, ignorable.
 */
import { ascii } from './bytes.ts';
import { octahedron, type MeshData } from './mesh-data.ts';
import type { Rng } from './rng.ts';
import { meshScene } from './scene-wrap.ts';
import type { Generator, Mutation, Sample } from './types.ts';

type RefStyle = 'v' | 'v/vt' | 'v//vn' | 'v/vt/vn';

interface Obj {
  mesh: MeshData;
  style: RefStyle;
  negative: boolean;
  quads: boolean;
  extras: boolean;
}

function lines(o: Obj): string[] {
  const out: string[] = ['# spec-fuzz'];
  if (o.extras) out.push('mtllib none.mtl', 'o thing', 'g group', 's 1');
  for (const p of o.mesh.positions) out.push(`v ${p.join(' ')}`);
  if (o.style.includes('vt')) for (const p of o.mesh.positions) out.push(`vt ${p[0]} ${p[1]}`);
  if (o.style.endsWith('vn')) for (const n of o.mesh.normals) out.push(`vn ${n.join(' ')}`);
  if (o.extras) out.push('usemtl stone');
  const nv = o.mesh.positions.length;
  let faces = o.mesh.faces;
  if (o.quads) {
    // Two triangles sharing an edge (a, b) become one quad; still planar enough to split.
    faces = [[0, 2, 4, 3], ...faces.slice(1, 4), ...faces.slice(5)];
  }
  for (const f of faces) {
    const refs = f.map((i) => {
      const k = o.negative ? i - nv : i + 1;
      switch (o.style) {
        case 'v':
          return `${k}`;
        case 'v/vt':
          return `${k}/${k}`;
        case 'v//vn':
          return `${k}//${k}`;
        default:
          return `${k}/${k}/${k}`;
      }
    });
    out.push(`f ${refs.join(' ')}`);
  }
  return out;
}

const encode = (ls: string[], crlf = false): Uint8Array =>
  ascii(ls.join(crlf ? '\r\n' : '\n') + '\n');

function mutations(o: Obj): Mutation[] {
  const edit = (
    name: string,
    f: (ls: string[], rng: Rng) => string[],
    invalid = false,
  ): Mutation => ({
    name,
    invalid,
    apply: (rng) => ({ 'mesh.obj': encode(f(lines(o), rng)) }),
  });
  const faceAt = (ls: string[], rng: Rng) => {
    const fs = ls.map((l, i) => (l.startsWith('f ') ? i : -1)).filter((i) => i >= 0);
    return rng.pick(fs);
  };
  const vertexAt = (ls: string[], rng: Rng) => {
    const vs = ls.map((l, i) => (l.startsWith('v ') ? i : -1)).filter((i) => i >= 0);
    return rng.pick(vs);
  };
  return [
    edit(
      'obj:index-out-of-range',
      (ls, r) => {
        const i = faceAt(ls, r);
        ls[i] = `f 1 2 ${r.pick([7, 1000, 2147483648, 1e20])}`;
        return ls;
      },
      true,
    ),
    edit(
      'obj:index-zero',
      (ls, r) => {
        ls[faceAt(ls, r)] = 'f 0 1 2';
        return ls;
      },
      true,
    ),
    edit(
      'obj:negative-too-far',
      (ls, r) => {
        ls[faceAt(ls, r)] = 'f -1 -2 -99';
        return ls;
      },
      true,
    ),
    edit('obj:two-vertex-face', (ls, r) => {
      ls[faceAt(ls, r)] = 'f 1 2';
      return ls;
    }),
    edit('obj:non-finite', (ls, r) => {
      ls[vertexAt(ls, r)] = `v ${r.pick(['nan', 'inf', '-inf', 'NaN', '1e400', 'Infinity'])} 0 0`;
      return ls;
    }),
    edit('obj:huge-coordinate', (ls, r) => {
      ls[vertexAt(ls, r)] = `v ${r.pick(['1e308', '-1.7e308', '1e200'])} 1 1`;
      return ls;
    }),
    edit('obj:missing-coordinate', (ls, r) => {
      ls[vertexAt(ls, r)] = 'v 1 2';
      return ls;
    }),
    edit('obj:garbage-number', (ls, r) => {
      ls[vertexAt(ls, r)] = `v 1 ${r.pick(['0x10', '1,5', '--1', '1e', '.', '१'])} 0`;
      return ls;
    }),
    edit('obj:bad-reference', (ls, r) => {
      ls[faceAt(ls, r)] = `f ${r.pick(['1/2/3/4 2 3', '1// 2 3', 'a b c', '1/x 2 3', '/1 2 3'])}`;
      return ls;
    }),
    edit(
      'obj:missing-normal',
      (ls, r) => {
        ls[faceAt(ls, r)] = 'f 1//99 2//99 3//99';
        return ls;
      },
      true,
    ),
    edit('obj:zero-normal', (ls) => {
      ls.push('vn 0 0 0', 'f 1//-1 2//-1 3//-1');
      return ls;
    }),
    edit('obj:huge-polygon', (ls) => {
      ls.push(`f ${Array.from({ length: 50_000 }, (_, i) => (i % 6) + 1).join(' ')}`);
      return ls;
    }),
    edit('obj:long-line', (ls) => {
      ls.push(`# ${'x'.repeat(1_500_000)}`);
      return ls;
    }),
    edit('obj:no-faces', (ls) => ls.filter((l) => !l.startsWith('f '))),
    edit('obj:crlf', (ls) => [ls.join('\r\n')]),
    edit('obj:backslash-continuation', (ls, r) => {
      const i = vertexAt(ls, r);
      ls[i] = ls[i].replace(' ', ' \\\n');
      return ls;
    }),
    {
      name: 'obj:nul-bytes',
      apply: (rng) => {
        const b = encode(lines(o));
        for (let k = 0; k < 4; k++) b[rng.int(b.length)] = 0;
        return { 'mesh.obj': b };
      },
    },
  ];
}

export const objGenerator: Generator = {
  format: 'obj',
  generate(rng: Rng): Sample {
    const o: Obj = {
      mesh: octahedron(rng),
      style: rng.pick<RefStyle>(['v', 'v/vt', 'v//vn', 'v/vt/vn']),
      negative: rng.chance(0.3),
      quads: rng.chance(0.3),
      extras: rng.chance(0.5),
    };
    return {
      variant: `${o.style}${o.negative ? ' negative' : ''}${o.quads ? ' quads' : ''}`,
      files: { 'mesh.obj': encode(lines(o), rng.chance(0.2)), 'scene.json': meshScene('mesh.obj') },
      target: 'mesh.obj',
      args: ['render', 'scene.json'],
      lit: true,
      mutations: mutations(o),
    };
  },
};
