// The report page's viewer: plain WebGL 1 (no library, no network).
// The map's points come in their scans' frames with each scan's index; they
// are placed once with the input poses and once with the optimized ones, so
// the input/optimized toggle swaps a buffer and nothing is recomputed.
'use strict';

const status = { errors: [], drawn: false, points: 0, frames: 0, map: '', ms: {} };
window.addEventListener('error', (e) => { status.errors.push(String(e.message)); showStatus(); });
const consoleError = console.error.bind(console);
console.error = (...args) => { status.errors.push(args.map(String).join(' ')); showStatus(); consoleError(...args); };

function showStatus() {
  const el = document.getElementById('hba-status');
  if (el) el.textContent = JSON.stringify(status);
}

// ---- data ----

function bytesOf(id) {
  const el = document.getElementById('hba-' + id);
  if (!el) return null;
  const text = atob(el.textContent.trim());
  const out = new Uint8Array(text.length);
  for (let i = 0; i < text.length; ++i) out[i] = text.charCodeAt(i);
  return out;
}

// Milliseconds from the script's start to each step (in the status, for tests and benchmarks).
const started = performance.now();
const lap = (step) => { status.ms[step] = Math.round(performance.now() - started); };
const data = JSON.parse(document.getElementById('hba-data').textContent);
const report = data.report || {};
const frames = data.frames;

function loadPoses(id) {
  const bytes = bytesOf(id);
  return bytes ? new Float32Array(bytes.buffer) : null;
}
const poses = {
  input: loadPoses('pose-input'),
  optimized: loadPoses('pose-optimized'),
  truth: loadPoses('pose-ground-truth'),
};
const xyz = new Int16Array(bytesOf('xyz').buffer);
const perScan = new Uint32Array(bytesOf('per-scan').buffer);
const change = bytesOf('change');
const intensity = bytesOf('intensity');
const pointCount = xyz.length / 3;
const scanOf = new Uint32Array(pointCount);
{
  let k = 0;
  for (let s = 0; s < perScan.length; ++s) for (let j = 0; j < perScan[s]; ++j) scanOf[k++] = s;
}

// The points placed by one pose set (12 floats a pose: rotation row by row, position).
function placePoints(rows) {
  const out = new Float32Array(pointCount * 3);
  const step = data.step_m;
  for (let i = 0; i < pointCount; ++i) {
    const p = 12 * scanOf[i];
    const x = xyz[3 * i] * step, y = xyz[3 * i + 1] * step, z = xyz[3 * i + 2] * step;
    out[3 * i] = rows[p] * x + rows[p + 1] * y + rows[p + 2] * z + rows[p + 9];
    out[3 * i + 1] = rows[p + 3] * x + rows[p + 4] * y + rows[p + 5] * z + rows[p + 10];
    out[3 * i + 2] = rows[p + 6] * x + rows[p + 7] * y + rows[p + 8] * z + rows[p + 11];
  }
  return out;
}
lap('decoded');
const placed = { input: placePoints(poses.input), optimized: placePoints(poses.optimized) };
lap('placed');

function positionsOf(rows) {
  const out = new Float32Array(frames * 3);
  for (let i = 0; i < frames; ++i) for (let a = 0; a < 3; ++a) out[3 * i + a] = rows[12 * i + 9 + a];
  return out;
}
const tracks = {
  input: positionsOf(poses.input),
  optimized: positionsOf(poses.optimized),
  truth: poses.truth ? positionsOf(poses.truth) : null,
};

// ---- colours ----

const RAINBOW = [
  [48, 18, 59], [65, 105, 225], [32, 200, 210], [110, 230, 90], [240, 205, 40], [235, 90, 25], [140, 10, 10],
];
function rainbow(t) {
  t = Math.min(1, Math.max(0, t)) * (RAINBOW.length - 1);
  const i = Math.min(RAINBOW.length - 2, Math.floor(t));
  const f = t - i;
  return RAINBOW[i].map((c, a) => c + (RAINBOW[i + 1][a] - c) * f);
}
// Thinner after (crisper) green, thicker red, unchanged grey.
function diverging(t) {
  const grey = [95, 100, 108];
  const end = t > 0 ? [60, 235, 120] : [240, 70, 70];
  const f = Math.min(1, Math.abs(t));
  return grey.map((c, a) => c + (end[a] - c) * f);
}

