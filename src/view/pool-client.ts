/**
 * The controller as a client of the page's worker pool (pool.ts): where its
 * tasks come from, where results go, and how it recovers the work of
 * workers that died. Results and lost tasks of an older configuration
 * version are dropped: the film they were for has been reset.
 */
import type { JobConfig } from '../../workers/render-protocol.ts';
import type { Films } from './films.ts';
import type { PoolClient } from './pool.ts';

export interface ClientHost {
  readonly id: number;
  readonly films: Films;
  config(): JobConfig;
  /** The configuration version now in force. */
  version(): number;
  /** Wakes the frame loop (something may have changed on screen). */
  wake(): void;
  emit(type: string, detail: unknown): void;
}

export function poolClient(host: ClientHost): PoolClient {
  const { id, films } = host;
  return {
    id,
    config: host.config,
    nextTask: () => films.active()?.nextTask?.(id) ?? null,
    onResult: (r) => {
      const job = films.active();
      if (job && r.version === host.version()) job.onResult?.(r);
      host.wake();
    },
    onWorkerError: (message) => host.emit('error', { message }),
    onTaskLost: (task) => {
      const job = films.active();
      if (job && task.version === host.version()) job.onTaskLost?.(task);
      host.wake();
    },
    recover: () => {
      let done = true;
      for (const job of [films.full, films.preview]) {
        if (job?.recover && !job.recover()) done = false;
      }
      host.wake();
      return done;
    },
  };
}
