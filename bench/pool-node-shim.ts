/**
 * Gives a worker_threads worker the Web Worker globals the browser's render
 * worker uses (self-addressed postMessage and message events), so that
 * workers/browser/render-worker.ts runs unchanged in Node (bench/pool-node.ts).
 * Imported before the render worker, whose module body calls
 * Comlink.expose on these globals.
 */
import { parentPort } from 'node:worker_threads';

const g = globalThis as unknown as {
  postMessage(message: unknown, transfer?: Transferable[]): void;
  addEventListener(type: string, listener: (event: { data: unknown }) => void): void;
  removeEventListener(type: string, listener: unknown): void;
};
g.postMessage = (message, transfer) =>
  parentPort!.postMessage(message, transfer as readonly never[] | undefined);
g.addEventListener = (type, listener) => {
  if (type === 'message') parentPort!.on('message', (data) => listener({ data }));
};
g.removeEventListener = () => {};