function quantile(values, q) {
  const sorted = Float32Array.from(values).sort();
  return sorted.length ? sorted[Math.floor(q * (sorted.length - 1))] : 0;
}

// Per point RGB for a colour mode, with the legend's text.
function colorsFor(mode) {
  const out = new Uint8Array(pointCount * 3);
  const set = (i, rgb) => { out[3 * i] = rgb[0]; out[3 * i + 1] = rgb[1]; out[3 * i + 2] = rgb[2]; };
  let legend = { low: '', high: '', scale: rainbow };
  if (mode === 'intensity' && intensity) {
    for (let i = 0; i < pointCount; ++i) set(i, rainbow(intensity[i] / 255));
    legend = { low: 'intensity 1 %', high: '99 %', scale: rainbow };
  } else if (mode === 'time') {
    for (let i = 0; i < pointCount; ++i) set(i, rainbow(scanOf[i] / Math.max(1, frames - 1)));
    legend = { low: 'scan 0', high: 'scan ' + (frames - 1), scale: rainbow };
  } else if (mode === 'crisper') {
    const full = 10 / data.change_step_mm;  // codes for 10 mm: the colour's end
    for (let i = 0; i < pointCount; ++i) set(i, change[i] === 0 ? [55, 58, 64] : diverging((change[i] - 128) / full));
    legend = { low: 'thicker by 1 cm', high: 'thinner by 1 cm', scale: (t) => diverging(2 * t - 1) };
  } else {
    const z = placed.optimized;
    const heights = new Float32Array(Math.min(pointCount, 200000));
    const stride = Math.max(1, Math.floor(pointCount / heights.length));
    for (let i = 0; i < heights.length; ++i) heights[i] = z[3 * Math.min(pointCount - 1, i * stride) + 2];
    const low = quantile(heights, 0.02), high = Math.max(low + 1e-3, quantile(heights, 0.98));
    for (let i = 0; i < pointCount; ++i) set(i, rainbow((z[3 * i + 2] - low) / (high - low)));
    const metres = (z) => (z + data.origin[2]).toFixed(1) + ' m';
    legend = { low: 'z ' + metres(low), high: metres(high), scale: rainbow };
  }
  return { colors: out, legend };
}

function showLegend(legend) {
  const el = document.getElementById('legend');
  el.textContent = '';
  const bar = document.createElement('canvas');
  bar.width = 240; bar.height = 1;
  const ctx = bar.getContext('2d');
  for (let x = 0; x < 240; ++x) {
    const c = legend.scale(x / 239);
    ctx.fillStyle = 'rgb(' + c.map(Math.round).join(',') + ')';
    ctx.fillRect(x, 0, 1, 1);
  }
  el.appendChild(bar);
  el.appendChild(document.createTextNode(legend.low + ' \u2192 ' + legend.high));
}

// ---- camera ----

const mat4 = {
  multiply(a, b) {
    const o = new Float32Array(16);
    for (let c = 0; c < 4; ++c) for (let r = 0; r < 4; ++r) {
      let s = 0;
      for (let k = 0; k < 4; ++k) s += a[k * 4 + r] * b[c * 4 + k];
      o[c * 4 + r] = s;
    }
    return o;
  },
  perspective(fovy, aspect, near, far) {
    const f = 1 / Math.tan(fovy / 2), o = new Float32Array(16);
    o[0] = f / aspect; o[5] = f; o[10] = (far + near) / (near - far); o[11] = -1; o[14] = 2 * far * near / (near - far);
    return o;
  },
  lookAt(eye, target, up) {
    const sub = (a, b) => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
    const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
    const norm = (a) => { const l = Math.hypot(...a) || 1; return a.map((v) => v / l); };
    const z = norm(sub(eye, target)), x = norm(cross(up, z)), y = cross(z, x);
    const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    return new Float32Array([
      x[0], y[0], z[0], 0, x[1], y[1], z[1], 0, x[2], y[2], z[2], 0, -dot(x, eye), -dot(y, eye), -dot(z, eye), 1,
    ]);
  },
};

function bounds(points) {
  const lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
  for (let i = 0; i < points.length; i += 3) for (let a = 0; a < 3; ++a) {
    lo[a] = Math.min(lo[a], points[i + a]); hi[a] = Math.max(hi[a], points[i + a]);
  }
  return { lo, hi };
}

