/**
 * A barrier for threads that share an Int32Array of BARRIER_WORDS words (zeros at first):
 * `barrier(words, parties)` returns in each of `parties` threads once all of them have
 * called it. The last to arrive resets the count and advances the generation, which
 * wakes the others (Atomics.wait on the generation word). `abortBarrier` makes every
 * waiting and every later call throw instead of returning, so that one thread's failure
 * neither leaves the others waiting for ever nor lets them go on as if it had arrived.
 */
const ARRIVED = 0;
const GENERATION = 1;
const ABORTED = 2;
export const BARRIER_WORDS = 3;

function checkAborted(words: Int32Array): void {
  if (Atomics.load(words, ABORTED)) throw new Error('barrier aborted: another thread failed');
}

export function barrier(words: Int32Array, parties: number): void {
  checkAborted(words);
  const generation = Atomics.load(words, GENERATION);
  if (Atomics.add(words, ARRIVED, 1) === parties - 1) {
    Atomics.store(words, ARRIVED, 0);
    Atomics.add(words, GENERATION, 1);
    Atomics.notify(words, GENERATION);
  } else {
    // The timeout only bounds a wait whose wake-up was missed; the loop re-checks.
    while (Atomics.load(words, GENERATION) === generation) {
      checkAborted(words);
      Atomics.wait(words, GENERATION, generation, 1000);
    }
  }
  // An abort advances the generation too: a thread woken by it must not go on.
  checkAborted(words);
}

export function abortBarrier(words: Int32Array): void {
  Atomics.store(words, ABORTED, 1);
  Atomics.add(words, GENERATION, 1);
  Atomics.notify(words, GENERATION);
}
