// field_data.js: fetches what `relume publish` wrote (manifest.json, data/field.bin, the tiles
// data/tiles/L/C_R.bin and the maps data/env/N.bin: lib/publish/web_layout.hpp and
// web_bundle.hpp), inflates and unfilters their arrays, and unpacks a tile into the flat arrays
// the renderer uploads as textures (a one-basis field's tiles take their weights from its
// decoded planes, weight_planes.js).

const arrayTypes = {
  uint8: Uint8Array, uint16: Uint16Array, uint32: Uint32Array, int16: Int16Array,
  float32: Float32Array, med16: Uint16Array,
};

export async function fetchOk(path, base) {
  const response = await fetch(new URL(path, base));
  if (!response.ok) throw new Error(`${path}: ${response.status} ${response.statusText}`);
  return response;
}

export async function fetchManifest(base) {
  const manifest = await (await fetchOk('manifest.json', base)).json();
  if (manifest.format !== 'relume-web' || manifest.version !== 1)
    throw new Error(`manifest.json is ${manifest.format} version ${manifest.version} ` +
                    '(this page reads relume-web version 1)');
  return manifest;
}

// Undoes the container's section filters (lib/container/section_coding.cpp) on elements of
// `size` bytes: 1 byte shuffle, 2 delta of elements modulo 2^(8 size) then shuffle. Returns a
// typed array of unsigned elements over its own buffer.
function unfilter(bytes, filter, size) {
  const count = bytes.length / size;
  if (filter > 2) throw new Error(`unknown section filter ${filter}`);
  if (size === 1) {
    const out = filter === 0 ? bytes.slice() : bytes;
    if (filter === 2) for (let i = 1; i < count; ++i) out[i] = (out[i] + out[i - 1]) & 0xff;
    return out;
  }
  if (filter === 0) return new (size === 2 ? Uint16Array : Uint32Array)(bytes.slice().buffer);
  if (size === 2) {
    const out = new Uint16Array(count);
    let previous = 0;
    for (let i = 0; i < count; ++i) {
      const value = bytes[i] | (bytes[count + i] << 8);
      out[i] = previous = filter === 2 ? (previous + value) & 0xffff : value;
    }
    return out;
  }
  if (size !== 4) throw new Error(`a section of ${size}-byte elements`);
  const out = new Uint32Array(count);
  let previous = 0;
  for (let i = 0; i < count; ++i) {
    const value = (bytes[i] | (bytes[count + i] << 8) | (bytes[2 * count + i] << 16) |
                   (bytes[3 * count + i] << 24)) >>> 0;
    out[i] = previous = filter === 2 ? (previous + value) >>> 0 : value;
  }
  return out;
}

// Raw deflate (RFC 1951), decoded by the browser itself.
async function inflate(bytes) {
  const stream = new Blob([bytes]).stream().pipeThrough(new DecompressionStream('deflate-raw'));
  return new Uint8Array(await new Response(stream).arrayBuffer());
}

// A bundle's arrays by name, as typed arrays, and its bytes. `arrays`: the manifest's
// [{name, type}] for it.
export async function fetchBundle(path, arrays, base) {
  const buffer = await (await fetchOk(path, base)).arrayBuffer();
  const header = new DataView(buffer);
  const magic = String.fromCharCode(...new Uint8Array(buffer, 0, 4));
  if (magic !== 'RLWB' || header.getUint32(4, true) !== 1 ||
      header.getUint32(8, true) !== arrays.length)
    throw new Error(`${path} is not a relume-web bundle of ${arrays.length} arrays`);
  let offset = 12 + arrays.length * 12;
  const result = {};
  await Promise.all(arrays.map(async ({ name, type }, k) => {
    const word = header.getUint32(12 + k * 12, true);
    const coded = header.getUint32(16 + k * 12, true), raw = header.getUint32(20 + k * 12, true);
    const Type = arrayTypes[type];
    const start = offset;
    offset += coded;
    if (offset > buffer.byteLength || raw % Type.BYTES_PER_ELEMENT !== 0)
      throw new Error(`${path}: array ${name} does not fit the file`);
    let bytes = new Uint8Array(buffer, start, coded);
    if ((word & 0xff) === 2) bytes = await inflate(bytes);
    if (bytes.length !== raw) throw new Error(`${path}: array ${name} is damaged`);
    const elements = unfilter(bytes, (word >> 8) & 0xff, Type.BYTES_PER_ELEMENT);
    result[name] = new Type(elements.buffer, elements.byteOffset, elements.length);
  }));
  return { arrays: result, bytes: buffer.byteLength };
}