const camera = { target: [0, 0, 0], yaw: -Math.PI / 2, pitch: Math.PI / 2 - 1e-3, distance: 100, view: 'top' };
// The view on the map's bulk: the 2nd to 98th percentile of its points in
// each axis (a few far returns, a tree 30 m up, would leave it a speck).
function fitWhole() {
  const points = pointCount ? placed.optimized : tracks.optimized;
  const n = points.length / 3;
  const stride = Math.max(1, Math.floor(n / 100000));
  const range = (axis) => {
    const values = [];
    for (let i = 0; i < n; i += stride) values.push(points[3 * i + axis]);
    return [quantile(values, 0.02), quantile(values, 0.98)];
  };
  const [x, y, z] = [range(0), range(1), range(2)];
  camera.target = [(x[0] + x[1]) / 2, (y[0] + y[1]) / 2, (z[0] + z[1]) / 2];
  const span = Math.max(x[1] - x[0], y[1] - y[0], 1);
  // The span across a panel's narrower side (side by side, panels are half as wide).
  const panels = state.map === 'both' ? 2 : 1;
  const aspect = canvas.clientWidth / panels / Math.max(1, canvas.clientHeight);
  camera.distance = 1.2 * span / (2 * Math.tan(Math.PI / 8)) / Math.min(1, aspect);
}
function setView(view) {
  camera.view = view;
  if (view === 'top') { camera.yaw = -Math.PI / 2; camera.pitch = Math.PI / 2 - 1e-3; }
  if (view === 'side') { camera.yaw = -Math.PI / 2; camera.pitch = 0; }
  if (view === 'free') { camera.yaw = -Math.PI / 3; camera.pitch = Math.PI / 5; }
  for (const v of ['top', 'side', 'free']) document.getElementById('view-' + v).classList.toggle('active', v === view);
  requestDraw();
}
function eyeOf() {
  const c = Math.cos(camera.pitch), t = camera.target, d = camera.distance;
  return [t[0] - d * c * Math.cos(camera.yaw), t[1] - d * c * Math.sin(camera.yaw), t[2] + d * Math.sin(camera.pitch)];
}
function viewProjection(aspect) {
  const up = camera.pitch > Math.PI / 2 - 0.01 ? [Math.cos(camera.yaw), Math.sin(camera.yaw), 0] : [0, 0, 1];
  const proj = mat4.perspective(Math.PI / 4, aspect, camera.distance / 1000, camera.distance * 100);
  return mat4.multiply(proj, mat4.lookAt(eyeOf(), camera.target, up));
}

// ---- WebGL ----

const canvas = document.getElementById('map');
const gl = canvas.getContext('webgl', { preserveDrawingBuffer: true, antialias: true });
const state = {
  map: 'optimized', color: 'height', pointSize: 2,
  layers: { map: true, trajectory: true, links: true, regions: false },
};
let program = null, buffers = null;

function compile(type, source) {
  const shader = gl.createShader(type);
  gl.shaderSource(shader, source);
  gl.compileShader(shader);
  if (!gl.getShaderParameter(shader, gl.COMPILE_STATUS)) throw new Error(gl.getShaderInfoLog(shader));
  return shader;
}
function setupGl() {
  program = gl.createProgram();
  gl.attachShader(program, compile(gl.VERTEX_SHADER, [
    'attribute vec3 a_pos; attribute vec3 a_color; uniform mat4 u_mvp; uniform float u_size; varying vec3 v_color;',
    'void main() { gl_Position = u_mvp * vec4(a_pos, 1.0); gl_PointSize = u_size; v_color = a_color; }'].join('\n')));
  gl.attachShader(program, compile(gl.FRAGMENT_SHADER,
    'precision mediump float; varying vec3 v_color; void main() { gl_FragColor = vec4(v_color, 1.0); }'));
  gl.linkProgram(program);
  if (!gl.getProgramParameter(program, gl.LINK_STATUS)) throw new Error(gl.getProgramInfoLog(program));
  const buffer = (array) => {
    const b = gl.createBuffer();
    gl.bindBuffer(gl.ARRAY_BUFFER, b);
    gl.bufferData(gl.ARRAY_BUFFER, array, gl.STATIC_DRAW);
    return b;
  };
  buffers = {
    input: buffer(placed.input), optimized: buffer(placed.optimized), colors: gl.createBuffer(),
    track: {
      input: buffer(tracks.input),
      optimized: buffer(tracks.optimized),
      truth: tracks.truth ? buffer(tracks.truth) : null,
    },
    links: { input: buffer(linkLines(tracks.input)), optimized: buffer(linkLines(tracks.optimized)) },
    regions: buffer(regionBoxes()),
  };
  recolor();
}

