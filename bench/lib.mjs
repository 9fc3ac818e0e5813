// Shared helpers of the benchmarks: running the command line, reading PFM,
// error metrics against the Mitsuba references, statistics and hand-written
// SVG plots (no plotting dependency).
import { execFileSync, spawnSync } from 'node:child_process';
import { existsSync, readFileSync } from 'node:fs';
import os from 'node:os';
import { fileURLToPath } from 'node:url';

export const ROOT = fileURLToPath(new URL('..', import.meta.url));
export const CLI = fileURLToPath(new URL('../bin/pathwise.js', import.meta.url));

/** What the figures were measured on: absolute times only compare within one machine. */
export function machineInfo() {
  let commit = null;
  let dirty = null;
  // A copy of the tree on another machine names its commit here.
  if (process.env.PATHWISE_GIT_COMMIT) return machineFields(process.env.PATHWISE_GIT_COMMIT, null);
  try {
    commit = execFileSync('git', ['rev-parse', 'HEAD'], { cwd: ROOT, encoding: 'utf8' }).trim();
    dirty =
      execFileSync('git', ['status', '--porcelain'], { cwd: ROOT, encoding: 'utf8' }).trim() !== '';
  } catch {
    // Not a git checkout, and no commit named: leave it null.
    commit = null;
  }
  return machineFields(commit, dirty);
}

function machineFields(commit, dirty) {
  return {
    cpu: os.cpus()[0]?.model ?? 'unknown',
    cores: os.availableParallelism(),
    memory_gib: +(os.totalmem() / 2 ** 30).toFixed(1),
    platform: `${os.platform()} ${os.release()} ${os.arch()}`,
    hostname: os.hostname(),
    node: process.version,
    v8: process.versions.v8,
    date: new Date().toISOString(),
    git_commit: commit,
    git_dirty: dirty,
    loadavg_start: os.loadavg(),
  };
}

const TIME = existsSync('/usr/bin/time') ? '/usr/bin/time' : null;

/**
 * The command line (node's arguments) of one render: scene, width, height,
 * spp, threads, out; seed (default 1); bounces, estimator and sampler when
 * given, else the CLI's defaults apply (what bench:core measures).
 */
export function cliArgs(opts) {
  const args = [
    CLI,
    'render',
    opts.scene,
    '--width',
    String(opts.width),
    '--height',
    String(opts.height),
    '--spp',
    String(opts.spp),
    '--threads',
    String(opts.threads),
    '--seed',
    String(opts.seed ?? 1),
    '--json',
    '--out',
    opts.out,
  ];
  if (opts.bounces !== undefined) args.push('--bounces', String(opts.bounces));
  if (opts.estimator !== undefined) args.push('--estimator', opts.estimator);
  if (opts.sampler !== undefined) args.push('--sampler', opts.sampler);
  if (opts.adaptive !== undefined) args.push('--adaptive', opts.adaptive ? 'on' : 'off');
  return args;
}

/**
 * Renders one configuration in a fresh process (so no run warms the JIT of
 * another) and returns the CLI's JSON statistics plus the process wall time.
 */
export function renderOnce(opts) {
  const args = cliArgs(opts);
  const t0 = performance.now();
  // GNU time, where there is one, adds the CPU seconds of the process: unlike
  // wall time they barely change when other processes share the cores.
  const r = TIME
    ? spawnSync(TIME, ['-f', 'cpu %U %S', process.execPath, ...args], {
        cwd: ROOT,
        encoding: 'utf8',
      })
    : spawnSync(process.execPath, args, { cwd: ROOT, encoding: 'utf8' });
  const processSeconds = (performance.now() - t0) / 1000;
  if (r.status !== 0) {
    throw new Error(`pathwise ${args.slice(1).join(' ')} failed (${r.status}): ${r.stderr}`);
  }
  const line = r.stdout.trim().split('\n').pop();
  const cpu = /cpu ([\d.]+) ([\d.]+)\s*$/.exec(r.stderr ?? '');
  return {
    ...JSON.parse(line),
    process_seconds: processSeconds,
    cpu_seconds: cpu ? Number(cpu[1]) + Number(cpu[2]) : null,
  };
}

