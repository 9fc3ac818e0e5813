/**
 * The layers the README names, checked on the import graph (tests/helpers/imports.ts):
 * each layer imports only itself and the layers below it (type-only imports count: a
 * type is a dependency too); no two folders import each other, directly or round a
 * loop; no module loads itself again through its imports at run time. The checks are
 * first run on small made-up graphs, so that a checker that finds nothing is itself
 * caught.
 */
import { describe, expect, it } from 'vitest';
import { cycles, importGraph, importsOf, sourceFiles, type Edge } from '../../helpers/imports.ts';
import { ROOT } from '../../helpers/render.ts';

/**
 * Layers, each with those it may import: the core (pure TypeScript, no DOM) at the
 * bottom; the two worker hosts above it, which share nothing; the page's view over the
 * browser's workers; the three.js bridge over the core alone; the demo and the widget
 * over the view (the widget over the bridge too); the command line over the Node workers.
 */
const LAYERS: Record<string, string[]> = {
  'src/core': [],
  'workers/browser': ['src/core'],
  'workers/node': ['src/core'],
  'src/view': ['src/core', 'workers/browser'],
  'src/app': ['src/core', 'workers/browser', 'src/view'],
  'src/three': ['src/core'],
  'src/widget': ['src/core', 'workers/browser', 'src/view', 'src/three'],
  'src/cli': ['src/core', 'workers/node'],
};

function layerOf(path: string): string | null {
  for (const layer of Object.keys(LAYERS)) if (path.startsWith(layer + '/')) return layer;
  return null;
}

/** Imports that leave their layer for one it may not use, as "from -> to". */
function upward(edges: Edge[]): string[] {
  const bad: string[] = [];
  for (const { from, to } of edges) {
    const a = layerOf(from);
    const b = layerOf(to);
    if (a === null || b === null || a === b) continue;
    if (!LAYERS[a].includes(b)) bad.push(`${from} -> ${to}`);
  }
  return bad;
}

const folderOf = (path: string) => path.slice(0, path.lastIndexOf('/'));

/** Loops between folders: each folder is a node, any import between two an edge. */
function folderLoops(edges: Edge[]): string[][] {
  return cycles(
    edges
      .map((e) => ({ from: folderOf(e.from), to: folderOf(e.to) }))
      .filter((e) => e.from !== e.to),
  );
}

/** Loops of modules loading each other at run time (type-only imports load nothing). */
function runtimeLoops(edges: Edge[]): string[][] {
  return cycles(edges.filter((e) => !e.typeOnly));
}

const files = sourceFiles(ROOT, ['src', 'workers']);
const edges = importGraph(ROOT, files);

describe('the checker', () => {
  it('reads every form of relative import', () => {
    const text = [
      "import { a } from './a.ts';",
      "import type { B } from '../b.ts';",
      "export { c } from './c.ts';",
      "export type { D } from './d.ts';",
      "export * from './star.ts';",
      "import './e.ts';",
      "const f = await import('./f.ts');",
      "new Worker(new URL('../../workers/browser/g.ts', import.meta.url));",
      "import {\n  h,\n  type H,\n} from './h.ts';",
      "import x from 'node:fs';",
    ].join('\n');
    expect(importsOf(text)).toEqual([
      { spec: './a.ts', typeOnly: false },
      { spec: '../b.ts', typeOnly: true },
      { spec: './c.ts', typeOnly: false },
      { spec: './d.ts', typeOnly: true },
      { spec: './star.ts', typeOnly: false },
      { spec: './e.ts', typeOnly: false },
      { spec: './f.ts', typeOnly: false },
      { spec: '../../workers/browser/g.ts', typeOnly: false },
      { spec: './h.ts', typeOnly: false },
    ]);
  });

  it('finds an upward import, a folder loop and a run-time loop in a made-up graph', () => {
    const made: Edge[] = [
      { from: 'src/core/a/x.ts', to: 'src/core/b/y.ts', typeOnly: false },
      { from: 'src/core/b/y.ts', to: 'src/core/c/z.ts', typeOnly: true },
      { from: 'src/core/c/z.ts', to: 'src/core/a/w.ts', typeOnly: true },
      { from: 'src/core/c/z.ts', to: 'src/view/v.ts', typeOnly: true },
      { from: 'workers/node/n.ts', to: 'workers/browser/b.ts', typeOnly: false },
      { from: 'src/cli/p.ts', to: 'src/cli/q.ts', typeOnly: false },
      { from: 'src/cli/q.ts', to: 'src/cli/p.ts', typeOnly: false },
      { from: 'src/cli/r.ts', to: 'src/cli/s.ts', typeOnly: true },
      { from: 'src/cli/s.ts', to: 'src/cli/r.ts', typeOnly: false },
    ];
    expect(upward(made)).toEqual([
      'src/core/c/z.ts -> src/view/v.ts',
      'workers/node/n.ts -> workers/browser/b.ts',
    ]);
    expect(folderLoops(made)).toEqual([['src/core/a', 'src/core/b', 'src/core/c']]);
    expect(runtimeLoops(made)).toEqual([['src/cli/p.ts', 'src/cli/q.ts']]);
  });
});

describe('the source tree', () => {
  it('has every file in a layer and every import resolving to a file', () => {
    expect(files.filter((f) => layerOf(f) === null)).toEqual([]);
    const known = new Set(files);
    // Assets, and `?url` imports (a URL to fetch, such as vendor/basis/'s transcoder): no code.
    const code = edges.filter(
      (e) => !/\.(css|json|glsl|obj|hdr)(\?\w+)?$/.test(e.to) && !e.to.endsWith('?url'),
    );
    expect(code.filter((e) => !known.has(e.to)).map((e) => `${e.from} -> ${e.to}`)).toEqual([]);
    // The graph is the whole tree, not a sample (198 modules when this was written).
    expect(files.length).toBeGreaterThan(180);
    expect(edges.length).toBeGreaterThan(600);
  });

  it('imports only downward: core ← workers (browser | node) ← view ← app, widget; cli', () => {
    expect(upward(edges)).toEqual([]);
  });

  it('has no loop between folders', () => {
    expect(folderLoops(edges)).toEqual([]);
  });

  it('has no module that loads itself again at run time', () => {
    expect(runtimeLoops(edges)).toEqual([]);
  });
});