function recolor() {
  const { colors, legend } = colorsFor(state.color);
  gl.bindBuffer(gl.ARRAY_BUFFER, buffers.colors);
  gl.bufferData(gl.ARRAY_BUFFER, colors, gl.STATIC_DRAW);
  showLegend(legend);
}

// Loop closures and revisits as segments between the two frames' positions;
// each vertex carries its colour (used: yellow, refused: dark red).
const loops = ((report.closure || {}).loops || []).filter((l) => l.from < frames && l.to < frames);
function linkLines(track) {
  const out = [];
  for (const l of loops) {
    const color = l.used ? [1.0, 0.82, 0.29] : [0.69, 0.23, 0.23];
    for (const f of [l.from, l.to]) out.push(track[3 * f], track[3 * f + 1], track[3 * f + 2], ...color);
  }
  return new Float32Array(out);
}

// The self-check's regions: each a stretch of frames, drawn as the box
// around its optimized positions, green where it got more consistent.
function regionList() {
  const regions = ((report.consistency || {}).regions || []).filter((r) => r.input_rms_m > 0 && r.first_frame < frames);
  const firsts = regions.map((r) => r.first_frame);
  return regions.map((r) => {
    const later = firsts.filter((f) => f > r.first_frame);
    return { ...r, end: later.length ? Math.min(...later) : frames };
  });
}
// A box's 12 edges between its corners, numbered by bits (x, y, z).
const BOX_EDGES = [[0, 1], [2, 3], [4, 5], [6, 7], [0, 2], [1, 3], [4, 6], [5, 7], [0, 4], [1, 5], [2, 6], [3, 7]];
function regionBoxes() {
  const out = [];
  for (const r of regionList()) {
    const slice = tracks.optimized.subarray(3 * r.first_frame, 3 * r.end);
    const b = bounds(slice);
    const lo = [b.lo[0] - 5, b.lo[1] - 5, b.lo[2] - 2], hi = [b.hi[0] + 5, b.hi[1] + 5, b.hi[2] + 2];
    const ratio = r.final_rms_m / r.input_rms_m;
    const color = ratio < 0.95 ? [0.3, 0.9, 0.5] : ratio > 1.05 ? [1.0, 0.35, 0.3] : [0.9, 0.9, 0.4];
    const corner = (i) => [i & 1 ? hi[0] : lo[0], i & 2 ? hi[1] : lo[1], i & 4 ? hi[2] : lo[2]];
    for (const [a, c] of BOX_EDGES) out.push(...corner(a), ...color, ...corner(c), ...color);
  }
  return new Float32Array(out);
}

function bindAttributes(posBuffer, stride, colorBuffer, constantColor) {
  const aPos = gl.getAttribLocation(program, 'a_pos'), aColor = gl.getAttribLocation(program, 'a_color');
  gl.bindBuffer(gl.ARRAY_BUFFER, posBuffer);
  gl.enableVertexAttribArray(aPos);
  gl.vertexAttribPointer(aPos, 3, gl.FLOAT, false, stride, 0);
  if (constantColor) {
    gl.disableVertexAttribArray(aColor);
    gl.vertexAttrib3f(aColor, ...constantColor);
  } else if (colorBuffer) {
    gl.bindBuffer(gl.ARRAY_BUFFER, colorBuffer);
    gl.enableVertexAttribArray(aColor);
    gl.vertexAttribPointer(aColor, 3, gl.UNSIGNED_BYTE, true, 0, 0);
  } else {  // colours interleaved after the positions
    gl.enableVertexAttribArray(aColor);
    gl.vertexAttribPointer(aColor, 3, gl.FLOAT, false, stride, 12);
  }
}

const TRACK_COLORS = { input: [1.0, 0.27, 0.78], optimized: [0.96, 0.96, 0.96], truth: [0.16, 1.0, 0.55] };
let picked = null;  // a scan index, marked on the map

