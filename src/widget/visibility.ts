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
    // Until the first observation arrives, assume on screen: the first
    // callback comes within a frame, and starting early costs nothing.
    this.onScreen = true;
    if (typeof IntersectionObserver !== 'undefined') {
      this.observer = new IntersectionObserver((entries) => {
        const entry = entries[entries.length - 1];
        if (!entry) return;
        const onScreen = entry.isIntersecting;
        if (onScreen !== this.onScreen) {
          this.onScreen = onScreen;
          this.changed();
        }
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
