/**
 * Seconds a film has been traced since its last restart, pauses excluded:
 * the time axis of the demo's error plot.
 */
export class TraceClock {
  private start = 0;
  private pausedMs = 0;
  private pausedAt = -1;

  restart(now: number, paused: boolean): void {
    this.start = now;
    this.pausedMs = 0;
    this.pausedAt = paused ? now : -1;
  }

  pause(now: number): void {
    if (this.pausedAt < 0) this.pausedAt = now;
  }

  resume(now: number): void {
    if (this.pausedAt >= 0) this.pausedMs += now - this.pausedAt;
    this.pausedAt = -1;
  }

  seconds(now: number): number {
    const paused = this.pausedMs + (this.pausedAt >= 0 ? now - this.pausedAt : 0);
    return Math.max(0, now - this.start - paused) / 1000;
  }
}