function drawScene(which, mvp) {
  gl.uniformMatrix4fv(gl.getUniformLocation(program, 'u_mvp'), false, mvp);
  const size = gl.getUniformLocation(program, 'u_size');
  if (state.layers.map && pointCount) {
    gl.uniform1f(size, state.pointSize * (window.devicePixelRatio || 1));
    bindAttributes(buffers[which], 0, buffers.colors);
    gl.drawArrays(gl.POINTS, 0, pointCount);
  }
  gl.uniform1f(size, 9);
  if (state.layers.regions && buffers.regions) {
    bindAttributes(buffers.regions, 24);
    gl.drawArrays(gl.LINES, 0, regionList().length * 24);
  }
  if (state.layers.links && loops.length) {
    bindAttributes(buffers.links[which], 24);
    gl.drawArrays(gl.LINES, 0, 2 * loops.length);
  }
  if (state.layers.trajectory) {
    for (const name of [which, 'truth']) {
      if (!buffers.track[name]) continue;
      bindAttributes(buffers.track[name], 0, null, TRACK_COLORS[name]);
      gl.drawArrays(gl.LINE_STRIP, 0, frames);
      // Lines are one pixel wide in WebGL: each pose also a dot, to be seen over the map.
      gl.uniform1f(size, 3 * (window.devicePixelRatio || 1));
      gl.drawArrays(gl.POINTS, 0, frames);
    }
  }
  if (picked !== null) {
    gl.uniform1f(size, 9);
    bindAttributes(buffers.track[which], 0, null, [1.0, 0.85, 0.4]);
    gl.drawArrays(gl.POINTS, picked, 1);
  }
}

function draw() {
  const dpr = window.devicePixelRatio || 1;
  const w = Math.max(1, Math.round(canvas.clientWidth * dpr)), h = Math.max(1, Math.round(canvas.clientHeight * dpr));
  if (canvas.width !== w || canvas.height !== h) { canvas.width = w; canvas.height = h; }
  gl.clearColor(0.067, 0.078, 0.094, 1);
  gl.clear(gl.COLOR_BUFFER_BIT | gl.DEPTH_BUFFER_BIT);
  gl.enable(gl.DEPTH_TEST);
  gl.useProgram(program);
  const panels = state.map === 'both' ? ['input', 'optimized'] : [state.map];
  const width = Math.floor(w / panels.length);
  panels.forEach((which, k) => {
    gl.viewport(k * width, 0, width, h);
    drawScene(which, viewProjection(width / h));
  });
  const label = (which) => which + ' poses';
  document.getElementById('label-left').textContent = label(panels[0]);
  document.getElementById('label-right').textContent = panels.length === 2 ? label(panels[1]) : '';
  status.drawn = true;
  status.map = state.map;
  showStatus();
}
let drawPending = false;
function requestDraw() {
  if (!gl || drawPending) return;
  drawPending = true;
  requestAnimationFrame(() => { drawPending = false; draw(); });
}

// ---- interaction ----

function nearestScan(x, y) {
  const panels = state.map === 'both' ? ['input', 'optimized'] : [state.map];
  const width = canvas.clientWidth / panels.length;
  const k = Math.min(panels.length - 1, Math.floor(x / width));
  const mvp = viewProjection(width / canvas.clientHeight);
  const points = placed[panels[k]];
  let best = -1, bestD = 36;  // the nearest within 6 px
  const px = x - k * width;
  for (let i = 0; i < pointCount; ++i) {
    const X = points[3 * i], Y = points[3 * i + 1], Z = points[3 * i + 2];
    const cw = mvp[3] * X + mvp[7] * Y + mvp[11] * Z + mvp[15];
    if (cw <= 0) continue;
    const sx = ((mvp[0] * X + mvp[4] * Y + mvp[8] * Z + mvp[12]) / cw * 0.5 + 0.5) * width;
    const sy = (0.5 - (mvp[1] * X + mvp[5] * Y + mvp[9] * Z + mvp[13]) / cw * 0.5) * canvas.clientHeight;
    const d = (sx - px) ** 2 + (sy - y) ** 2;
    if (d < bestD) { best = i; bestD = d; }
  }
  return best < 0 ? null : scanOf[best];
}

// The scan of the point drawn nearest to (x, y) in CSS pixels of the canvas, marked and named.
function pick(x, y) {
  picked = nearestScan(x, y);
  document.getElementById('picked').textContent = picked === null ? '' : 'scan ' + picked + ' (of ' + frames + ')';
  requestDraw();
}

