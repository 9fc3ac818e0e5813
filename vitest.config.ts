import { defineConfig } from 'vitest/config';

export default defineConfig({
  test: {
    include: ['tests/**/*.test.ts'],
    globalSetup: ['tests/global-setup.ts'],
    testTimeout: 120_000,
    hookTimeout: 180_000,
    // Statistical and scene tests are CPU-bound; two cores, so keep file-level parallelism modest.
    maxWorkers: 2,
  },
});
