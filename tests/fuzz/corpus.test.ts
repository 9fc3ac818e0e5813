/**
 * The fixed hostile corpus (tests/fuzz/corpus.ts) through the real command line: every
 * case meets the contract (exit 0 with a finite image, or exit 2 with one printable line;
 * no crash, no hang, bounded memory) and gives its expected message. Also what a corpus
 * file cannot express: the output is written atomically, and nothing is left behind.
 */
import {
  linkSync,
  mkdirSync,
  mkdtempSync,
  readFileSync,
  readdirSync,
  statSync,
  writeFileSync,
} from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { beforeAll, describe, expect, it } from 'vitest';
import { expectContract, expectOneLine, runCli } from '../helpers/cli.ts';
import { CORPUS, CORPUS_DIR, setOutDir } from './corpus.ts';

let dir = '';
let outDir = '';
beforeAll(() => {
  dir = mkdtempSync(join(tmpdir(), 'pathwise-corpus-'));
  outDir = join(dir, 'out');
  mkdirSync(outDir);
  setOutDir(outDir);
});

describe('hostile corpus through pathwise render', () => {
  it.each(CORPUS.map((c) => [c.covers, c.name, c] as const))('%s: %s', async (_, __, c) => {
    const args = c.args(dir);
    const seconds = c.seconds ?? 30;
    const r = await runCli(args, {
      pipeFrom: c.pipeFrom,
      timeoutMs: seconds * 1000,
      rssCapMiB: c.rssMiB ?? 1024,
    });
    const out = args[args.indexOf('--out') + 1];
    expectContract(r, args.includes('--out') ? out : undefined);
    expect(r.status, r.stderr).toBe(c.status);
    if (c.status === 0) {
      expect(statSync(out).size).toBeGreaterThan(0);
      // A valid scene renders without dropping samples silently: none are dropped here.
      expect(r.stderr).toBe('');
    }
    if (c.message) expect(r.stderr.trimEnd()).toMatch(c.message);
    if (c.notMessage) expect(r.stderr).not.toMatch(c.notMessage);
  });

  it('has one case per finding and per rule, and uses every committed corpus file', () => {
    const covered = new Set(CORPUS.map((c) => c.covers.split(' ')[0]));
    for (const f of ['F1', 'F2', 'F3', 'F4', 'F5', 'F6', 'F7', 'F8', 'F9', 'F10', 'F11', 'F12']) {
      expect(covered).toContain(f);
    }
    for (const f of ['F13', 'F14', 'R1', 'R2', 'R3', 'R4', 'R5', 'R6', 'R7', 'R8']) {
      expect(covered).toContain(f);
    }
    const used = CORPUS.map((c) => c.args(mkdtempSync(join(tmpdir(), 'pathwise-args-'))).join(' '));
    for (const name of readdirSync(CORPUS_DIR)) {
      expect(
        used.some((a) => a.includes(name)),
        name,
      ).toBe(true);
    }
  });
});

describe('output', () => {
  const scene = join(CORPUS_DIR, 'valid-base.json');

  it('replaces the output atomically (a new file renamed into place, not rewritten)', async () => {
    const out = join(dir, 'atomic.pfm');
    const link = join(dir, 'atomic-link.pfm');
    writeFileSync(out, 'old contents');
    linkSync(out, link);
    const r = await runCli(['render', scene, '--out', out]);
    expectContract(r, out);
    expect(r.status).toBe(0);
    // Written in place, the hard link would show the new image too.
    expect(readFileSync(link, 'utf8')).toBe('old contents');
    expect(readFileSync(out).subarray(0, 3).toString('latin1')).toBe('PF\n');
    expect(readdirSync(dir).filter((f) => f.endsWith('.tmp'))).toEqual([]);
  });

  it('leaves no temporary file and the old output untouched when the render fails', async () => {
    const out = join(dir, 'kept.pfm');
    writeFileSync(out, 'kept');
    // An invalid override is found after the output was prepared? No: settings come
    // first. Use a scene that fails validation: nothing is created at all.
    const r = await runCli(['render', join(CORPUS_DIR, 'limit-spp.json'), '--out', out]);
    expect(r.status).toBe(2);
    expectOneLine(r.stderr);
    expect(readFileSync(out, 'utf8')).toBe('kept');
    expect(readdirSync(dir).filter((f) => f.endsWith('.tmp'))).toEqual([]);
  });

  it('removes its temporary file when interrupted (SIGINT) during a render', async () => {
    const s = JSON.parse(readFileSync(scene, 'utf8'));
    s.settings = { width: 256, height: 256, maxBounces: 8, spp: 100000 };
    const long = join(dir, 'interrupt.json');
    writeFileSync(long, JSON.stringify(s));
    const sub = mkdtempSync(join(dir, 'sigint-'));
    const { spawn } = await import('node:child_process');
    const { BIN } = await import('../helpers/cli.ts');
    const child = spawn(process.execPath, [BIN, 'render', long, '--out', join(sub, 'i.pfm')]);
    // Wait until the temporary file exists (the output was prepared), then interrupt.
    const closed = new Promise<number | null>((r) => child.on('close', r));
    try {
      for (let i = 0; i < 200 && readdirSync(sub).length === 0; i++) {
        await new Promise((r) => setTimeout(r, 25));
      }
      expect(readdirSync(sub).some((f) => f.endsWith('.tmp'))).toBe(true);
      child.kill('SIGINT');
      expect(await closed).toBe(130);
      expect(readdirSync(sub)).toEqual([]);
    } finally {
      child.kill('SIGKILL');
    }
  });
});
