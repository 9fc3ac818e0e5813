/** Types of hard-scenes.mjs for the TypeScript tests that import it. */
export declare function caustic(): Record<string, unknown>;
export declare function windowRoom(): Record<string, unknown>;
export declare const HARD_SCENES: Record<string, () => Record<string, unknown>>;
