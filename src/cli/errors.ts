/**
 * Errors the command line reports as one line on stderr with exit status 2: bad
 * arguments, an unreadable or oversized input, an output that cannot be written. Anything
 * else that escapes is a bug (exit status 1).
 */
export class CliError extends Error {
  override name = 'CliError';
}

/** A bad command line: the message says which argument and why. */
export class UsageError extends CliError {
  override name = 'UsageError';
}
