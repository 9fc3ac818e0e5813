/**
 * A campaign: the valid baseline of every format, then cases 0 … n−1 of a seed run a few at a
 * time, each judged by classify.ts and then against its format's baseline (the acceptance
 * of issue 27: no input costs more than 2 s or 512 MB above a valid file of its format).
 * Failing cases are written to a folder, one sub-folder each, to be replayed.
 */
import { mkdirSync, readFileSync, readdirSync, statSync, writeFileSync } from 'node:fs';
import { join, relative } from 'node:path';
import { FORMAT_NAMES, makeCase, type FuzzCase } from './cases.ts';
import { FAILURES, GOOD, isFailure, type Outcome } from './classify.ts';
import { runCase, writeCase, type CaseResult, type RunOptions } from './runner.ts';

export interface CampaignOptions extends Omit<RunOptions, 'keep'> {
  seed: number;
  cases: number;
  /** Cases run at once. */
  jobs: number;
  /** Valid runs per format for its baseline (the median is taken). */
  baselineRuns: number;
  /** Above the format's baseline: seconds for `slow`, MiB for `heavy`. */
  slowSeconds: number;
  heavyMiB: number;
  /** Where failing cases are saved (none if undefined). */
  failDir?: string;
  log?: (line: string) => void;
}

export interface Baseline {
  seconds: number;
  rssMiB: number;
}

export interface CampaignReport {
  results: CaseResult[];
  baselines: Record<string, Baseline>;
  failures: CaseResult[];
}

const median = (xs: number[]) => [...xs].sort((a, b) => a - b)[Math.floor(xs.length / 2)] ?? 0;

async function pool<T, R>(items: T[], jobs: number, f: (t: T) => Promise<R>): Promise<R[]> {
  const out: R[] = new Array(items.length);
  let next = 0;
  await Promise.all(
    Array.from({ length: Math.min(jobs, items.length) }, async () => {
      while (next < items.length) {
        const i = next++;
        out[i] = await f(items[i]);
      }
    }),
  );
  return out;
}

/** Judges a result against its format's baseline: slow or heavy, if a good outcome was costly. */
export function judge(
  r: CaseResult,
  b: Baseline | undefined,
  o: Pick<CampaignOptions, 'slowSeconds' | 'heavyMiB'>,
): CaseResult {
  if (!b || isFailure(r.outcome)) return r;
  if (r.seconds > b.seconds + o.slowSeconds) {
    return {
      ...r,
      outcome: 'slow',
      why: `${r.seconds.toFixed(2)} s, baseline ${b.seconds.toFixed(2)} s (was ${r.outcome})`,
    };
  }
  if (r.rssMiB > b.rssMiB + o.heavyMiB) {
    return {
      ...r,
      outcome: 'heavy',
      why: `${r.rssMiB.toFixed(0)} MiB, baseline ${b.rssMiB.toFixed(0)} MiB (was ${r.outcome})`,
    };
  }
  return r;
}

export async function baselines(o: CampaignOptions): Promise<Record<string, Baseline>> {
  const n = FORMAT_NAMES.length;
  const cases: FuzzCase[] = [];
  for (let k = 0; k < o.baselineRuns; k++)
    for (let f = 0; f < n; f++) cases.push(makeCase(o.seed, k * n + f, true));
  const rs = await pool(cases, o.jobs, (c) => runCase(c, o));
  const out: Record<string, Baseline> = {};
  for (const format of FORMAT_NAMES) {
    const mine = rs.filter((r) => r.format === format);
    const good = mine.filter((r) => r.outcome === 'image' || r.outcome === 'note');
    const use = good.length > 0 ? good : mine;
    out[format] = {
      seconds: median(use.map((r) => r.seconds)),
      rssMiB: median(use.map((r) => r.rssMiB)),
    };
  }
  return out;
}

export function saveCase(dir: string, c: FuzzCase, r: CaseResult): string {
  const sub = join(dir, r.outcome, `${c.format}-${c.seed}-${c.index}`);
  mkdirSync(sub, { recursive: true });
  writeCase(sub, c);
  writeFileSync(join(sub, 'result.json'), JSON.stringify(r, null, 2) + '\n');
  return sub;
}

export async function runCampaign(o: CampaignOptions): Promise<CampaignReport> {
  const log = o.log ?? (() => undefined);
  const base = await baselines(o);
  for (const [f, b] of Object.entries(base))
    log(`baseline ${f}: ${b.seconds.toFixed(2)} s, ${b.rssMiB.toFixed(0)} MiB`);
  const indices = Array.from({ length: o.cases }, (_, i) => i);
  let done = 0;
  const results = await pool(indices, o.jobs, async (i) => {
    const c = makeCase(o.seed, i);
    const r = judge(await runCase(c, o), base[c.format], o);
    if (isFailure(r.outcome)) {
      const where = o.failDir ? saveCase(o.failDir, c, r) : '';
      log(`FAIL ${r.outcome} ${r.id} ${r.format} [${r.variant}] ${r.mutation}: ${r.why} ${where}`);
    }
    if (++done % 100 === 0) log(`${done}/${o.cases} cases`);
    return r;
  });
  return { results, baselines: base, failures: results.filter((r) => isFailure(r.outcome)) };
}

