/**
 * WebGL2 display: every frame the film's sums go up as an RGBA32F texture
 * and a fragment shader divides by the sample count and tone maps
 * (shaders/display.frag.glsl, the same transform as the core's
 * tonemapSums). The main thread's cost is one texSubImage2D and one draw.
 *
 * The context may be lost (a GPU reset, too many contexts on the page) and
 * restored later; `rebuild` then makes the program and textures again, and
 * the next draw uploads the whole film (display-standin.ts covers the gap).
 */
import fragmentSource from '../../shaders/display.frag.glsl?raw';
import vertexSource from '../../shaders/display.vert.glsl?raw';
import type { Backdrop } from './backdrop.ts';
import type { Display, DisplayPixels } from './display.ts';

function compile(gl: WebGL2RenderingContext, type: number, source: string): WebGLShader {
  const shader = gl.createShader(type)!;
  gl.shaderSource(shader, source);
  gl.compileShader(shader);
  if (!gl.getShaderParameter(shader, gl.COMPILE_STATUS)) {
    throw new Error(`display shader: ${gl.getShaderInfoLog(shader) ?? 'compile error'}`);
  }
  return shader;
}

/** Dirty row spans at most this far apart are uploaded together. */
const UPLOAD_GAP_ROWS = 4;

/** A nearest-sampled, edge-clamped texture bound to texture unit `unit` (left bound there). */
function newTexture(gl: WebGL2RenderingContext, unit: number): WebGLTexture {
  const texture = gl.createTexture()!;
  gl.activeTexture(gl.TEXTURE0 + unit);
  gl.bindTexture(gl.TEXTURE_2D, texture);
  gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MIN_FILTER, gl.NEAREST);
  gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MAG_FILTER, gl.NEAREST);
  gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_WRAP_S, gl.CLAMP_TO_EDGE);
  gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_WRAP_T, gl.CLAMP_TO_EDGE);
  return texture;
}

export class WebGLDisplay implements Display {
  readonly mode = 'webgl2' as const;
  readonly canvas: HTMLCanvasElement;
  readonly gl: WebGL2RenderingContext;
  private program!: WebGLProgram;
  private texture!: WebGLTexture;
  /** The last picture (linear RGB, A = shown), sampled where the film has no sample yet. */
  private backdrop!: WebGLTexture;
  private uExposure: WebGLUniformLocation | null = null;
  private uCanvasSize: WebGLUniformLocation | null = null;
  /** The largest texture side (MAX_TEXTURE_SIZE, at least 2048 in WebGL2). */
  readonly maxTextureSize: number;
  private texWidth = 0;
  private texHeight = 0;
  /**
   * Browsers that refuse a SharedArrayBuffer view in texSubImage2D get the
   * sums through this ordinary copy instead.
   */
  private staging: Float32Array | null = null;
  private sharedUploadFails = false;

  /** Throws, with the reason in plain words, when WebGL2 or float textures are unavailable. */
  constructor(canvas: HTMLCanvasElement) {
    const gl = canvas.getContext('webgl2', {
      alpha: false,
      antialias: false,
      depth: false,
      stencil: false,
      preserveDrawingBuffer: false,
    });
    if (!gl) throw new Error('WebGL2 is unavailable');
    this.canvas = canvas;
    this.gl = gl;
    this.maxTextureSize = Number(gl.getParameter(gl.MAX_TEXTURE_SIZE)) || 2048;
    this.build(null);
  }

  /**
   * Makes the program and textures (again, after a context was restored:
   * everything made in the lost context is gone). The texture starts at
   * 1×1, so the next draw allocates it at the film's size and uploads every
   * row; `backdrop` is what the last clear() was given.
   */
  build(backdrop: Backdrop | null): void {
    const gl = this.gl;
    const program = gl.createProgram()!;
    gl.attachShader(program, compile(gl, gl.VERTEX_SHADER, vertexSource));
    gl.attachShader(program, compile(gl, gl.FRAGMENT_SHADER, fragmentSource));
    gl.linkProgram(program);
    if (!gl.getProgramParameter(program, gl.LINK_STATUS)) {
      throw new Error(`display shader: ${gl.getProgramInfoLog(program) ?? 'link error'}`);
    }
    this.program = program;
    this.uExposure = gl.getUniformLocation(program, 'u_exposure');
    this.uCanvasSize = gl.getUniformLocation(program, 'u_canvasSize');
    gl.useProgram(program);
    gl.uniform1i(gl.getUniformLocation(program, 'u_sums'), 0);
    gl.uniform1i(gl.getUniformLocation(program, 'u_backdrop'), 1);
    this.backdrop = newTexture(gl, 1);
    this.texture = newTexture(gl, 0);
    // Probe: a 1×1 float texture must upload without error.
    gl.texImage2D(gl.TEXTURE_2D, 0, gl.RGBA32F, 1, 1, 0, gl.RGBA, gl.FLOAT, new Float32Array(4));
    if (gl.getError() !== gl.NO_ERROR) throw new Error('float textures are unavailable');
    this.texWidth = 1;
    this.texHeight = 1;
    this.setBackdrop(backdrop);
  }

