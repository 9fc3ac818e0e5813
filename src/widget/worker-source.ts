/**
 * A worker factory for a render-worker URL that may be on another origin.
 * Browsers only start workers from same-origin scripts, so a package served
 * from a CDN cannot start `new Worker(cdnUrl)` directly; a same-origin blob
 * module that imports the CDN script can (module imports are fetched with
 * CORS, which public CDNs allow).
 */
export function moduleWorkerFactory(url: string | URL): () => Worker {
  const href = new URL(url, document.baseURI).href;
  if (new URL(href).origin === location.origin) {
    return () => new Worker(href, { type: 'module' });
  }
  const shim = URL.createObjectURL(
    new Blob([`import ${JSON.stringify(href)};`], { type: 'text/javascript' }),
  );
  return () => new Worker(shim, { type: 'module' });
}
