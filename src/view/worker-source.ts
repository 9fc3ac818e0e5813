/**
 * Starting a module worker from a URL that may be on another origin.
 * Browsers only start workers from same-origin scripts, so a package served
 * from a CDN cannot start `new Worker(cdnUrl)` directly; a same-origin blob
 * module that imports the CDN script can (module imports are fetched with
 * CORS, which public CDNs allow). Shared by the pool's default worker URL
 * and by hosts that pass a worker URL (the widget's `worker-url`).
 *
 * Nothing here runs at import time (no `document` or `location` on a server).
 */

/** One blob shim per cross-origin script, kept for the page's life (a few bytes each). */
const shims = new Map<string, string>();

function pageBase(): string | undefined {
  if (typeof document !== 'undefined') return document.baseURI;
  return typeof location !== 'undefined' ? location.href : undefined;
}

/** A URL that `new Worker(url, { type: 'module' })` accepts on this page for the script `url`. */
export function sameOriginWorkerUrl(url: string | URL): string {
  const base = pageBase();
  const href = new URL(url, base).href;
  if (base === undefined || new URL(href).origin === new URL(base).origin) return href;
  let shim = shims.get(href);
  if (!shim) {
    shim = URL.createObjectURL(
      new Blob([`import ${JSON.stringify(href)};`], { type: 'text/javascript' }),
    );
    shims.set(href, shim);
  }
  return shim;
}

/** Starts the module worker at `url`, through a same-origin shim when it is on another origin. */
export function startModuleWorker(url: string | URL): Worker {
  return new Worker(sameOriginWorkerUrl(url), { type: 'module' });
}

/** A worker factory for a render-worker URL that may be on another origin. */
export function moduleWorkerFactory(url: string | URL): () => Worker {
  const resolved = sameOriginWorkerUrl(url);
  return () => new Worker(resolved, { type: 'module' });
}
