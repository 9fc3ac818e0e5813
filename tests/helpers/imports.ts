/**
 * The import graph of the source tree, read from the files themselves: every relative
 * `import … from`, `export … from`, `import(…)` and `new URL(…, import.meta.url)` (a
 * worker's script), with type-only imports marked. The layering test
 * (tests/unit/architecture/layers.test.ts) checks it against the layers the README
 * names.
 */
import { readFileSync, readdirSync, statSync } from 'node:fs';
import { dirname, join, normalize, relative } from 'node:path';

export interface Edge {
  from: string;
  to: string;
  /** `import type` / `export type`: no module is loaded at run time. */
  typeOnly: boolean;
}

const SPECIFIER =
  /(?:^|[;\n])\s*(import|export)\s+(type\s+)?(?:[^'";]*?\s+from\s+)?['"](\.{1,2}\/[^'"]+)['"]|import\(\s*['"](\.{1,2}\/[^'"]+)['"]\s*\)|new URL\(\s*['"](\.{1,2}\/[^'"]+\.ts)['"]/g;

/** The relative imports of one file's text (paths as written, not resolved). */
export function importsOf(text: string): { spec: string; typeOnly: boolean }[] {
  const out: { spec: string; typeOnly: boolean }[] = [];
  for (const m of text.matchAll(SPECIFIER)) {
    const spec = m[3] ?? m[4] ?? m[5];
    out.push({ spec, typeOnly: m[2] !== undefined });
  }
  return out;
}

/** Every .ts file under `dirs` of `root`, as paths relative to it. */
export function sourceFiles(root: string, dirs: string[]): string[] {
  const files: string[] = [];
  const walk = (dir: string) => {
    for (const name of readdirSync(join(root, dir))) {
      const path = join(dir, name);
      if (statSync(join(root, path)).isDirectory()) walk(path);
      else if (name.endsWith('.ts')) files.push(path);
    }
  };
  for (const d of dirs) walk(d);
  return files.sort();
}

/** The edges between `files` (and to files outside them that they name). */
export function importGraph(root: string, files: string[]): Edge[] {
  const edges: Edge[] = [];
  for (const from of files) {
    for (const { spec, typeOnly } of importsOf(readFileSync(join(root, from), 'utf8'))) {
      const to = relative('.', normalize(join(dirname(from), spec)));
      edges.push({ from, to, typeOnly });
    }
  }
  return edges;
}

/** The strongly connected components of more than one node (Tarjan), each sorted. */
export function cycles(edges: { from: string; to: string }[]): string[][] {
  const next = new Map<string, string[]>();
  for (const { from, to } of edges) {
    if (!next.has(from)) next.set(from, []);
    if (!next.has(to)) next.set(to, []);
    next.get(from)!.push(to);
  }
  const index = new Map<string, number>();
  const low = new Map<string, number>();
  const stack: string[] = [];
  const onStack = new Set<string>();
  const found: string[][] = [];
  let counter = 0;
  const visit = (v: string) => {
    index.set(v, counter);
    low.set(v, counter++);
    stack.push(v);
    onStack.add(v);
    for (const w of next.get(v)!) {
      if (!index.has(w)) {
        visit(w);
        low.set(v, Math.min(low.get(v)!, low.get(w)!));
      } else if (onStack.has(w)) {
        low.set(v, Math.min(low.get(v)!, index.get(w)!));
      }
    }
    if (low.get(v) === index.get(v)) {
      const component: string[] = [];
      let w: string;
      do {
        w = stack.pop()!;
        onStack.delete(w);
        component.push(w);
      } while (w !== v);
      if (component.length > 1) found.push(component.sort());
    }
  };
  for (const v of [...next.keys()].sort()) if (!index.has(v)) visit(v);
  return found;
}
