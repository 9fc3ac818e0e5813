/**
 * Writes the mesh files of the canonical scenes (scenes/meshes/):
 * - bunny.ply: the Stanford bunny of the npm package `bunny` (public domain; the
 *   Stanford 3D Scanning Repository's, decimated to 1,839 vertices and 3,674 triangles,
 *   closed), as a binary little-endian PLY with float vertices, wound to face outward;
 * - torus.obj: a torus of 48 × 24 quads split into triangles, as OBJ with texture
 *   coordinates and comments (ignored by the loaders) and no normals, so it renders
 *   with geometric normals like every validation scene.
 *
 *   node scripts/run-ts.mjs scripts/make-meshes.ts
 */
import { mkdirSync, writeFileSync } from 'node:fs';
import { createRequire } from 'node:module';
import { resolve } from 'node:path';

// Resolved from the project (this script runs bundled from a temporary folder).
const require = createRequire(resolve('package.json'));
const bunny = require('bunny') as { positions: number[][]; cells: number[][] };

mkdirSync('scenes/meshes', { recursive: true });

// --- bunny.ply -----------------------------------------------------------------
{
  const { positions, cells } = bunny;
  // Signed volume by the divergence theorem: positive when the faces point outward.
  let volume = 0;
  for (const [a, b, c] of cells) {
    const [p, q, r] = [positions[a], positions[b], positions[c]];
    volume +=
      (p[0] * (q[1] * r[2] - q[2] * r[1]) -
        p[1] * (q[0] * r[2] - q[2] * r[0]) +
        p[2] * (q[0] * r[1] - q[1] * r[0])) /
      6;
  }
  const faces = volume > 0 ? cells : cells.map(([a, b, c]) => [a, c, b]);
  const header =
    'ply\nformat binary_little_endian 1.0\n' +
    'comment Stanford bunny (Stanford 3D Scanning Repository), from the npm package bunny\n' +
    `element vertex ${positions.length}\nproperty float x\nproperty float y\nproperty float z\n` +
    `element face ${faces.length}\nproperty list uchar int vertex_indices\nend_header\n`;
  const body = new DataView(new ArrayBuffer(positions.length * 12 + faces.length * 13));
  let o = 0;
  for (const p of positions) {
    for (const x of p) {
      body.setFloat32(o, x, true);
      o += 4;
    }
  }
  for (const f of faces) {
    body.setUint8(o++, 3);
    for (const i of f) {
      body.setInt32(o, i, true);
      o += 4;
    }
  }
  const bytes = new Uint8Array(header.length + o);
  bytes.set(Uint8Array.from(header, (ch) => ch.charCodeAt(0)));
  bytes.set(new Uint8Array(body.buffer), header.length);
  writeFileSync('scenes/meshes/bunny.ply', bytes);
  process.stdout.write(
    `bunny.ply: ${positions.length} vertices, ${faces.length} triangles` +
      `${volume > 0 ? '' : ' (winding reversed to face outward)'}\n`,
  );
}

// --- torus.obj ------------------------------------------------------------------
{
  const R = 1;
  const r = 0.4;
  const nu = 48;
  const nv = 24;
  const lines = ['# torus, R = 1, r = 0.4, axis +y; written by scripts/make-meshes.ts', 'o torus'];
  for (let i = 0; i < nu; i++) {
    const u = (2 * Math.PI * i) / nu;
    for (let j = 0; j < nv; j++) {
      const v = (2 * Math.PI * j) / nv;
      const x = (R + r * Math.cos(v)) * Math.cos(u);
      const z = (R + r * Math.cos(v)) * Math.sin(u);
      const y = r * Math.sin(v);
      lines.push(`v ${x.toFixed(6)} ${y.toFixed(6)} ${z.toFixed(6)}`);
    }
  }
  for (let i = 0; i < nu; i++) for (let j = 0; j < nv; j++) lines.push(`vt ${i / nu} ${j / nv}`);
  lines.push('s 1');
  const id = (i: number, j: number) => (i % nu) * nv + (j % nv) + 1;
  for (let i = 0; i < nu; i++) {
    for (let j = 0; j < nv; j++) {
      // Counter-clockwise seen from outside the tube.
      const [a, b, c, d] = [id(i, j), id(i, j + 1), id(i + 1, j + 1), id(i + 1, j)];
      lines.push(`f ${a}/${a} ${b}/${b} ${c}/${c}`, `f ${a}/${a} ${c}/${c} ${d}/${d}`);
    }
  }
  writeFileSync('scenes/meshes/torus.obj', lines.join('\n') + '\n');
  process.stdout.write(`torus.obj: ${nu * nv} vertices, ${2 * nu * nv} triangles\n`);
}
