// weight_planes.js: the weights of a one-basis field (a rate target's model), which `relume
// publish` writes as its container codes them: one JPEG 2000 codestream of channels x terms
// signed 16-bit planes (data/weights.j2k; lib/model/weight_planes.hpp). Decodes it whole, once,
// with OpenJPEG built for WebAssembly (openjpeg/j2k_decode.js and .wasm.gz, loaded only by such
// sites), and gives each tile its stored rows' weights from the planes as relume's reader does
// (set_weights_from_planes in lib/model/weight_planes.cpp): plane values float(sample x step);
// with three channels each term's orthonormal colour transform (the manifest's colour_angles, else
// one fixed transform) undone in double precision, rounded to float. Whole planes, not regions at a
// resolution level: a pyramid level holds every 2^L-th pixel, which JPEG 2000's reduced resolutions
// (low-pass images) are not, and one decode serves every tile of every level.
import { fetchOk, forEachSetBit } from './field_data.js';

// Gzipped: a third of the bytes from any server. A server that declares .gz files as
// Content-Encoding hands over the .wasm itself, which is taken as it is.
const decoderWasm = './openjpeg/j2k_decode.wasm.gz';

// The decoder's .wasm bytes from the fetched file: inflated where they are still gzip's.
async function wasmBytes(response) {
  const bytes = await response.arrayBuffer();
  const head = new Uint8Array(bytes, 0, Math.min(2, bytes.byteLength));
  if (head[0] !== 0x1f || head[1] !== 0x8b) return bytes;
  const inflated = new Blob([bytes]).stream().pipeThrough(new DecompressionStream('gzip'));
  return new Response(inflated).arrayBuffer();
}

// transform[a][c]: component a's entry for channel c in term j (lib/model/weight_planes.cpp):
// with three channels the rotation Rz(a) Ry(b) Rx(c) of the term's angles (units of pi / 32767)
// in `angles`, or without them the fixed luma / R - G / R + G - 2B transform.
function colourTransform(channels, angles, j) {
  const identity = (a) => Array.from({ length: channels }, (_, c) => (a === c ? 1 : 0));
  if (channels !== 3) return Array.from({ length: channels }, (_, a) => identity(a));
  if (!angles) {
    const a = 1 / Math.sqrt(3), b = 1 / Math.sqrt(2), c = 1 / Math.sqrt(6);
    return [[a, a, a], [b, -b, 0], [c, c, -2 * c]];
  }
  const [a, b, c] = angles.slice(3 * j, 3 * j + 3).map((units) => (units * Math.PI) / 32767);
  const [ca, sa, cb, sb, cc, sc] =
      [Math.cos(a), Math.sin(a), Math.cos(b), Math.sin(b), Math.cos(c), Math.sin(c)];
  return [
    [ca * cb, ca * sb * sc - sa * cc, ca * sb * cc + sa * sc],
    [sa * cb, sa * sb * sc + ca * cc, sa * sb * cc - ca * sc], [-sb, cb * sc, cb * cc]
  ];
}

// Bytes the browser fetched for these URLs (its resource timings; `fallback` where it gives none).
function fetchedBytes(urls, fallback) {
  const sizes = urls.map((url) => performance.getEntriesByName(url).at(-1)?.encodedBodySize || 0);
  return sizes.reduce((sum, size) => sum + size, 0) || fallback;
}

export class WeightPlanes {
  // entry: the manifest's weight_planes; field: its field; samples: the decoded planes; bytes
  // fetched for them (the codestream and the decoder); seconds from asking to decoded.
  constructor(entry, field, samples, bytes, seconds) {
    this.field = field;
    this.step = entry.step;
    this.samples = samples;
    // entries[j][c][a]: term j's transform's entry of component a for channel c.
    this.entries = Array.from({length: field.terms}, (_, j) => {
      const transform = colourTransform(field.channels, entry.colour_angles, j);
      return transform.map((_, c) => transform.map((row) => row[c]));
    });
    this.bytes = bytes;
    this.seconds = seconds;
  }

  // Fetches and decodes the manifest's weight_planes `entry`; rejects naming the file when it is
  // missing, damaged or not the field's planes.
  static async fetch(entry, field, base) {
    const started = performance.now();
    // The .wasm fetched here, not by the module, so that a server's MIME type for it does not
    // matter and a failed fetch is named.
    const [bytes, wasmBinary, { default: createDecoder }] = await Promise.all([
      fetchOk(entry.file, base).then((response) => response.arrayBuffer()),
      fetchOk(decoderWasm, import.meta.url).then(wasmBytes),
      import('./openjpeg/j2k_decode.js'),
    ]);
    const decoder = await createDecoder({ wasmBinary });
    const input = decoder._malloc(bytes.byteLength);
    decoder.HEAPU8.set(new Uint8Array(bytes), input);
    const planes = decoder._j2k_decode(input, bytes.byteLength);
    decoder._free(input);
    if (!planes)
      throw new Error(`${entry.file}: the JPEG 2000 codestream does not decode: ` +
                      decoder.UTF8ToString(decoder._j2k_errors()));
    try {
      const [count, width, height, samples] =
          decoder.HEAP32.subarray(planes >> 2, (planes >> 2) + 4);
      if (count !== entry.planes || width !== field.width || height !== field.height)
        throw new Error(`${entry.file} holds ${count} planes of ${width} x ${height}, expected ` +
                        `${entry.planes} of ${field.width} x ${field.height}`);
      const first = samples >> 1;
      const copy = decoder.HEAP16.slice(first, first + count * width * height);
      const urls = [new URL(entry.file, base), new URL('./openjpeg/j2k_decode.js', import.meta.url),
                    new URL(decoderWasm, import.meta.url)].map((url) => url.href);
      return new WeightPlanes(entry, field, copy, fetchedBytes(urls, bytes.byteLength),
                              (performance.now() - started) / 1000);
    } finally {
      decoder._j2k_free_planes(planes);
    }
  }

  // The weights (stored rows x terms, float32) of the tile whose arrays are `a` (its stored
  // functions and one cluster per stored row); its pixel (x', y') is the field's pixel
  // (x + stride x', y + stride y').
  tileWeights(a, { width, x, y, stride }) {
    const { channels, terms } = this.field, step = this.step, samples = this.samples;
    const area = this.field.width * this.field.height, planes = channels * terms;
    const weights = new Float32Array(a.clusters.length * terms);
    const values = new Float64Array(planes);  // a pixel's plane values, plane after plane
    let valuesOf = -1;  // that pixel (a pixel's functions come one after the other)
    forEachSetBit(a.stored_functions, (f, row) => {
      const channel = f % channels, pixel = (f - channel) / channels;
      if (pixel !== valuesOf) {
        valuesOf = pixel;
        const fieldPixel = (y + stride * Math.floor(pixel / width)) * this.field.width + x +
                           stride * (pixel % width);
        for (let plane = 0; plane < planes; ++plane)
          values[plane] = Math.fround(samples[plane * area + fieldPixel] * step);
      }
      for (let j = 0; j < terms; ++j) {
        const entries = this.entries[j][channel];
        let weight = 0;
        for (let component = 0; component < channels; ++component)
          weight += entries[component] * values[component * terms + j];
        weights[row * terms + j] = weight;
      }
    });
    return weights;
  }
}

// A function that returns the planes of `entry` (a promise, fetched and decoded when first
// asked for), or null when the site has none (the tiles hold their weights).
export function weightPlanesOnce(entry, field, base) {
  let planes = null;
  return () => (entry ? (planes ??= WeightPlanes.fetch(entry, field, base)) : null);
}
