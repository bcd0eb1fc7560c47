// relume_page.js: the published page. Loads the manifest and the field's bases, relights the
// tiles the view shows with WebGL2 as the light (or a map and its rotation), the exposure, the
// residual cap and the view change, and shows frames/s. Without WebGL2 it says so.
//
// URL parameters (for links and scripts): light=x,y,z (the light's direction), env=N and
// rotate=DEGREES (light with map N of the manifest, turned), residual=N|all, exposure=STOPS,
// readback=1 (the whole field at full resolution is drawn off screen and its RGBA bytes, rows
// from the top, go base64-encoded into <pre id="readback"> before <body data-state> becomes
// "ready"; tests read them with `chromium --headless --dump-dom`), workers=0 (tiles decode on
// the page's thread: the virtual time of --dump-dom runs does not wait for workers). Scripts can
// also call window.relume: fullResolutionPixels(), framesPerSecond(cap, frames), firstImage,
// bytesOnTheWire(), view, state.
import { fetchBundle, fetchManifest } from './field_data.js';
import { LightPad } from './light_pad.js';
import { EnvironmentLighting, LightInterpolation, lightInFieldBasis } from './light_vector.js';
import { RelightRenderer } from './relight_renderer.js';
import { TilePyramid } from './tile_pyramid.js';

const $ = (id) => document.getElementById(id);
const status = $('status');

function fail(state, message) {
  document.body.dataset.state = state;
  status.textContent = message;
}

function numbers(text, count, name) {
  const values = text.split(',').map(Number);
  if (values.length !== count || !values.every(Number.isFinite))
    throw new Error(`URL parameter ${name}=${text}: expected ${count} numbers separated by commas`);
  return values;
}

function base64(bytes) {
  let text = '';
  for (let i = 0; i < bytes.length; i += 0x8000)
    text += String.fromCharCode.apply(null, bytes.subarray(i, i + 0x8000));
  return btoa(text);
}

function kilobytes(bytes) {
  return bytes < 1e6 ? `${(bytes / 1e3).toFixed(1)} kB` : `${(bytes / 1e6).toFixed(2)} MB`;
}

// Bytes fetched by this page's thread (its HTML, modules, manifest, field and maps), as the
// browser counts them; the tiles' workers count theirs (TilePyramid.bytes).
function pageBytes() {
  return performance.getEntriesByType('navigation').concat(performance.getEntriesByType('resource'))
      .reduce((sum, entry) => sum + (entry.encodedBodySize || 0), 0);
}

function readSettings(params, manifest) {
  const field = manifest.field;
  const state = {
    light: params.has('light') ? numbers(params.get('light'), 3, 'light') : [0.35, 0.45, 0.82],
    env: -1, rotation: 0, residual: field.residual_longest_row, exposure: manifest.exposure,
  };
  if (params.has('env')) {
    state.env = Number(params.get('env'));
    if (!Number.isInteger(state.env) || state.env < 0 || state.env >= manifest.environments.length)
      throw new Error(`URL parameter env=${params.get('env')}: this site has ` +
                      `${manifest.environments.length} maps (0 to ${manifest.environments.length - 1})`);
  }
  if (params.has('rotate')) state.rotation = numbers(params.get('rotate'), 1, 'rotate')[0];
  if (params.has('residual') && params.get('residual') !== 'all') {
    state.residual = Number(params.get('residual'));
    if (!Number.isInteger(state.residual) || state.residual < 0)
      throw new Error(`URL parameter residual=${params.get('residual')}: expected all or N >= 0`);
  }
  if (params.has('exposure')) state.exposure = numbers(params.get('exposure'), 1, 'exposure')[0];
  return state;
}

