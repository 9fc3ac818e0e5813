/**
 * Mesh shapes in scenes: inline arrays, files through a SceneFileReader, transforms
 * (normals by the inverse transpose), zero-area triangles skipped and counted, and one
 * clear error naming the shape (and the file's line or element) for every bad mesh.
 */
import { mkdtempSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { describe, expect, it } from 'vitest';
import {
  LIMITS,
  SceneError,
  loadScene,
  parseScene,
  resolveSceneFiles,
  validateScene,
  type MeshDesc,
  type Scene,
  type SceneFileReader,
} from '../../../src/core/index.ts';
import { nodeSceneFiles } from '../../../src/cli/scene-files.ts';

function base(shapes: unknown[], extra: Record<string, unknown> = {}): Record<string, unknown> {
  return {
    format: 'pathwise-scene/1',
    camera: { position: [0, 0, -4], target: [0, 0, 0], up: [0, 1, 0], fovY: 40 },
    materials: { m: { type: 'diffuse', albedo: [0.5, 0.5, 0.5] } },
    shapes,
    ...extra,
  };
}

function mesh(extra: Record<string, unknown>): Record<string, unknown> {
  return { type: 'mesh', material: 'm', ...extra };
}

const TRI = [0, 0, 0, 1, 0, 0, 0, 1, 0];

function problemsOf(f: () => unknown): string[] {
  try {
    f();
  } catch (e) {
    if (e instanceof SceneError) return e.problems;
    throw e;
  }
  throw new Error('expected a SceneError');
}

async function asyncProblems(p: Promise<unknown>): Promise<string[]> {
  try {
    await p;
  } catch (e) {
    if (e instanceof SceneError) return e.problems;
    throw e;
  }
  throw new Error('expected a SceneError');
}

const meshOf = (s: Scene, i = 0) => s.shapes[i] as MeshDesc;

describe('inline meshes', () => {
  it('take consecutive triples without indices, and keep the given indices', () => {
    const s = validateScene(base([mesh({ positions: [...TRI, 0, 0, 1, 1, 0, 1, 0, 1, 1] })]));
    const d = meshOf(s).data!;
    expect(Array.from(d.indices)).toEqual([0, 1, 2, 3, 4, 5]);
    expect(d.normals).toBeNull();
    expect(d.skipped).toBe(0);
    expect(meshOf(s).file).toBeNull();
    expect(s.environmentMap).toBeNull();
    const t = validateScene(
      base([mesh({ positions: [...TRI, 1, 1, 0], indices: [0, 1, 2, 2, 1, 3] })]),
    );
    expect(Array.from(meshOf(t).data!.indices)).toEqual([0, 1, 2, 2, 1, 3]);
  });

  it('skip and count zero-area triangles, judged in double precision after the transform', () => {
    const s = validateScene(
      base([
        mesh({
          positions: [
            0, 0, 0, 1, 0, 0, 2, 0, 0, 0, 1, 0, 1e-300, 0, 0, 0, 1e-300, 0, 1e300, 0, 0, 0, 1e300,
            0,
          ],
          // collinear, repeated vertex, a tiny and a huge triangle (both fine)
          indices: [0, 1, 2, 0, 0, 3, 0, 4, 5, 0, 6, 7, 0, 1, 3],
        }),
      ]),
    );
    const d = meshOf(s).data!;
    expect(d.skipped).toBe(2);
    expect(Array.from(d.indices)).toEqual([0, 4, 5, 0, 6, 7, 0, 1, 3]);
    // A transform that flattens nothing but scales to 1e-200 keeps every triangle.
    const k = 1e-200;
    const tiny = validateScene(
      base([mesh({ positions: TRI, transform: [k, 0, 0, 0, 0, k, 0, 0, 0, 0, k, 0, 0, 0, 0, 1] })]),
    );
    expect(meshOf(tiny).data!.skipped).toBe(0);
    expect(meshOf(tiny).data!.positions[3]).toBe(1e-200);
  });

  it('transform positions by the matrix and normals by its inverse transpose', () => {
    // Shear x += y, then translate by (5, 0, 0). A normal (1, 0, 0) of the plane x = 0
    // becomes (1, −1, 0)/√2, perpendicular to the sheared plane x = y.
    const s = validateScene(
      base([
        mesh({
          positions: [0, 0, 0, 0, 1, 0, 0, 0, 1],
          normals: [1, 0, 0, 2, 0, 0, 0.5, 0, 0],
          transform: [1, 1, 0, 5, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1],
        }),
      ]),
    );
    const d = meshOf(s).data!;
    expect(Array.from(d.positions)).toEqual([5, 0, 0, 6, 1, 0, 5, 0, 1]);
    for (let v = 0; v < 3; v++) {
      expect(d.normals![3 * v]).toBeCloseTo(Math.SQRT1_2, 6);
      expect(d.normals![3 * v + 1]).toBeCloseTo(-Math.SQRT1_2, 6);
      expect(d.normals![3 * v + 2]).toBe(0);
    }
    // A mirror keeps a normal's side of the surface: z → −z maps (0,0,1) to (0,0,−1).
    const m = validateScene(
      base([
        mesh({
          positions: TRI,
          normals: [0, 0, 1, 0, 0, 1, 0, 0, 1],
          transform: [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, -1, 0, 0, 0, 0, 1],
        }),
      ]),
    );
    expect(Array.from(meshOf(m).data!.normals!.slice(0, 3))).toEqual([0, 0, -1]);
  });

  it('reject every malformed mesh with one message naming it', () => {
    const cases: [Record<string, unknown>, string | RegExp][] = [
      [
        { positions: TRI, file: 'a.obj' },
        'shapes[0] has both file and positions: a mesh takes its triangles from one',
      ],
      [{}, 'shapes[0] needs positions (a flat array of numbers) or file'],
      [
        { positions: [0, 0, 0, 1] },
        'shapes[0].positions must have a length that is a multiple of 3, got 4',
      ],
      [
        { positions: [0, 0, 0, 1, 0, 0] },
        /holds 2 vertices; without indices they are taken three per triangle/,
      ],
      [
        { positions: [...TRI.slice(0, 8), null] },
        'shapes[0].positions[8] must be a finite number, got null',
      ],
      [
        { positions: [...TRI.slice(0, 8), '1'] },
        'shapes[0].positions[8] must be a finite number, got the string "1"',
      ],
      [
        { positions: 'x' },
        'shapes[0].positions must be a flat array of numbers, got the string "x"',
      ],
      [
        { positions: TRI, indices: [0, 1, 3] },
        'shapes[0].indices[2] must be a vertex index in [0, 2], got 3',
      ],
      [
        { positions: TRI, indices: [0, 1, 1.5] },
        'shapes[0].indices[2] must be a vertex index in [0, 2], got 1.5',
      ],
      [
        { positions: TRI, indices: [0, 1, -1] },
        'shapes[0].indices[2] must be a vertex index in [0, 2], got -1',
      ],
      [
        { positions: TRI, indices: [0, 1] },
        'shapes[0].indices must have a length that is a multiple of 3, got 2',
      ],
      [{ positions: [], indices: [] }, 'shapes[0] has no triangles'],
      [
        { positions: TRI, normals: [0, 0, 1] },
        'shapes[0].normals must have the length of positions (9), got 3',
      ],
      [
        { positions: TRI, normals: [0, 0, 1, 0, 0, 0, 0, 0, 1] },
        'shapes[0].normals: the normal of vertex 1 is zero',
      ],
      [
        { positions: TRI, transform: [1, 0, 0] },
        /^shapes\[0\]\.transform must be an array of 16 numbers/,
      ],
      [
        { positions: TRI, transform: [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 1, 1] },
        'shapes[0].transform: its last row must be 0 0 0 1, got 0 0 1 1',
      ],
      [
        { positions: TRI, transform: [1, 0, 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 0, 0, 0, 1] },
        'shapes[0].transform: it is not invertible (its 3×3 part is singular)',
      ],
      [
        { positions: TRI, transform: [1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1] },
        'shapes[0].transform: it is not invertible (row 2 of its 3×3 part is zero)',
      ],
      [
        {
          positions: [0, 0, 0, 1e10, 0, 0, 0, 1, 0],
          transform: [1e300, 0, 0, 0, 0, 1e300, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1],
        },
        'shapes[0]: the transform takes vertex 1 out of the range of finite numbers',
      ],
      [{ file: 'bunny.stl' }, 'shapes[0].file must name an .obj or .ply file, got "bunny.stl"'],
      [{ positions: TRI, colour: 1 }, 'shapes[0].colour is not a known key'],
    ];
    for (const [m, message] of cases) {
      const problems = problemsOf(() => validateScene(base([mesh(m)])));
      expect(problems, JSON.stringify(m)).toHaveLength(1);
      if (typeof message === 'string') expect(problems[0]).toBe(message);
      else expect(problems[0]).toMatch(message);
    }
    expect(
      problemsOf(() => validateScene(base([mesh({ positions: TRI, material: 'n' })]))),
    ).toEqual(['shapes[0].material names unknown material "n"']);
  });

  it('parse from JSON text like every other shape', () => {
    const s = parseScene(JSON.stringify(base([mesh({ positions: TRI })])));
    expect(meshOf(s).data!.positions).toBeInstanceOf(Float64Array);
  });
});

/** An in-memory SceneFileReader that records what it was asked. */
function memoryFiles(
  files: Record<string, Uint8Array | string>,
): SceneFileReader & { asked: number[] } {
  const asked: number[] = [];
  return {
    asked,
    async read(path, maxBytes) {
      asked.push(maxBytes);
      const f = files[path];
      if (f === undefined) throw new Error('no such file');
      const bytes = typeof f === 'string' ? new TextEncoder().encode(f) : f;
      if (bytes.length > maxBytes) throw new Error(`the file is more than ${maxBytes} bytes`);
      return bytes;
    },
  };
}

const QUAD_OBJ = 'v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n';

describe('mesh files', () => {
  it('are read through the reader, with the mesh file limit, and transformed', async () => {
    const files = memoryFiles({ 'm/quad.obj': QUAD_OBJ });
    const text = JSON.stringify(
      base([
        mesh({ file: 'm/quad.obj', transform: [2, 0, 0, 0, 0, 2, 0, 0, 0, 0, 2, 0, 0, 0, 0, 1] }),
        mesh({ positions: TRI }),
      ]),
    );
    const scene = await loadScene(text, files);
    expect(files.asked).toEqual([LIMITS.meshFileBytes]);
    const d = meshOf(scene).data!;
    expect(Array.from(d.positions)).toEqual([0, 0, 0, 2, 0, 0, 2, 2, 0, 0, 2, 0]);
    expect(Array.from(d.indices)).toEqual([0, 1, 2, 0, 2, 3]);
    expect(meshOf(scene).file).toBe('m/quad.obj');
    // The parsed scene is not changed, and a resolved one is returned as it is.
    const parsed = parseScene(text);
    const again = await resolveSceneFiles(parsed, files);
    expect(meshOf(parsed).data).toBeNull();
    expect(await resolveSceneFiles(again, null)).toBe(again);
  });

  it('name the shape and the file, and the line or element, in every error', async () => {
    const scene = (file: string) =>
      JSON.stringify(base([mesh({ positions: TRI }), mesh({ file })]));
    const files = memoryFiles({
      'bad.obj': 'v 0 0 0\nv 1 0 0\nf 1 2 3\n',
      'bad.ply':
        'ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n3 0 0 7\n',
      'flat.obj': 'v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n',
    });
    expect(await asyncProblems(loadScene(scene('bad.obj'), files))).toEqual([
      'shapes[1].file "bad.obj": OBJ: line 3: vertex index 3 is out of range: the file has 2 vertices',
    ]);
    expect(await asyncProblems(loadScene(scene('bad.ply'), files))).toEqual([
      'shapes[1].file "bad.ply": PLY: face 0 (line 11): vertex index 7 is out of range (the file has 1 vertices)',
    ]);
    expect(await asyncProblems(loadScene(scene('missing.obj'), files))).toEqual([
      'shapes[1].file "missing.obj": no such file',
    ]);
    expect(await asyncProblems(loadScene(scene('bad.obj'), null))).toEqual([
      'shapes[1].file "bad.obj": this scene names files, but it was given without a way to read ' +
        'them (load it from a file or URL, or drop its files together with it)',
    ]);
    // All triangles of zero area: a mesh that would render as nothing is an error (issue 27).
    expect(await asyncProblems(loadScene(scene('flat.obj'), files))).toEqual([
      'shapes[1].file "flat.obj": its only triangle has zero area, so nothing of the mesh would render',
    ]);
  });

  it('share the scene limit of 10,000,000 triangles, checked before allocating', async () => {
    // Inline meshes use some of the budget, so a file may use only what is left.
    const files: SceneFileReader = {
      async read() {
        return new TextEncoder().encode(QUAD_OBJ);
      },
    };
    const scene = parseScene(
      JSON.stringify(base([mesh({ positions: TRI }), mesh({ file: 'q.obj' })])),
    );
    expect(meshOf(await resolveSceneFiles(scene, files), 1).data!.indices.length).toBe(6);
    // Near the limit (an inline mesh that had many zero-area triangles), nothing is left.
    const heavy = {
      ...scene,
      shapes: [
        { ...meshOf(scene), data: { ...meshOf(scene).data!, skipped: LIMITS.triangles - 1 } },
        scene.shapes[1],
      ],
    };
    expect(await asyncProblems(resolveSceneFiles(heavy, files))).toEqual([
      'shapes[1].file "q.obj": OBJ: the faces up to line 5 hold 2 triangles, more than the 0 left of ' +
        'the limit of 10000000 per scene',
    ]);
  });

  it('are read from disk by the command line relative to the scene, with a bound', async () => {
    const dir = mkdtempSync(join(tmpdir(), 'pathwise-mesh-'));
    writeFileSync(join(dir, 'quad.obj'), QUAD_OBJ);
    const reader = nodeSceneFiles(dir);
    expect((await reader.read('quad.obj', 1000)).length).toBe(QUAD_OBJ.length);
    await expect(reader.read('quad.obj', 10)).rejects.toThrow(
      `the file has ${QUAD_OBJ.length} bytes, more than the limit of 10`,
    );
    await expect(reader.read('nope.obj', 10)).rejects.toThrow(
      /cannot read .*nope\.obj: no such file or directory/,
    );
    await expect(reader.read('.', 10)).rejects.toThrow(/directory/);
    // A device reports no size: the read stops past the limit instead of running on
    // (/dev is outside the scene's folder: allowed as --allow-read /dev would).
    const devices = nodeSceneFiles(dir, { allowRead: ['/dev'] });
    await expect(devices.read('/dev/zero', 1 << 16)).rejects.toThrow(
      'the file has more than the limit of 65536 bytes',
    );
  });
});
