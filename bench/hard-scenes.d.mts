/** Types of hard-scenes.mjs for the TypeScript tests that import it. */
export declare function caustic(): Record<string, unknown>;
export declare function windowRoom(): Record<string, unknown>;
export declare function dense(dir: string): Record<string, unknown>;
/** Each scene's maker; `dir` is where a scene with a mesh file writes it (dense.ply). */
export declare const HARD_SCENES: Record<string, (dir: string) => Record<string, unknown>>;
