/**
 * Puts a glTF model in a case: rendered bare (`pathwise render s/m/model.glb`: framed in
 * the studio environment) or named by a scene (`s/scene.json` with a `gltf` shape and the
 * lamp of scene-wrap.ts). Files that a hostile `uri` may reach for are written outside both
 * folders, at the case's root.
 */
import { ascii, type Files } from './bytes.ts';
import type { Model } from './gltf-doc.ts';
import { modelPath, pack, type Container } from './gltf-pack.ts';
import type { Rng } from './rng.ts';
import { wrapScene } from './scene-wrap.ts';
import type { Mutation, Sample } from './types.ts';

export const OUTSIDE: Files = {
  'outside.bin': new Uint8Array(4096).fill(0x3f),
  'outside.png': ascii('not really a png, but outside the model folder'),
};

/** A mutation of the model (a fresh copy each time), packed as the sample's container. */
export interface ModelEdit {
  name: string;
  invalid?: boolean;
  expect?: RegExp;
  /** Applies to this container only (a GLB chunk lie). */
  only?: Container;
  edit(m: Model, rng: Rng, c: Container): void | Files;
}

export function modelSample(
  rng: Rng,
  model: Model,
  edits: ModelEdit[],
  variant: string,
  container?: Container,
): Sample {
  const c = container ?? rng.pick<Container>(['gltf', 'glb', 'data']);
  const bare = rng.chance(0.5);
  const files: Files = { ...OUTSIDE, ...pack(model, c) };
  const path = modelPath(c);
  if (!bare) files['s/scene.json'] = wrapScene({ shapes: [{ type: 'gltf', file: path.slice(2) }] });
  const mutations: Mutation[] = edits
    .filter((e) => !e.only || e.only === c)
    .map((e) => ({
      name: e.name,
      invalid: e.invalid,
      expect: e.expect,
      apply: (r: Rng) => {
        const m: Model = {
          json: structuredClone(model.json),
          bin: model.bin.slice(),
          image: model.image,
        };
        const raw = e.edit(m, r, c);
        return raw ?? pack(m, c);
      },
    }));
  return {
    variant: `${variant}${variant ? ' ' : ''}${c}${bare ? ' bare' : ' in scene'}`,
    files,
    target: path,
    args: ['render', bare ? path : 's/scene.json'],
    lit: true,
    mutations,
    // Blind changes of an image hit the image's own bytes, wherever the container keeps them.
    blind: model.image && {
      bytes: model.image.bytes,
      rebuild: (bytes) => pack({ ...model, image: { ...model.image!, bytes } }, c),
    },
  };
}
