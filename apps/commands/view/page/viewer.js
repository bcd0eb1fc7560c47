// The relume view page: reads /info, draws the hemisphere of captured light directions, turns
// drags and controls into the viewer's state and shows GET /frame for it. Requests are coalesced:
// at most one frame is in flight, and when it has arrived the newest state is sent (latest wins)
// while the arrived one is decoded, so dragging stays responsive however long a frame takes.
// window.relumeViewer exposes the state, the query of the frame on screen and requestFrame() (for
// scripts, tests and the benchmark).
'use strict';

const viewer = (window.relumeViewer = {
  info: null,
  // mode 'light': a directional light from `light`; mode 'map': map `map` turned by `rotate`.
  state: {
    mode: 'light',
    light: [0, 0, 1],
    map: 0,
    rotate: 0,
    color: [1, 1, 1],
    spread: 0,
    exposure: 0,
    residual: 'all',
    view: 'image',
  },
  shownQuery: null, // the /frame query (without format) of the frame on screen
  framesShown: 0,
  inFlight: false,
  pending: false,
});

const element = (id) => document.getElementById(id);
const frameTimes = []; // when recent frames were shown, for frames/s

function srgbToLinear(v) {
  return v <= 0.04045 ? v / 12.92 : Math.pow((v + 0.055) / 1.055, 2.4);
}

// The /frame query of a state, without the format: every parameter spelled out.
function frameQuery(state) {
  const parts = [];
  if (state.mode === 'light') {
    parts.push('light=' + state.light.map((v) => v.toFixed(4)).join(','));
    if (state.spread > 0) parts.push('spread=' + state.spread);
  } else {
    parts.push('rotate=' + state.rotate.toFixed(2), 'map=' + state.map);
  }
  parts.push(
    'color=' + state.color.map((v) => v.toFixed(4)).join(','),
    'exposure=' + state.exposure,
    'residual=' + state.residual,
    'view=' + state.view,
  );
  return parts.join('&');
}
viewer.frameQuery = frameQuery;

function frameUrl(format) {
  return '/frame?' + frameQuery(viewer.state) + '&format=' + format;
}

// Asks for a frame of the current state: sent now, or when the frame in flight has arrived.
function requestFrame() {
  viewer.pending = true;
  redrawControls();
  if (!viewer.inFlight) sendFrame();
}
viewer.requestFrame = requestFrame;

// The widget, the light's description and the save links, redrawn at most once per display
// frame however fast pointer moves come.
let redrawScheduled = false;
function redrawControls() {
  if (redrawScheduled) return;
  redrawScheduled = true;
  requestAnimationFrame(() => {
    redrawScheduled = false;
    element('save-png').href = frameUrl('png');
    element('save-exr').href = frameUrl('exr');
    describeLight();
    drawHemisphere();
  });
}

let framesSent = 0; // numbers the frames, so that a late decode never replaces a newer frame
let newestShown = 0;

// Sends the current state; once its frame has arrived the next state (if any) is sent while this
// one is decoded and shown, so decoding overlaps the server's next render.
async function sendFrame() {
  viewer.pending = false;
  viewer.inFlight = true;
  const query = frameQuery(viewer.state);
  const number = ++framesSent;
  const started = performance.now();
  let frame = null;
  try {
    const response = await fetch('/frame?' + query + '&format=' + element('transfer').value);
    if (response.status === 429) {
      element('message').textContent = 'the server is busy (too many requests); retrying';
      viewer.pending = true;
      await new Promise((resolve) => setTimeout(resolve, 1000));
    } else if (!response.ok) {
      element('message').textContent = await response.text();
    } else {
      frame = { blob: await response.blob(), headers: response.headers };
    }
  } catch (error) {
    element('message').textContent = 'no answer from relume view: ' + error;
  }
  viewer.inFlight = false;
  if (viewer.pending) sendFrame();
  if (frame) await showFrame(frame, number, query, performance.now() - started);
}

