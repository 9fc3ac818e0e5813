/**
 * Attribute ⇄ property conversions for <pathwise-view>. Attributes are
 * strings written by hand in HTML, so parsing is forgiving: anything that is
 * not a finite number counts as "not set" and the documented default applies,
 * rather than throwing from an attribute callback the author cannot catch.
 */

/** The observed attributes, in HTML spelling. */
export const OBSERVED_ATTRIBUTES = [
  'src',
  'spp',
  'bounces',
  'exposure',
  'seed',
  'camera-controls',
  'autoplay',
  'paused',
  'render-scale',
  'alt',
  'denoise',
  'adaptive',
] as const;

export type ObservedAttribute = (typeof OBSERVED_ATTRIBUTES)[number];

export const DEFAULT_SPP = 512;
export const DEFAULT_EXPOSURE = 1;

/** A finite number, or undefined when the attribute is absent or not a number. */
export function parseNumber(value: string | null): number | undefined {
  if (value === null || value.trim() === '') return undefined;
  const n = Number(value);
  return Number.isFinite(n) ? n : undefined;
}

/** A positive number, or undefined (for sizes and scales where 0 is meaningless). */
export function parsePositive(value: string | null): number | undefined {
  const n = parseNumber(value);
  return n !== undefined && n > 0 ? n : undefined;
}

/**
 * `autoplay` is on unless written `autoplay="false"`: a drop-in element
 * should start tracing without extra markup, yet authors need a way to opt
 * out, and a plain boolean attribute cannot default to true.
 */
export function parseAutoplay(value: string | null): boolean {
  return value === null || value.trim().toLowerCase() !== 'false';
}

/** `adaptive` (adaptive sampling) is on unless written `adaptive="false"`, as `autoplay`. */
export const parseAdaptive = parseAutoplay;

/** Writes a number attribute, or removes it for null/undefined (back to the default). */
export function writeNumber(
  el: Element,
  name: ObservedAttribute,
  value: number | null | undefined,
) {
  if (value === null || value === undefined) el.removeAttribute(name);
  else el.setAttribute(name, String(value));
}

/** Writes a boolean attribute the HTML way: present for true, absent for false. */
export function writeBoolean(el: Element, name: ObservedAttribute, value: boolean) {
  el.toggleAttribute(name, value);
}
