// tile_worker.js: a module Web Worker of tile_decoder.js: fetches, inflates and unpacks one tile
// at a time (field_data.js) off the page's thread, and hands the arrays back without copying,
// with the bytes the browser fetched for it.
import { fetchBundle, unpackTile } from './field_data.js';

let setup = null;  // {base, field, arrays}: the site's URL, the manifest's field and tile arrays

onmessage = async ({ data }) => {
  if (data.setup) {
    setup = data.setup;
    return;
  }
  try {
    const { arrays, bytes } = await fetchBundle(data.file, setup.arrays, setup.base);
    const fetched = performance.getEntriesByName(new URL(data.file, setup.base).href).at(-1);
    const tile = unpackTile(setup.field, data.width, data.height, arrays);
    const buffers = new Set(Object.values(tile).filter(ArrayBuffer.isView).map((a) => a.buffer));
    postMessage({ id: data.id, tile, bytes: fetched?.encodedBodySize || bytes }, [...buffers]);
  } catch (error) {
    postMessage({ id: data.id, error: error.message });
  }
};
