/**
 * Whether an element is worth tracing for: on screen (IntersectionObserver)
 * and in a visible tab (document.visibilityState). Path tracing keeps every
 * core busy, so a view nobody can see must give the CPU back to the page.
 */
export class VisibilityWatcher {
  private onScreen = true;
  private observer: IntersectionObserver | null = null;
  private readonly onVisibilityChange = () => this.changed();

  constructor(
    private readonly target: Element,
    private readonly changed: () => void,
  ) {}

  /** True while the element intersects the viewport and the tab is visible. */
  get visible(): boolean {
    return this.onScreen && !(typeof document !== 'undefined' && document.hidden);
  }

  start(): void {
    if (this.observer) return;
    // An observer always reports once right after observe(), within a
    // frame; until then count as off screen, so an element below the fold
    // never traces a single pass. Without IntersectionObserver, always on.
    this.onScreen = typeof IntersectionObserver === 'undefined';
    if (typeof IntersectionObserver !== 'undefined') {
      this.observer = new IntersectionObserver((entries) => {
        const entry = entries[entries.length - 1];
        if (!entry) return;
        this.onScreen = entry.isIntersecting;
        this.changed();
      });
      this.observer.observe(this.target);
    }
    document.addEventListener('visibilitychange', this.onVisibilityChange);
  }

  stop(): void {
    this.observer?.disconnect();
    this.observer = null;
    document.removeEventListener('visibilitychange', this.onVisibilityChange);
  }
}
