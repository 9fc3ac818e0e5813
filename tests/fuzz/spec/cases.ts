/**
 * Case `index` of a campaign seeded `seed`: a format (round robin, so every budget covers
 * every format), a valid sample of it, and then either nothing (a valid case: it checks the
 * generator and gives the format's baseline), one format-aware mutation, or blind byte
 * changes of the sample's main file.
 */
import type { Files } from './bytes.ts';
import { GENERATORS } from './generators.ts';
import { blindMutate } from './mutate.ts';
import { Rng, caseSeed } from './rng.ts';

export interface FuzzCase {
  id: string;
  seed: number;
  index: number;
  format: string;
  variant: string;
  mutation: string;
  invalid: boolean;
  /** Source of a regular expression the error line must match (Mutation.expect). */
  expect?: string;
  lit: boolean;
  files: Files;
  args: string[];
}

export const FORMAT_NAMES = GENERATORS.map((g) => g.format);

/** `valid` forces the unmutated sample (baselines); otherwise 10 % of cases are valid. */
export function makeCase(seed: number, index: number, valid = false): FuzzCase {
  const rng = new Rng(caseSeed(seed, index));
  const gen = GENERATORS[index % GENERATORS.length];
  const sample = gen.generate(rng);
  const base = {
    id: `${seed}:${index}`,
    seed,
    index,
    format: gen.format,
    variant: sample.variant,
    lit: sample.lit,
    args: sample.args,
  };
  const r = rng.next();
  if (valid || r < 0.1) {
    return { ...base, mutation: 'valid', invalid: false, files: sample.files };
  }
  if (r < 0.65 && sample.mutations.length > 0) {
    const m = rng.pick(sample.mutations);
    return {
      ...base,
      mutation: m.name,
      invalid: m.invalid ?? false,
      expect: m.expect?.source,
      args: m.args ?? base.args,
      files: { ...sample.files, ...m.apply(rng) },
    };
  }
  if (sample.blind) {
    const { bytes, name } = blindMutate(sample.blind.bytes, rng);
    return {
      ...base,
      mutation: name,
      invalid: false,
      files: { ...sample.files, ...sample.blind.rebuild(bytes) },
    };
  }
  const { bytes, name } = blindMutate(sample.files[sample.target], rng);
  return {
    ...base,
    mutation: name,
    invalid: false,
    files: { ...sample.files, [sample.target]: bytes },
  };
}
