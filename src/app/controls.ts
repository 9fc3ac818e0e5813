/**
 * The control panel: each input calls one controller method. Sliders that
 * follow the scene (bounces, aperture) are refreshed whenever a scene loads.
 */
import type { Controller } from '../view/index.ts';

function byId<T extends HTMLElement>(id: string): T {
  return document.getElementById(id) as T;
}

function slider(id: string, format: (v: number) => string, onInput: (v: number) => void) {
  const input = byId<HTMLInputElement>(id);
  const out = byId<HTMLOutputElement>(`${id}-out`);
  const show = () => (out.textContent = format(Number(input.value)));
  input.addEventListener('input', () => {
    show();
    onInput(Number(input.value));
  });
  return {
    set(value: number) {
      input.value = String(value);
      show();
    },
  };
}

/** Lens radius at the aperture slider's full travel, as a fraction of the distance to the target. */
const APERTURE_RANGE = 0.05;

function targetDistance(c: Controller): number {
  const cam = c.getCamera();
  return Math.hypot(
    cam.position[0] - cam.target[0],
    cam.position[1] - cam.target[1],
    cam.position[2] - cam.target[2],
  );
}

export interface Controls {
  /** Brings the sliders in line with the controller (after a scene load). */
  sync(): void;
}

export function attachControls(c: Controller, renderScale = 1): Controls {
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
    (v) => String(v),
    (v) => c.setBounces(v),
  );
  const exposure = slider(
    'exposure',
    (v) => v.toFixed(2),
    (v) => c.setExposure(v),
  );
  const aperture = slider(
    'aperture',
    (v) => (v === 0 ? 'pinhole' : (v * APERTURE_RANGE * targetDistance(c)).toPrecision(2)),
    (v) => c.setAperture(v * APERTURE_RANGE * targetDistance(c)),
  );
  const scale = slider(
    'scale',
    (v) => `${Math.round(v * 100)} %`,
    (v) => c.setRenderScale(v),
  );
  const workersInput = byId<HTMLInputElement>('workers');
  workersInput.max = String(Math.max(16, navigator.hardwareConcurrency || 4));
  const workers = slider(
    'workers',
    (v) => String(v),
    (v) => void c.setWorkers(v),
  );

  exposure.set(1);
  scale.set(renderScale);
  const sync = () => {
    const s = c.stats();
    workers.set(s.workers);
    showPause();
    if (!c.scene) return;
    bounces.set(Math.min(12, Math.max(1, c.scene.settings.maxBounces)));
    const cam = c.getCamera();
    aperture.set(Math.min(1, cam.aperture / (APERTURE_RANGE * targetDistance(c))));
  };
  return { sync };
}
