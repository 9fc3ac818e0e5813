/**
 * The browser's scene file readers, run on Node's fetch, Response and File: relative
 * URLs resolve against the scene's URL, dropped files match by path or name, and both
 * refuse a file over the limit without holding more than the limit.
 */
import { afterEach, describe, expect, it, vi } from 'vitest';
import { droppedSceneFiles, urlSceneFiles } from '../../../workers/browser/scene-files.ts';
import { loadScene } from '../../../src/core/index.ts';

afterEach(() => vi.unstubAllGlobals());

describe('scene files by URL', () => {
  it('resolves paths against the scene URL and returns the bytes', async () => {
    const asked: string[] = [];
    vi.stubGlobal('fetch', async (url: URL) => {
      asked.push(url.href);
      return new Response(new Uint8Array([1, 2, 3]));
    });
    const reader = urlSceneFiles('https://example.test/scenes/room.json');
    expect(Array.from(await reader.read('meshes/bunny.ply', 10))).toEqual([1, 2, 3]);
    await reader.read('../sky.hdr', 10);
    expect(asked).toEqual([
      'https://example.test/scenes/meshes/bunny.ply',
      'https://example.test/sky.hdr',
    ]);
  });

  it('refuses by Content-Length, by the bytes streamed, and on HTTP errors', async () => {
    let body: () => Response = () => new Response('');
    vi.stubGlobal('fetch', async () => body());
    const reader = urlSceneFiles('https://example.test/a.json');
    body = () => new Response('x'.repeat(100), { headers: { 'content-length': '100' } });
    await expect(reader.read('m.obj', 50)).rejects.toThrow(
      'the file has 100 bytes, more than the limit of 50',
    );
    // No length declared: a stream that goes on forever is cut at the limit.
    let pulled = 0;
    body = () =>
      new Response(
        new ReadableStream({
          pull(c) {
            pulled++;
            c.enqueue(new Uint8Array(16));
          },
        }),
      );
    await expect(reader.read('m.obj', 100)).rejects.toThrow(
      'the file has more than the limit of 100 bytes',
    );
    expect(pulled).toBeLessThan(20);
    body = () => new Response('nope', { status: 404 });
    await expect(reader.read('m.obj', 100)).rejects.toThrow(
      'cannot fetch https://example.test/m.obj: HTTP 404',
    );
  });
});

describe('dropped scene files', () => {
  const files = [
    new File(['v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n'], 'tri.obj'),
    new File(['abc'], 'sky.hdr'),
    new File(['a'], 'twin.ply'),
    new File(['b'], 'twin.ply'),
  ];

  it('match by name (or relative path), and load a scene with them', async () => {
    const reader = droppedSceneFiles(files);
    expect(new TextDecoder().decode(await reader.read('maps/sky.hdr', 10))).toBe('abc');
    const scene = await loadScene(
      JSON.stringify({
        format: 'pathwise-scene/1',
        camera: { position: [0, 0, -4], target: [0, 0, 0], up: [0, 1, 0], fovY: 40 },
        materials: { m: { type: 'diffuse', albedo: [0.5, 0.5, 0.5] } },
        shapes: [{ type: 'mesh', material: 'm', file: 'meshes/tri.obj' }],
      }),
      reader,
    );
    expect(scene.shapes[0].type === 'mesh' && scene.shapes[0].data!.indices.length).toBe(3);
  });

  it('say what is missing, ambiguous or too large', async () => {
    const reader = droppedSceneFiles(files);
    await expect(reader.read('bunny.ply', 10)).rejects.toThrow(
      'it was not among the dropped files; drop the scene together with bunny.ply',
    );
    await expect(reader.read('twin.ply', 10)).rejects.toThrow(
      '2 dropped files are named twin.ply; drop only one',
    );
    await expect(reader.read('tri.obj', 5)).rejects.toThrow(
      /^the file has \d+ bytes, more than the limit of 5$/,
    );
  });
});
