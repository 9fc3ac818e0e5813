/**
 * The Web Worker interface the browser pool (src/view/pool.ts) and comlink use, over a
 * worker_threads worker: lets the pool's own code run in Node (bench/pool-node.ts,
 * tests/unit/view/pool-faults.test.ts).
 */
import { Worker as NodeWorker } from 'node:worker_threads';

export class NodeWebWorker {
  private readonly w: NodeWorker;
  constructor(file: string) {
    this.w = new NodeWorker(file);
  }
  postMessage(message: unknown, transfer?: Transferable[]): void {
    this.w.postMessage(message, transfer as readonly never[] | undefined);
  }
  addEventListener(type: string, listener: (event: { data?: unknown; message?: string }) => void) {
    if (type === 'message') this.w.on('message', (data) => listener({ data }));
    if (type === 'error') this.w.on('error', (e) => listener({ message: e.message }));
    if (type === 'exit') this.w.on('exit', () => listener({}));
  }
  removeEventListener(): void {}
  terminate(): void {
    void this.w.terminate();
  }
}
