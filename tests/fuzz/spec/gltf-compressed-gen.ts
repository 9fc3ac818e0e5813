/**
 * glTF mutations that declare compressed data (meshopt, Draco) over the model's plain
 * buffer views: each breaks a MUST of its extension (EXT_meshopt_compression "JSON schema
 * updates": byteLength == byteStride × count, a known mode, the parent view's byteStride;
 * KHR_draco_mesh_compression: the attributes name the primitive's) or is not a stream of
 * the format at all, and must end as one line naming the extension.
 */
import type { Json } from './gltf-doc.ts';
import type { ModelEdit } from './gltf-host.ts';
import type { Rng } from './rng.ts';

const MESHOPT = 'EXT_meshopt_compression';
const DRACO = 'KHR_draco_mesh_compression';

function requireExtension(g: Json, name: string): void {
  g.extensionsUsed = [...(g.extensionsUsed ?? []), name];
  g.extensionsRequired = [...(g.extensionsRequired ?? []), name];
}

/** bufferViews[0] (POSITION: 24 × 12 bytes) marked compressed, its extension edited by `f`. */
function meshopt(name: string, f: (ext: Json, view: Json, rng: Rng) => void): ModelEdit {
  return {
    name: `gltf:${name}`,
    invalid: true,
    expect: /EXT_meshopt_compression/,
    edit: (m, rng) => {
      const view = m.json.bufferViews[0];
      const ext: Json = {
        buffer: 0,
        byteOffset: view.byteOffset,
        byteLength: view.byteLength,
        byteStride: 12,
        count: 24,
        mode: 'ATTRIBUTES',
      };
      f(ext, view, rng);
      view.extensions = { [MESHOPT]: ext };
      requireExtension(m.json, MESHOPT);
    },
  };
}

function draco(name: string, attributes: Json): ModelEdit {
  return {
    name: `gltf:${name}`,
    invalid: true,
    expect: /KHR_draco_mesh_compression/,
    edit: (m) => {
      m.json.meshes[0].primitives[0].extensions = { [DRACO]: { bufferView: 0, attributes } };
      requireExtension(m.json, DRACO);
    },
  };
}

export const COMPRESSED_EDITS: ModelEdit[] = [
  meshopt('meshopt-count-lie', (e, _v, r) => void (e.count = r.pick([25, 1e8, 2 ** 40]))),
  meshopt('meshopt-stride-lie', (e, v) => {
    v.byteStride = 12;
    e.byteStride = 16;
    e.count = 18;
  }),
  meshopt('meshopt-mode-unknown', (e, _v, r) => void (e.mode = r.pick(['QUADS', 7, null]))),
  meshopt('meshopt-not-a-stream', () => {}),
  meshopt('meshopt-stream-past-buffer', (e) => void (e.byteOffset = 2 ** 31)),
  draco('draco-not-a-stream', { POSITION: 0 }),
  draco('draco-attribute-missing', { TEXCOORD_1: 0 }),
];
