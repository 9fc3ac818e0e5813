/**
 * Strict parsing of option values, shared by every `pathwise` subcommand. Numbers are
 * decimal only: `Number()` alone would read `0x10` as 16, `1e3` as a count, `''` and `' '`
 * as 0 and `Infinity` as a number, so a typo in a batch script would run with a value
 * nobody wrote. Values are quoted in messages through `quote` (escaped, truncated).
 */
import { quote } from '../core/util/message.ts';
import { CliError } from './errors.ts';

/** A decimal integer: optional minus sign and digits, nothing else. */
const INTEGER = /^-?[0-9]+$/;
/** A decimal number: `2`, `-0.5`, `.5`, `1.`, `1e-3`; no hex, no `Infinity`, no spaces. */
const DECIMAL = /^-?([0-9]+\.?[0-9]*|\.[0-9]+)([eE][-+]?[0-9]+)?$/;

/** An integer in [min, max] written in decimal, or a CliError naming the option. */
export function parseIntegerValue(option: string, text: string, min: number, max: number): number {
  const value = Number(text);
  if (!INTEGER.test(text) || !Number.isSafeInteger(value) || value < min || value > max) {
    throw new CliError(`${option} must be an integer in [${min}, ${max}], got ${quote(text)}`);
  }
  return value;
}

export interface DecimalRule {
  /** Accepts the value; `rule` completes "<option> must be a decimal number ...". */
  ok: (x: number) => boolean;
  rule: string;
}

export const POSITIVE_DECIMAL: DecimalRule = { ok: (x) => x > 0, rule: '> 0' };

/** A finite decimal number obeying `rule`, or a CliError naming the option. */
export function parseDecimalValue(option: string, text: string, rule: DecimalRule): number {
  const value = Number(text);
  if (!DECIMAL.test(text) || !Number.isFinite(value) || !rule.ok(value)) {
    throw new CliError(`${option} must be a decimal number ${rule.rule}, got ${quote(text)}`);
  }
  return value;
}

/**
 * A switch (`--json`) takes no value: `--json=false` is an error rather than a silent
 * "true" (or a guess at what "false", "0" or "no" mean).
 */
export function switchWithoutValue(option: string, given: string): never {
  throw new CliError(
    `${option} is a switch and takes no value: give ${option} or leave it out, got ${quote(given)}`,
  );
}
