/**
 * The corpus of real public glTF models (issue 25; tests/corpus/corpus.json): every
 * committed model rendered by the CLI at a tiny size (one thread, 1 sample per pixel)
 * must finish with a finite image that is not one uniform colour, and print exactly the
 * messages that tests/cli/corpus-pending.ts lists for it today — no new one (something
 * else ignored) and none that has gone (a feature landed: remove the entry). The
 * corpus itself must keep its promises: at least 20 models, at least 8 compressed with
 * Draco or meshopt, each listed extension used by one, a licence and a SOURCE.md beside
 * each, and at most 30 MB in all.
 */
import { spawn } from 'node:child_process';
import { existsSync, mkdtempSync, readFileSync, readdirSync, statSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { beforeAll, describe, expect, it } from 'vitest';
import { decodePfm } from '../../src/core/index.ts';
import { ROOT } from '../helpers/render.ts';
import { PENDING, cliMessages, pendingDiff } from './corpus-pending.ts';

interface Entry {
  name: string;
  file: string;
  licence: string;
}
const corpusDir = join(ROOT, 'tests/corpus');
const manifest = JSON.parse(readFileSync(join(corpusDir, 'corpus.json'), 'utf8')) as {
  models: Entry[];
};
const bin = join(ROOT, 'bin/pathwise.js');
const out = mkdtempSync(join(tmpdir(), 'pathwise-corpus-'));

/** The glTF JSON of a .glb or .gltf. */
function gltfJson(path: string): { extensionsUsed?: string[] } {
  const bytes = readFileSync(path);
  if (bytes.readUInt32LE(0) === 0x46546c67) {
    return JSON.parse(bytes.subarray(20, 20 + bytes.readUInt32LE(12)).toString('utf8'));
  }
  return JSON.parse(bytes.toString('utf8'));
}

interface Result {
  status: number | null;
  stderr: string;
}
function render(path: string, pfm: string): Promise<Result> {
  const args = [bin, 'render', path, '--width', '16', '--height', '12', '--spp', '1'];
  return new Promise((resolve) => {
    const child = spawn(process.execPath, [...args, '--threads', '1', '--out', pfm], {
      cwd: ROOT,
      stdio: ['ignore', 'ignore', 'pipe'],
    });
    let stderr = '';
    child.stderr.on('data', (d) => (stderr += d));
    child.on('close', (status) => resolve({ status, stderr }));
  });
}

const results = new Map<string, Result>();

beforeAll(async () => {
  // Two renders at a time (two cores); each is one thread.
  const queue = [...manifest.models];
  const worker = async () => {
    for (let m = queue.shift(); m; m = queue.shift()) {
      results.set(m.name, await render(join(corpusDir, m.file), join(out, `${m.name}.pfm`)));
    }
  };
  await Promise.all([worker(), worker()]);
}, 300_000);

describe('the glTF corpus in the CLI', () => {
  for (const m of manifest.models) {
    it(`${m.name}: ${PENDING[m.name] ? `${PENDING[m.name].length} known message(s)` : 'renders with nothing ignored'}`, () => {
      const path = join(corpusDir, m.file);
      const r = results.get(m.name)!;
      const messages = cliMessages(r.stderr, path);
      const { unexpected, gone } = pendingDiff(m.name, messages);
      expect(unexpected, 'messages not in PENDING (corpus-pending.ts)').toEqual([]);
      expect(gone, 'PENDING lists messages that are gone: remove them').toEqual([]);
      if (messages.some((x) => x.startsWith('error: '))) {
        expect(r.status).toBe(2);
        return;
      }
      expect(r.status, r.stderr).toBe(0);
      const img = decodePfm(readFileSync(join(out, `${m.name}.pfm`)));
      let min = Infinity;
      let max = -Infinity;
      for (const v of img.rgb) {
        expect(Number.isFinite(v)).toBe(true);
        if (v < min) min = v;
        if (v > max) max = v;
      }
      // Not blank: not one uniform value (a black or empty image).
      expect(max).toBeGreaterThan(min);
    });
  }

  it('PENDING names only corpus models', () => {
    const names = new Set(manifest.models.map((m) => m.name));
    expect(Object.keys(PENDING).filter((n) => !names.has(n))).toEqual([]);
  });
});

describe('the corpus keeps its promises', () => {
  const used = new Map<string, string[]>();
  for (const m of manifest.models) {
    used.set(m.name, gltfJson(join(corpusDir, m.file)).extensionsUsed ?? []);
  }
  const users = (ext: string) => [...used].filter(([, e]) => e.includes(ext)).map(([n]) => n);

  it('has at least 20 models, at least 8 of them compressed with Draco or meshopt', () => {
    expect(manifest.models.length).toBeGreaterThanOrEqual(20);
    const compressed = [
      ...users('KHR_draco_mesh_compression'),
      ...users('EXT_meshopt_compression'),
      ...users('KHR_meshopt_compression'),
    ];
    expect(new Set(compressed).size).toBeGreaterThanOrEqual(8);
  });

  it('uses every extension of issue 25, but KHR_materials_diffuse_transmission (no real file here)', () => {
    const wanted = [
      'KHR_draco_mesh_compression',
      'EXT_texture_webp',
      'KHR_texture_basisu',
      'KHR_materials_clearcoat',
      'KHR_materials_sheen',
      'KHR_materials_volume',
      'KHR_materials_iridescence',
      'KHR_materials_anisotropy',
      'KHR_materials_unlit',
      'KHR_materials_pbrSpecularGlossiness',
      'KHR_materials_dispersion',
      'KHR_lights_punctual',
      'EXT_mesh_gpu_instancing',
    ];
    expect(wanted.filter((e) => users(e).length === 0)).toEqual([]);
    expect(
      users('EXT_meshopt_compression').length + users('KHR_meshopt_compression').length,
    ).toBeGreaterThan(0);
    // The one gap, said here so that the test notices when it closes.
    expect(users('KHR_materials_diffuse_transmission')).toEqual([]);
  });

  it('has a licence and a SOURCE.md beside each model, and at most 30 MB in all', () => {
    let bytes = 0;
    const walk = (dir: string): void => {
      for (const f of readdirSync(dir, { withFileTypes: true })) {
        if (f.isDirectory()) {
          if (f.name !== 'local') walk(join(dir, f.name));
        } else bytes += statSync(join(dir, f.name)).size;
      }
    };
    walk(corpusDir);
    expect(bytes).toBeLessThanOrEqual(30 * 2 ** 20);
    for (const m of manifest.models) {
      const dir = join(corpusDir, m.file.split('/')[0]);
      expect(existsSync(join(dir, 'SOURCE.md')), m.name).toBe(true);
      expect(['CC0-1.0', 'CC-BY-4.0', 'LicenseRef-CC-BY-TM', 'MIT']).toContain(m.licence);
      const licences = readdirSync(dir).filter((f) => f.startsWith('LICENSE'));
      // CC-BY models carry their attribution in SOURCE.md when the origin has no licence file.
      if (m.licence !== 'CC-BY-4.0') expect(licences.length, m.name).toBeGreaterThan(0);
    }
  });
});
