import { configDefaults, defineConfig } from 'vitest/config';

/** The generated-scene consistency suite: minutes of CPU, run by `npm run test:validation` (CI runs it too). */
export const VALIDATION_SUITE = [
  'tests/validation/consistency-*.test.ts',
  'tests/validation/references-adaptive.test.ts',
];

export default defineConfig({
  test: {
    include: ['tests/**/*.test.ts'],
    // tests/timing runs alone after the rest (vitest.timing.config.ts).
    exclude: [...configDefaults.exclude, ...VALIDATION_SUITE, 'tests/timing/**'],
    globalSetup: ['tests/global-setup.ts'],
    testTimeout: 120_000,
    hookTimeout: 180_000,
    // expect.poll waits for a condition in a page (a resize to settle, a
    // worker to be seen, an error line): its default of 1 s is a frame budget
    // on an idle machine, not a limit for two loaded cores.
    expect: { poll: { timeout: 30_000 } },
    // Statistical and scene tests are CPU-bound; two cores, so keep file-level parallelism modest.
    maxWorkers: 2,
  },
});
