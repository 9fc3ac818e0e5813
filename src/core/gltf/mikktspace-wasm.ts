/**
 * MikkTSpace from the `mikktspace` package (the reference C implementation
 * by Morten Mikkelsen, compiled to WebAssembly by Don McCurdy, MIT) without
 * its bundler- or Node-specific loaders: the caller hands over the bytes of
 * `mikktspace/dist/module/mikktspace_module_bg.wasm` (Node reads the file,
 * the browser fetches it), and this is the small calling convention of
 * wasm-bindgen that the package's own glue implements. The same code then
 * runs in Node, in the page and in workers.
 */
import type { TangentGenerator } from './tangents.ts';

// WebAssembly and TextDecoder are in Node, browsers and workers alike, but not
// in the ES2022 lib that src/core compiles against: declare the little used.
interface WasmExports {
  memory: { buffer: ArrayBuffer };
  generateTangents(
    ret: number,
    p: number,
    pl: number,
    n: number,
    nl: number,
    t: number,
    tl: number,
  ): void;
  __wbindgen_add_to_stack_pointer(delta: number): number;
  __wbindgen_malloc(size: number): number;
  __wbindgen_free(ptr: number, size: number): void;
}
declare const WebAssembly: {
  instantiate(bytes: Uint8Array, imports: object): Promise<{ instance: { exports: unknown } }>;
};
declare const TextDecoder: new (label: string) => { decode(input: Uint8Array): string };

/** The module name the package's wasm imports its two helpers from. */
const IMPORT_MODULE = './mikktspace_module_bg.js';

export async function createMikkTSpace(wasmBytes: Uint8Array): Promise<TangentGenerator> {
  // wasm-bindgen's table of JS values handed to the module (here: error strings).
  const heap: unknown[] = new Array(32).fill(undefined);
  heap.push(undefined, null, true, false);
  let next = heap.length;
  const add = (v: unknown): number => {
    if (next === heap.length) heap.push(heap.length + 1);
    const i = next;
    next = heap[i] as number;
    heap[i] = v;
    return i;
  };
  const take = (i: number): unknown => {
    const v = heap[i];
    if (i >= 36) {
      heap[i] = next;
      next = i;
    }
    return v;
  };
  let wasm: WasmExports;
  const decoder = new TextDecoder('utf-8');
  const imports = {
    [IMPORT_MODULE]: {
      __wbindgen_string_new: (ptr: number, len: number): number =>
        add(decoder.decode(new Uint8Array(wasm.memory.buffer, ptr, len))),
      __wbindgen_rethrow: (i: number): never => {
        throw take(i);
      },
    },
  };
  const { instance } = await WebAssembly.instantiate(wasmBytes, imports);
  wasm = instance.exports as WasmExports;
  const pass = (a: Float32Array): number => {
    const ptr = wasm.__wbindgen_malloc(a.length * 4);
    new Float32Array(wasm.memory.buffer).set(a, ptr / 4);
    return ptr;
  };
  return (positions, normals, uvs) => {
    const ret = wasm.__wbindgen_add_to_stack_pointer(-16);
    try {
      const p = pass(positions);
      const n = pass(normals);
      const t = pass(uvs);
      wasm.generateTangents(ret, p, positions.length, n, normals.length, t, uvs.length);
      const words = new Int32Array(wasm.memory.buffer);
      const ptr = words[ret / 4];
      const len = words[ret / 4 + 1];
      const out = new Float32Array(wasm.memory.buffer).slice(ptr / 4, ptr / 4 + len);
      wasm.__wbindgen_free(ptr, len * 4);
      return out;
    } finally {
      wasm.__wbindgen_add_to_stack_pointer(16);
    }
  };
}
