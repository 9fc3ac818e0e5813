// Types of bench/scenes.mjs for the TypeScript benchmarks.

export function spheresField(count: number, seed?: number): unknown;
export function manyLights(count: number, seed?: number): unknown;
export function writeSpheresField(file: string, count: number, seed?: number): string;
