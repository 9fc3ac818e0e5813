/**
 * The controller's job in the page's worker pool (pool.ts): the
 * configuration the workers render, its version, and the controller's
 * client in the pool (where tasks come from, where results go, how the work
 * of workers that died is recovered).
 *
 * Every restart bumps the version before it resets the film: results and
 * lost tasks of an older version are dropped, as the film they were for
 * has been reset.
 */
import {
  DEFAULT_SAMPLER,
  type CameraDesc,
  type PackedScene,
  type RenderSettings,
} from '../core/index.ts';
import type { JobConfig } from '../../workers/browser/render-protocol.ts';
import type { FilmJob } from './film-job.ts';
import type { Films } from './films.ts';
import { releasePool, type PoolClient, type WorkerPool } from './pool.ts';
import { SharedFilmJob } from './shared-job.ts';
import { TraceClock } from './trace-clock.ts';
import type { ComputeMode } from './types.ts';

/** The image a restart configures (the film's size comes from the film). */
export interface ImageSettings extends Pick<RenderSettings, 'maxBounces' | 'seed'> {
  mode: ComputeMode;
  sceneId: number;
  scene: PackedScene;
  camera: CameraDesc;
}

export class RenderJob {
  readonly pool: WorkerPool;
  readonly client: PoolClient;
  private readonly films: Films;
  version = 0;
  config: JobConfig | null = null;
  /** Tracing time of the active film since its last restart. */
  readonly clock = new TraceClock();

  /** `wake` wakes the frame loop (a result may change the picture). */
  constructor(
    id: number,
    pool: WorkerPool,
    films: Films,
    wake: () => void,
    emit: (type: string, detail: unknown) => void,
  ) {
    this.pool = pool;
    this.films = films;
    this.client = {
      id,
      config: () => this.config!,
      nextTask: () => films.active()?.nextTask?.(id) ?? null,
      onResult: (r) => {
        const job = films.active();
        if (job && r.version === this.version) job.onResult?.(r);
        wake();
      },
      onWorkerError: (message) => emit('error', { message }),
      onTaskLost: (task) => {
        const job = films.active();
        if (job && task.version === this.version) job.onTaskLost?.(task);
        wake();
      },
      recover: () => {
        let done = true;
        for (const job of [films.full, films.preview]) {
          if (job?.recover && !job.recover()) done = false;
        }
        wake();
        return done;
      },
    };
  }

  /** A new configuration version for `active`, reset; send() hands it to the workers. */
  start(active: FilmJob, image: ImageSettings, target: number, paused: boolean): void {
    this.version++;
    // Version first, then reset: a worker still holding the old
    // configuration can claim nothing once the version moved on.
    active.setVersion(this.version);
    active.setTarget(target);
    active.setPaused(paused);
    active.reset();
    active.takeRenewed?.();
    const shared = active instanceof SharedFilmJob ? active : null;
    this.config = {
      mode: image.mode,
      version: this.version,
      sceneId: image.sceneId,
      scene: image.scene,
      width: active.width,
      height: active.height,
      maxBounces: image.maxBounces,
      seed: image.seed,
      estimator: 'nee-mis',
      sampler: DEFAULT_SAMPLER,
      camera: image.camera,
      stripeRows: active.stripeRows,
      aux: active.aux,
      adaptive: active.adaptive,
      map: shared?.mapBuffer ?? undefined,
      film: shared?.filmBuffer,
      ctrl: shared?.ctrlBuffer,
      journal: shared?.journalBuffer,
    };
  }

  /** The configuration to the workers, and work asked of them. */
  send(): void {
    this.pool.register(this.client);
    this.pool.configure(this.client);
    this.pool.kick();
  }

  /** Resets `job` (the active film) to zero samples, same configuration. */
  reset(job: FilmJob, paused: boolean): void {
    job.reset();
    if (job instanceof SharedFilmJob && job.takeRenewed()) {
      // The film moved to new buffers (a lock its holder would not let go):
      // the workers need them.
      this.config = {
        ...this.config!,
        film: job.filmBuffer,
        ctrl: job.ctrlBuffer,
        journal: job.journalBuffer,
      };
      this.pool.configure(this.client);
    }
    this.clock.restart(performance.now(), paused);
  }

  /** The camera's focus changed without changing the image (a pinhole's). */
  setCamera(camera: CameraDesc): void {
    if (this.config) this.config = { ...this.config, camera };
  }

  async setWorkers(count: number): Promise<void> {
    await this.pool.setSize(count);
    this.pool.kick();
  }

  /** Leaves the pool (destroy); the pool ends with its last client. */
  release(): void {
    this.pool.unregister(this.client);
    releasePool(this.pool);
  }
}
