import { defineConfig } from 'vitest/config';

/**
 * Tests that time something a user waits for (tests/timing): run by `npm run test:timing`
 * (CI calls it after `npm test`), one at a time, so that no other test shares the two cores with them.
 */
export default defineConfig({
  test: {
    include: ['tests/timing/**/*.test.ts'],
    testTimeout: 180_000,
    hookTimeout: 180_000,
    maxWorkers: 1,
    fileParallelism: false,
  },
});
