#!/usr/bin/env node
/**
 * The glTF corpus (issue 25): renders every model of tests/corpus/corpus.json that is
 * present — the committed ones under tests/corpus/, and the "local" ones (listed with
 * their source, not committed for size or licence) wherever they were put under
 * tests/corpus/local/ — with the built command line (bin/pathwise.js; run
 * `npm run build:cli` first), and in headless Chromium through the <pathwise-view>
 * widget, and prints one markdown table: model, source, extensions (used; required
 * marked *), triangles, load seconds, peak MB, M paths/s, and whether each render
 * succeeded. Success means: the render finished, every value is finite, the image is
 * not blank (not one uniform colour), and no message says that something the model
 * uses was ignored or is not supported. Notes that the model is shown in its rest pose
 * (animations, skins, morph targets: a still image has no time) are listed, not failed.
 *
 *   node scripts/corpus.mjs [--width 160] [--height 120] [--spp 16] [--threads 2]
 *                           [--only A,B] [--no-browser] [--write] [--json FILE]
 *
 * --write also writes docs/gallery.md and a PNG thumbnail per model under docs/gallery/
 * (tone-mapped as the CLI's PNG output is: ACES filmic, sRGB). --json writes the raw
 * results. The table goes to standard output, progress to standard error.
 */
import { spawn } from 'node:child_process';
import {
  existsSync,
  mkdirSync,
  mkdtempSync,
  readFileSync,
  rmSync,
  statSync,
  writeFileSync,
} from 'node:fs';
import { tmpdir } from 'node:os';
import { basename, dirname, join, relative } from 'node:path';
import { fileURLToPath } from 'node:url';
import { deflateSync } from 'node:zlib';

const root = fileURLToPath(new URL('..', import.meta.url));
const corpusDir = join(root, 'tests/corpus');
const localDir = join(corpusDir, 'local');
const cli = join(root, 'bin/pathwise.js');

// ---------------------------------------------------------------- arguments

function parseArgs(argv) {
  const o = {
    width: 160,
    height: 120,
    spp: 16,
    threads: 2,
    only: null,
    browser: true,
    write: false,
    json: null,
    browserSpp: 2,
    browserTimeout: 120,
  };
  for (let i = 0; i < argv.length; i++) {
    const a = argv[i];
    const next = () => {
      if (i + 1 >= argv.length) throw new Error(`${a} needs a value`);
      return argv[++i];
    };
    if (a === '--width') o.width = Number(next());
    else if (a === '--height') o.height = Number(next());
    else if (a === '--spp') o.spp = Number(next());
    else if (a === '--threads') o.threads = Number(next());
    else if (a === '--only') o.only = new Set(next().split(','));
    else if (a === '--no-browser') o.browser = false;
    else if (a === '--write') o.write = true;
    else if (a === '--json') o.json = next();
    else if (a === '--browser-spp') o.browserSpp = Number(next());
    else if (a === '--browser-timeout') o.browserTimeout = Number(next());
    else if (a === '--help' || a === '-h') {
      process.stdout.write(readFileSync(fileURLToPath(import.meta.url), 'utf8').split('*/')[0]);
      process.exit(0);
    } else throw new Error(`unknown argument ${a}`);
  }
  return o;
}

// ---------------------------------------------------------------- the corpus

/** Every model of the manifest that is present here, committed ones first. */
function corpusModels(only) {
  const manifest = JSON.parse(readFileSync(join(corpusDir, 'corpus.json'), 'utf8'));
  const models = [];
  for (const m of manifest.models) {
    models.push({ ...m, committed: true, path: join(corpusDir, m.file) });
  }
  for (const m of manifest.local) {
    models.push({ ...m, committed: false, path: join(localDir, m.file) });
  }
  const present = models.filter((m) => existsSync(m.path) && (!only || only.has(m.name)));
  const absent = manifest.local.filter((m) => !existsSync(join(localDir, m.file)));
  return { present, absent, manifest };
}

