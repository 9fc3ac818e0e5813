import { defineConfig } from 'vitest/config';
import base, { VALIDATION_SUITE } from './vitest.config.ts';

/** `npm run test:validation`: only the generated-scene consistency suite (see vitest.config.ts). */
export default defineConfig({ test: { ...base.test, include: VALIDATION_SUITE, exclude: [] } });