/** Reads a colour PFM into top-to-bottom RGB floats (same layout as the core's decodePfm). */
export function readPfm(path) {
  const bytes = readFileSync(path);
  let pos = 0;
  const tokens = [];
  const isSpace = (b) => b === 0x20 || b === 0x0a || b === 0x0d || b === 0x09;
  while (tokens.length < 4) {
    while (isSpace(bytes[pos])) pos++;
    let tok = '';
    while (pos < bytes.length && !isSpace(bytes[pos])) tok += String.fromCharCode(bytes[pos++]);
    tokens.push(tok);
  }
  pos++;
  const [magic, ws, hs, ss] = tokens;
  if (magic !== 'PF') throw new Error(`${path}: not a colour PFM`);
  const width = Number(ws);
  const height = Number(hs);
  const little = Number(ss) < 0;
  const view = new DataView(bytes.buffer, bytes.byteOffset + pos);
  const rgb = new Float32Array(width * height * 3);
  // Rows are stored bottom to top.
  let k = 0;
  for (let y = height - 1; y >= 0; y--) {
    for (let i = y * width * 3, end = i + width * 3; i < end; i++) {
      rgb[i] = view.getFloat32(k, little);
      k += 4;
    }
  }
  return { width, height, rgb };
}

/**
 * Relative MSE as the issue defines it: mean over pixels and channels of
 * (x − r)² / (r² + 0.01). The 0.01 keeps black pixels from dominating.
 */
export function relMse(x, r) {
  let s = 0;
  for (let i = 0; i < r.length; i++) {
    const d = x[i] - r[i];
    s += (d * d) / (r[i] * r[i] + 0.01);
  }
  return s / r.length;
}

/**
 * Mean absolute relative error of block averages: the image is cut into
 * block × block tiles (partial tiles at the edges kept), each channel
 * averaged per tile, and |x̄ − r̄| / (r̄ + 0.01) averaged over tiles and
 * channels. It sees low-frequency bias that per-pixel noise hides.
 */
export function blockMare(x, r, width, height, block = 8) {
  let s = 0;
  let n = 0;
  for (let by = 0; by < height; by += block) {
    for (let bx = 0; bx < width; bx += block) {
      for (let c = 0; c < 3; c++) {
        let sx = 0;
        let sr = 0;
        let count = 0;
        for (let y = by; y < Math.min(height, by + block); y++) {
          for (let xx = bx; xx < Math.min(width, bx + block); xx++) {
            const i = (y * width + xx) * 3 + c;
            sx += x[i];
            sr += r[i];
            count++;
          }
        }
        s += Math.abs(sx - sr) / count / (Math.abs(sr / count) + 0.01);
        n++;
      }
    }
  }
  return s / n;
}

export function median(values) {
  const v = [...values].sort((a, b) => a - b);
  const m = v.length >> 1;
  return v.length % 2 ? v[m] : (v[m - 1] + v[m]) / 2;
}

/** Least-squares slope and intercept of log10(y) against log10(x). */
export function logLogFit(points) {
  const n = points.length;
  if (n < 2) return { slope: null, intercept: null, n };
  let sx = 0,
    sy = 0,
    sxx = 0,
    sxy = 0;
  for (const [x, y] of points) {
    const lx = Math.log10(x);
    const ly = Math.log10(y);
    sx += lx;
    sy += ly;
    sxx += lx * lx;
    sxy += lx * ly;
  }
  const slope = (n * sxy - sx * sy) / (n * sxx - sx * sx);
  return { slope, intercept: (sy - slope * sx) / n, n };
}

/**
 * y at x on the log-log polyline through `points` (sorted by x). Outside
 * the range, extrapolates along the end segment; returns null for fewer
 * than two points.
 */
