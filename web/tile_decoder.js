// tile_decoder.js: decodes the pyramid's tiles in module Web Workers (tile_worker.js), one per
// core up to four, so that tiles inflate and unpack in parallel while the page stays responsive;
// with no workers asked for, on the page's own thread.
import { fetchBundle, unpackTile } from './field_data.js';

export class TileDecoder {
  // workers: how many (default one per core up to four; 0: none).
  constructor(manifest, base, workers = Math.max(1, Math.min(4, navigator.hardwareConcurrency || 2))) {
    this.manifest = manifest;
    this.base = base;
    this.pending = new Map();  // id -> {resolve, reject}
    this.next = 0;
    this.workers = Array.from({ length: workers }, () => {
      const worker = new Worker(new URL('./tile_worker.js', import.meta.url), { type: 'module' });
      worker.onmessage = ({ data }) => {
        const { resolve, reject } = this.pending.get(data.id);
        this.pending.delete(data.id);
        if (data.error) reject(new Error(data.error));
        else resolve({ tile: data.tile, bytes: data.bytes });
      };
      worker.onerror = (event) => {
        for (const { reject } of this.pending.values()) reject(new Error(`a tile decoder failed: ${event.message}`));
        this.pending.clear();
      };
      worker.postMessage({ setup: { base, field: manifest.field, arrays: manifest.tiles.arrays } });
      return worker;
    });
  }

  // Resolves to {tile: unpackTile's arrays, bytes: fetched for it by a worker}.
  async decode(file, width, height) {
    if (this.workers.length === 0) {
      const { arrays } = await fetchBundle(file, this.manifest.tiles.arrays, this.base);
      // The page's own resource timings count this fetch.
      return { tile: unpackTile(this.manifest.field, width, height, arrays), bytes: 0 };
    }
    const id = this.next++;
    return new Promise((resolve, reject) => {
      this.pending.set(id, { resolve, reject });
      this.workers[id % this.workers.length].postMessage({ id, file, width, height });
    });
  }
}
