// tile_worker.js: a module Web Worker of tile_decoder.js: fetches, inflates and unpacks one tile
// at a time (field_data.js) off the page's thread, and hands the arrays back without copying,
// with the bytes the browser fetched for it. A one-basis field's worker (there is one) also
// decodes the weight planes, once, and fills each tile's weights from them (weight_planes.js);
// its first tile's message adds their bytes and says how long they took.
import { fetchTile } from './field_data.js';
import { weightPlanesOnce } from './weight_planes.js';

let setup = null;  // {base, field, arrays, weightPlanes}: the site's URL and the manifest's entries
let planes = null;  // weightPlanesOnce's function
let planesReported = false;  // whether a tile's message said the planes' bytes and seconds

onmessage = async ({ data }) => {
  if (data.setup) {
    setup = data.setup;
    planes = weightPlanesOnce(setup.weightPlanes, setup.field, setup.base);
    return;
  }
  try {
    const { tile, bytes } =
        await fetchTile(data.file, data.region, setup.field, setup.arrays, setup.base, planes());
    const fetched = performance.getEntriesByName(new URL(data.file, setup.base).href).at(-1);
    const message = { id: data.id, tile, bytes: fetched?.encodedBodySize || bytes };
    if (planes() && !planesReported) {
      planesReported = true;
      const { bytes: planeBytes, seconds } = await planes();
      message.bytes += planeBytes;
      message.planeSeconds = seconds;
    }
    const buffers = new Set(Object.values(tile).filter(ArrayBuffer.isView).map((a) => a.buffer));
    postMessage(message, [...buffers]);
  } catch (error) {
    postMessage({ id: data.id, error: error.message });
  }
};