/** The glTF JSON of a .glb or .gltf file. */
function gltfJson(path) {
  const bytes = readFileSync(path);
  if (bytes.length >= 20 && bytes.readUInt32LE(0) === 0x46546c67) {
    const length = bytes.readUInt32LE(12);
    return JSON.parse(bytes.subarray(20, 20 + length).toString('utf8'));
  }
  return JSON.parse(bytes.toString('utf8'));
}

/**
 * Triangles drawn by the default scene, from the accessor counts of the JSON (so also
 * for compressed files): every node instance counts, EXT_mesh_gpu_instancing included.
 */
function triangleCount(json) {
  const accessors = json.accessors ?? [];
  const meshTriangles = (mesh) => {
    let n = 0;
    for (const p of mesh.primitives ?? []) {
      const mode = p.mode ?? 4;
      const count =
        p.indices !== undefined
          ? accessors[p.indices]?.count
          : accessors[p.attributes?.POSITION]?.count;
      if (!count) continue;
      if (mode === 4) n += Math.floor(count / 3);
      else if (mode === 5 || mode === 6) n += Math.max(0, count - 2);
    }
    return n;
  };
  const scene = json.scenes?.[json.scene ?? 0];
  const roots = scene?.nodes ?? [];
  let total = 0;
  const seen = new Set();
  const visit = (index) => {
    if (seen.has(index)) return; // a malformed cycle; validate.ts refuses it anyway
    seen.add(index);
    const node = json.nodes?.[index];
    if (!node) return;
    if (node.mesh !== undefined && json.meshes?.[node.mesh]) {
      const inst = node.extensions?.EXT_mesh_gpu_instancing?.attributes;
      const first = inst ? Object.values(inst)[0] : undefined;
      const copies = first !== undefined ? (accessors[first]?.count ?? 1) : 1;
      total += copies * meshTriangles(json.meshes[node.mesh]);
    }
    for (const c of node.children ?? []) visit(c);
    seen.delete(index);
  };
  for (const r of roots) visit(r);
  return total;
}

// ---------------------------------------------------------------- messages

/** A message that a still image rightly ignores: the rest pose of an animated model. */
const REST_POSE = /rendered in its rest pose$/;
/**
 * Notes about faults of the file itself, which pathwise repairs: declared accessor bounds
 * that the decoded vertices exceed, and degenerate triangles (tests/cli/corpus-pending.ts,
 * FILE_NOTES).
 */
const FILE_FAULT =
  /the bounds are taken from the vertices$|^note: skipped \d+ triangles? of zero area$/;

/** CLI standard error → messages without the "pathwise: " and shape prefixes. */
function cliMessages(stderr, path) {
  const out = [];
  for (const line of stderr.split('\n')) {
    if (!line.startsWith('pathwise: ')) continue;
    let m = line.slice('pathwise: '.length);
    const note = /^note: shapes\[\d+\] \([^)]*\): (.*)$/.exec(m);
    if (note) m = note[1];
    else if (m.startsWith(`${path}: `)) m = `error: ${m.slice(path.length + 2)}`;
    else if (m.startsWith(`${relative(root, path)}: `)) {
      m = `error: ${m.slice(relative(root, path).length + 2)}`;
    }
    out.push(m);
  }
  return out;
}

/** Messages of the widget's warning event, without the shape prefix. */
function widgetMessages(messages) {
  return messages.map((m) => m.replace(/^shapes\[\d+\] \([^)]*\): /, ''));
}

/** Whether a message says that something the model uses was not honoured. */
function ignoring(message) {
  return !REST_POSE.test(message) && !FILE_FAULT.test(message);
}

// ---------------------------------------------------------------- images

