// The hodr web demo's front end: plain ES modules and canvases, no build step.
// Optimisation runs are Rust async functions (hodr-web's `runMethod`) that call back
// after every iteration; the callback hands back a promise for the next animation frame
// once a frame's work is done, so several runs interleave and the page never freezes.
// Image to shapes runs in a worker (fit-worker.js).

import init, { taskInfo, render, losses, runMethod, RenderBench } from './pkg/hodr_web.js';

const COLOURS = { Auto: '#1f6feb', FR22: '#e8710a', 'CMA-ES': '#2da44e', OurH: '#8250df' };
const FRAME_BUDGET_MS = 10;
const $ = (id) => document.getElementById(id);

function say(text) { $('message').textContent = text || ''; }
function errorText(e) { return (e && e.message) ? e.message : String(e); }
function numberOr(id, fallback) {
  const v = parseFloat($(id).value);
  return Number.isFinite(v) ? v : fallback;
}

// ---------------------------------------------------------------- frame pacing
let frameStart = performance.now();
let frameWaiters = [];
function nextFrame() {
  return new Promise((resolve) => {
    if (frameWaiters.push(resolve) === 1) {
      requestAnimationFrame(() => {
        frameStart = meter.mark = performance.now();
        const waiting = frameWaiters;
        frameWaiters = [];
        waiting.forEach((r) => r());
      });
    }
  });
}
async function frames(n) { for (let i = 0; i < n; i++) await nextFrame(); }

/** Evaluations per second of the scene's runs: the evaluations over the time the page
 * spent in WebAssembly, i.e. between leaving one of our callbacks (or the start of a
 * frame) and entering the next one. */
const meter = { evaluations: 0, ms: 0, mark: performance.now() };
function meterReset() { meter.evaluations = 0; meter.ms = 0; meter.mark = performance.now(); }

/** One paced run of a method; `onIteration(progress)` redraws, `yieldAfter(progress)`
 * says how many frames to wait (0: go on while the frame has time). */
class Run {
  constructor(task, method, settings, onIteration, yieldAfter) {
    this.method = method;
    this.evaluations = 0;
    this.history = [];
    this.last = null;
    this.outcome = null;
    this.cancelled = false;
    this.sinceYield = 0;
    const { seed, sigma0, pairs, start } = settings;
    meter.mark = performance.now();
    this.done = runMethod(task, method, seed, sigma0, pairs, start, undefined, (p) => {
      meter.ms += performance.now() - meter.mark;
      meter.evaluations += p.evaluations - this.evaluations;
      this.sinceYield += p.evaluations - this.evaluations;
      this.evaluations = p.evaluations;
      this.history.push([p.evaluations, p.error]);
      this.last = p;
      if (this.cancelled) return false;
      onIteration(p, this);
      const wait = yieldAfter(p, this);
      meter.mark = performance.now();
      if (wait > 0 || meter.mark - frameStart > FRAME_BUDGET_MS) {
        this.sinceYield = 0;
        return frames(Math.max(1, wait)).then(() => !this.cancelled);
      }
      return true;
    }).then((out) => { this.outcome = out; onIteration(this.last, this); meter.mark = performance.now(); return out; },
      (e) => { if (!this.cancelled) say(`${method}: ${errorText(e)}`); meter.mark = performance.now(); });
  }
  cancel() { this.cancelled = true; }
}

// ---------------------------------------------------------------- status bar
const status = { runs: [], fit: null };
function updateStatus() {
  let evals = meter.evaluations, ms = meter.ms;
  if (status.fit) { evals = status.fit.evaluations; ms = status.fit.ms; }
  $('evals').textContent = evals.toLocaleString('en');
  $('rate').textContent = ms > 0 ? Math.round(evals / (ms / 1000)).toLocaleString('en') : '–';
}

