// relight_renderer.js: relights the published field's tiles with WebGL2 (relight_shaders.js
// holds the per-pixel program). A tile's arrays are uploaded once as its own textures; each new
// light uploads the light vector and the per-cluster products v_k = F^k . I, computed here in
// double precision as lib/relight/compressed_relight_reference.cpp does (clusters x terms x
// lights multiply-adds: far less than the per-pixel work). A frame draws each tile clipped to
// its rectangle on the canvas.
import { vertexShader, fragmentShader } from './relight_shaders.js';

function compile(gl, type, source) {
  const shader = gl.createShader(type);
  gl.shaderSource(shader, source);
  gl.compileShader(shader);
  if (!gl.getShaderParameter(shader, gl.COMPILE_STATUS))
    throw new Error(`WebGL2 shader compilation failed: ${gl.getShaderInfoLog(shader)}`);
  return shader;
}

function link(gl, fragmentSource) {
  const program = gl.createProgram();
  gl.attachShader(program, compile(gl, gl.VERTEX_SHADER, vertexShader));
  gl.attachShader(program, compile(gl, gl.FRAGMENT_SHADER, fragmentSource));
  gl.linkProgram(program);
  if (!gl.getProgramParameter(program, gl.LINK_STATUS))
    throw new Error(`WebGL2 program link failed: ${gl.getProgramInfoLog(program)}`);
  return program;
}

// Texel formats: [internal format, format, type, components, typed array].
function formats(gl) {
  return {
    r8ui: [gl.R8UI, gl.RED_INTEGER, gl.UNSIGNED_BYTE, 1, Uint8Array],
    r16ui: [gl.R16UI, gl.RED_INTEGER, gl.UNSIGNED_SHORT, 1, Uint16Array],
    r32ui: [gl.R32UI, gl.RED_INTEGER, gl.UNSIGNED_INT, 1, Uint32Array],
    r16i: [gl.R16I, gl.RED_INTEGER, gl.SHORT, 1, Int16Array],
    rgba32i: [gl.RGBA32I, gl.RGBA_INTEGER, gl.INT, 4, Int32Array],
    rgba32ui: [gl.RGBA32UI, gl.RGBA_INTEGER, gl.UNSIGNED_INT, 4, Uint32Array],
    rgba32f: [gl.RGBA32F, gl.RGBA, gl.FLOAT, 4, Float32Array],
    r32f: [gl.R32F, gl.RED, gl.FLOAT, 1, Float32Array],
  };
}

// The one-component format of a typed array's values.
const singleFormat = (values) => ({
  Uint8Array: 'r8ui', Uint16Array: 'r16ui', Uint32Array: 'r32ui', Int16Array: 'r16i', Float32Array: 'r32f',
})[values.constructor.name];

// The samplers of a tile (texture units 0..5) and of the whole field (6..8).
const tileSamplers = ['pixelRows', 'rowInfo', 'weights', 'residualValues', 'residualLights', 'darkGains'];
const fieldSamplers = ['products', 'light', 'srgbThresholds'];