export function forEachSetBit(bits, visit) {
  let ordinal = 0;
  for (let byte = 0; byte < bits.length; ++byte) {
    const value = bits[byte];
    if (value === 0) continue;
    for (let bit = 0; bit < 8; ++bit)
      if (value & (1 << bit)) visit(byte * 8 + bit, ordinal++);
  }
}

// A tile's unpackTile arrays and the bytes of its file. `region` {width, height, x, y, stride}:
// its size and where its pixels lie in the field (pixel (x', y') is the field's pixel
// (x + stride x', y + stride y')); `planes`: a promise of the field's WeightPlanes
// (weight_planes.js), or null when the tiles hold their weights.
export async function fetchTile(file, region, field, arrays, base, planes) {
  const { arrays: a, bytes } = await fetchBundle(file, arrays, base);
  if (planes) a.weights = (await planes).tileWeights(a, region);
  return { tile: unpackTile(field, region.width, region.height, a), bytes };
}

// The median edge detector's prediction (lib/container/weight_prediction.cpp) from the left,
// upper and upper-left rows' weights (-1: no row).
function predicted(weights, terms, j, left, up, upLeft) {
  const at = (row) => weights[row * terms + j];
  if (left >= 0 && up >= 0) {
    const a = at(left), b = at(up);
    const c = upLeft >= 0 ? at(upLeft) : Math.trunc((a + b) / 2);
    if (c >= Math.max(a, b)) return Math.min(a, b);
    if (c <= Math.min(a, b)) return Math.max(a, b);
    return a + b - c;
  }
  if (left >= 0) return at(left);
  if (up >= 0) return at(up);
  return 0;
}

// The arrays of one tile (width x height pixels) the renderer uploads: per pixel its stored row
// per channel (-1 none, -2 - d dark pixel d), per row its cluster and residual span, the weights
// and residual values as stored (16-bit integers times the field's steps, or floats), the
// residual's lights, per dark pixel its gains.
export function unpackTile(field, width, height, a) {
  const { channels, terms } = field;
  const pixels = width * height;
  const pixelRows = new Int32Array(pixels * 4).fill(-1);
  const rowFunction = new Uint32Array(a.clusters.length);
  forEachSetBit(a.stored_functions, (f, row) => {
    pixelRows[Math.floor(f / channels) * 4 + (f % channels)] = row;
    rowFunction[row] = f;
  });
  let darkCount = 0;
  if (a.dark_pixels)
    forEachSetBit(a.dark_pixels, (q, d) => {
      pixelRows.fill(-2 - d, q * 4, q * 4 + channels);
      darkCount = d + 1;
    });

  const rows = a.clusters.length;
  const rowInfo = new Uint32Array(rows * 4);
  let first = 0;
  for (let r = 0; r < rows; ++r) {
    rowInfo[r * 4] = a.clusters[r];
    rowInfo[r * 4 + 1] = first;
    rowInfo[r * 4 + 2] = a.residual_lengths[r];
    first += a.residual_lengths[r];
  }

  // Quantized weights (med16): the prediction undone in row order, kept as integers.
  let weights = a.weights;
  if (weights instanceof Uint16Array) {
    const integers = new Int32Array(weights.length);
    const rowAt = (x, y, c) => (x < 0 || y < 0 ? -1 : pixelRows[(y * width + x) * 4 + c]);
    for (let r = 0; r < rows; ++r) {
      const f = rowFunction[r], c = f % channels, pixel = Math.floor(f / channels);
      const x = pixel % width, y = Math.floor(pixel / width);
      const left = rowAt(x - 1, y, c), up = rowAt(x, y - 1, c), upLeft = rowAt(x - 1, y - 1, c);
      for (let j = 0; j < terms; ++j) {
        const i = r * terms + j;
        integers[i] = ((weights[i] + predicted(integers, terms, j, left, up, upLeft)) << 16) >> 16;
      }
    }
    weights = Int16Array.from(integers);
  }

  const darkGains = new Float32Array(Math.max(1, darkCount) * 4).fill(1);
  if (a.dark_gains)
    for (let d = 0; d < darkCount; ++d)
      for (let c = 0; c < channels; ++c)
        darkGains[d * 4 + c] = Math.fround(a.dark_gains[d * channels + c] * field.dark_gain_step);
  return {
    width, height, pixelRows, rowInfo, weights, darkGains,
    residualValues: a.residual_values, residualLights: a.residual_lights,
  };
}