// ---------------------------------------------------------------- drawing helpers
function drawRgba(canvas, rgba, width, height, { alpha = 1, clear = true, smooth = false } = {}) {
  const off = new OffscreenCanvas(width, height);
  off.getContext('2d').putImageData(new ImageData(new Uint8ClampedArray(rgba), width, height), 0, 0);
  const ctx = canvas.getContext('2d');
  ctx.imageSmoothingEnabled = smooth;
  if (clear) ctx.clearRect(0, 0, canvas.width, canvas.height);
  ctx.globalAlpha = alpha;
  ctx.drawImage(off, 0, 0, canvas.width, canvas.height);
  ctx.globalAlpha = 1;
}

function axes(ctx, box, xs, ys, xlabel, ylabel) {
  ctx.strokeStyle = '#99a1b0'; ctx.fillStyle = '#5b6475'; ctx.lineWidth = 1;
  ctx.font = '12px system-ui, sans-serif';
  ctx.strokeRect(box.x, box.y, box.w, box.h);
  ctx.textAlign = 'center';
  for (const x of xs.ticks) ctx.fillText(xs.label(x), xs.map(x), box.y + box.h + 15);
  ctx.fillText(xlabel, box.x + box.w / 2, box.y + box.h + 32);
  ctx.textAlign = 'right';
  for (const y of ys.ticks) ctx.fillText(ys.label(y), box.x - 5, ys.map(y) + 4);
  ctx.save(); ctx.translate(14, box.y + box.h / 2); ctx.rotate(-Math.PI / 2);
  ctx.textAlign = 'center'; ctx.fillText(ylabel, 0, 0); ctx.restore();
}

function linear(lo, hi, a, b) {
  const map = (v) => a + (v - lo) / (hi - lo) * (b - a);
  const raw = (hi - lo) / 6, decade = Math.pow(10, Math.floor(Math.log10(raw)));
  const step = [1, 2, 5, 10].map((m) => m * decade).find((s) => s >= raw);
  const ticks = [];
  for (let t = Math.ceil(lo / step) * step; t <= hi + 1e-9; t += step) ticks.push(t);
  return { map, ticks, label: (v) => +v.toFixed(6) + '' };
}

// ---------------------------------------------------------------- TRI1D
const tri = { info: null, grid: null, raw: null, runs: [], target: null };
const TRI_GRID = 600;

function triSetup() {
  const info = taskInfo('tri1d', 1);
  tri.info = info;
  const lo = info.lower[0] - 0.5, hi = info.upper[0] + 0.5;
  tri.grid = Float64Array.from({ length: TRI_GRID }, (_, i) => lo + (hi - lo) * i / (TRI_GRID - 1));
  tri.raw = losses('tri1d', tri.grid);
  tri.target = render('tri1d', info.thetaTrue);
  $('t-sigma').value = info.sigma0;
  $('t-pairs').value = info.pairs;
}

/** f̄(θ) = E f(θ − τ), τ ~ N(0, σ²), as a discrete convolution on the grid; beyond the
 * grid f keeps its edge values (θ beyond the clamp renders as at the clamp). */
function triSmoothed(sigma) {
  const g = tri.grid, n = g.length, h = g[1] - g[0];
  if (sigma < h) return tri.raw;
  const radius = Math.ceil(4 * sigma / h), w = new Float64Array(2 * radius + 1);
  let total = 0;
  for (let k = -radius; k <= radius; k++) { w[k + radius] = Math.exp(-0.5 * (k * h / sigma) ** 2); total += w[k + radius]; }
  const out = new Float64Array(n);
  for (let i = 0; i < n; i++) {
    let s = 0;
    for (let k = -radius; k <= radius; k++) s += w[k + radius] * tri.raw[Math.max(0, Math.min(n - 1, i - k))];
    out[i] = s / total;
  }
  return out;
}