/** Cases saved by saveCase under `dir` (any depth), read back. */
export function loadSaved(dir: string): FuzzCase[] {
  const out: FuzzCase[] = [];
  const walk = (d: string) => {
    if (readdirSync(d).includes('case.json')) {
      const meta = JSON.parse(readFileSync(join(d, 'case.json'), 'utf8'));
      const files: Record<string, Uint8Array> = {};
      const collect = (x: string) => {
        for (const name of readdirSync(x)) {
          const p = join(x, name);
          if (statSync(p).isDirectory()) collect(p);
          else if (x !== d || !['case.json', 'result.json'].includes(name))
            files[relative(d, p)] = readFileSync(p);
        }
      };
      collect(d);
      const [seed, index] = String(meta.id).split(':').map(Number);
      out.push({ ...meta, seed, index, files });
      return;
    }
    for (const name of readdirSync(d))
      if (statSync(join(d, name)).isDirectory()) walk(join(d, name));
  };
  walk(dir);
  return out;
}

/** The table of issue 27's acceptance: counts per format and outcome, worst time and RSS. */
export function table(rep: CampaignReport): string {
  const outcomes = [...GOOD, ...FAILURES].filter((o) =>
    rep.results.some((r) => r.outcome === o),
  ) as Outcome[];
  const formats = [...new Set(rep.results.map((r) => r.format))];
  const w = Math.max(8, ...outcomes.map((o) => o.length));
  const row = (name: string, cells: (string | number)[]) =>
    `${name.padEnd(8)}${cells.map((c) => String(c).padStart(w + 1)).join('')}`;
  const lines = [row('format', [...outcomes, 'total'])];
  for (const f of formats) {
    const mine = rep.results.filter((r) => r.format === f);
    lines.push(
      row(f, [
        ...outcomes.map((o) => mine.filter((r) => r.outcome === o).length || '.'),
        mine.length,
      ]),
    );
  }
  lines.push(
    row('all', [
      ...outcomes.map((o) => rep.results.filter((r) => r.outcome === o).length),
      rep.results.length,
    ]),
  );
  const worst = (key: 'seconds' | 'rssMiB', above: boolean) =>
    rep.results.reduce<CaseResult | undefined>((best, r) => {
      const v = (x: CaseResult) => x[key] - (above ? (rep.baselines[x.format]?.[key] ?? 0) : 0);
      return !best || v(r) > v(best) ? r : best;
    }, undefined);
  const say = (r: CaseResult | undefined, key: 'seconds' | 'rssMiB', unit: string) =>
    r
      ? `${r[key].toFixed(key === 'seconds' ? 2 : 0)} ${unit} (${(r[key] - (rep.baselines[r.format]?.[key] ?? 0)).toFixed(key === 'seconds' ? 2 : 0)} above the ${r.format} baseline): case ${r.id} ${r.format} [${r.variant}] ${r.mutation} -> ${r.outcome}`
      : '-';
  lines.push('');
  lines.push(`worst time:             ${say(worst('seconds', false), 'seconds', 's')}`);
  lines.push(`worst time above base:  ${say(worst('seconds', true), 'seconds', 's')}`);
  lines.push(`worst RSS:              ${say(worst('rssMiB', false), 'rssMiB', 'MiB')}`);
  lines.push(`worst RSS above base:   ${say(worst('rssMiB', true), 'rssMiB', 'MiB')}`);
  const refused = rep.results.filter((r) => r.mutation === 'valid' && r.outcome === 'error');
  if (refused.length > 0) {
    lines.push(
      '',
      `valid files refused (${refused.length}; not failures, but each is a reader's limit or bug):`,
    );
    const seen = new Map<string, number>();
    for (const r of refused) {
      const k = `${r.format} [${r.variant}]: ${r.stderr.split('\n')[0].slice(0, 160)}`;
      seen.set(k, (seen.get(k) ?? 0) + 1);
    }
    for (const [k, n] of seen) lines.push(`  ${n}× ${k}`);
  }
  return lines.join('\n');
}

/** One line per failure, grouped by outcome, for a test's message. */
export function listing(failures: CaseResult[]): string {
  return failures
    .map(
      (r) =>
        `${r.outcome.padEnd(16)} case ${r.id} ${r.format} [${r.variant}] ${r.mutation}: ${r.why} ${r.outcome === 'internals' || r.outcome === 'crash' ? '' : ''}`,
    )
    .sort()
    .join('\n');
}
