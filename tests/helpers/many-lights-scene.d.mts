// Types of many-lights-scene.mjs.
export function manyLights(count: number, seed?: number): unknown;
