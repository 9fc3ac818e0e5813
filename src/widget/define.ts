/**
 * Registers <pathwise-view> (or the element under another name). Never
 * throws on a name that is already taken: a page may load two copies of the
 * package (two bundles, two versions), and the first registration wins.
 */
import { PathwiseViewElement } from './element.ts';

let baseRegistered = false;

/**
 * Defines the element under `name` unless the name is taken. Returns the
 * constructor registered under `name` afterwards (ours, or whoever got there
 * first), or undefined where there is no custom element registry (SSR).
 */
export function definePathwiseView(name = 'pathwise-view'): CustomElementConstructor | undefined {
  if (typeof customElements === 'undefined') return undefined;
  const existing = customElements.get(name);
  if (existing) return existing;
  // A constructor can back only one name, so further names get a subclass;
  // instances of every name are still `instanceof PathwiseViewElement`.
  const ctor = baseRegistered ? class extends PathwiseViewElement {} : PathwiseViewElement;
  customElements.define(name, ctor);
  if (ctor === PathwiseViewElement) baseRegistered = true;
  return ctor;
}