function triDraw() {
  const canvas = $('t-plot'), ctx = canvas.getContext('2d');
  ctx.clearRect(0, 0, canvas.width, canvas.height);
  const box = { x: 60, y: 16, w: canvas.width - 80, h: canvas.height - 64 };
  const g = tri.grid;
  const ymax = Math.max(...tri.raw) * 1.15;
  const xs = linear(g[0], g[g.length - 1], box.x, box.x + box.w);
  const ys = linear(0, ymax, box.y + box.h, box.y);
  axes(ctx, box, xs, ys, 'θ (triangle position, units of 1/8 image)', 'loss (MSE)');
  const curve = (values, colour, width, dash = []) => {
    ctx.strokeStyle = colour; ctx.lineWidth = width; ctx.setLineDash(dash); ctx.beginPath();
    values.forEach((v, i) => (i ? ctx.lineTo : ctx.moveTo).call(ctx, xs.map(g[i]), ys.map(v)));
    ctx.stroke(); ctx.setLineDash([]);
  };
  curve(tri.raw, '#9aa3b2', 2);
  ctx.strokeStyle = '#1d2330'; ctx.setLineDash([4, 4]); ctx.beginPath();
  ctx.moveTo(xs.map(tri.info.thetaTrue[0]), box.y); ctx.lineTo(xs.map(tri.info.thetaTrue[0]), box.y + box.h); ctx.stroke();
  ctx.setLineDash([]);
  const legendX = box.x + box.w * 0.42;
  let legendY = box.y + box.h * 0.62;
  ctx.textAlign = 'left'; ctx.font = '13px system-ui, sans-serif';
  ctx.fillStyle = '#9aa3b2'; ctx.fillText('raw loss (θ* = 2 dashed)', legendX, legendY);
  for (const run of tri.runs) {
    const p = run.last, colour = COLOURS[run.method];
    legendY += 17; ctx.fillStyle = colour;
    const state = run.outcome ? ` — ${run.outcome.stopped}` : '';
    ctx.fillText(`${run.method}: smoothed at σ = ${p ? p.sigma.toPrecision(3) : '…'}, ${run.evaluations} evaluations${state}`, legendX, legendY);
    if (!p) continue;
    curve(triSmoothed(p.sigma), colour, 2.5);
    ctx.fillStyle = colour; ctx.globalAlpha = 0.75;
    for (let k = 0; k < p.values.length; k++) {
      ctx.beginPath();
      ctx.arc(xs.map(Math.max(g[0], Math.min(g[g.length - 1], p.samples[k]))), ys.map(p.values[k]), 3.5, 0, 2 * Math.PI);
      ctx.fill();
    }
    ctx.globalAlpha = 1; ctx.strokeStyle = colour; ctx.lineWidth = 2; ctx.beginPath();
    ctx.moveTo(xs.map(p.theta[0]), box.y); ctx.lineTo(xs.map(p.theta[0]), box.y + box.h); ctx.stroke();
  }
  tri.runs.forEach((run, i) => {
    const canvas = $(i ? 't-img-b' : 't-img-a');
    const theta = run.last ? run.last.theta : [run.start];
    drawRgba(canvas, render('tri1d', Float64Array.from(theta)), tri.info.size, tri.info.size);
    drawRgba(canvas, tri.target, tri.info.size, tri.info.size, { alpha: 0.3, clear: false });
    $(i ? 't-cap-b' : 't-cap-a').textContent = `${run.method}: θ = ${theta[0].toFixed(3)} (target 2, faint)`;
  });
}

function triReset() {
  tri.runs.forEach((r) => r.cancel());
  say('');
  const seed = Math.max(0, Math.floor(numberOr('t-seed', 1)));
  const settings = {
    seed,
    sigma0: numberOr('t-sigma', tri.info.sigma0),
    pairs: Math.floor(numberOr('t-pairs', tri.info.pairs)),
    start: undefined,
  };
  const start = taskInfo('tri1d', seed).start[0];
  const pace = () => 31 - parseInt($('t-speed').value, 10);
  tri.runs = [$('t-method').value, 'FR22'].map((m) => {
    const run = new Run('tri1d', m, settings, () => { triDraw(); updateStatus(); }, pace);
    run.start = start;
    return run;
  });
  status.runs = tri.runs; status.fit = null; meterReset();
  triDraw(); updateStatus();
}

// ---------------------------------------------------------------- BOX2 / BOX10 race
const race = { task: 'box2', info: null, start: null, runs: [], target: null, drag: null, side: 1.5 };

