/**
 * Reading and writing files on the command line (src/cli/read-bounded.ts, output.ts) and
 * reading in the browser (workers/browser/read-bounded.ts, exercised with Node's web streams):
 * bounded reads from any source, checked and atomic output.
 */
import { execFileSync, spawn } from 'node:child_process';
import {
  existsSync,
  mkdirSync,
  mkdtempSync,
  readFileSync,
  readdirSync,
  rmSync,
  writeFileSync,
} from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { describe, expect, it } from 'vitest';
import { CliError } from '../../../src/cli/errors.ts';
import { OutputFile } from '../../../src/cli/output.ts';
import { temps } from '../../../src/cli/host.ts';
import { ReadLimitError, readBounded } from '../../../src/cli/read-bounded.ts';
import {
  ByteLimitError,
  readBlobBounded,
  readResponseBounded,
} from '../../../workers/browser/read-bounded.ts';

const dir = mkdtempSync(join(tmpdir(), 'pathwise-io-'));

async function rejection(p: Promise<unknown>): Promise<Error> {
  try {
    await p;
  } catch (e) {
    return e as Error;
  }
  throw new Error('expected a rejection');
}

describe('readBounded', () => {
  it('reads a regular file whole, and rejects one over the limit by its size', async () => {
    const file = join(dir, 'a.json');
    writeFileSync(file, 'x'.repeat(3000));
    expect((await readBounded(file, 3000)).length).toBe(3000);
    const e = await rejection(readBounded(file, 2999));
    expect(e).toBeInstanceOf(ReadLimitError);
    expect((e as ReadLimitError).exact).toBe(true);
    expect((e as ReadLimitError).size).toBe(3000);
  });

  it('stops reading a device at the limit: /dev/zero, /dev/urandom', async () => {
    for (const device of ['/dev/zero', '/dev/urandom']) {
      const e = await rejection(readBounded(device, 5_000_000));
      expect(e).toBeInstanceOf(ReadLimitError);
      expect((e as ReadLimitError).exact).toBe(false);
      expect((e as ReadLimitError).size).toBe(5_000_001);
    }
  });

  it('reads a named pipe to its end, and bounds an endless one', async () => {
    const fifo = join(dir, 'fifo');
    execFileSync('mkfifo', [fifo]);
    const writer = spawn('bash', ['-c', `printf '{"a": 1}' > '${fifo}'`]);
    const written = new Promise((r) => writer.on('close', r));
    expect(new TextDecoder().decode(await readBounded(fifo, 100))).toBe('{"a": 1}');
    await written;
    const endless = spawn('bash', ['-c', `yes '[' > '${fifo}'`]);
    try {
      const e = await rejection(readBounded(fifo, 1_000_000));
      expect(e).toBeInstanceOf(ReadLimitError);
    } finally {
      endless.kill('SIGKILL');
    }
  });

  it('names the problem of a path that cannot be read, escaping the path', async () => {
    expect((await rejection(readBounded(dir, 10))).message).toBe(
      `cannot read ${dir}: it is a directory`,
    );
    const missing = join(dir, 'no\u001b[2Jpe.json');
    const e = await rejection(readBounded(missing, 10));
    expect(e).toBeInstanceOf(CliError);
    expect(e.message).toBe(
      `cannot read ${join(dir, 'no\\u001b[2Jpe.json')}: no such file or directory`,
    );
  });
});

