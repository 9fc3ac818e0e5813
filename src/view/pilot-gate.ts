/**
 * Adaptive sampling in the browser (core/film/adaptive.ts): the gate at the
 * end of the uniform pilot.
 *
 * Every pixel takes the first ADAPTIVE_PILOT passes. The per-pixel rates
 * are then built from the film at exactly that many passes, the map the
 * command line builds from the same passes, and only then may any stripe
 * start pass ADAPTIVE_PILOT. So until the map exists the workers are given
 * a target of at most the pilot's passes; the main thread (which alone
 * writes the map) builds it once every stripe holds the pilot and then
 * raises the target to the caller's. A pass is the same unit as before, so
 * the film equals the command line's `--adaptive on` render of as many
 * passes, bit for bit, whatever the workers and whichever mode.
 *
 * A reset closes the gate again: the map belongs to the film's samples.
 */
import {
  ADAPTIVE_PILOT,
  RATE_ONE,
  adaptiveCount,
  buildSampleMap,
  type Film,
} from '../core/index.ts';

export class PilotGate {
  /** The per-pixel rates, row-major (the workers read them); null for a uniform render. */
  readonly map: Uint8Array | null;
  private built = false;
  /** Pixels of each rate in the built map (for meanSamples: O(rates), not O(pixels)). */
  private readonly rates = new Float64Array(RATE_ONE + 1);

  /** `map`: width·height bytes for an adaptive film (shared with the workers or not); else null. */
  constructor(map: Uint8Array | null) {
    this.map = map;
  }

  get adaptive(): boolean {
    return this.map !== null;
  }

  /** True while passes past the pilot must wait for the map. */
  get closed(): boolean {
    return this.map !== null && !this.built;
  }

  /** The target the workers may render to now, for the caller's `target`. */
  cap(target: number): number {
    return this.closed ? Math.min(target, ADAPTIVE_PILOT) : target;
  }

  /** The film was cleared: its next pilot builds a new map. */
  close(): void {
    this.built = false;
  }

  /**
   * Builds the map when the gate is closed and every stripe holds the pilot
   * (`passesDone`, which the capped target keeps from going past it), so
   * that `film` holds exactly the pilot's passes. Returns true when it did:
   * the caller raises the target and wakes the workers.
   */
  tryOpen(film: Film, passesDone: number): boolean {
    if (!this.closed || passesDone < ADAPTIVE_PILOT) return false;
    const map = buildSampleMap(film, this.map!);
    const rates = this.rates.fill(0);
    for (let p = 0; p < map.length; p++) rates[map[p]]++;
    this.built = true;
    return true;
  }

  /**
   * The mean samples per pixel after `passes` whole passes (film/adaptive.ts's counts
   * over the map): `passes` itself for a uniform film or before the map exists.
   */
  meanSamples(passes: number): number {
    if (this.map === null || !this.built || passes <= ADAPTIVE_PILOT) return passes;
    let sum = 0;
    for (let k = 0; k <= RATE_ONE; k++) {
      if (this.rates[k] > 0) sum += this.rates[k] * adaptiveCount(passes, ADAPTIVE_PILOT, k);
    }
    return sum / this.map.length;
  }
}