function raceSetup(task) {
  race.task = task;
  race.info = taskInfo(task, 1);
  race.side = task === 'box2' ? 1.5 : 1.0;
  race.target = render(task, race.info.thetaTrue);
  $('r-sigma').value = race.info.sigma0;
  $('r-pairs').value = race.info.pairs;
  race.start = Array.from(taskInfo(task, Math.floor(numberOr('r-seed', 1))).start);
}

function raceSetupDraw() {
  const canvas = $('r-setup'), info = race.info;
  drawRgba(canvas, render(race.task, Float64Array.from(race.start)), info.size, info.size);
  drawRgba(canvas, race.target, info.size, info.size, { alpha: 0.3, clear: false });
}

function panelFor(method) {
  let fig = document.querySelector(`#r-panels figure[data-method="${method}"]`);
  if (!fig) {
    fig = document.createElement('figure');
    fig.dataset.method = method;
    fig.innerHTML = `<canvas width="176" height="176"></canvas><figcaption style="color:${COLOURS[method]}">${method}</figcaption>`;
    $('r-panels').appendChild(fig);
  }
  return fig;
}

function racePanel(run) {
  const info = race.info, fig = panelFor(run.method), canvas = fig.querySelector('canvas');
  const theta = run.last ? run.last.theta : Float64Array.from(race.start);
  drawRgba(canvas, render(race.task, theta), info.size, info.size);
  const ctx = canvas.getContext('2d'), px = canvas.width / 8;
  ctx.strokeStyle = '#ffffff'; ctx.setLineDash([3, 3]); ctx.lineWidth = 1;
  const t = info.thetaTrue;
  for (let i = 0; i < t.length; i += 2) {
    ctx.strokeRect((t[i] - race.side / 2) * px, (t[i + 1] - race.side / 2) * px, race.side * px, race.side * px);
  }
  ctx.setLineDash([]);
  if (run.last) {
    ctx.strokeStyle = COLOURS[run.method]; ctx.lineWidth = 2;
    for (let i = 0; i < theta.length; i += 2) {
      ctx.beginPath();
      ctx.arc(theta[i] * px, theta[i + 1] * px, Math.min(run.last.sigma, 16) * px, 0, 2 * Math.PI);
      ctx.stroke();
    }
  }
  const p = run.last;
  fig.querySelector('figcaption').textContent =
    `${run.method} — σ ${p ? p.sigma.toPrecision(2) : '–'}, error ${p ? p.error.toPrecision(2) : '–'}`;
}

function racePlot() {
  const canvas = $('r-plot'), ctx = canvas.getContext('2d');
  ctx.clearRect(0, 0, canvas.width, canvas.height);
  const box = { x: 60, y: 12, w: canvas.width - 100, h: canvas.height - 56 };
  let xmax = 1000;
  for (const r of race.runs) xmax = Math.max(xmax, r.evaluations);
  const decades = Math.ceil(Math.log10(xmax));
  const xs = {
    map: (v) => box.x + Math.log10(Math.max(v, 1)) / decades * box.w,
    ticks: Array.from({ length: decades + 1 }, (_, k) => 10 ** k),
    label: (v) => v.toLocaleString('en'),
  };
  const lo = -3, hi = 1;
  const ys = {
    map: (v) => box.y + box.h - (Math.log10(Math.max(v, 1e-3)) - lo) / (hi - lo) * box.h,
    ticks: [1e-3, 1e-2, 1e-1, 1, 10],
    label: (v) => v >= 1 ? String(v) : v.toExponential(0),
  };
  axes(ctx, box, xs, ys, 'evaluations (log scale)', 'parameter error');
  if (race.initialError > 0) {
    const goal = 0.01 * race.initialError;
    ctx.strokeStyle = '#1d2330'; ctx.setLineDash([5, 4]); ctx.beginPath();
    ctx.moveTo(box.x, ys.map(goal)); ctx.lineTo(box.x + box.w, ys.map(goal)); ctx.stroke(); ctx.setLineDash([]);
  }
  for (const r of race.runs) {
    ctx.strokeStyle = COLOURS[r.method]; ctx.lineWidth = 2; ctx.beginPath();
    r.history.forEach(([e, err], i) => (i ? ctx.lineTo : ctx.moveTo).call(ctx, xs.map(e), ys.map(err)));
    ctx.stroke();
  }
}

