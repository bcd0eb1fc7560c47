// tile_pyramid.js: the published field's tile pyramid (lib/publish/web_layout.hpp) on the page:
// which level and tiles a view needs, fetching each tile once when first needed (decoded in Web
// Workers, tile_decoder.js; the first view's tiles even before the renderer exists), and drawing
// a view with the tiles it has (a tile not yet arrived is stood in for by a coarser one already
// here). A tile becomes textures when first drawn. Tiles far from the view are dropped when many
// are held.
import { TileDecoder } from './tile_decoder.js';

const heldTiles = 96;

export class TilePyramid {
  // onError(error) is called when a tile fails. workers: TileDecoder's.
  constructor(manifest, base, onError, workers) {
    this.manifest = manifest;
    this.renderer = null;
    this.onTile = null;
    this.decoder = new TileDecoder(manifest, base, workers);
    this.onError = onError;
    this.size = manifest.tiles.size;
    this.levels = manifest.tiles.levels;
    this.tiles = new Map();  // "level/column/row" -> {ready, tile, used, promise}
    this.frame = 0;
    this.bytes = 0;  // fetched by the decoder's workers, as the browser counts them
  }

  // The level whose pixels are nearest the screen's without being larger: field pixels per
  // canvas pixel 1 / scale.
  levelFor(scale) {
    const level = Math.floor(Math.log2(1 / scale));
    return Math.max(0, Math.min(this.levels.length - 1, level));
  }

  // The tiles of `level` that a canvas of width x height under `view` shows.
  visible(level, view, width, height) {
    const { stride, columns, rows } = this.levels[level], span = this.size * stride;
    const clamp = (v, n) => Math.max(0, Math.min(n - 1, v));
    const c0 = clamp(Math.floor(view.x / span), columns), r0 = clamp(Math.floor(view.y / span), rows);
    const c1 = clamp(Math.floor((view.x + width / view.scale) / span), columns);
    const r1 = clamp(Math.floor((view.y + height / view.scale) / span), rows);
    const list = [];
    for (let r = r0; r <= r1; ++r) for (let c = c0; c <= c1; ++c) list.push([c, r]);
    return list;
  }

  // The tile, fetching it when it was not asked for before; resolves to the entry.
  request(level, column, row) {
    const key = `${level}/${column}/${row}`;
    let entry = this.tiles.get(key);
    if (!entry) {
      entry = { ready: false, data: null, tile: null, used: this.frame };
      const { width, height, stride } = this.levels[level];
      const file = this.manifest.tiles.file.replace('{level}', level).replace('{column}', column)
          .replace('{row}', row);
      const decoded = this.decoder.decode(file, {
        width: Math.min(this.size, width - column * this.size),
        height: Math.min(this.size, height - row * this.size),
        x: column * this.size * stride, y: row * this.size * stride, stride,
      });
      entry.promise = decoded.then(({ tile, bytes }) => {
        this.bytes += bytes;
        entry.data = tile;
        entry.ready = true;
        if (this.renderer) this.onTile(level, column, row, this.textures(entry));
        return entry;
      });
      entry.promise.catch(this.onError);
      this.tiles.set(key, entry);
    }
    entry.used = this.frame;
    return entry;
  }

  // The renderer that draws the tiles (RelightRenderer), and onTile(level, column, row, tile),
  // called from then on when a fetched tile is ready to draw (prefetched tiles may arrive before:
  // the first draw takes them).
  attach(renderer, onTile) {
    this.renderer = renderer;
    this.onTile = onTile;
  }

  // Asks for the tiles of `level` that a canvas of width x height under `view` shows.
  prefetch(level, view, width, height) {
    for (const [c, r] of this.visible(level, view, width, height)) this.request(level, c, r);
  }

  // A ready entry's textures, uploaded on first use.
  textures(entry) {
    if (!entry.tile) {
      entry.tile = this.renderer.uploadTile(entry.data);
      entry.data = null;
    }
    return entry.tile;
  }

  // Resolves when every tile of `level` is here.
  loadLevel(level) {
    const { columns, rows } = this.levels[level], all = [];
    for (let r = 0; r < rows; ++r) for (let c = 0; c < columns; ++c) all.push(this.request(level, c, r).promise);
    return Promise.all(all);
  }

  // Whether every tile of `level` that the view shows is here.
  complete(level, view, width, height) {
    return this.visible(level, view, width, height)
        .every(([c, r]) => this.tiles.get(`${level}/${c}/${r}`)?.ready);
  }

  // Draws the view (renderer.begin called) with the tiles of `level` it shows; true when all
  // of them were here.
  draw(level, view, width, height) {
    ++this.frame;
    let complete = true;
    const { stride } = this.levels[level];
    for (const [c, r] of this.visible(level, view, width, height)) {
      const entry = this.request(level, c, r);
      if (entry.ready) {
        this.renderer.drawTile(this.textures(entry), stride, c * this.size, r * this.size);
        continue;
      }
      complete = false;
      const span = this.size * stride;
      const clip = { x0: c * span, y0: r * span, x1: (c + 1) * span, y1: (r + 1) * span };
      for (let up = level + 1; up < this.levels.length; ++up) {
        const upSpan = this.size * this.levels[up].stride;
        const ancestor = this.tiles.get(`${up}/${Math.floor(clip.x0 / upSpan)}/${Math.floor(clip.y0 / upSpan)}`);
        if (ancestor && ancestor.ready) {
          ancestor.used = this.frame;
          this.renderer.drawTile(this.textures(ancestor), this.levels[up].stride,
                                 Math.floor(clip.x0 / upSpan) * this.size,
                                 Math.floor(clip.y0 / upSpan) * this.size, clip);
          break;
        }
      }
    }
    this.evict();
    return complete;
  }

  evict() {
    if (this.tiles.size <= heldTiles) return;
    const old = [...this.tiles.entries()].filter(([, e]) => e.ready && e.used < this.frame)
        .sort((a, b) => a[1].used - b[1].used);
    for (const [key, entry] of old.slice(0, this.tiles.size - heldTiles)) {
      if (entry.tile) this.renderer.deleteTile(entry.tile);
      this.tiles.delete(key);
    }
  }
}
