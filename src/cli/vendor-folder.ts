/**
 * A folder of this package's vendor/ (data read at run time: the KTX2 transcoder, the
 * denoiser's weights), found beside src/ when run from the sources and beside dist/ when
 * run from the bundle (dist/cli/ or dist/cli/chunks/).
 */
import { existsSync } from 'node:fs';
import { fileURLToPath } from 'node:url';

/** vendor/`name`/ (with a trailing slash), checked by one file it must hold. */
export function vendorFolder(name: string, file: string): string {
  for (const up of ['../../', '../../../']) {
    const folder = fileURLToPath(new URL(`${up}vendor/${name}/`, import.meta.url));
    if (existsSync(folder + file)) return folder;
  }
  throw new Error(`vendor/${name}/${file} is missing from the installation`);
}