function raceTable() {
  const rows = race.runs.map((r) => {
    const p = r.last, out = r.outcome;
    const hit = out ? (out.evaluationsToTarget ?? '–') : (r.hit ?? '…');
    return `<tr><td style="color:${COLOURS[r.method]}">${r.method}</td><td>${r.evaluations}</td>` +
      `<td>${p ? p.error.toExponential(2) : '–'}</td><td>${hit}</td><td>${out ? out.stopped : 'running'}</td></tr>`;
  });
  document.querySelector('#r-table tbody').innerHTML = rows.join('');
}

function raceDraw() {
  race.runs.forEach(racePanel);
  racePlot(); raceTable(); updateStatus();
}

function raceReset(keepStart = false) {
  race.runs.forEach((r) => r.cancel());
  say('');
  const task = $('r-task').value;
  if (task !== race.task || !keepStart) {
    const sigma = $('r-sigma').value, pairs = $('r-pairs').value, same = task === race.task;
    raceSetup(task);
    if (same) { $('r-sigma').value = sigma; $('r-pairs').value = pairs; }
  }
  $('r-panels').innerHTML = '';
  const settings = {
    seed: Math.max(0, Math.floor(numberOr('r-seed', 1))),
    sigma0: numberOr('r-sigma', race.info.sigma0),
    pairs: Math.floor(numberOr('r-pairs', race.info.pairs)),
    start: Float64Array.from(race.start),
  };
  race.initialError = Math.sqrt(race.start.reduce((s, v, i) => s + (v - race.info.thetaTrue[i]) ** 2, 0) / race.start.length);
  const methods = [...document.querySelectorAll('.methods input:checked')].map((i) => i.value);
  if (!methods.length) say('pick at least one method');
  const speed = () => parseInt($('r-speed').value, 10);
  meterReset();
  race.runs = methods.map((m) => new Run(race.task, m, settings, (p, run) => {
    if (run.hit === undefined && p && p.error <= 0.01 * race.initialError) run.hit = p.evaluations;
  }, (p, run) => (speed() < 200 && run.sinceYield >= speed() ? 1 : 0)));
  // Every line starts at the start's error (drawn at one evaluation on the log axis).
  race.runs.forEach((r) => r.history.unshift([1, race.initialError]));
  status.runs = race.runs; status.fit = null;
  raceSetupDraw(); raceDraw();
}

function raceDrag() {
  const canvas = $('r-setup');
  const toUnits = (e) => {
    const r = canvas.getBoundingClientRect();
    return [(e.clientX - r.left) / r.width * 8, (e.clientY - r.top) / r.height * 8];
  };
  canvas.addEventListener('pointerdown', (e) => {
    const [x, y] = toUnits(e);
    for (let i = 0; i < race.start.length; i += 2) {
      if (Math.abs(x - race.start[i]) <= race.side / 2 && Math.abs(y - race.start[i + 1]) <= race.side / 2) {
        race.drag = { i, dx: race.start[i] - x, dy: race.start[i + 1] - y };
        canvas.setPointerCapture(e.pointerId);
        race.runs.forEach((r) => r.cancel());
        return;
      }
    }
  });
  canvas.addEventListener('pointermove', (e) => {
    if (!race.drag) return;
    const [x, y] = toUnits(e), { i, dx, dy } = race.drag;
    race.start[i] = Math.max(race.info.lower[i], Math.min(race.info.upper[i], x + dx));
    race.start[i + 1] = Math.max(race.info.lower[i + 1], Math.min(race.info.upper[i + 1], y + dy));
    raceSetupDraw();
  });
  canvas.addEventListener('pointerup', () => {
    if (!race.drag) return;
    race.drag = null;
    raceReset(true);
  });
}