/** A little-endian colour PFM: width, height and the RGB values (row order irrelevant here). */
function readPfm(path) {
  const bytes = readFileSync(path);
  let k = 0;
  const fields = [];
  while (fields.length < 4) {
    let s = '';
    while (k < bytes.length && !/\s/.test(String.fromCharCode(bytes[k])))
      s += String.fromCharCode(bytes[k++]);
    k++;
    fields.push(s);
  }
  const [magic, w, h, scale] = fields;
  if (magic !== 'PF' || Number(scale) >= 0) throw new Error(`${path}: not a little-endian PF`);
  const width = Number(w);
  const height = Number(h);
  const rgb = new Float32Array(width * height * 3);
  const view = new DataView(bytes.buffer, bytes.byteOffset + k);
  // Rows are stored bottom to top; flip them so row 0 is the top.
  for (let y = 0; y < height; y++) {
    for (let i = 0; i < width * 3; i++) {
      rgb[(height - 1 - y) * width * 3 + i] = view.getFloat32((y * width * 3 + i) * 4, true);
    }
  }
  return { width, height, rgb };
}

/** Finite, not blank (not one uniform value), and the mean. */
function imageStats(rgb) {
  let nonFinite = 0;
  let sum = 0;
  let min = Infinity;
  let max = -Infinity;
  for (const v of rgb) {
    if (!Number.isFinite(v)) {
      nonFinite++;
      continue;
    }
    sum += v;
    if (v < min) min = v;
    if (v > max) max = v;
  }
  return { nonFinite, mean: sum / rgb.length, blank: !(max > min) };
}

const CRC_TABLE = Array.from({ length: 256 }, (_, n) => {
  let c = n;
  for (let k = 0; k < 8; k++) c = c & 1 ? 0xedb88320 ^ (c >>> 1) : c >>> 1;
  return c >>> 0;
});
function crc32(bytes) {
  let c = 0xffffffff;
  for (const b of bytes) c = CRC_TABLE[(c ^ b) & 0xff] ^ (c >>> 8);
  return (c ^ 0xffffffff) >>> 0;
}

/** The CLI's display transform (src/core/io/tonemap.ts): ACES filmic (Narkowicz), sRGB. */
function displayByte(linear) {
  const v = linear * 0.6;
  let y = (v * (2.51 * v + 0.03)) / (v * (2.43 * v + 0.59) + 0.14);
  y = y < 0 || !Number.isFinite(y) ? 0 : y > 1 ? 1 : y;
  const s = y <= 0.0031308 ? 12.92 * y : 1.055 * Math.pow(y, 1 / 2.4) - 0.055;
  return Math.round(s * 255);
}

/** An 8-bit RGB PNG of a linear image (filter 0 rows, zlib level 9). */
function encodePng({ width, height, rgb }) {
  const raw = Buffer.alloc(height * (1 + width * 3));
  for (let y = 0; y < height; y++) {
    const row = y * (1 + width * 3);
    raw[row] = 0;
    for (let i = 0; i < width * 3; i++) raw[row + 1 + i] = displayByte(rgb[y * width * 3 + i]);
  }
  const chunk = (type, data) => {
    const head = Buffer.alloc(8);
    head.writeUInt32BE(data.length, 0);
    head.write(type, 4, 'latin1');
    const crc = Buffer.alloc(4);
    crc.writeUInt32BE(crc32(Buffer.concat([head.subarray(4), data])), 0);
    return Buffer.concat([head, data, crc]);
  };
  const ihdr = Buffer.alloc(13);
  ihdr.writeUInt32BE(width, 0);
  ihdr.writeUInt32BE(height, 4);
  ihdr.set([8, 2, 0, 0, 0], 8);
  return Buffer.concat([
    Buffer.from([0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a]),
    chunk('IHDR', ihdr),
    chunk('IDAT', deflateSync(raw, { level: 9 })),
    chunk('IEND', Buffer.alloc(0)),
  ]);
}

// ---------------------------------------------------------------- the CLI

function run(command, args) {
  return new Promise((resolve) => {
    const child = spawn(command, args, { cwd: root, stdio: ['ignore', 'pipe', 'pipe'] });
    let stdout = '';
    let stderr = '';
    child.stdout.on('data', (d) => (stdout += d));
    child.stderr.on('data', (d) => (stderr += d));
    child.on('close', (code) => resolve({ code, stdout, stderr }));
  });
}