async function showFrame(frame, number, query, latencyMs) {
  const decoded = new Image();
  decoded.src = URL.createObjectURL(frame.blob);
  try {
    await decoded.decode();
  } catch (error) {
    element('message').textContent = 'cannot decode the frame: ' + error;
  }
  if (number < newestShown) {
    URL.revokeObjectURL(decoded.src);
    return;
  }
  newestShown = number;
  const image = element('frame');
  const previous = image.src;
  image.src = decoded.src;
  if (previous.startsWith('blob:')) URL.revokeObjectURL(previous);
  viewer.shownQuery = query;
  viewer.framesShown += 1;
  element('message').textContent = '';
  const now = performance.now();
  frameTimes.push(now);
  while (frameTimes[0] < now - 1000) frameTimes.shift();
  const render = frame.headers.get('X-Relume-Render-Ms');
  const error = frame.headers.get('X-Relume-Residual-Error');
  const covered = frame.headers.get('X-Relume-Light-Covered');
  element('stats').textContent =
    frameTimes.length + ' frames/s · frame ' + latencyMs.toFixed(1) + ' ms' +
    (render ? ' · render ' + Number(render).toFixed(1) + ' ms' : '') +
    (error !== null ? ' · cap error ' + Number(error).toPrecision(3) : '') +
    (covered === '0' ? ' · outside the captured lights: lit from their rim' : '');
}

// --- the hemisphere widget: what the camera sees, x right, y up, z towards the viewer ---

function hemisphereGeometry() {
  const canvas = element('hemisphere');
  return { canvas, cx: canvas.width / 2, cy: canvas.height / 2, r: canvas.width / 2 - 10 };
}

function drawHemisphere() {
  if (!viewer.info) return;
  const { canvas, cx, cy, r } = hemisphereGeometry();
  const g = canvas.getContext('2d');
  g.clearRect(0, 0, canvas.width, canvas.height);
  g.strokeStyle = '#555';
  g.beginPath();
  g.arc(cx, cy, r, 0, 2 * Math.PI);
  g.stroke();
  for (const [x, y, z] of viewer.info.light_directions) {
    g.beginPath();
    g.arc(cx + x * r, cy - y * r, 2.5, 0, 2 * Math.PI);
    if (z >= 0) {
      g.fillStyle = '#9e9e9e';
      g.fill();
    } else {
      g.strokeStyle = '#666';
      g.stroke();
    }
  }
  const state = viewer.state;
  if (state.mode === 'light') {
    const [x, y, z] = state.light;
    const n = Math.hypot(x, y, z);
    g.beginPath();
    g.arc(cx + (x / n) * r, cy - (y / n) * r, 7, 0, 2 * Math.PI);
    g.fillStyle = '#ffd54f';
    g.fill();
  } else {
    // The map's forward direction (-z at rotate 0) after the rotation about +y, seen from above.
    const angle = (state.rotate * Math.PI) / 180;
    g.strokeStyle = '#ffd54f';
    g.lineWidth = 3;
    g.beginPath();
    g.moveTo(cx, cy);
    g.lineTo(cx - Math.sin(angle) * r, cy - Math.cos(angle) * r);
    g.stroke();
    g.lineWidth = 1;
  }
}

// A point of a rectangle (fractions u, v in [0, 1] from its top left) as a light direction: the
// rectangle is the hemisphere's disc seen from the camera; outside the disc, the rim.
function directionAt(u, v) {
  let x = 2 * u - 1;
  let y = 1 - 2 * v;
  const d = Math.hypot(x, y);
  if (d > 1) {
    x /= d;
    y /= d;
  }
  return [x, y, Math.sqrt(Math.max(0, 1 - x * x - y * y))];
}

// Drags on `target`: in light mode the pointer's place is the light, in map mode a horizontal
// drag across the whole target is a full turn.
function dragOn(target) {
  let lastX = null;
  const move = (event) => {
    const box = target.getBoundingClientRect();
    if (viewer.state.mode === 'light') {
      viewer.state.light = directionAt(
        (event.clientX - box.left) / box.width,
        (event.clientY - box.top) / box.height,
      );
    } else if (lastX !== null) {
      const turned = viewer.state.rotate + ((event.clientX - lastX) * 360) / box.width;
      viewer.state.rotate = ((turned % 360) + 360) % 360;
    }
    lastX = event.clientX;
    requestFrame();
  };
  target.addEventListener('pointerdown', (event) => {
    target.setPointerCapture(event.pointerId);
    lastX = null;
    move(event);
  });
  target.addEventListener('pointermove', (event) => {
    if (target.hasPointerCapture(event.pointerId)) move(event);
  });
}

// --- the controls ---

