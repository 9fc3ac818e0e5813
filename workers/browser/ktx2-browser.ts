/**
 * KHR_texture_basisu in the browser: the Basis Universal transcoder vendored in
 * vendor/basis/ (its .js and .wasm fetched from the bundle's assets) and ktx-parse's
 * container reader, over the core's transcoder (ktx2-transcode.ts). Imported only
 * through gltf-browser.ts's lazy getter, so that a page or worker loads it only for a
 * file that has a KTX2 texture.
 */
import { read as readKtx2Container } from 'ktx-parse';
import basisJsUrl from '../../vendor/basis/basis_transcoder.js?url';
import basisWasmUrl from '../../vendor/basis/basis_transcoder.wasm?url';
import type { Ktx2Transcoder } from '../../src/core/scene/format/gltf-model.ts';
import { basisKtx2Transcoder, type BasisModule } from '../../src/core/texture/ktx2-transcode.ts';

async function fetchBytes(url: string, what: string): Promise<ArrayBuffer> {
  const r = await fetch(url);
  if (!r.ok) throw new Error(`cannot load ${what} (${r.status} ${r.statusText})`);
  return r.arrayBuffer();
}

let ktx2: Promise<Ktx2Transcoder> | null = null;

/**
 * The Basis Universal transcoder, loaded once per page or worker (its heap, which never
 * shrinks, goes with the scene worker). Its glue is CommonJS, so it is run as a function
 * body with `module` given (as three.js's KTX2Loader does; a page whose
 * Content-Security-Policy forbids that gets the error, and the file's fallback images
 * are not used then).
 */
export function browserKtx2Transcoder(): Promise<Ktx2Transcoder> {
  ktx2 ??= (async () => {
    const [glue, wasm] = await Promise.all([
      fetchBytes(basisJsUrl, 'the Basis Universal transcoder'),
      fetchBytes(basisWasmUrl, 'the Basis Universal transcoder'),
    ]);
    const module = { exports: {} as unknown };
    new Function('module', 'exports', new TextDecoder().decode(glue))(module, module.exports);
    const factory = module.exports as (options: {
      wasmBinary: Uint8Array;
    }) => Promise<BasisModule & { initializeBasis(): void }>;
    const basis = await factory({ wasmBinary: new Uint8Array(wasm) });
    basis.initializeBasis();
    return basisKtx2Transcoder(basis, readKtx2Container);
  })();
  return ktx2;
}