export class RelightRenderer {
  // gl: a WebGL2 context; manifest: the site's manifest; bases, darkModel: data/field.bin's.
  constructor(gl, manifest, bases, darkModel) {
    this.gl = gl;
    this.field = manifest.field;
    this.bases = bases;
    this.darkModel = darkModel;
    this.formats = formats(gl);
    this.texWidth = Math.min(4096, gl.getParameter(gl.MAX_TEXTURE_SIZE));
    gl.pixelStorei(gl.UNPACK_ALIGNMENT, 1);
    this.program = link(gl, fragmentShader(this.field.weight_step > 0, this.field.residual_step > 0));
    gl.useProgram(this.program);
    [...tileSamplers, ...fieldSamplers].forEach((name, unit) =>
      gl.uniform1i(gl.getUniformLocation(this.program, name), unit));
    const { clusters, terms, lights, channels } = this.field;
    this.products = new Float32Array(clusters * terms * 4);
    this.lightTexels = new Float32Array(lights * 4);
    this.fieldTextures = {
      products: this.arrayTexture('rgba32f', this.products),
      light: this.arrayTexture('rgba32f', this.lightTexels),
      srgbThresholds: this.texture('r32f', new Float32Array(manifest.srgb_thresholds), 256, 1),
    };
    for (const [name, value] of Object.entries({
      texWidth: this.texWidth, terms, channels,
    }))
      gl.uniform1i(gl.getUniformLocation(this.program, name), value);
    gl.uniform1f(gl.getUniformLocation(this.program, 'weightStep'), this.field.weight_step);
    gl.uniform1f(gl.getUniformLocation(this.program, 'residualStep'), this.field.residual_step);
    this.location = Object.fromEntries(
        ['cap', 'dark', 'scale', 'viewOrigin', 'viewScale', 'canvasHeight', 'stride',
         'tileOrigin', 'tileSize'].map((name) => [name, gl.getUniformLocation(this.program, name)]));
    this.dark = [0, 0, 0];
  }

