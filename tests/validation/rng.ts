/**
 * A small seeded random stream for the scene generator, built on the
 * project's PCG hash (src/core/rng/pcg.ts): number k of stream `seed` is
 * hash(hash(seed) + k·golden). Pure and counter-based, so a scene depends
 * only on its seed — never on the order scenes are generated in, nor on the
 * tracer's own streams (which hash (seed, pixel, sample) differently).
 */
import { pcgHash } from '../../src/core/rng/pcg.ts';

export class Rng {
  private readonly key: number;
  private counter = 0;

  constructor(seed: number) {
    this.key = pcgHash((pcgHash(seed >>> 0) + 0x6a09e667) >>> 0);
  }

  /** Uniform in [0, 1), with 53 random bits (two hashes). */
  next(): number {
    const hi = pcgHash((this.key + Math.imul(this.counter++, 0x9e3779b9)) >>> 0) >>> 5;
    const lo = pcgHash((this.key + Math.imul(this.counter++, 0x9e3779b9)) >>> 0) >>> 6;
    return (hi * 67108864 + lo) / 9007199254740992;
  }

  uniform(a: number, b: number): number {
    return a + (b - a) * this.next();
  }

  /** Log-uniform in [a, b] (a, b > 0): every decade equally likely. */
  logUniform(a: number, b: number): number {
    return a * Math.pow(b / a, this.next());
  }

  /** Integer in [a, b], both included. */
  int(a: number, b: number): number {
    return a + Math.min(b - a, Math.floor(this.next() * (b - a + 1)));
  }

  chance(p: number): boolean {
    return this.next() < p;
  }

  pick<T>(items: readonly T[]): T {
    return items[Math.min(items.length - 1, Math.floor(this.next() * items.length))];
  }

  /** One of `items` with probability proportional to its weight. */
  weighted<T>(items: readonly (readonly [T, number])[]): T {
    const total = items.reduce((s, [, w]) => s + w, 0);
    let u = this.next() * total;
    for (const [item, w] of items) {
      if (u < w) return item;
      u -= w;
    }
    return items[items.length - 1][0];
  }

  /** Uniform direction on the unit sphere. */
  direction(): [number, number, number] {
    const z = 1 - 2 * this.next();
    const r = Math.sqrt(Math.max(0, 1 - z * z));
    const phi = 2 * Math.PI * this.next();
    return [r * Math.cos(phi), r * Math.sin(phi), z];
  }
}
