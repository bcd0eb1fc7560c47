// relight_shaders.js: the WebGL2 (GLSL ES 3.00) programs that relight the field, one fragment per
// pixel. Per channel c of pixel p, as lib/relight/compressed_relight_reference.cpp:
//   a stored row r:  sum_j W[r][j] * v[cluster(r)][j][c] + sum_{e < min(length, cap)} E[r][e] * I[light(e)][c]
//   dark pixel d:    gain(d, c) * (dark model . I)[c]
//   otherwise:       0 (outside the mask, or an all-zero function)
// where v = F^k . I (computed per frame in JS, relight_renderer.js) and I is the light in the
// field's basis. The value is exposed (x 2^stops) and written as its 8-bit sRGB code, found among
// relume's own code thresholds (image/srgb_codes.hpp), so the canvas holds write_image's bytes.
// The program draws one tile: the canvas pixel's field position is viewOrigin + pixel / viewScale,
// its pixel on the tile's pyramid level that position / stride; pixels outside the tile are
// discarded. Every array lives in a 2D texture `texWidth` texels wide, element i at
// (i % texWidth, i / texWidth).

export const vertexShader = `#version 300 es
// One triangle that covers the viewport.
void main() {
  vec2 corner = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
  gl_Position = vec4(corner * 2.0 - 1.0, 0.0, 1.0);
}
`;

// The fragment program for weights and residual values stored as 16-bit integers times their
// step (`integerWeights`, `integerResidual`: the quantized fields relume writes) or as floats.
export const fragmentShader = (integerWeights, integerResidual) => `#version 300 es
#define INTEGER_WEIGHTS ${integerWeights ? 1 : 0}
#define INTEGER_RESIDUAL ${integerResidual ? 1 : 0}
precision highp float;
precision highp int;
precision highp sampler2D;
precision highp isampler2D;
precision highp usampler2D;

// The tile's:
uniform isampler2D pixelRows;  // its pixels: per channel the stored row, -1 none, -2 - d dark d
uniform usampler2D rowInfo;    // per stored row: cluster, first residual entry, entries
#if INTEGER_WEIGHTS
uniform isampler2D weights;    // per stored row and term: the weight / weightStep
#else
uniform sampler2D weights;     // per stored row and term: the weight
#endif
#if INTEGER_RESIDUAL
uniform isampler2D residualValues;  // per entry: the value / residualStep
#else
uniform sampler2D residualValues;   // per entry: the value
#endif
uniform usampler2D residualLights;  // per entry: its light
uniform sampler2D darkGains;   // per dark pixel: its gains (RGB)
// The field's:
uniform sampler2D products;    // per cluster and term: v[k][j] (RGB)
uniform sampler2D light;       // per light: I in the field's basis (RGB)
uniform sampler2D srgbThresholds;  // 256 x 1: the 8-bit sRGB codes' thresholds
uniform int texWidth, terms, channels, cap, canvasHeight, stride;
uniform float weightStep, residualStep;
uniform ivec2 tileOrigin, tileSize;  // in pixels of the tile's level
uniform vec2 viewOrigin;
uniform float viewScale;
uniform vec3 dark;   // the dark model times I, per channel
uniform float scale;  // 2^exposure
out vec4 color;

ivec2 at(int i) { return ivec2(i % texWidth, i / texWidth); }

float relightRow(int row, int c) {
  uvec4 info = texelFetch(rowInfo, at(row), 0);
  int cluster = int(info.x);
  float sum = 0.0;
  for (int j = 0; j < terms; ++j) {
#if INTEGER_WEIGHTS
    float w = float(texelFetch(weights, at(row * terms + j), 0).x) * weightStep;
#else
    float w = texelFetch(weights, at(row * terms + j), 0).x;
#endif
    sum += w * texelFetch(products, at(cluster * terms + j), 0)[c];
  }
  int first = int(info.y);
  int used = min(int(info.z), cap);
  for (int e = first; e < first + used; ++e) {
#if INTEGER_RESIDUAL
    float value = float(texelFetch(residualValues, at(e), 0).x) * residualStep;
#else
    float value = texelFetch(residualValues, at(e), 0).x;
#endif
    sum += value * texelFetch(light, at(int(texelFetch(residualLights, at(e), 0).x)), 0)[c];
  }
  return sum;
}

// The code of linear value v: how many of thresholds 1..255 are at or below it.
float srgbCode(float v) {
  v = clamp(v, 0.0, 1.0);
  int low = 0, high = 255;
  while (low < high) {
    int middle = (low + high + 1) / 2;
    if (texelFetch(srgbThresholds, ivec2(middle, 0), 0).x <= v) low = middle;
    else high = middle - 1;
  }
  return float(low);
}

void main() {
  vec2 position = viewOrigin + vec2(gl_FragCoord.x, float(canvasHeight) - gl_FragCoord.y) / viewScale;
  ivec2 pixel = ivec2(floor(position / float(stride))) - tileOrigin;
  if (any(lessThan(pixel, ivec2(0))) || any(greaterThanEqual(pixel, tileSize))) discard;
  ivec4 rows = texelFetch(pixelRows, pixel, 0);
  vec3 codes = vec3(0.0);
  for (int c = 0; c < channels; ++c) {
    float value = 0.0;
    if (rows[c] >= 0)
      value = relightRow(rows[c], c);
    else if (rows[c] <= -2)
      value = texelFetch(darkGains, at(-2 - rows[c]), 0)[c] * dark[c];
    codes[c] = srgbCode(value * scale);
  }
  if (channels == 1) codes = codes.xxx;
  color = vec4(codes / 255.0, 1.0);
}
`;