describe('OutputFile', () => {
  it('refuses a missing directory, a directory, a device before any work', async () => {
    const cases: [string, RegExp][] = [
      [join(dir, 'missing', 'x.pfm'), /the directory .*missing does not exist$/],
      [dir, /it is a directory$/],
      ['/dev/full', /it is a character device, not a regular file$/],
      [join(dir, 'a.json', 'x.pfm'), /a component of the path is not a directory$/],
    ];
    for (const [path, message] of cases) {
      const e = await rejection(OutputFile.prepare(path));
      expect(e).toBeInstanceOf(CliError);
      expect(e.message).toMatch(message);
    }
  });

  it('writes a temporary file beside the target and renames it into place', async () => {
    const sub = mkdtempSync(join(dir, 'out-'));
    const target = join(sub, 'image.pfm');
    writeFileSync(target, 'old');
    const out = await OutputFile.prepare(target);
    expect(readdirSync(sub).filter((f) => f.endsWith('.tmp'))).toHaveLength(1);
    expect(readFileSync(target, 'utf8')).toBe('old'); // untouched until commit
    await out.commit(new TextEncoder().encode('new'));
    expect(readFileSync(target, 'utf8')).toBe('new');
    expect(readdirSync(sub)).toEqual(['image.pfm']);
  });

  it('reports a failed commit as one line and removes the temporary file', async () => {
    const sub = mkdtempSync(join(dir, 'gone-'));
    const out = await OutputFile.prepare(join(sub, 'image.pfm'));
    // The directory disappears during the render: the rename cannot succeed.
    rmSync(sub, { recursive: true, force: true });
    const e = await rejection(out.commit(new Uint8Array(10)));
    expect(e).toBeInstanceOf(CliError);
    expect(e.message).toMatch(/^cannot write .*image\.pfm: no such file or directory$/);
    expect(existsSync(out.temp)).toBe(false);
  });

  it('discards its temporary file when the work is abandoned or the process is signalled', async () => {
    const sub = mkdtempSync(join(dir, 'discard-'));
    const out = await OutputFile.prepare(join(sub, 'image.png'));
    await out.discard();
    expect(readdirSync(sub)).toEqual([]);
    mkdirSync(join(sub, 'x'));
    // A signal's handler (main.ts) removes it through the shared registry.
    await OutputFile.prepare(join(sub, 'x', 'image.png'));
    expect(readdirSync(join(sub, 'x'))).toHaveLength(1);
    temps.removeAll();
    expect(readdirSync(join(sub, 'x'))).toEqual([]);
  });
});

describe('browser reads (workers/browser/read-bounded.ts)', () => {
  it('reads a fetched body as a stream and stops at the limit', async () => {
    let pulls = 0;
    const endless = new ReadableStream<Uint8Array>({
      pull(controller) {
        pulls++;
        controller.enqueue(new Uint8Array(65536).fill(0x5b));
      },
    });
    const e = await rejection(readResponseBounded(new Response(endless), 1_000_000));
    expect(e).toBeInstanceOf(ByteLimitError);
    expect((e as ByteLimitError).exact).toBe(false);
    expect((e as ByteLimitError).size).toBeGreaterThan(1_000_000);
    expect(pulls).toBeLessThan(40);
    const ok = await readResponseBounded(new Response('{"a": 1}'), 8);
    expect(new TextDecoder().decode(ok)).toBe('{"a": 1}');
  });

  it('gives the bytes the body holds, whatever Content-Length says', async () => {
    // 300 chunks of 1,000 bytes, each byte its own position mod 251.
    const body = () =>
      new ReadableStream<Uint8Array>({
        start(controller) {
          for (let c = 0; c < 300; c++) {
            controller.enqueue(Uint8Array.from({ length: 1000 }, (_, i) => (c * 1000 + i) % 251));
          }
          controller.close();
        },
      });
    const expected = Uint8Array.from({ length: 300_000 }, (_, i) => i % 251);
    for (const length of [null, '300000', '10', '5000000', 'lots']) {
      const headers = length === null ? undefined : { 'content-length': length };
      const got = await readResponseBounded(new Response(body(), { headers }), 1_000_000);
      expect(got.length, `Content-Length ${length}`).toBe(300_000);
      expect(Buffer.from(got).equals(Buffer.from(expected)), `Content-Length ${length}`).toBe(true);
    }
    // A header that claims more than the limit allocates nothing for it.
    const e = await rejection(
      readResponseBounded(
        new Response(body(), { headers: { 'content-length': String(2 ** 40) } }),
        100_000,
      ),
    );
    expect((e as ByteLimitError).size).toBe(101_000);
  });

  it('checks a File by its size before reading it', async () => {
    const e = await rejection(readBlobBounded(new Blob([new Uint8Array(101)]), 100));
    expect(e).toBeInstanceOf(ByteLimitError);
    expect((e as ByteLimitError).size).toBe(101);
    expect((await readBlobBounded(new Blob(['abc']), 100)).length).toBe(3);
  });
});