/** One CLI render of `model`: statistics, messages, image checks; the image itself. */
async function renderCli(model, o, work) {
  const out = join(work, `${model.name}.pfm`);
  const rss = join(work, `${model.name}.rss`);
  rmSync(out, { force: true });
  const args = [
    cli,
    'render',
    model.path,
    '--width',
    String(o.width),
    '--height',
    String(o.height),
    '--spp',
    String(o.spp),
    '--threads',
    String(o.threads),
    '--json',
    '--out',
    out,
  ];
  // /usr/bin/time gives the peak resident set of the whole process (workers included).
  const timed = existsSync('/usr/bin/time');
  const started = performance.now();
  const r = timed
    ? await run('/usr/bin/time', ['-f', '%M', '-o', rss, process.execPath, ...args])
    : await run(process.execPath, args);
  const wall = (performance.now() - started) / 1000;
  const messages = cliMessages(r.stderr, model.path);
  const result = { exit: r.code, wall, messages };
  if (timed && existsSync(rss)) {
    const kb = Number(readFileSync(rss, 'utf8').trim().split('\n').pop());
    if (Number.isFinite(kb)) result.peakMb = kb / 1024;
  }
  const line = r.stdout.trim().split('\n').pop();
  if (r.code === 0 && line) {
    const stats = JSON.parse(line);
    result.renderSeconds = stats.seconds;
    // Everything before the render: Node's start, reading and decoding the model, the BVH.
    result.loadSeconds = wall - stats.seconds;
    result.mpathsPerS = stats.mpaths_per_s;
  }
  let image = null;
  if (r.code === 0 && existsSync(out)) {
    image = readPfm(out);
    Object.assign(result, imageStats(image.rgb));
  }
  result.ok =
    r.code === 0 &&
    image !== null &&
    result.nonFinite === 0 &&
    !result.blank &&
    !messages.some(ignoring);
  return { result, image };
}

// ---------------------------------------------------------------- Chromium

/**
 * Renders each model through <pathwise-view> in headless Chromium: the Vite dev server
 * of this checkout (with its cross-origin isolation headers) serves the widget from the
 * sources and the model files from tests/corpus/; Debian's Chromium is driven by
 * playwright-core as the tests drive it (scripts/chromium.mjs).
 */
async function renderBrowser(models, o, log) {
  const results = new Map();
  const { CHROMIUM, launchChromium } = await import('./chromium.mjs');
  if (!existsSync(CHROMIUM)) {
    for (const m of models) results.set(m.name, { ok: false, error: `${CHROMIUM} missing` });
    return results;
  }
  const { createServer } = await import('vite');
  const cacheDir = mkdtempSync(join(tmpdir(), 'pathwise-vite-'));
  const server = await createServer({
    root,
    cacheDir,
    server: { host: '127.0.0.1', port: 0, strictPort: false, hmr: false },
    logLevel: 'error',
  });
  await server.listen();
  const url = server.resolvedUrls.local[0];
  const browser = await launchChromium();
  try {
    for (const m of models) {
      log(`chromium: ${m.name}`);
      const context = await browser.newContext({ viewport: { width: 800, height: 600 } });
      const page = await context.newPage();
      const pageErrors = [];
      page.on('pageerror', (e) => pageErrors.push(e.message));
      const started = performance.now();
      try {
        await page.goto(`${url}tests/browser/fixtures/widget.html`);
        await page.waitForFunction(() => window.__ready === true, null, { timeout: 60_000 });
        const src = `/${relative(root, m.path).split('\\').join('/')}`;
        const r = await page.evaluate(
          async ({ src, spp, width, height, timeout }) => {
            const el = document.createElement('pathwise-view');
            el.setAttribute('spp', String(spp));
            el.setAttribute('src', src);
            el.style.width = `${width}px`;
            el.style.height = `${height}px`;
            const events = [];
            for (const t of ['load', 'warning', 'converged', 'error']) {
              el.addEventListener(t, (e) => events.push({ type: t, detail: e.detail }));
            }
            document.body.append(el);
            const done = await new Promise((resolve) => {
              const until = performance.now() + timeout * 1000;
              const poll = () => {
                if (events.some((e) => e.type === 'converged' || e.type === 'error')) resolve(true);
                else if (performance.now() > until) resolve(false);
                else setTimeout(poll, 100);
              };
              poll();
            });
            const error = events.find((e) => e.type === 'error')?.detail?.message ?? null;
            const warnings = events
              .filter((e) => e.type === 'warning')
              .flatMap((e) => e.detail?.messages ?? []);
            let rgb = null;
            if (done && !error) rgb = Array.from(el.controller.readLinear().rgb);
            el.remove();
            return { done, error, warnings, rgb };
          },
          {
            src,
            spp: o.browserSpp,
            width: 64,
            height: 48,
            timeout: o.browserTimeout,
          },
        );
        const messages = widgetMessages(r.warnings);
        if (r.error) messages.push(`error: ${r.error.replace(/^[^:]*: /, '')}`);
        const stats = r.rgb ? imageStats(r.rgb) : {};
        results.set(m.name, {
          seconds: (performance.now() - started) / 1000,
          timedOut: !r.done,
          messages,
          pageErrors,
          ...stats,
          ok:
            r.done &&
            !r.error &&
            r.rgb !== null &&
            stats.nonFinite === 0 &&
            !stats.blank &&
            pageErrors.length === 0 &&
            !messages.some(ignoring),
        });
      } catch (e) {
        results.set(m.name, { ok: false, messages: [`error: ${e.message.split('\n')[0]}`] });
      } finally {
        await context.close();
      }
    }
  } finally {
    await browser.close();
    await server.close();
    rmSync(cacheDir, { recursive: true, force: true });
  }
  return results;
}

