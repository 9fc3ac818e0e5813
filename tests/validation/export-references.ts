/**
 * Writes the reference set's scene files into tests/validation/references/
 * (run: node scripts/run-ts.mjs tests/validation/export-references.ts).
 * Then render them with references/make-references.py. The committed JSON
 * files, not the generator, are what the reference test reads: a later
 * change to the generator does not silently change the references.
 */
import { writeFileSync } from 'node:fs';
import { dirname, join } from 'node:path';
import { referenceSet } from './reference-set.ts';

// run-ts bundles this file elsewhere; it sets argv[1] to this file's own path.
const dir = join(dirname(process.argv[1]), 'references');
const index: Record<
  string,
  { seed?: number; archetype?: string; family?: string; features?: string[]; files?: string[] }
> = {};
for (const { name, json, generated, files } of referenceSet()) {
  writeFileSync(join(dir, `${name}.json`), JSON.stringify(json, null, 2) + '\n');
  // Mesh and map files beside the scene, as it names them.
  for (const [file, bytes] of Object.entries(files ?? {})) writeFileSync(join(dir, file), bytes);
  index[name] = generated
    ? {
        seed: generated.seed,
        archetype: generated.archetype,
        ...(files ? { family: 'mesh', files: Object.keys(files).sort() } : {}),
        features: generated.features,
      }
    : {};
  process.stdout.write(`${name}\n`);
}
// What each scene covers, for the coverage check of the reference test.
writeFileSync(join(dir, 'set.json'), JSON.stringify(index, null, 2) + '\n');