function raceLoop() {
  if (scene === 'race') raceDraw();
  else updateStatus();
  meter.mark = performance.now();
  requestAnimationFrame(raceLoop);
}

// ---------------------------------------------------------------- image to shapes
const img = { worker: null, bytes: null, size: [0, 0], started: 0, pngUrl: null, svgUrl: null };

function imgStop() {
  if (img.worker) img.worker.terminate();
  img.worker = null;
}

function imgLinks(svg) {
  for (const url of [img.pngUrl, img.svgUrl]) if (url) URL.revokeObjectURL(url);
  img.pngUrl = img.svgUrl = null;
  $('i-png').classList.add('disabled'); $('i-svg').classList.add('disabled');
  if (!svg) return;
  img.svgUrl = URL.createObjectURL(new Blob([svg], { type: 'image/svg+xml' }));
  $('i-svg').href = img.svgUrl; $('i-svg').classList.remove('disabled');
  // The PNG is the vector result drawn at PNG_SCALE× the fit's resolution.
  const vector = new Image();
  vector.onload = () => {
    const [w, h] = img.size, png = new OffscreenCanvas(w * PNG_SCALE, h * PNG_SCALE);
    png.getContext('2d').drawImage(vector, 0, 0, png.width, png.height);
    png.convertToBlob({ type: 'image/png' }).then((blob) => {
      img.pngUrl = URL.createObjectURL(blob);
      $('i-png').href = img.pngUrl; $('i-png').classList.remove('disabled');
    });
  };
  vector.onerror = () => say('could not draw the SVG for the PNG download');
  vector.src = img.svgUrl;
}
const PNG_SCALE = 4;

function imgFit() {
  imgStop(); imgLinks(null); say('');
  status.runs = []; status.fit = { evaluations: 0, ms: 0 };
  updateStatus();
  const count = Number($('i-count').value);
  const worker = new Worker('fit-worker.js', { type: 'module' });
  img.worker = worker;
  img.started = performance.now();
  $('i-cap').textContent = 'shapes: starting…';
  worker.onmessage = ({ data }) => {
    if (data.type === 'target') {
      img.size = [data.width, data.height];
      fitCanvases(data.width, data.height);
      drawRgba($('i-target'), data.rgba, data.width, data.height, { smooth: true });
      $('i-fit').getContext('2d').clearRect(0, 0, $('i-fit').width, $('i-fit').height);
    } else if (data.type === 'shape') {
      const [w, h] = img.size;
      drawRgba($('i-fit'), data.rgba, w, h, { smooth: true });
      $('i-cap').textContent = `shapes: ${data.count} of ${count}, RMSE ${data.rmse.toFixed(4)}`;
      status.fit = { evaluations: data.evaluations, ms: performance.now() - img.started };
      updateStatus();
    } else if (data.type === 'done') {
      status.fit = { evaluations: data.evaluations, ms: performance.now() - img.started };
      $('i-cap').textContent = `${data.count} shapes, RMSE ${data.rmse.toFixed(4)}, ${data.evaluations.toLocaleString('en')} evaluations`;
      img.done = data;
      updateStatus();
      imgLinks(data.svg);
      imgStop();
    } else if (data.type === 'error') {
      say(data.message);
      $('i-cap').textContent = 'shapes: stopped';
      imgStop();
    }
  };
  worker.onerror = (e) => { say(`the fit stopped: ${e.message || 'worker error'}`); imgStop(); };
  img.done = null;
  worker.postMessage({ bytes: img.bytes, kind: $('i-kind').value, count, seed: Math.max(0, Math.floor(numberOr('i-seed', 1))) });
}

function fitCanvases(w, h) {
  const side = 384, scale = side / Math.max(w, h);
  for (const id of ['i-target', 'i-fit']) {
    $(id).width = Math.round(w * scale); $(id).height = Math.round(h * scale);
  }
}

async function imgFile(file) {
  if (!file) return;
  img.bytes = new Uint8Array(await file.arrayBuffer());
  imgFit();
}

