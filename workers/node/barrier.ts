/**
 * A barrier for threads that share an Int32Array of BARRIER_WORDS words (zeros at first):
 * `barrier(words, parties)` returns in each of `parties` threads once all of them have
 * called it. The last to arrive resets the count and advances the generation, which
 * wakes the others (Atomics.wait on the generation word). `abortBarrier` makes every
 * waiting or later call throw instead, so that one thread's failure cannot leave the
 * others waiting forever.
 */
const ARRIVED = 0;
const GENERATION = 1;
const ABORTED = 2;
export const BARRIER_WORDS = 3;

export function barrier(words: Int32Array, parties: number): void {
  const generation = Atomics.load(words, GENERATION);
  if (Atomics.add(words, ARRIVED, 1) === parties - 1) {
    Atomics.store(words, ARRIVED, 0);
    Atomics.add(words, GENERATION, 1);
    Atomics.notify(words, GENERATION);
    return;
  }
  while (Atomics.load(words, GENERATION) === generation) {
    if (Atomics.load(words, ABORTED)) throw new Error('barrier aborted: another thread failed');
    Atomics.wait(words, GENERATION, generation, 1000);
  }
}

export function abortBarrier(words: Int32Array): void {
  Atomics.store(words, ABORTED, 1);
  Atomics.add(words, GENERATION, 1);
  Atomics.notify(words, GENERATION);
}
