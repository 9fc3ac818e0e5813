/** Number formatting for the stats panel. */

export function formatBytes(bytes: number): string {
  if (bytes < 1024) return `${bytes} B`;
  if (bytes < 1024 * 1024) return `${(bytes / 1024).toFixed(0)} KiB`;
  return `${(bytes / (1024 * 1024)).toFixed(1)} MiB`;
}

export function formatRate(raysPerSecond: number): string {
  return raysPerSecond > 0 ? (raysPerSecond / 1e6).toFixed(2) : '–';
}
