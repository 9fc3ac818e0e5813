/**
 * Cancelling a load from outside its thread: the long loops of loading and compiling a
 * scene (the BVH build, OBJ and PLY parsing) call `checkCancel` every few thousand
 * steps, and a host that can be told to stop (the browser's scene worker, through a
 * shared stop word) installs a check that throws. Nothing is checked unless one is set,
 * so the command line and tests pay one branch per thousand steps.
 *
 * Why not just terminate the worker: Chromium stops a worker that is in a long task only
 * after about 2 s (Blink's forcible-termination delay), and a superseded load should
 * give its thread and memory back within a second.
 */
let check: (() => void) | null = null;

/** Installs (or, with null, removes) the check of this thread. */
export function setCancelCheck(fn: (() => void) | null): void {
  check = fn;
}

/** Throws when this thread's load was cancelled. */
export function checkCancel(): void {
  if (check !== null) check();
}

/** The error a cancelled load ends with. */
export class CancelledError extends Error {
  constructor() {
    super('the load was cancelled');
  }
}