// ---------------------------------------------------------------- the table

const fmt = (v, digits) => (v === undefined || v === null ? '–' : v.toFixed(digits));

function extensionsCell(json) {
  const required = new Set(json.extensionsRequired ?? []);
  const used = json.extensionsUsed ?? [];
  if (used.length === 0) return '–';
  return used.map((e) => (required.has(e) ? `${e}*` : e)).join(', ');
}

function verdict(r) {
  if (!r) return 'not run';
  if (r.ok) return '✅';
  if (r.timedOut) return '❌ timed out';
  const err = r.messages?.find((m) => m.startsWith('error: '));
  if (err || r.exit > 0) return '❌ fails';
  if (r.nonFinite > 0) return '❌ non-finite';
  if (r.blank) return '❌ blank';
  const ignored = (r.messages ?? []).filter(ignoring).length;
  return ignored ? `❌ ${ignored} ignored` : '❌';
}

function sourceCell(m) {
  if (!m.committed) return `local: ${m.origin}`;
  return m.originUrl ? `[${m.title}](${m.originUrl})` : m.title;
}

function table(rows, withBrowser, links = false) {
  const head = [
    'model',
    'source',
    'licence',
    'extensions (used; * required)',
    'triangles',
    'load s',
    'peak MB',
    'M paths/s',
    'CLI',
    'Chromium',
  ];
  const lines = [`| ${head.join(' | ')} |`, `|${head.map(() => '---').join('|')}|`];
  for (const { model: m, info, cli, browser } of rows) {
    const name = links && m.thumb ? `[${m.name}](#${m.name.toLowerCase()})` : m.name;
    lines.push(
      `| ${[
        name,
        sourceCell(m),
        m.licence,
        info.extensions,
        info.triangles.toLocaleString('en-US'),
        fmt(cli.loadSeconds, 2),
        fmt(cli.peakMb, 0),
        fmt(cli.mpathsPerS, 3),
        verdict(cli),
        withBrowser ? verdict(browser) : 'not run',
      ].join(' | ')} |`,
    );
  }
  return lines.join('\n');
}

