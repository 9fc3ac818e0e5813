/**
 * pathwise core: the DOM-free tracer. Runs in Node, in Web Workers and on
 * the main thread alike.
 */
export * from './tracer.ts';
export * from './loading.ts';