async function main() {
  const params = new URLSearchParams(location.search);
  const canvas = $('image');
  const gl = canvas.getContext('webgl2', { antialias: false, preserveDrawingBuffer: true });
  if (!gl) {
    fail('no-webgl2',
         'This page needs WebGL2, which this browser does not offer or has turned off. ' +
         'Try a current Chrome, Edge, Firefox or Safari with hardware acceleration on.');
    return;
  }
  const started = performance.now();
  const base = document.baseURI;
  const manifest = await fetchManifest(base);
  const field = manifest.field;
  document.title = manifest.title;
  $('title').textContent = manifest.title;
  const state = readSettings(params, manifest);
  const view = { x: 0, y: 0, scale: 1 };
  const fit = () => {
    view.scale = Math.min(canvas.width / field.width, canvas.height / field.height);
    view.x = (field.width - canvas.width / view.scale) / 2;
    view.y = (field.height - canvas.height / view.scale) / 2;
  };
  const resize = () => {
    const ratio = window.devicePixelRatio || 1;
    canvas.width = Math.max(1, Math.round(canvas.clientWidth * ratio));
    canvas.height = Math.max(1, Math.round(canvas.clientHeight * ratio));
  };
  // The first view's tiles are asked for at once: they are fetched and decoded while the field's
  // bases load and the shaders compile. Arrived tiles are drawn once the renderer is attached.
  const pyramid = new TilePyramid(manifest, base,
                                  (error) => fail('error', `Could not show the field: ${error.message}`),
                                  params.get('workers') === '0' ? 0 : undefined);
  resize();
  fit();
  pyramid.prefetch(pyramid.levelFor(view.scale), view, canvas.width, canvas.height);
  const { arrays: globals } = await fetchBundle(manifest.field_file.file, manifest.field_file.arrays, base);
  const scales = globals.basis_scales, lights = field.lights;
  const bases = scales ? Float32Array.from(globals.bases, (q, i) => Math.fround(q * scales[Math.floor(i / lights)]))
                       : globals.bases;
  const renderer = new RelightRenderer(gl, manifest, bases, globals.dark_model || null);
  const interpolation = new LightInterpolation(manifest.light_cover, field.lights);
  const maps = new Map();  // index -> Promise<EnvironmentLighting>
  const mapLighting = (index) => {
    if (!maps.has(index)) {
      const entry = manifest.environments[index];
      maps.set(index, fetchBundle(entry.file, entry.arrays, base).then(({ arrays }) =>
        new EnvironmentLighting(manifest.light_cover, field.lights, entry, arrays.energy)));
    }
    return maps.get(index);
  };

  let lightChanged = true, pending = false, frames = [], lastFrameMs = 0, firstImage = null;
  // A tile that arrives while the view stands still is drawn alone over the frame on screen.
  const tileArrived = (level, column, row, tile) => {
    if (pending || level !== pyramid.levelFor(view.scale)) return schedule();
    renderer.begin(canvas.width, canvas.height, view, state.residual, state.exposure, false);
    renderer.drawTile(tile, pyramid.levels[level].stride, column * pyramid.size, row * pyramid.size);
    noteFirstImage(pyramid.complete(level, view, canvas.width, canvas.height));
  };
  pyramid.attach(renderer, tileArrived);
  const bytesOnTheWire = () => pageBytes() + pyramid.bytes;
  // Keeps field point (fx, fy) under canvas pixel (px, py) while the scale changes.
  const zoomAt = (factor, px, py) => {
    const fx = view.x + px / view.scale, fy = view.y + py / view.scale;
    view.scale = Math.max(1 / 2 ** (pyramid.levels.length + 2), Math.min(32, view.scale * factor));
    view.x = fx - px / view.scale;
    view.y = fy - py / view.scale;
  };

  const updateLight = async () => {
    const vector = state.env < 0 ? interpolation.lightVector(state.light)
                                 : (await mapLighting(state.env)).lightVector(state.rotation);
    renderer.setLight(lightInFieldBasis(field, vector));
  };
  const render = () => {
    const begin = performance.now();
    renderer.begin(canvas.width, canvas.height, view, state.residual, state.exposure);
    const complete = pyramid.draw(pyramid.levelFor(view.scale), view, canvas.width, canvas.height);
    if (!$('continuous').checked && complete) {  // frames with tiles missing are not timed
      renderer.finish();
      lastFrameMs = performance.now() - begin;
    }
    frames.push(performance.now());
    noteFirstImage(complete);
  };
  function noteFirstImage(complete) {
    if (!complete || firstImage) return;
    renderer.finish();
    // planeSeconds: a one-basis field's weight planes, fetched and decoded (else null).
    firstImage = { seconds: (performance.now() - started) / 1000, bytes: bytesOnTheWire(),
                   planeSeconds: pyramid.decoder.planeSeconds };
    const planes = firstImage.planeSeconds === null ? ''
                 : ` (weights decoded in ${firstImage.planeSeconds.toFixed(2)} s)`;
    status.textContent = `First image in ${firstImage.seconds.toFixed(2)} s${planes}, ` +
                         `${kilobytes(firstImage.bytes)} fetched`;
  }
  const pad = new LightPad($('light-pad'), manifest.light_cover.directions, (light) => {
    state.light = light;
    lightChanged = true;
    schedule();
  });
  const showControls = () => {
    $('lighting').value = state.env < 0 ? 'light' : String(state.env);
    $('light-control').hidden = state.env >= 0;
    $('rotation-control').hidden = state.env < 0;
    $('rotation').value = ((state.rotation % 360) + 360) % 360;
    $('rotation-value').textContent = `${state.rotation.toFixed(0)}°`;
    $('exposure').value = state.exposure;
    $('exposure-value').textContent = `${state.exposure >= 0 ? '+' : ''}${state.exposure.toFixed(1)} stops`;
    const cap = Math.min(state.residual, field.residual_longest_row);
    $('residual').value = cap;
    $('residual-value').textContent = `${cap} of ${field.residual_longest_row} entries`;
    $('zoom-value').textContent = `${(view.scale * 100).toFixed(0)}%, level ${pyramid.levelFor(view.scale)}`;
    pad.draw(state.light);
  };
  const frame = async () => {
    if (lightChanged) {
      lightChanged = false;
      await updateLight();
    }
    pending = false;
    render();
    showControls();
    if ($('continuous').checked) schedule();
  };
  function schedule() {
    if (!pending) {
      pending = true;
      requestAnimationFrame(() => frame().catch((error) => fail('error', error.message)));
    }
  }

  for (const [index, entry] of manifest.environments.entries())
    $('lighting').add(new Option(`Map: ${entry.name}`, String(index)));
  // Picking a map exposes it as bright as the moved light (whose weights sum to one): the
  // exposure takes minus log2 of the light vector's mean-RGB total.
  $('lighting').addEventListener('change', async () => {
    state.env = $('lighting').value === 'light' ? -1 : Number($('lighting').value);
    if (state.env >= 0) {
      const vector = (await mapLighting(state.env)).lightVector(state.rotation);
      const total = vector.reduce((sum, v) => sum + v, 0) / 3;
      if (total > 0) state.exposure = Math.max(-12, Math.min(12, manifest.exposure - Math.log2(total)));
    } else {
      state.exposure = manifest.exposure;
    }
    lightChanged = true;
    schedule();
  });
  $('rotation').addEventListener('input', () => {
    state.rotation = Number($('rotation').value);
    lightChanged = true;
    schedule();
  });
  $('exposure').addEventListener('input', () => { state.exposure = Number($('exposure').value); schedule(); });
  $('residual').max = field.residual_longest_row;
  $('residual').addEventListener('input', () => { state.residual = Number($('residual').value); schedule(); });
  $('continuous').addEventListener('change', schedule);
  $('fit').addEventListener('click', () => { fit(); schedule(); });
  $('actual-size').addEventListener('click', () => {
    zoomAt(1 / view.scale, canvas.width / 2, canvas.height / 2);
    schedule();
  });
  const canvasPoint = (event) => {
    const box = canvas.getBoundingClientRect();
    return [(event.clientX - box.left) * canvas.width / box.width,
            (event.clientY - box.top) * canvas.height / box.height];
  };
  canvas.addEventListener('wheel', (event) => {
    event.preventDefault();
    zoomAt(Math.exp(-event.deltaY * 0.002), ...canvasPoint(event));
    schedule();
  }, { passive: false });
  let dragFrom = null;
  canvas.addEventListener('pointerdown', (event) => {
    canvas.setPointerCapture(event.pointerId);
    dragFrom = canvasPoint(event);
  });
  canvas.addEventListener('pointermove', (event) => {
    if (!dragFrom || !canvas.hasPointerCapture(event.pointerId)) return;
    const [x, y] = canvasPoint(event);
    view.x -= (x - dragFrom[0]) / view.scale;
    view.y -= (y - dragFrom[1]) / view.scale;
    dragFrom = [x, y];
    schedule();
  });
  canvas.addEventListener('pointerup', () => { dragFrom = null; });
  canvas.addEventListener('dblclick', () => { fit(); schedule(); });
  new ResizeObserver(() => { resize(); fit(); schedule(); }).observe(canvas);
  setInterval(() => {
    const now = performance.now();
    frames = frames.filter((t) => now - t < 1000);
    $('rate').textContent = $('continuous').checked
        ? `${frames.length} frames/s`
        : lastFrameMs > 0
        ? `${(1000 / lastFrameMs).toFixed(1)} frames/s (last frame ${lastFrameMs.toFixed(1)} ms)`
        : '– frames/s (no frame timed yet)';
  }, 500);

  // The whole field at full resolution off screen (level 0): its RGBA bytes, rows from the top.
  const fullResolutionPixels = async () => {
    await pyramid.loadLevel(0);
    if (lightChanged) lightChanged = false, await updateLight();
    const framebuffer = gl.createFramebuffer(), target = gl.createRenderbuffer();
    gl.bindRenderbuffer(gl.RENDERBUFFER, target);
    gl.renderbufferStorage(gl.RENDERBUFFER, gl.RGBA8, field.width, field.height);
    gl.bindFramebuffer(gl.FRAMEBUFFER, framebuffer);
    gl.framebufferRenderbuffer(gl.FRAMEBUFFER, gl.COLOR_ATTACHMENT0, gl.RENDERBUFFER, target);
    renderer.begin(field.width, field.height, { x: 0, y: 0, scale: 1 }, state.residual, state.exposure);
    pyramid.draw(0, { x: 0, y: 0, scale: 1 }, field.width, field.height);
    const pixels = renderer.readPixels(field.width, field.height);
    gl.bindFramebuffer(gl.FRAMEBUFFER, null);
    gl.deleteFramebuffer(framebuffer);
    gl.deleteRenderbuffer(target);
    return pixels;
  };
  // Frames/s of the current view with `cap` entries (frames drawn back to back, each waited for).
  const framesPerSecond = (cap, count = 30) => {
    const saved = state.residual;
    state.residual = cap;
    render();
    const begin = performance.now();
    for (let i = 0; i < count; ++i) render();
    state.residual = saved;
    return count / ((performance.now() - begin) / 1000);
  };
  window.relume = {
    manifest, state, view, fullResolutionPixels, framesPerSecond,
    get firstImage() { return firstImage; },
    bytesOnTheWire,
  };

  resize();
  fit();
  $('controls').hidden = false;
  $('bytes').textContent = `${field.width} × ${field.height} pixels, ${field.lights} lights, ` +
                           `${pyramid.levels.length} levels of ${pyramid.size}-pixel tiles`;
  await updateLight();
  lightChanged = false;
  if (params.has('readback')) $('readback').textContent = base64(await fullResolutionPixels());
  schedule();
  await new Promise((resolve) => {
    const check = () => (firstImage || document.body.dataset.state === 'error' ? resolve()
                                                                           : setTimeout(check, 10));
    check();
  });
  if (document.body.dataset.state !== 'error') document.body.dataset.state = 'ready';
}

main().catch((error) => fail('error', `Could not show the field: ${error.message}`));