function messagesSection(rows, withBrowser) {
  const lines = [];
  for (const { model: m, cli, browser } of rows) {
    const c = cli.messages ?? [];
    const b = browser?.messages ?? [];
    if (c.length === 0 && b.length === 0) continue;
    lines.push(`- **${m.name}**`);
    for (const msg of c) lines.push(`  - CLI: ${msg.replace(/\|/g, '\\|')}`);
    if (withBrowser) {
      const same = b.length === c.length && b.every((x, i) => x === c[i]);
      if (same && b.length) lines.push('  - Chromium: the same messages');
      else for (const msg of b) lines.push(`  - Chromium: ${msg.replace(/\|/g, '\\|')}`);
    }
  }
  return lines.join('\n');
}

// ---------------------------------------------------------------- main

async function main() {
  const o = parseArgs(process.argv.slice(2));
  if (!existsSync(join(root, 'dist/cli/pathwise.js'))) {
    throw new Error('dist/cli is missing: run `npm run build:cli` first');
  }
  const log = (s) => process.stderr.write(`corpus: ${s}\n`);
  const { present, absent, manifest } = corpusModels(o.only);
  const work = mkdtempSync(join(tmpdir(), 'pathwise-corpus-'));
  const thumbs = join(root, 'docs/gallery');
  if (o.write) mkdirSync(thumbs, { recursive: true });
  const rows = [];
  try {
    for (const m of present) {
      log(`cli: ${m.name}`);
      const json = gltfJson(m.path);
      const info = { extensions: extensionsCell(json), triangles: triangleCount(json) };
      const { result, image } = await renderCli(m, o, work);
      // Thumbnails only of committed models: the others' licences are unclear or unchecked.
      if (o.write && image && m.committed) {
        const png = encodePng(image);
        writeFileSync(join(thumbs, `${m.name}.png`), png);
        m.thumb = `gallery/${m.name}.png`;
      }
      rows.push({ model: m, info, cli: result, browser: null });
    }
    if (o.browser) {
      const browser = await renderBrowser(
        rows.map((r) => r.model),
        o,
        log,
      );
      for (const r of rows) r.browser = browser.get(r.model.name);
    }
  } finally {
    rmSync(work, { recursive: true, force: true });
  }
  const settings =
    `CLI: ${o.width}×${o.height}, ${o.spp} spp, ${o.threads} thread(s); ` +
    (o.browser ? `Chromium: <pathwise-view> 64×48, ${o.browserSpp} spp` : 'Chromium: not run');
  const md = `${table(rows, o.browser)}\n\n${settings}\n`;
  process.stdout.write(md);
  const messages = messagesSection(rows, o.browser);
  if (messages) process.stdout.write(`\nMessages:\n\n${messages}\n`);
  if (o.json) {
    writeFileSync(
      o.json,
      JSON.stringify(
        rows.map((r) => ({
          name: r.model.name,
          committed: r.model.committed,
          ...r.info,
          cli: r.cli,
          browser: r.browser,
        })),
        null,
        1,
      ),
    );
  }
  if (o.write) await writeGallery(rows, absent, manifest, o, settings, messages);
  const failed = rows.filter((r) => !r.cli.ok || (o.browser && !r.browser?.ok)).length;
  log(`${rows.length} model(s), ${failed} not yet rendering cleanly everywhere`);
}