export function logLogInterp(points, x) {
  const p = [...points].sort((a, b) => a[0] - b[0]);
  if (p.length < 2) return null;
  let i = 0;
  while (i < p.length - 2 && p[i + 1][0] < x) i++;
  const [x0, y0] = p[i];
  const [x1, y1] = p[i + 1];
  const t = (Math.log(x) - Math.log(x0)) / (Math.log(x1) - Math.log(x0));
  return Math.exp(Math.log(y0) + t * (Math.log(y1) - Math.log(y0)));
}

/** x where the log-log polyline through (x, y) first falls to `target`, or null if it never does. */
export function logLogCrossing(points, target) {
  const p = [...points].sort((a, b) => a[0] - b[0]);
  for (let i = 0; i + 1 < p.length; i++) {
    const [x0, y0] = p[i];
    const [x1, y1] = p[i + 1];
    if (y0 >= target && y1 <= target) {
      if (y0 === y1) return x0;
      const t = (Math.log(target) - Math.log(y0)) / (Math.log(y1) - Math.log(y0));
      return Math.exp(Math.log(x0) + t * (Math.log(x1) - Math.log(x0)));
    }
  }
  if (p.length && p[0][1] <= target) return p[0][0];
  return null;
}

/**
 * Seconds to relMSE `target` of a sweep of renders ({ seconds, error }, by time): the
 * log-log crossing, or, where the sweep ended above it, the last render's time scaled as
 * error ∝ 1/time ({ extrapolated: true }).
 */
export function timeToError(points, target) {
  const crossing = logLogCrossing(
    points.map((p) => [p.seconds, p.error]),
    target,
  );
  if (crossing !== null) return { seconds: crossing, extrapolated: false };
  const last = points.at(-1);
  return { seconds: (last.seconds * last.error) / target, extrapolated: true };
}

// ---------------------------------------------------------------- SVG plots

const COLORS = ['#1f77b4', '#d62728', '#2ca02c', '#ff7f0e', '#9467bd', '#8c564b', '#e377c2'];
export const color = (i) => COLORS[i % COLORS.length];

const esc = (s) => String(s).replace(/&/g, '&amp;').replace(/</g, '&lt;').replace(/>/g, '&gt;');

function fmtTick(v) {
  const e = Math.round(Math.log10(v));
  if (e >= 0 && e <= 4) return String(10 ** e);
  if (e < 0 && e >= -2) return String(+(10 ** e).toFixed(-e));
  return `1e${e}`;
}

/**
 * A plot with log or linear axes. series: [{ name, color, points: [[x, y]],
 * dash?, marker? }]. Hand-written SVG so the report needs no plotting
 * package.
 */
