/**
 * A browser denoiser thread (src/view/denoise-view.ts starts them on demand): Open
 * Image Denoise's "RT" U-Net in TypeScript (src/core/denoise), with the weights OIDN runs
 * at quality "fast" (rt_hdr_alb_nrm_small), which match native OIDN 2.5.1 at that
 * quality (tests/unit/core/denoise-oidn.test.ts) and take half the base network's time,
 * so a still view is denoised within half a second on two cores (tests/timing). The weights are
 * fetched once, on the first request; one workspace is kept for the tile size in use.
 * Each request names the tiles this worker runs; it writes only their regions.
 */
import {
  allocDenoiseWorkspace,
  prepareDenoise,
  runDenoiseTile,
} from '../../src/core/denoise/denoise.ts';
import { parseTza } from '../../src/core/denoise/tza.ts';
import type { UNetWorkspace } from '../../src/core/denoise/unet.ts';
import { unetWeights, type UNetWeights } from '../../src/core/denoise/unet-weights.ts';
import {
  DENOISE_TILE_OPTIONS,
  type DenoiseReply,
  type DenoiseRequest,
} from './denoise-protocol.ts';

const WEIGHTS_URL = new URL('../../vendor/oidn-weights/rt_hdr_alb_nrm_small.tza', import.meta.url);

let weights: Promise<UNetWeights> | null = null;
let workspace: UNetWorkspace | null = null;

async function loadWeights(): Promise<UNetWeights> {
  const response = await fetch(WEIGHTS_URL);
  if (!response.ok) throw new Error(`denoiser weights: HTTP ${response.status} for ${WEIGHTS_URL}`);
  return unetWeights(parseTza(new Uint8Array(await response.arrayBuffer())));
}

function post(reply: DenoiseReply, transfer: Transferable[] = []): void {
  (self as unknown as Worker).postMessage(reply, transfer);
}

self.onmessage = async (e: MessageEvent<DenoiseRequest>) => {
  const req = e.data;
  if (req?.type !== 'denoise') return;
  try {
    weights ??= loadWeights();
    const w = await weights;
    const t0 = performance.now();
    const { width, height, color, albedo, normal } = req;
    // Every worker of a request sees the whole image: the same autoexposure, the same plan.
    const job = prepareDenoise({ width, height, color, albedo, normal }, w, DENOISE_TILE_OPTIONS);
    if (workspace?.h !== job.plan.tileH || workspace.w !== job.plan.tileW) {
      workspace = null; // the old one is garbage before the new one is allocated
      workspace = allocDenoiseWorkspace(job);
    }
    const rgb = new Float32Array(width * height * 3);
    const flag = req.stop ? new Int32Array(req.stop) : null;
    const stop = flag ? () => Atomics.load(flag, 0) !== req.id : undefined;
    for (const i of req.tiles) {
      if (!runDenoiseTile(job, i, workspace, rgb, stop)) {
        post({ type: 'cancelled', id: req.id });
        return;
      }
    }
    post({ type: 'done', id: req.id, tiles: req.tiles, rgb, ms: performance.now() - t0 }, [
      rgb.buffer,
    ]);
  } catch (err) {
    // A failed weights fetch is tried again on the next request.
    if (
      weights &&
      (await weights.then(
        () => false,
        () => true,
      ))
    )
      weights = null;
    post({ type: 'error', id: req.id, message: err instanceof Error ? err.message : String(err) });
  }
};

post({ type: 'ready' });