function updateColor() {
  const hex = element('color').value;
  const intensity = Number(element('intensity').value);
  viewer.state.color = [1, 3, 5].map(
    (i) => srgbToLinear(parseInt(hex.substr(i, 2), 16) / 255) * intensity,
  );
  element('intensity-value').textContent = intensity.toFixed(2);
}

function describeLight() {
  const state = viewer.state;
  element('light-readout').textContent =
    state.mode === 'light'
      ? 'light from (' + state.light.map((v) => v.toFixed(2)).join(', ') + ')'
      : viewer.info.maps[state.map] + ' turned ' + state.rotate.toFixed(1) + '°';
  element('spread-control').hidden = state.mode !== 'light';
}

const legends = {
  image: '',
  error:
    '|capped − full residual| per pixel against the bright level: black none, dark blue 1e-4, ' +
    'red 1e-2, yellow 1e-1, white 1 and above.',
  mask: 'white: stored pixels; blue: the dark model; dark red: inside the mask, nothing stored; ' +
    'black: outside the mask.',
};

function setUpControls(info) {
  const defaults = info.defaults;
  const state = viewer.state;
  element('field-description').textContent =
    info.input + ' · ' + info.width + '×' + info.height + ', ' + info.lights + ' lights, ' +
    info.clusters + ' clusters × ' + info.terms + ' terms · ' + info.device;

  const source = element('source');
  source.add(new Option('directional light', 'light'));
  info.maps.forEach((name, i) => source.add(new Option(name, 'map:' + i)));
  if (defaults.light) {
    state.mode = 'light';
    state.light = defaults.light;
  } else {
    state.mode = 'map';
    state.map = defaults.map;
    source.value = 'map:' + defaults.map;
  }
  state.rotate = defaults.rotate;
  state.color = defaults.color;
  state.spread = defaults.spread;
  source.addEventListener('change', () => {
    state.mode = source.value === 'light' ? 'light' : 'map';
    if (state.mode === 'map') state.map = Number(source.value.slice(4));
    requestFrame();
  });

  const exposure = element('exposure');
  exposure.value = defaults.exposure;
  state.exposure = defaults.exposure;
  exposure.addEventListener('input', () => {
    state.exposure = Number(exposure.value);
    element('exposure-value').textContent = state.exposure.toFixed(1) + ' stops';
    requestFrame();
  });
  element('exposure-value').textContent = state.exposure.toFixed(1) + ' stops';

  // The slider's top is the full residual ("all"); below it, entries per function.
  const residual = element('residual');
  const longest = info.residual_entries_max;
  residual.max = longest + 1;
  residual.value = defaults.residual === 'all' ? longest + 1 : Math.min(Number(defaults.residual), longest);
  const readResidual = () => {
    const value = Number(residual.value);
    state.residual = value > longest ? 'all' : String(value);
    element('residual-value').textContent =
      state.residual === 'all' ? 'all (' + longest + ')' : state.residual + ' of ' + longest;
  };
  readResidual();
  residual.addEventListener('input', () => {
    readResidual();
    requestFrame();
  });

  element('color').addEventListener('input', () => {
    updateColor();
    requestFrame();
  });
  element('intensity').addEventListener('input', () => {
    updateColor();
    requestFrame();
  });
  element('intensity-value').textContent = '1.00';
  const spread = element('spread');
  spread.value = state.spread;
  element('spread-value').textContent = state.spread;
  spread.addEventListener('input', () => {
    state.spread = Number(spread.value);
    element('spread-value').textContent = state.spread;
    requestFrame();
  });

  for (const radio of document.querySelectorAll('input[name="view"]')) {
    radio.addEventListener('change', () => {
      state.view = radio.value;
      element('view-legend').textContent = legends[state.view];
      requestFrame();
    });
  }
  const transfer = new URLSearchParams(location.search).get('transfer');
  if (transfer === 'png' || transfer === 'jpeg') element('transfer').value = transfer;
  element('transfer').addEventListener('change', requestFrame);

  dragOn(element('frame'));
  dragOn(element('hemisphere'));
}

async function start() {
  try {
    const response = await fetch('/info');
    if (!response.ok) throw new Error(await response.text());
    viewer.info = await response.json();
  } catch (error) {
    element('message').textContent = 'cannot read /info: ' + error;
    return;
  }
  setUpControls(viewer.info);
  requestFrame();
}

window.addEventListener('load', start);
