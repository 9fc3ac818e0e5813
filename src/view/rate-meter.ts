/**
 * A rate over a sliding window (about a second): events or amounts per
 * second, for the FPS and M rays/s readouts.
 */
const WINDOW_MS = 1000;

export class RateMeter {
  private times: number[] = [];
  private amounts: number[] = [];

  add(now: number, amount: number): void {
    this.times.push(now);
    this.amounts.push(amount);
    this.trim(now);
  }

  reset(): void {
    this.times = [];
    this.amounts = [];
  }

  private trim(now: number): void {
    let drop = 0;
    while (drop < this.times.length - 1 && now - this.times[drop] > WINDOW_MS) drop++;
    if (drop > 0) {
      this.times.splice(0, drop);
      this.amounts.splice(0, drop);
    }
  }

  /** Amount per second over the window; the first sample only marks its start. */
  rate(now: number): number {
    this.trim(now);
    const n = this.times.length;
    if (n < 2) return 0;
    const span = Math.max(now, this.times[n - 1]) - this.times[0];
    if (span <= 0) return 0;
    let sum = 0;
    for (let i = 1; i < n; i++) sum += this.amounts[i];
    return (sum * 1000) / span;
  }
}
