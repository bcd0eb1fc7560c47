// tile_decoder.js: decodes the pyramid's tiles in module Web Workers (tile_worker.js), one per
// core up to four, so that tiles inflate and unpack in parallel while the page stays responsive;
// with no workers asked for, on the page's own thread. A one-basis field's weight planes are
// decoded once, where its tiles are: in its one worker, or on the page's thread.
import { fetchTile } from './field_data.js';
import { weightPlanesOnce } from './weight_planes.js';

export class TileDecoder {
  // workers: how many (default one per core up to four, one for a one-basis field; 0: none).
  constructor(manifest, base, workers = Math.max(1, Math.min(4, navigator.hardwareConcurrency || 2))) {
    this.manifest = manifest;
    this.base = base;
    this.pending = new Map();  // id -> {resolve, reject}
    this.next = 0;
    const weightPlanes = manifest.weight_planes ?? null;
    if (weightPlanes) workers = Math.min(workers, 1);
    this.planes = weightPlanesOnce(weightPlanes, manifest.field, base);
    this.planeSeconds = null;  // a one-basis field's: from asking for the planes to decoded
    this.workers = Array.from({ length: workers }, () => {
      const worker = new Worker(new URL('./tile_worker.js', import.meta.url), { type: 'module' });
      worker.onmessage = ({ data }) => {
        const { resolve, reject } = this.pending.get(data.id);
        this.pending.delete(data.id);
        if (data.planeSeconds !== undefined) this.planeSeconds = data.planeSeconds;
        if (data.error) reject(new Error(data.error));
        else resolve({ tile: data.tile, bytes: data.bytes });
      };
      worker.onerror = (event) => {
        for (const { reject } of this.pending.values()) reject(new Error(`a tile decoder failed: ${event.message}`));
        this.pending.clear();
      };
      const { field, tiles: { arrays } } = manifest;
      worker.postMessage({ setup: { base, field, arrays, weightPlanes } });
      return worker;
    });
  }

  // Resolves to {tile: unpackTile's arrays, bytes: fetched for it by a worker}. region:
  // fetchTile's.
  async decode(file, region) {
    if (this.workers.length === 0) {
      const planes = this.planes();
      const { tile } = await fetchTile(file, region, this.manifest.field, this.manifest.tiles.arrays,
                                       this.base, planes);
      if (planes) this.planeSeconds = (await planes).seconds;
      // The page's own resource timings count these fetches.
      return { tile, bytes: 0 };
    }
    const id = this.next++;
    return new Promise((resolve, reject) => {
      this.pending.set(id, { resolve, reject });
      this.workers[id % this.workers.length].postMessage({ id, file, region });
    });
  }
}
