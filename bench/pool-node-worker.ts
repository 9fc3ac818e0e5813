/** The browser's render worker, run in a worker_threads worker (see pool-node-shim.ts). */
import './pool-node-shim.ts';
import '../workers/browser/render-worker.ts';