export function plotSvg({ title, xLabel, yLabel, series, logX = true, logY = true }) {
  const W = 640,
    H = 420,
    L = 70,
    R = 190,
    T = 36,
    B = 52;
  const pw = W - L - R,
    ph = H - T - B;
  const all = series.flatMap((s) => s.points).filter(([x, y]) => isFinite(x) && isFinite(y));
  const fx = logX ? Math.log10 : (v) => v;
  const fy = logY ? Math.log10 : (v) => v;
  let x0 = Math.min(...all.map((p) => fx(p[0])));
  let x1 = Math.max(...all.map((p) => fx(p[0])));
  let y0 = Math.min(...all.map((p) => fy(p[1])));
  let y1 = Math.max(...all.map((p) => fy(p[1])));
  if (logX) {
    x0 = Math.floor(x0);
    x1 = Math.ceil(x1);
  } else {
    x0 = Math.min(0, x0);
    x1 = x1 * 1.05;
  }
  if (logY) {
    y0 = Math.floor(y0);
    y1 = Math.ceil(y1);
  } else {
    y0 = Math.min(0, y0);
    y1 = y1 * 1.08;
  }
  if (x1 === x0) x1 = x0 + 1;
  if (y1 === y0) y1 = y0 + 1;
  const sx = (v) => L + ((fx(v) - x0) / (x1 - x0)) * pw;
  const sy = (v) => T + ph - ((fy(v) - y0) / (y1 - y0)) * ph;
  const out = [];
  out.push(
    `<svg xmlns="http://www.w3.org/2000/svg" width="${W}" height="${H}" viewBox="0 0 ${W} ${H}" font-family="sans-serif" font-size="12">`,
    `<rect width="${W}" height="${H}" fill="white"/>`,
    `<text x="${L + pw / 2}" y="20" text-anchor="middle" font-size="14" font-weight="bold">${esc(title)}</text>`,
  );
  // Grid and ticks.
  const ticks = (lo, hi, log) => {
    if (log) {
      const t = [];
      for (let e = lo; e <= hi; e++) t.push(10 ** e);
      return t;
    }
    const span = hi - lo;
    const step = 10 ** Math.floor(Math.log10(span / 5));
    const nice = [1, 2, 5, 10].map((m) => m * step).find((s) => span / s <= 8) ?? step * 10;
    const t = [];
    for (let v = Math.ceil(lo / nice) * nice; v <= hi + 1e-9; v += nice) t.push(+v.toPrecision(6));
    return t;
  };
  for (const v of ticks(x0, x1, logX)) {
    const X = sx(v);
    out.push(
      `<line x1="${X}" y1="${T}" x2="${X}" y2="${T + ph}" stroke="#ddd"/>`,
      `<text x="${X}" y="${T + ph + 16}" text-anchor="middle">${logX ? fmtTick(v) : v}</text>`,
    );
  }
  for (const v of ticks(y0, y1, logY)) {
    const Y = sy(v);
    out.push(
      `<line x1="${L}" y1="${Y}" x2="${L + pw}" y2="${Y}" stroke="#ddd"/>`,
      `<text x="${L - 6}" y="${Y + 4}" text-anchor="end">${logY ? fmtTick(v) : v}</text>`,
    );
  }
  out.push(
    `<rect x="${L}" y="${T}" width="${pw}" height="${ph}" fill="none" stroke="#333"/>`,
    `<text x="${L + pw / 2}" y="${H - 12}" text-anchor="middle">${esc(xLabel)}</text>`,
    `<text transform="translate(16 ${T + ph / 2}) rotate(-90)" text-anchor="middle">${esc(yLabel)}</text>`,
  );
  // Clip the lines to the plot area (reference lines may leave it).
  out.push(
    `<clipPath id="plot"><rect x="${L}" y="${T}" width="${pw}" height="${ph}"/></clipPath>`,
    `<g clip-path="url(#plot)">`,
  );
  for (const s of series) {
    const pts = s.points.filter(([x, y]) => isFinite(x) && isFinite(y) && (!logY || y > 0));
    if (!pts.length) continue;
    const d = pts
      .map(([x, y], i) => `${i ? 'L' : 'M'}${sx(x).toFixed(1)},${sy(y).toFixed(1)}`)
      .join(' ');
    out.push(
      `<path d="${d}" fill="none" stroke="${s.color}" stroke-width="${s.dash ? 1.2 : 2}"${s.dash ? ` stroke-dasharray="${s.dash}"` : ''}/>`,
    );
    if (s.marker !== false) {
      for (const [x, y] of pts) {
        out.push(
          `<circle cx="${sx(x).toFixed(1)}" cy="${sy(y).toFixed(1)}" r="2.8" fill="${s.color}"/>`,
        );
      }
    }
  }
  out.push('</g>');
  // Legend.
  series.forEach((s, i) => {
    const Y = T + 10 + i * 18;
    out.push(
      `<line x1="${L + pw + 12}" y1="${Y}" x2="${L + pw + 36}" y2="${Y}" stroke="${s.color}" stroke-width="2"${s.dash ? ` stroke-dasharray="${s.dash}"` : ''}/>`,
      `<text x="${L + pw + 42}" y="${Y + 4}">${esc(s.name)}</text>`,
    );
  });
  out.push('</svg>');
  return out.join('\n') + '\n';
}
