/**
 * Lies in the binary container of glTF (spec §4.4): the 12-byte header's length and
 * version, chunk lengths and types, a missing BIN chunk, a BOM, truncation. Applied only to
 * samples stored as .glb.
 */
import { ByteWriter, type Files } from './bytes.ts';
import type { Model } from './gltf-doc.ts';
import type { ModelEdit } from './gltf-host.ts';
import { MODEL_DIR, glb, pack } from './gltf-pack.ts';
import type { Rng } from './rng.ts';

/** GLB-level lies (§4.4): applied only when the sample is a .glb. */
export function glbEdits(): ModelEdit[] {
  const g = (name: string, f: (m: Model, rng: Rng) => Uint8Array, invalid = true): ModelEdit => ({
    name: `glb:${name}`,
    invalid,
    only: 'glb',
    edit: (m, rng): Files => ({ [`${MODEL_DIR}/model.glb`]: f(m, rng) }),
  });
  const bin = (m: Model) => {
    const files = pack(m, 'glb');
    return files[`${MODEL_DIR}/model.glb`];
  };
  return [
    g('total-length-lie', (m, r) => {
      const b = bin(m);
      new DataView(b.buffer).setUint32(8, r.pick([0, 12, b.length + 4, 0xffffffff]), true);
      return b;
    }),
    g('json-length-huge', (m) => glb(m.json, m.bin, { jsonLength: 0x7ffffff0 })),
    g('json-length-odd', (m) => glb(m.json, m.bin, { jsonLength: 3 })),
    g('bin-length-huge', (m) => glb(m.json, m.bin, { binLength: 0xfffffff0 })),
    g('version-1', (m) => glb(m.json, m.bin, { version: 1 })),
    g('json-chunk-type', (m) => glb(m.json, m.bin, { jsonType: 0x004e4942 })),
    g('no-bin-chunk', (m) => glb(m.json, null)),
    g('truncated', (m, r) => {
      const b = bin(m);
      return b.subarray(0, r.range(0, b.length - 1));
    }),
    g('json-not-utf8', (m) => {
      const b = bin(m);
      b[24] = 0xff;
      return b;
    }),
    g('bom', (m) => {
      const text = JSON.stringify(m.json);
      const w = new ByteWriter().bytes([0xef, 0xbb, 0xbf]).text(text);
      while (w.length % 4) w.u8(0x20);
      const json = w.done();
      return new ByteWriter()
        .u32(0x46546c67, true)
        .u32(2, true)
        .u32(12 + 8 + json.length, true)
        .u32(json.length, true)
        .u32(0x4e4f534a, true)
        .bytes(json)
        .done();
    }),
  ];
}
