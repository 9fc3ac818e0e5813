/**
 * Test hook, not API: with PATHWISE_TEST_FAULTS="kill=3,crash=2,seed=7" in
 * its environment, `pathwise render` kills 3 of its worker threads and
 * makes 2 throw (at a random step of a stripe, round-claims.ts) at random
 * moments of its rounds, so that tests can check that a render survives
 * dying workers bit-identical, through the real command line.
 */
import type { RenderPool } from './render.ts';

export const TEST_FAULTS_ENV = 'PATHWISE_TEST_FAULTS';

/** A small seeded PRNG (Tommy Ettinger's Mulberry32) for reproducible fault moments. */
export function mulberry32(seed: number): () => number {
  let a = seed >>> 0;
  return () => {
    a = (a + 0x6d2b79f5) | 0;
    let t = Math.imul(a ^ (a >>> 15), 1 | a);
    t = (t + Math.imul(t ^ (t >>> 7), 61 | t)) ^ t;
    return ((t ^ (t >>> 14)) >>> 0) / 4294967296;
  };
}

/** Starts the faults `spec` asks for; returns the function that stops them. */
export function startTestFaults(pool: RenderPool, spec: string): () => void {
  const fields = new Map(
    spec.split(',').map((kv) => {
      const [k, v] = kv.split('=');
      return [k.trim(), Number(v)] as const;
    }),
  );
  const random = mulberry32(fields.get('seed') ?? 1);
  const kinds: ('kill' | 'crash')[] = [
    ...Array<'kill'>(fields.get('kill') ?? 0).fill('kill'),
    ...Array<'crash'>(fields.get('crash') ?? 0).fill('crash'),
  ];
  // Shuffled, each at its own point of a round (fraction of its stripes done).
  for (let i = kinds.length - 1; i > 0; i--) {
    const j = Math.floor(random() * (i + 1));
    [kinds[i], kinds[j]] = [kinds[j], kinds[i]];
  }
  const at = kinds.map(() => 0.05 + 0.85 * random()).sort((a, b) => a - b);
  let next = 0;
  const timer = setInterval(() => {
    if (next >= kinds.length) return;
    if (pool.stripesDone() / pool.stripes < at[next]) return;
    const slot = Math.floor(random() * pool.threads);
    if (kinds[next] === 'kill') pool.killWorker(slot);
    else pool.crashWorker(slot, 1 + Math.floor(random() * 4));
    next++;
  }, 1);
  return () => clearInterval(timer);
}
