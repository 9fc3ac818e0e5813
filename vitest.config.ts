import { defineConfig } from 'vitest/config';

export default defineConfig({
  test: {
    include: ['tests/**/*.test.ts'],
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
