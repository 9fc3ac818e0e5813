// Types of the parts of bench/lib.mjs that the TypeScript benchmarks use.

/** Relative MSE: mean over pixels and channels of (x − r)² / (r² + 0.01). */
export function relMse(x: ArrayLike<number>, r: ArrayLike<number>): number;