function setupMouse() {
  let drag = null;
  canvas.addEventListener('contextmenu', (e) => e.preventDefault());
  canvas.addEventListener('mousedown', (e) => {
    drag = { x: e.clientX, y: e.clientY, pan: e.button === 2 || e.shiftKey, moved: false };
  });
  window.addEventListener('mouseup', (e) => {
    if (drag && !drag.moved && e.target === canvas) {
      const r = canvas.getBoundingClientRect();
      pick(e.clientX - r.left, e.clientY - r.top);
    }
    drag = null;
  });
  window.addEventListener('mousemove', (e) => {
    if (!drag) return;
    const dx = e.clientX - drag.x, dy = e.clientY - drag.y;
    if (Math.abs(dx) + Math.abs(dy) > 2) drag.moved = true;
    drag.x = e.clientX; drag.y = e.clientY;
    if (drag.pan) {
      const s = camera.distance / canvas.clientHeight;
      const cy = Math.cos(camera.yaw), sy = Math.sin(camera.yaw);
      // Right of the view, and its up (or forward, seen from above) on the ground.
      camera.target[0] += -dx * s * sy + dy * s * cy;
      camera.target[1] += dx * s * cy + dy * s * sy;
    } else {
      if (camera.view !== 'free') setView('free');
      camera.yaw -= dx * 0.005;
      camera.pitch = Math.min(Math.PI / 2 - 1e-3, Math.max(-Math.PI / 2 + 1e-3, camera.pitch + dy * 0.005));
    }
    requestDraw();
  });
  canvas.addEventListener('wheel', (e) => {
    e.preventDefault();
    camera.distance *= Math.exp(e.deltaY * 0.001);
    requestDraw();
  }, { passive: false });
}

function setupControls() {
  for (const input of document.querySelectorAll('input[name=map]'))
    input.addEventListener('change', () => { state.map = input.value; requestDraw(); });
  document.getElementById('color').addEventListener('change', (e) => {
    state.color = e.target.value;
    recolor();
    requestDraw();
  });
  const size = document.getElementById('point-size');
  const sizeText = () => { document.getElementById('point-size-text').textContent = size.value + ' px'; };
  size.addEventListener('input', () => { state.pointSize = Number(size.value); sizeText(); requestDraw(); });
  sizeText();
  for (const box of document.querySelectorAll('input[data-layer]'))
    box.addEventListener('change', () => { state.layers[box.dataset.layer] = box.checked; requestDraw(); });
  for (const v of ['top', 'side', 'free'])
    document.getElementById('view-' + v).addEventListener('click', () => setView(v));
  document.getElementById('view-reset').addEventListener('click', () => { fitWhole(); requestDraw(); });
  window.addEventListener('resize', requestDraw);
  if (!intensity) document.querySelector('#color option[value=intensity]').disabled = true;
}

// Settings from the address: #map=input|optimized|both&color=...&view=top|side|free&layers=map,trajectory,...
// and pick=X,Y (a click at canvas pixel X, Y).
function applyAddress() {
  const params = new URLSearchParams(location.hash.slice(1));
  if (params.has('map')) {
    state.map = params.get('map');
    for (const input of document.querySelectorAll('input[name=map]')) input.checked = input.value === state.map;
  }
  if (params.has('color')) { state.color = params.get('color'); document.getElementById('color').value = state.color; }
  if (params.has('layers')) {
    const on = params.get('layers').split(',');
    for (const box of document.querySelectorAll('input[data-layer]')) {
      box.checked = on.includes(box.dataset.layer);
      state.layers[box.dataset.layer] = box.checked;
    }
  }
  if (params.has('size')) {
    state.pointSize = Number(params.get('size'));
    document.getElementById('point-size').value = state.pointSize;
    document.getElementById('point-size-text').textContent = state.pointSize + ' px';
  }
  setView(params.get('view') || camera.view);
  if (params.has('pick')) {
    const [x, y] = params.get('pick').split(',').map(Number);
    pick(x, y);
  }
}

// ---- tables ----