async function writeGallery(rows, absent, manifest, o, settings, messages) {
  const committed = rows.filter((r) => r.model.committed);
  const compressed = committed.filter((r) =>
    /KHR_draco_mesh_compression|EXT_meshopt_compression|KHR_meshopt_compression/.test(
      r.info.extensions,
    ),
  ).length;
  const date = new Date().toISOString().slice(0, 10);
  const out = [];
  out.push('# Gallery: real-world glTF models');
  out.push('');
  out.push(
    'Generated by `node scripts/corpus.mjs --write` (after `npm run build:cli`); do not edit by hand. ' +
      `Last run: ${date}. The corpus is tests/corpus/corpus.json: ${committed.length} models ` +
      `committed under tests/corpus/ (${compressed} of them compressed with Draco or meshopt), each ` +
      'with its licence file(s) and a SOURCE.md; models that could not be committed are listed at the ' +
      'end with their source, and the script renders any of them placed under tests/corpus/local/.',
  );
  out.push('');
  out.push(
    '**Success** (✅) means: the render finished, every value is finite, the image is not blank ' +
      '(one uniform colour), and no message says that something the model uses was ignored or ' +
      'is not supported. A note that an animated model is shown in its rest pose is not a failure, ' +
      'nor is a note about a fault of the file that pathwise repairs (declared bounds that the ' +
      'vertices exceed, zero-area triangles). ' +
      '❌ *n* ignored counts such messages (listed below the table); ❌ fails means the file was ' +
      'refused. **load s** is the wall time of the CLI process minus its render time: Node start ' +
      '(about 0.3 s), reading, decoding, and building the BVH. **peak MB** is the peak resident ' +
      'set of the CLI process, workers included. **M paths/s** is what the CLI reports ' +
      '(`mpaths_per_s` of `--json`: paths over the render’s seconds, which at this small size ' +
      'include the workers’ start) on a machine shared with other jobs: a rough figure, not a ' +
      'benchmark (see BENCHMARKS.md). Triangles count every node instance (GPU instancing included) ' +
      'from the file’s accessor counts.',
  );
  out.push('');
  out.push(settings + '.');
  out.push('');
  out.push(table(rows, o.browser, true));
  out.push('');
  if (messages) {
    out.push('## Messages');
    out.push('');
    out.push(messages);
    out.push('');
  }
  out.push('## Renders');
  out.push('');
  out.push('Rendered by the CLI at the size above, tone-mapped as its PNG output is.');
  out.push('');
  for (const { model: m } of rows) {
    if (!m.thumb) continue;
    out.push(`### ${m.name}`);
    out.push('');
    out.push(`![${m.title}](${m.thumb})`);
    out.push('');
  }
  out.push('## Attributions');
  out.push('');
  out.push(
    'The committed models are redistributed under their own licences, unchanged; each folder under ' +
      'tests/corpus/ has the licence file(s) of its origin and a SOURCE.md saying where the copy came ' +
      'from (repository, commit, path).',
  );
  out.push('');
  for (const m of manifest.models) {
    const lic =
      {
        'CC-BY-4.0': '[CC BY 4.0](https://creativecommons.org/licenses/by/4.0/)',
        'CC0-1.0': '[CC0 1.0](https://creativecommons.org/publicdomain/zero/1.0/)',
        'LicenseRef-CC-BY-TM':
          '[CC BY 4.0](https://creativecommons.org/licenses/by/4.0/), trademarks excluded',
        MIT: 'MIT',
      }[m.licence] ?? m.licence;
    out.push(
      `- **${m.title}** (\`tests/corpus/${m.file}\`) by ${m.author}; ${m.owner}; ${lic}. ` +
        `Source: ${m.originUrl}.${m.notes ? ` ${m.notes[0].toUpperCase()}${m.notes.slice(1)}.` : ''}`,
    );
  }
  out.push('');
  out.push('## Not committed');
  out.push('');
  out.push(
    'Put a file at `tests/corpus/local/<file>` (the folder is ignored by git) and the script renders it.',
  );
  out.push('');
  out.push('| model | file under tests/corpus/local/ | licence | source | why not committed |');
  out.push('|---|---|---|---|---|');
  for (const m of manifest.local) {
    const here = absent.some((a) => a.name === m.name) ? '' : ' (present here)';
    out.push(`| ${m.name}${here} | \`${m.file}\` | ${m.licence} | ${m.origin} | ${m.reason} |`);
  }
  out.push('');
  // In the project's style, so that `npm run format:check` passes on the generated file.
  const path = join(root, 'docs/gallery.md');
  const prettier = await import('prettier');
  const options = (await prettier.resolveConfig(path)) ?? {};
  writeFileSync(path, await prettier.format(out.join('\n'), { ...options, filepath: path }));
}

await main().catch((e) => {
  process.stderr.write(`corpus: ${e.stack ?? e}\n`);
  process.exit(1);
});
