#version 300 es
// The display transform of src/core/io/tonemap.ts, on the GPU: mean of the
// accumulated sums (RGB / sample count A), exposure, ACES filmic
// (Narkowicz's fit, input pre-scaled by 0.6) and the sRGB transfer function.
// Dividing by each pixel's own count is what keeps a half-finished pass
// from showing as a darker band.
precision highp float;
precision highp sampler2D;

uniform sampler2D u_sums;
// The last picture (linear mean RGB, A = 1 where it holds one), shown where
// the film has no sample yet, so a restart never blanks the screen.
uniform sampler2D u_backdrop;
uniform float u_exposure;
uniform vec2 u_canvasSize;

out vec4 fragColor;

vec3 aces(vec3 x) {
  vec3 v = x * 0.6;
  return clamp((v * (2.51 * v + 0.03)) / (v * (2.43 * v + 0.59) + 0.14), 0.0, 1.0);
}

vec3 srgb(vec3 c) {
  vec3 lo = 12.92 * c;
  vec3 hi = 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055;
  return mix(hi, lo, vec3(lessThanEqual(c, vec3(0.0031308))));
}

void main() {
  // Film row 0 is the top row; gl_FragCoord's origin is the bottom left.
  // Texel fetch (no filtering): RGBA32F is not filterable everywhere, and a
  // low-resolution preview is fine with nearest neighbours.
  ivec2 size = textureSize(u_sums, 0);
  vec2 uv = vec2(gl_FragCoord.x, u_canvasSize.y - gl_FragCoord.y) / u_canvasSize;
  ivec2 texel = min(ivec2(uv * vec2(size)), size - 1);
  vec4 s = texelFetch(u_sums, texel, 0);
  ivec2 backSize = textureSize(u_backdrop, 0);
  vec4 back = texelFetch(u_backdrop, min(ivec2(uv * vec2(backSize)), backSize - 1), 0);
  vec3 mean = s.a > 0.0 ? s.rgb / s.a : back.rgb * back.a;
  fragColor = vec4(srgb(aces(mean * u_exposure)), 1.0);
}