function imgSetup() {
  $('i-file').addEventListener('change', (e) => imgFile(e.target.files[0]));
  $('i-start').addEventListener('click', imgFit);
  $('i-reset').addEventListener('click', () => { img.bytes = null; $('i-file').value = ''; imgFit(); });
  document.addEventListener('dragover', (e) => { e.preventDefault(); $('i-drop').classList.add('over'); });
  document.addEventListener('dragleave', () => $('i-drop').classList.remove('over'));
  document.addEventListener('drop', (e) => {
    e.preventDefault(); $('i-drop').classList.remove('over');
    show('image');
    imgFile(e.dataTransfer.files[0]);
  });
}

// ---------------------------------------------------------------- scenes
let scene = 'tri1d';
function show(name, again = false) {
  if (name === scene && !again) return;
  scene = name;
  document.querySelectorAll('nav button').forEach((b) => b.classList.toggle('active', b.dataset.scene === name));
  document.querySelectorAll('.scene').forEach((s) => s.classList.toggle('active', s.id === name));
  tri.runs.forEach((r) => r.cancel());
  race.runs.forEach((r) => r.cancel());
  imgStop();
  say('');
  if (name === 'tri1d') triReset();
  if (name === 'race') raceReset(true);
  if (name === 'image') imgFit();
}

function guard(f) {
  return (...args) => { try { return f(...args); } catch (e) { say(errorText(e)); } };
}

async function main() {
  try {
    await init();
  } catch (e) {
    say(`could not load the WebAssembly module: ${errorText(e)}`);
    throw e;
  }
  document.querySelectorAll('nav button').forEach((b) => b.addEventListener('click', guard(() => show(b.dataset.scene))));
  triSetup();
  raceSetup('box2');
  for (const id of ['t-reset', 't-method']) $(id).addEventListener(id === 't-reset' ? 'click' : 'change', guard(triReset));
  $('r-reset').addEventListener('click', guard(() => raceReset(false)));
  $('r-task').addEventListener('change', guard(() => raceReset(false)));
  $('r-seed').addEventListener('change', guard(() => raceReset(false)));
  for (const id of ['r-sigma', 'r-pairs']) $(id).addEventListener('change', guard(() => raceReset(true)));
  for (const id of ['t-sigma', 't-pairs', 't-seed']) $(id).addEventListener('change', guard(triReset));
  document.querySelectorAll('.methods input').forEach((i) => i.addEventListener('change', guard(() => raceReset(true))));
  raceDrag();
  imgSetup();
  window.addEventListener('unhandledrejection', (e) => say(errorText(e.reason)));
  triReset();
  raceLoop();
}

// Hooks for the browser test (web/test/browser_test.py) and for the curious.
window.hodr = {
  ready: main(),
  /** Shows a scene and starts it afresh. */
  show: guard((name) => show(name, true)),
  /** One run to the end without pacing: the numbers the native reference prints. */
  run: (task, method, seed) => runMethod(task, method, seed, undefined, undefined, undefined, undefined, () => true),
  /** Stops the scene's runs and the fit, leaving the page idle (before timing). */
  stop() {
    tri.runs.forEach((r) => r.cancel());
    race.runs.forEach((r) => r.cancel());
    imgStop();
  },
  /** BENCHMARKS.md's render loop: BOX2 renders per second in this page. */
  bench(renders) {
    const bench = new RenderBench();
    bench.run(1000);
    const t0 = performance.now();
    const checksum = bench.run(renders);
    const seconds = (performance.now() - t0) / 1000;
    bench.free();
    return { renders, seconds, rendersPerSecond: renders / seconds, checksum };
  },
  state: () => ({
    scene,
    message: $('message').textContent,
    evaluations: $('evals').textContent,
    rate: $('rate').textContent,
    runs: status.runs.map((r) => ({
      method: r.method,
      evaluations: r.evaluations,
      outcome: r.outcome && { ...r.outcome, theta: Array.from(r.outcome.theta) },
    })),
    fit: img.done ? { count: img.done.count, rmse: img.done.rmse } : null,
    fitCaption: $('i-cap').textContent,
    raceStart: race.start,
  }),
};