  /** Uploads the backdrop (a 1×1 texture with A = 0, drawn black, for none). */
  private setBackdrop(backdrop: Backdrop | null): void {
    const gl = this.gl;
    gl.activeTexture(gl.TEXTURE1);
    gl.bindTexture(gl.TEXTURE_2D, this.backdrop);
    gl.pixelStorei(gl.UNPACK_ALIGNMENT, 4);
    const w = backdrop?.width ?? 1;
    const h = backdrop?.height ?? 1;
    const data = backdrop?.rgba ?? new Float32Array(4);
    gl.texImage2D(gl.TEXTURE_2D, 0, gl.RGBA32F, w, h, 0, gl.RGBA, gl.FLOAT, data);
    gl.activeTexture(gl.TEXTURE0);
  }

  draw(
    sums: Float32Array,
    filmWidth: number,
    filmHeight: number,
    exposure: number,
    dirtyRows: readonly number[] | null,
  ): void {
    const gl = this.gl;
    gl.bindTexture(gl.TEXTURE_2D, this.texture);
    // Tightly packed rows of 16-byte texels.
    gl.pixelStorei(gl.UNPACK_ALIGNMENT, 4);
    let rows = dirtyRows;
    if (filmWidth !== this.texWidth || filmHeight !== this.texHeight) {
      const f = gl.FLOAT;
      gl.texImage2D(gl.TEXTURE_2D, 0, gl.RGBA32F, filmWidth, filmHeight, 0, gl.RGBA, f, null);
      this.texWidth = filmWidth;
      this.texHeight = filmHeight;
      rows = null;
    }
    // Workers finish a few rows per frame; uploading only those keeps the
    // main thread's share to a fraction of a full 1280×520 upload.
    if (rows === null) rows = [0, filmHeight];
    const rowFloats = filmWidth * 4;
    for (let i = 0; i < rows.length; i += 2) {
      const y0 = rows[i];
      let y1 = rows[i + 1];
      // A pass visits stripes spread over the frame, so a frame's rows come
      // scattered: spans a few rows apart go up as one call, which costs
      // less than the calls it saves.
      while (i + 2 < rows.length && rows[i + 2] - y1 <= UPLOAD_GAP_ROWS) {
        y1 = rows[i + 3];
        i += 2;
      }
      this.upload(sums.subarray(y0 * rowFloats, y1 * rowFloats), filmWidth, y0, y1 - y0);
    }
    gl.viewport(0, 0, this.canvas.width, this.canvas.height);
    gl.useProgram(this.program);
    gl.uniform1f(this.uExposure, exposure);
    gl.uniform2f(this.uCanvasSize, this.canvas.width, this.canvas.height);
    gl.drawArrays(gl.TRIANGLES, 0, 3);
  }

  clear(filmWidth: number, filmHeight: number, backdrop: Backdrop | null): void {
    const gl = this.gl;
    this.setBackdrop(backdrop);
    gl.bindTexture(gl.TEXTURE_2D, this.texture);
    // A fresh texture is zero-filled by WebGL: no sums travel from here.
    const f = gl.FLOAT;
    gl.texImage2D(gl.TEXTURE_2D, 0, gl.RGBA32F, filmWidth, filmHeight, 0, gl.RGBA, f, null);
    this.texWidth = filmWidth;
    this.texHeight = filmHeight;
  }

  private upload(data: Float32Array, w: number, y0: number, h: number): void {
    const gl = this.gl;
    if (!this.sharedUploadFails) {
      try {
        gl.texSubImage2D(gl.TEXTURE_2D, 0, 0, y0, w, h, gl.RGBA, gl.FLOAT, data);
        return;
      } catch {
        this.sharedUploadFails = true;
      }
    }
    if (!this.staging || this.staging.length < data.length) {
      this.staging = new Float32Array(data.length);
    }
    const staging = this.staging.subarray(0, data.length);
    staging.set(data);
    gl.texSubImage2D(gl.TEXTURE_2D, 0, 0, y0, w, h, gl.RGBA, gl.FLOAT, staging);
  }

  readPixels(): DisplayPixels {
    // Without preserveDrawingBuffer the canvas may be cleared after a frame
    // is presented, so callers redraw right before reading (the controller does).
    const gl = this.gl;
    const { width, height } = this.canvas;
    const raw = new Uint8Array(width * height * 4);
    gl.readPixels(0, 0, width, height, gl.RGBA, gl.UNSIGNED_BYTE, raw);
    const rgba = new Uint8Array(raw.length);
    const stride = width * 4;
    for (let y = 0; y < height; y++) {
      rgba.set(raw.subarray((height - 1 - y) * stride, (height - y) * stride), y * stride);
    }
    return { width, height, rgba };
  }

  destroy(): void {
    this.gl.deleteTexture(this.texture);
    this.gl.deleteTexture(this.backdrop);
    this.gl.deleteProgram(this.program);
    // Browsers cap live WebGL contexts per page (about 16) and only free one
    // when its canvas is collected; losing it now frees the GPU side at once.
    // The canvas is done for: a re-connected <pathwise-view> starts on a new one.
    this.gl.getExtension('WEBGL_lose_context')?.loseContext();
  }
}
