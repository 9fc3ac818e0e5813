/**
 * The page's record of render-worker deaths: the lock tokens of workers
 * known to be dead (see workers/browser/render-protocol.ts), added by the pool once
 * a worker's life lock is released and read by the shared films when they
 * find a lock held; and counts of every fault survived, for tests and the
 * curious. A token is never reused, so a dead one stays dead; the set grows
 * by one small number per death.
 */
import { emptyReport, type RecoveryReport } from '../../workers/browser/shared-claims.ts';

export interface FaultCounts extends RecoveryReport {
  /** Workers terminated by the test hook (WorkerPool.killWorker). */
  killed: number;
  /** Workers that threw an uncaught error after starting. */
  crashed: number;
  /** Workers that died with no error and without the pool ending them. */
  vanished: number;
  /** Deaths made certain (the worker's life lock released). */
  confirmed: number;
  /** Workers started in place of dead ones. */
  replaced: number;
  /** Transfer mode: stripes handed out again because their worker died. */
  tasksResent: number;
  /** Films moved to new buffers because a lock's holder would not let go (shared-job.ts). */
  renewals: number;
}

export const faults: FaultCounts = {
  ...emptyReport(),
  killed: 0,
  crashed: 0,
  vanished: 0,
  confirmed: 0,
  replaced: 0,
  tasksResent: 0,
  renewals: 0,
};

const dead = new Set<number>();
let nextToken = 2;

/** A lock token for a new worker (MAIN_TOKEN is 1). */
export function newWorkerToken(): number {
  return nextToken++;
}

export function markDead(token: number): void {
  dead.add(token);
}

export function isDead(token: number): boolean {
  return dead.has(token);
}
