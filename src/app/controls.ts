/**
 * The control panel: each input calls one controller method. Sliders that
 * follow the scene (bounces, aperture) are refreshed whenever a scene
 * loads; the render scale follows the automatic choice until the user
 * moves it. Every slider has a <label for> (its accessible name) and an
 * aria-valuetext with the unit, mirrored by the <output> next to it.
 */
import type { Controller } from '../view/index.ts';

function byId<T extends HTMLElement>(id: string): T {
  return document.getElementById(id) as T;
}

interface Slider {
  readonly input: HTMLInputElement;
  set(value: number): void;
  /** Re-renders the text (its inputs other than the value changed). */
  show(): void;
}

function slider(id: string, format: (v: number) => string, onInput: (v: number) => void): Slider {
  const input = byId<HTMLInputElement>(id);
  const out = byId<HTMLOutputElement>(`${id}-out`);
  const show = () => {
    const text = format(Number(input.value));
    out.textContent = text;
    input.setAttribute('aria-valuetext', text);
  };
  input.addEventListener('input', () => {
    show();
    onInput(Number(input.value));
  });
  return {
    input,
    show,
    set(value: number) {
      input.value = String(value);
      show();
    },
  };
}

/** Lens radius at the aperture slider's full travel, as a fraction of the distance to the target. */
const APERTURE_RANGE = 0.05;
/** The bounce slider goes at least this far (further when a scene asks for more). */
const BOUNCES_MAX = 12;

function targetDistance(c: Controller): number {
  const cam = c.getCamera();
  return Math.hypot(
    cam.position[0] - cam.target[0],
    cam.position[1] - cam.target[1],
    cam.position[2] - cam.target[2],
  );
}

/** A length in scene units with two or three significant digits. */
function sceneLength(v: number): string {
  return v >= 100 ? v.toFixed(0) : v.toPrecision(2);
}

export interface Controls {
  /** Brings the sliders in line with the controller (after a scene load). */
  sync(): void;
  /** Follows what changes on its own: the automatic render scale and the render size. */
  refresh(): void;
}

export function attachControls(c: Controller): Controls {
  const pause = byId<HTMLButtonElement>('pause');
  const showPause = () => (pause.textContent = c.paused ? 'Resume' : 'Pause');
  pause.addEventListener('click', () => {
    if (c.paused) c.resume();
    else c.pause();
    showPause();
  });
  byId('reset').addEventListener('click', () => c.reset());

  const bounces = slider(
    'bounces',
    (v) => `${v} ${v === 1 ? 'bounce' : 'bounces'}`,
    (v) => c.setBounces(v),
  );
  const exposure = slider(
    'exposure',
    (v) => `× ${v.toFixed(2)}`,
    (v) => c.setExposure(v),
  );
  const aperture = slider(
    'aperture',
    (v) =>
      v === 0
        ? 'pinhole'
        : `radius ${sceneLength(v * APERTURE_RANGE * targetDistance(c))} scene units`,
    (v) => c.setAperture(v * APERTURE_RANGE * targetDistance(c)),
  );
  const scale = slider(
    'scale',
    (v) => {
      const s = c.stats();
      const auto = c.renderScaleInfo().auto ? ', automatic' : '';
      return `${Math.round(v * 100)} % (${s.width} × ${s.height}${auto})`;
    },
    (v) => c.setRenderScale(v),
  );
  const workersInput = byId<HTMLInputElement>('workers');
  workersInput.max = String(Math.max(16, navigator.hardwareConcurrency || 4));
  const workers = slider(
    'workers',
    (v) => `${v} ${v === 1 ? 'worker' : 'workers'}`,
    (v) => void c.setWorkers(v),
  );

  const adaptive = byId<HTMLInputElement>('adaptive');
  adaptive.addEventListener('change', () => c.setAdaptive(adaptive.checked));
  const denoise = byId<HTMLInputElement>('denoise');
  denoise.addEventListener('change', () => c.setDenoise(denoise.checked));

  byId('reset-view').addEventListener('click', () => {
    const scene = c.scene;
    if (!scene) return;
    c.setCamera(scene.camera);
    aperture.set(0);
  });

  exposure.set(1);
  const refresh = () => {
    // Not while the user holds the slider: the value is theirs then.
    if (document.activeElement !== scale.input || c.renderScaleInfo().auto) {
      scale.input.value = String(c.renderScaleInfo().scale);
    }
    scale.show();
  };
  const sync = () => {
    const s = c.stats();
    workers.set(s.workers);
    adaptive.checked = c.adaptive;
    denoise.checked = c.denoise;
    showPause();
    refresh();
    if (!c.scene) return;
    const b = c.maxBounces;
    bounces.input.max = String(Math.max(BOUNCES_MAX, b, c.scene.settings.maxBounces));
    bounces.set(b);
    const cam = c.getCamera();
    aperture.set(Math.min(1, cam.aperture / (APERTURE_RANGE * targetDistance(c))));
  };
  return { sync, refresh };
}
