/**
 * The URL of Draco's WebAssembly, in a module of its own that gltf-browser.ts imports
 * only when a model uses Draco: the library build inlines assets as data URLs, and the
 * 190 KB would otherwise travel with every glTF load.
 */
export { default } from 'draco3dgltf/draco_decoder_gltf.wasm?url';
