/**
 * draco3dgltf ships no declarations; its decoder glue (Emscripten, CommonJS) exports one
 * factory, `createDecoderModule(options)` (see gltf-browser.ts for how it is called).
 */
declare module 'draco3dgltf/draco_decoder_gltf_nodejs.js' {
  const createDecoderModule: (options: { wasmBinary: Uint8Array }) => Promise<unknown>;
  export default createDecoderModule;
}
