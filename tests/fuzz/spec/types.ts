/** The shapes shared by the generators, the case builder and the runner. */
import type { Files } from './bytes.ts';
import type { Rng } from './rng.ts';

export type { Files };

/** A format-aware change of a valid sample: returns the files it replaces or adds. */
export interface Mutation {
  name: string;
  /**
   * The result breaks a rule its specification states outright (an index out of range, an
   * accessor type an attribute does not allow, a file outside the model's folder): exit 0
   * for it is a failure (`accepted-invalid`), not an image.
   */
  invalid?: boolean;
  /**
   * What an error for it must say (a film damaged is reported as damaged, issue 27 item 5):
   * one clear line that does not match is `misleading`. For a case that is not `invalid`
   * (something pathwise honestly ignores), the note it must print: exit 0 without a
   * matching line is `accepted-invalid`.
   */
  expect?: RegExp;
  /** The command line, when the mutation changes it (a part given twice). */
  args?: string[];
  apply(rng: Rng): Files;
}

/** A valid file (and whatever names it), plus the ways to break it. */
export interface Sample {
  variant: string;
  files: Files;
  /** The file blind byte mutations hit. */
  target: string;
  /** `['render', 'scene.json']` or `['merge', 'a.film', 'b.film']`; size and --out are added. */
  args: string[];
  /**
   * Light reaches the camera whatever happens to the target file (an emitter in view that
   * the file cannot remove, or the studio environment of a bare model): an all-zero image
   * is then samples dropped, never an honest picture.
   */
  lit: boolean;
  mutations: Mutation[];
  /** Where blind changes go when not simply into `target` (an image inside a model). */
  blind?: { bytes: Uint8Array; rebuild(bytes: Uint8Array): Files };
}

export interface Generator {
  format: string;
  generate(rng: Rng): Sample;
}
