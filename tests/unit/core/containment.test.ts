/**
 * Files stay beside the model (issue 27, finding 6): a glTF's URIs resolve inside the
 * model's folder or the scene's, checked by name in the core (resolveUri), by real path
 * on disk in the command line's reader (links that point out), and as URLs in the
 * browser's reader (a model fetched by URL reads only files beside it).
 */
import { mkdirSync, mkdtempSync, symlinkSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { Document } from '@gltf-transform/core';
import { afterEach, describe, expect, it, vi } from 'vitest';
import { nodeSceneFiles } from '../../../src/cli/scene-files.ts';
import { resolveUri } from '../../../src/core/gltf/io.ts';
import { loadGltf } from '../../../src/core/gltf/load.ts';
import { loadBareModel } from '../../../src/core/scene/load/bare-scene.ts';
import { urlInside, urlSceneFiles } from '../../../workers/browser/scene-files.ts';
import { docWith, memoryOptions, quadPrimitive, toGltfFiles } from '../../helpers/gltf.ts';

const W = 'buffers[0].uri';

describe('resolveUri: a model names only files beside it', () => {
  it('resolves inside the model folder, or inside the scene folder', () => {
    expect(resolveUri('car.gltf', 'car.bin', W)).toBe('car.bin');
    expect(resolveUri('models/car/car.gltf', 'tex/a%20b.png', W)).toBe('models/car/tex/a b.png');
    // A texture in a sibling folder of the model, still inside the scene's folder.
    expect(resolveUri('models/car/car.gltf', '../textures/t.png', W)).toBe('models/textures/t.png');
    // A model outside the scene's folder reads its own folder.
    expect(resolveUri('../m/car.gltf', 'car.bin', W)).toBe('../m/car.bin');
    expect(resolveUri('/data/m/car.gltf', 'sub/../car.bin', W)).toBe('/data/m/car.bin');
  });

  it('refuses .. that leaves both folders, encoded or not, with one line', () => {
    const refused: [string, string][] = [
      ['car.gltf', '../outside.bin'],
      ['car.gltf', '../outside.png'],
      ['car.gltf', '../../../../../../../../etc/passwd'],
      ['car.gltf', '%2e%2e/outside.bin'],
      ['car.gltf', 'a/../../outside.bin'],
      ['models/car.gltf', '../../outside.bin'],
      ['../m/car.gltf', '../outside.bin'],
      ['/data/m/car.gltf', '../outside.bin'],
    ];
    for (const [model, uri] of refused) {
      expect(() => resolveUri(model, uri, W), `${model} ${uri}`).toThrow(
        /^glTF: buffers\[0\]\.uri: ".*" resolves to ".*", outside the model's folder.* and the scene's; a model may read only files beside it/,
      );
    }
    expect(() => resolveUri('car.gltf', '../outside.bin', W)).toThrow(
      'glTF: buffers[0].uri: "../outside.bin" resolves to "../outside.bin", outside the model\'s folder and the scene\'s; a model may read only files beside it (docs/gltf.md)',
    );
  });

  it('refuses absolute paths, schemes, backslashes and a scheme made by ..', () => {
    for (const uri of ['/etc/passwd', '%2Fetc%2Fpasswd', 'file:///etc/passwd', 'http://x/y.bin']) {
      expect(() => resolveUri('car.gltf', uri, W), uri).toThrow(/is not a relative path/);
    }
    for (const uri of ['..\\outside.bin', '..%5Coutside.bin', 'a%00.bin']) {
      expect(() => resolveUri('car.gltf', uri, W), uri).toThrow(
        /not a relative path of forward slashes/,
      );
    }
    expect(() => resolveUri('car.gltf', 'a/../http:evil.com', W)).toThrow(/reads as a URL/);
  });

  it('widens to the allowed folders only', () => {
    expect(resolveUri('car.gltf', '../textures/t.png', W, ['../textures'])).toBe(
      '../textures/t.png',
    );
    expect(() => resolveUri('car.gltf', '../texturesX/t.png', W, ['../textures'])).toThrow(
      /outside/,
    );
    expect(() => resolveUri('car.gltf', '../other/t.png', W, ['../textures'])).toThrow(/outside/);
  });
});

describe('loadGltf: a .gltf naming a file outside is refused before anything is read', () => {
  it('never asks the reader for ../outside.bin', async () => {
    const doc = new Document();
    const files = await toGltfFiles(docWith(doc, quadPrimitive(doc)), 'm');
    // Rewrite the buffer's URI to climb out of the folder.
    const json = JSON.parse(new TextDecoder().decode(files.get('m.gltf')!));
    const bytes = files.get(json.buffers[0].uri)!;
    json.buffers[0].uri = '../outside.bin';
    const asked: string[] = [];
    const options = await memoryOptions(new Map([['../outside.bin', bytes]]));
    const reader = options.reader!;
    options.reader = {
      read: (path, max) => {
        asked.push(path);
        return reader.read(path, max);
      },
    };
    const text = new TextEncoder().encode(JSON.stringify(json));
    await expect(loadGltf(text, 'm.gltf', options)).rejects.toThrow(
      /buffers\[0\]\.uri: "\.\.\/outside\.bin" resolves to "\.\.\/outside\.bin", outside/,
    );
    expect(asked).toEqual([]);
  });
});

describe('the command line reader: real paths inside the scene folder', () => {
  const root = mkdtempSync(join(tmpdir(), 'pathwise-contain-'));
  const scene = join(root, 'scene');
  mkdirSync(join(scene, 'models'), { recursive: true });
  mkdirSync(join(root, 'textures'), { recursive: true });
  writeFileSync(join(scene, 'models/a.bin'), 'inside');
  writeFileSync(join(root, 'outside.bin'), 'outside');
  writeFileSync(join(root, 'textures/t.png'), 'texture');
  symlinkSync(join(root, 'outside.bin'), join(scene, 'models/link.bin'));
  symlinkSync(join(scene, 'models/a.bin'), join(scene, 'models/inner-link.bin'));

  it('reads files inside, links that stay inside included', async () => {
    const files = nodeSceneFiles(scene);
    expect(new TextDecoder().decode(await files.read('models/a.bin', 100))).toBe('inside');
    expect(new TextDecoder().decode(await files.read('models/inner-link.bin', 100))).toBe('inside');
  });

  it('refuses .., absolute paths and links that point out', async () => {
    const files = nodeSceneFiles(scene);
    for (const path of ['../outside.bin', join(root, 'outside.bin'), '/etc/passwd']) {
      await expect(files.read(path, 100), path).rejects.toThrow(
        /^the file lies outside the scene's folder; only files beside the scene or the model are read, add --allow-read FOLDER to read others$/,
      );
    }
    await expect(files.read('models/link.bin', 100)).rejects.toThrow(
      /^the file lies outside the scene's folder \(through a link, to .*outside\.bin\)/,
    );
  });

  it('--allow-read widens it to the named folders, for the core check too', async () => {
    const files = nodeSceneFiles(scene, { allowRead: [join(root, 'textures')] });
    expect(files.allowedFolders).toEqual(['../textures']);
    expect(new TextDecoder().decode(await files.read('../textures/t.png', 100))).toBe('texture');
    await expect(files.read('../outside.bin', 100)).rejects.toThrow(/outside the scene's folder/);
  });
});

describe('the browser reader: URLs inside the base folder', () => {
  const base = 'https://site.example/models/car.gltf';
  it('resolves a path as a path, not as a URL', () => {
    expect(urlInside('car.bin', base).href).toBe('https://site.example/models/car.bin');
    expect(urlInside('tex/a b.png', base).href).toBe('https://site.example/models/tex/a%20b.png');
    // Percent signs, colons, ? and # are parts of a name, not a parent, scheme or query.
    expect(urlInside('%2e%2e/x.bin', base).href).toBe(
      'https://site.example/models/%252e%252e/x.bin',
    );
    expect(urlInside('http:evil.example/x', base).origin).toBe('https://site.example');
    expect(urlInside('a?b#c', base).href).toBe('https://site.example/models/a%3Fb%23c');
  });

  it("refuses a URL that leaves the origin; which folder is the core's rule", () => {
    for (const path of ['//evil.example/x', '//evil.example']) {
      expect(() => urlInside(path, base), path).toThrow(
        'it is not on the origin of https://site.example/models/; files are read from there only',
      );
    }
    // A scene's own .. stays on its origin (a model's URIs were checked by the core).
    expect(urlInside('../scenes/sky.hdr', base).href).toBe('https://site.example/scenes/sky.hdr');
  });
});

describe('a model fetched by URL', () => {
  afterEach(() => vi.unstubAllGlobals());

  it('reads its buffer beside it, and never fetches ../outside.bin', async () => {
    const doc = new Document();
    const files = await toGltfFiles(docWith(doc, quadPrimitive(doc)), 'm');
    const json = JSON.parse(new TextDecoder().decode(files.get('m.gltf')!));
    const bytes = files.get(json.buffers[0].uri)!;
    const asked: string[] = [];
    vi.stubGlobal('fetch', async (url: URL) => {
      asked.push(url.href);
      return new Response(bytes.slice().buffer);
    });
    const reader = urlSceneFiles('https://site.example/models/m.gltf');
    const text = (uri: string) =>
      new TextEncoder().encode(JSON.stringify({ ...json, buffers: [{ ...json.buffers[0], uri }] }));
    await loadBareModel(text('m.bin'), 'm.gltf', reader);
    expect(asked).toEqual(['https://site.example/models/m.bin']);
    await expect(loadBareModel(text('../outside.bin'), 'm.gltf', reader)).rejects.toThrow(
      /buffers\[0\]\.uri: "\.\.\/outside\.bin" resolves to "\.\.\/outside\.bin", outside the model's folder and the scene's/,
    );
    await expect(loadBareModel(text('%2e%2e/outside.bin'), 'm.gltf', reader)).rejects.toThrow(
      /outside the model's folder/,
    );
    expect(asked).toHaveLength(1);
  });
});