function fmt(v, digits) {
  if (typeof v === 'number') return Number.isInteger(v) ? String(v) : v.toFixed(digits === undefined ? 3 : digits);
  if (typeof v === 'boolean') return v ? 'yes' : 'no';
  if (v === null || v === undefined) return '';
  return typeof v === 'object' ? JSON.stringify(v) : String(v);
}
function table(title, header, rows) {
  if (!rows.length) return;
  const section = document.getElementById('tables');
  const h = document.createElement('h2');
  h.textContent = title;
  section.appendChild(h);
  const t = document.createElement('table');
  const addRow = (cells, tag) => {
    const tr = document.createElement('tr');
    for (const c of cells) { const td = document.createElement(tag); td.textContent = c; tr.appendChild(td); }
    t.appendChild(tr);
  };
  if (header) addRow(header, 'th');
  for (const r of rows) addRow(r, 'td');
  section.appendChild(t);
}
function flatten(object, prefix, out) {
  for (const [k, v] of Object.entries(object || {})) {
    if (v && typeof v === 'object' && !Array.isArray(v)) flatten(v, prefix + k + '.', out);
    else out.push([prefix + k, fmt(v)]);
  }
  return out;
}

function buildTables() {
  const c = report.consistency || {};
  const update = report.largest_update;
  table('Summary', null, [
    ['scans', fmt(frames)],
    ['points on this page', fmt(pointCount) + ' (one per ' + fmt(data.voxel_m, 2) + ' m voxel' +
      (data.kept_share < 1 ? ', ' + Math.round(100 * data.kept_share) + ' % of them' : '') + ')'],
    ['run time', report.seconds ? fmt(report.seconds.total, 1) + ' s' : ''],
    ['peak memory', report.peak_memory_mib ? fmt(report.peak_memory_mib, 0) + ' MiB' : ''],
    ['largest pose update', update ? fmt(update.translation_m) + ' m, ' + fmt(update.rotation_deg) + ' deg' : ''],
    ['hba', report.hba ? report.hba.version + ' (' + report.hba.revision + ')' : ''],
  ].filter((r) => r[1] !== ''));
  table('Consistency (plane RMS on the input\u2019s planes, lower is crisper)', ['poses', 'RMS (m)', 'note'], [
    ['input', fmt(c.input_rms_m, 4), ''],
    ['hierarchy', fmt(c.hierarchy_rms_m, 4), c.hierarchy_rejected ? 'rejected: refined from the input'
      : c.hierarchy_insignificant ? 'no gain beyond the noise: refined from the input' : ''],
    ['final', fmt(c.final_rms_m, 4), c.final_rejected ? 'rejected: input returned'
      : (report.refinement || {}).converged_at_start && update && update.translation_m === 0
        ? 'the input was converged: returned unchanged' : ''],
  ].filter((r) => r[1] !== ''));
  const warnings = report.warnings || [];
  if (warnings.length) table('Warnings', null, warnings.map((w) => [fmt(w)]));
  table('Time per stage (s)', ['stage', 'seconds'],
    Object.entries(report.seconds || {}).map(([k, v]) => [k, fmt(v, 2)]));
  table('Layers', ['layer', 'windows', 'frames', 'planes', 'RMS before (m)', 'after (m)', 's'],
    (report.layer_reports || []).map((l) => [l.global ? 'global' : l.layer, l.windows, l.frames, l.planes,
      fmt(l.plane_rms_before_m, 4), fmt(l.plane_rms_after_m, 4), fmt(l.seconds, 2)].map((v) => fmt(v))));
  table('Loop closures and revisits', ['from', 'to', 'source', 'used', 'correction (m)', 'why not'],
    loops.map((l) => [l.from, l.to, l.source, fmt(l.used), fmt(l.correction_m), l.reason || ''].map((v) => fmt(v))));
  table('Self-check regions (plane RMS, m)', ['frames', 'input', 'final'],
    regionList().map((r) => [r.first_frame + '\u2013' + (r.end - 1), fmt(r.input_rms_m, 4), fmt(r.final_rms_m, 4)]));
  table('Settings', null, flatten(report.settings, '', []));
  table('Input', null, flatten(report.input, '', []));
}

// ---- start ----

status.points = pointCount;
status.frames = frames;
buildTables();
if (!gl) {
  document.getElementById('no-webgl').hidden = false;
  console.warn('hba report: no WebGL');
} else {
  setupGl();
  setupControls();
  setupMouse();
  applyAddress();
  fitWhole();
  window.addEventListener('hashchange', () => { applyAddress(); recolor(); requestDraw(); });
  recolor();
  lap('ready');
  draw();
  gl.finish();
  lap('drawn');
}
showStatus();
