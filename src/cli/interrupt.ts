/**
 * Ctrl-C (SIGINT) and SIGTERM while a command has output files in the
 * making: every temporary file is removed and the process exits with
 * 130 / 143. The handlers are installed before the first temporary file is
 * created, and a signal that arrives while one is being created is acted
 * on as soon as its creation settles, so no window leaves a file behind
 * (OutputFile creates the file in the thread pool, before the promise of
 * `prepare` resolves).
 */
import { OutputFile } from './output.ts';

export class Interrupts {
  private readonly files = new Set<OutputFile>();
  private preparing = 0;
  private signal: NodeJS.Signals | undefined;
  private readonly onSignal = (signal: NodeJS.Signals) => {
    this.signal = signal;
    if (this.preparing === 0) this.exit();
  };

  constructor() {
    process.once('SIGINT', this.onSignal);
    process.once('SIGTERM', this.onSignal);
  }

  /** OutputFile.prepare, with the file removed if the process is interrupted. */
  async prepare(path: string): Promise<OutputFile> {
    this.preparing++;
    try {
      const file = await OutputFile.prepare(path);
      this.files.add(file);
      return file;
    } finally {
      this.preparing--;
      if (this.signal && this.preparing === 0) this.exit();
    }
  }

  /** The file was committed or discarded: nothing left to remove. */
  release(file: OutputFile): void {
    this.files.delete(file);
  }

  dispose(): void {
    process.off('SIGINT', this.onSignal);
    process.off('SIGTERM', this.onSignal);
  }

  private exit(): never {
    for (const file of this.files) file.discardSync();
    process.exit(this.signal === 'SIGINT' ? 130 : 143);
  }
}