  // A texture of width x height texels of `format` (values padded to whole rows).
  texture(format, values, width, height, texture = this.gl.createTexture()) {
    const gl = this.gl;
    const [internal, layout, type, components, Type] = this.formats[format];
    let texels = values;
    if (values.length < width * height * components) {
      texels = new Type(width * height * components);
      texels.set(values);
    }
    gl.activeTexture(gl.TEXTURE0);
    gl.bindTexture(gl.TEXTURE_2D, texture);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MIN_FILTER, gl.NEAREST);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MAG_FILTER, gl.NEAREST);
    gl.texImage2D(gl.TEXTURE_2D, 0, internal, width, height, 0, layout, type, texels);
    return texture;
  }

  // A 1-D array of texels laid out texWidth wide.
  arrayTexture(format, values, texture) {
    const components = this.formats[format][3];
    const texels = Math.max(1, Math.ceil(values.length / components));
    if (texels > this.texWidth * this.gl.getParameter(this.gl.MAX_TEXTURE_SIZE))
      throw new Error(`a tile holds ${texels} texels, more than this GPU's textures`);
    const width = Math.min(this.texWidth, texels);
    return this.texture(format, values, width, Math.ceil(texels / width), texture);
  }

  // The textures of one tile (unpackTile's arrays).
  uploadTile(data) {
    return {
      width: data.width,
      height: data.height,
      textures: [
        this.texture('rgba32i', data.pixelRows, data.width, data.height),
        this.arrayTexture('rgba32ui', data.rowInfo),
        this.arrayTexture(singleFormat(data.weights), data.weights),
        this.arrayTexture(singleFormat(data.residualValues), data.residualValues),
        this.arrayTexture(singleFormat(data.residualLights), data.residualLights),
        this.arrayTexture('rgba32f', data.darkGains),
      ],
    };
  }

  deleteTile(tile) {
    for (const texture of tile.textures) this.gl.deleteTexture(texture);
  }

  // The light in the field's basis (lights x channels, lightInFieldBasis): uploads it and the
  // per-cluster products, and computes the dark model's value.
  setLight(basisLight) {
    const { clusters, terms, lights, channels } = this.field;
    this.lightTexels.fill(0);
    for (let i = 0; i < lights; ++i)
      for (let c = 0; c < channels; ++c) this.lightTexels[i * 4 + c] = basisLight[i * channels + c];
    for (let k = 0; k < clusters; ++k)
      for (let j = 0; j < terms; ++j) {
        const row = (k * terms + j) * lights;
        for (let c = 0; c < channels; ++c) {
          let sum = 0;
          for (let i = 0; i < lights; ++i) sum += this.bases[row + i] * basisLight[i * channels + c];
          this.products[(k * terms + j) * 4 + c] = sum;
        }
      }
    this.dark = [0, 0, 0];
    if (this.darkModel)
      for (let c = 0; c < channels; ++c) {
        let sum = 0;
        for (let i = 0; i < lights; ++i) sum += this.darkModel[c * lights + i] * basisLight[i * channels + c];
        this.dark[c] = sum;
      }
    this.arrayTexture('rgba32f', this.lightTexels, this.fieldTextures.light);
    this.arrayTexture('rgba32f', this.products, this.fieldTextures.products);
  }

  // Starts a frame on the current framebuffer of width x height pixels: `view` maps its pixels
  // to the field's (field = origin + pixel / scale), `cap` residual entries per function at
  // most, exposed by `exposure` stops; `clear` false keeps what was drawn (to add a tile).
  begin(width, height, view, cap, exposure, clear = true) {
    const gl = this.gl;
    this.target = { width, height, view };
    gl.viewport(0, 0, width, height);
    gl.disable(gl.SCISSOR_TEST);
    gl.clearColor(0.086, 0.094, 0.11, 1);
    if (clear) gl.clear(gl.COLOR_BUFFER_BIT);
    gl.useProgram(this.program);
    gl.uniform1i(this.location.cap, Math.max(0, Math.min(cap, 0x7fffffff)));
    gl.uniform3f(this.location.dark, ...this.dark);
    gl.uniform1f(this.location.scale, Math.fround(2 ** exposure));
    gl.uniform2f(this.location.viewOrigin, view.x, view.y);
    gl.uniform1f(this.location.viewScale, view.scale);
    gl.uniform1i(this.location.canvasHeight, height);
    fieldSamplers.forEach((name, k) => {
      gl.activeTexture(gl.TEXTURE0 + tileSamplers.length + k);
      gl.bindTexture(gl.TEXTURE_2D, this.fieldTextures[name]);
    });
  }

  // Draws a tile of pyramid level `stride` whose first pixel is level pixel (x, y), clipped
  // to `clip` (field pixels [x0, x1) x [y0, y1); default: the whole tile).
  drawTile(tile, stride, x, y, clip) {
    const gl = this.gl, { width, height, view } = this.target;
    const x0 = clip ? clip.x0 : x * stride, y0 = clip ? clip.y0 : y * stride;
    const x1 = clip ? clip.x1 : (x + tile.width) * stride, y1 = clip ? clip.y1 : (y + tile.height) * stride;
    const left = Math.max(0, Math.floor((x0 - view.x) * view.scale));
    const right = Math.min(width, Math.ceil((x1 - view.x) * view.scale));
    const top = Math.max(0, Math.floor((y0 - view.y) * view.scale));
    const bottom = Math.min(height, Math.ceil((y1 - view.y) * view.scale));
    if (right <= left || bottom <= top) return;
    gl.enable(gl.SCISSOR_TEST);
    gl.scissor(left, height - bottom, right - left, bottom - top);
    tile.textures.forEach((texture, unit) => {
      gl.activeTexture(gl.TEXTURE0 + unit);
      gl.bindTexture(gl.TEXTURE_2D, texture);
    });
    gl.uniform1i(this.location.stride, stride);
    gl.uniform2i(this.location.tileOrigin, x, y);
    gl.uniform2i(this.location.tileSize, tile.width, tile.height);
    gl.drawArrays(gl.TRIANGLES, 0, 3);
  }

  // The current framebuffer's RGBA bytes (width x height), rows from the top.
  readPixels(width, height) {
    const gl = this.gl;
    const bottomUp = new Uint8Array(width * height * 4);
    gl.readPixels(0, 0, width, height, gl.RGBA, gl.UNSIGNED_BYTE, bottomUp);
    const topDown = new Uint8Array(bottomUp.length);
    for (let y = 0; y < height; ++y)
      topDown.set(bottomUp.subarray((height - 1 - y) * width * 4, (height - y) * width * 4), y * width * 4);
    return topDown;
  }

  // Waits for the GPU (a one-pixel read), for timing a frame.
  finish() {
    this.gl.readPixels(0, 0, 1, 1, this.gl.RGBA, this.gl.UNSIGNED_BYTE, new Uint8Array(4));
  }
}
