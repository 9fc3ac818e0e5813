/**
 * The package's main entry: everything from index.ts, and <pathwise-view>
 * registered on import if that name is still free. This is the one module
 * with a side effect (package.json "sideEffects" names its build output).
 * Safe to import where there is no DOM: definePathwiseView then does nothing.
 */
import { definePathwiseView } from './define.ts';

export * from './index.ts';

definePathwiseView();
