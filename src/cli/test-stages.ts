/**
 * Test hook, not API: with PATHWISE_TEST_STAGE=NAME in its environment, the command
 * writes `pathwise: test: stage NAME` to stderr when it enters that stage, and with
 * PATHWISE_TEST_STALL=1 also keeps its thread busy there for a minute, as a huge input
 * would. The signal tests (tests/cli/signals.test.ts) send SIGINT or SIGTERM then and
 * time the exit: it must come within a second at every stage.
 */
export const TEST_STAGE_ENV = 'PATHWISE_TEST_STAGE';
export const TEST_STALL_ENV = 'PATHWISE_TEST_STALL';

/** The stages of `render` and `merge`, in order. */
export type Stage =
  'read' | 'parse' | 'load' | 'compile' | 'render' | 'checkpoint' | 'write' | 'merge';

const STALL_MS = 60_000;

export function testStage(stage: Stage): void {
  if (process.env[TEST_STAGE_ENV] !== stage) return;
  process.stderr.write(`pathwise: test: stage ${stage}\n`);
  if (process.env[TEST_STALL_ENV] !== '1') return;
  // Synchronous, as a long parse or BVH build is: no event of this thread runs.
  const end = performance.now() + STALL_MS;
  while (performance.now() < end) {
    // busy
  }
}
