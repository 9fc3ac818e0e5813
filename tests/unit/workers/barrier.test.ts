/**
 * workers/node/barrier.ts, the denoiser bands' barrier (src/cli/denoise-pool.ts): every
 * thread passes only when all have arrived, for many rounds; and an abort releases a
 * thread that waits alone, with an exception, without terminating it.
 */
import { Worker } from 'node:worker_threads';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { abortBarrier, BARRIER_WORDS } from '../../../workers/node/barrier.ts';
import { bundleWorker } from '../../helpers/bundle-worker.ts';

let workerFile = '';
let dispose = (): void => {};
beforeAll(async () => {
  ({ file: workerFile, dispose } = await bundleWorker(
    'tests/fixtures/barrier-worker.ts',
    'barrier-worker',
  ));
});
afterAll(() => dispose());

function start(
  parties: number,
  threads: number,
  rounds: number,
  words = new SharedArrayBuffer(BARRIER_WORDS * 4),
) {
  const counter = new SharedArrayBuffer(4);
  const workers = Array.from(
    { length: threads },
    () => new Worker(workerFile, { workerData: { words, counter, parties, rounds } }),
  );
  const answers = workers.map(
    (w) =>
      new Promise<string>((resolve, reject) => {
        w.once('message', resolve);
        w.once('error', reject);
      }),
  );
  return { words, workers, answers };
}

describe('the bands barrier', () => {
  it('four threads pass 500 rounds together, none early', async () => {
    const { workers, answers } = start(4, 4, 500);
    try {
      expect(await Promise.all(answers)).toEqual(['done', 'done', 'done', 'done']);
    } finally {
      await Promise.all(workers.map((w) => w.terminate()));
    }
  });

  it('an abort makes a thread waiting alone throw, without terminating it', async () => {
    // Two parties, one thread: it waits at the first barrier until the abort.
    const { words, workers, answers } = start(2, 1, 1);
    try {
      await new Promise((r) => setTimeout(r, 100));
      abortBarrier(new Int32Array(words));
      const answer = await Promise.race([
        answers[0]!,
        new Promise<string>((r) => setTimeout(() => r('still waiting after 3 s'), 3000)),
      ]);
      expect(answer).toBe('threw: barrier aborted: another thread failed');
    } finally {
      await Promise.all(workers.map((w) => w.terminate()));
    }
  });

  it('after an abort, a thread that arrives last throws too instead of passing', async () => {
    const words = new SharedArrayBuffer(BARRIER_WORDS * 4);
    abortBarrier(new Int32Array(words)); // before the thread exists: no race
    const { workers, answers } = start(1, 1, 1, words);
    try {
      expect(await answers[0]).toBe('threw: barrier aborted: another thread failed');
    } finally {
      await Promise.all(workers.map((w) => w.terminate()));
    }
  });
});
