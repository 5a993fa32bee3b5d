// The page `moreau view DIR` serves: plays the run in DIR back. It reads /manifest.json (the
// directory's .pvd collections and probes), the chosen collection's frames under /data/, and
// probes.csv, and wires the controls: play/pause, the time slider, colouring by a point array with
// its colour bar, and the probe plot. `window.moreauViewer` lets scripts (and the browser test)
// drive it and read where things are drawn.
import 'uplot/dist/uPlot.min.css';

import { isPlaneSquare } from './cell_geometry.js';
import { paintColourBar, pointScalars } from './colour_map.js';
import { ProbePlot, readProbesCsv } from './probe_plot.js';
import { SceneView } from './scene_view.js';
import { readPvd, readVtk } from './vtk_reader.js';

const $ = (id) => document.getElementById(id);

async function fetchOk(url, as) {
  const response = await fetch(url);
  if (!response.ok) throw new Error(`${url}: ${response.status} ${response.statusText}`);
  return as === 'text' ? response.text() : as === 'json' ? response.json() : response.arrayBuffer();
}

// "frames/cloth_000012.vtu" -> "cloth"
function objectName(file) {
  return file.replace(/^.*\//, '').replace(/_\d+\.\w+$/, '');
}

class Player {
  constructor(manifest, collection, frames) {
    this.manifest = manifest;
    this.frames = frames;
    this.cache = new Map();  // frame index -> Promise<Map<part, {name, data}>>
    this.index = -1;
    this.shown = -1;  // the frame index last drawn
    this.playing = false;
    this.colourArray = '';
    this.colouring = null;
    this.base = '/data/' + collection.replace(/[^/]*$/, '');
    this.view = new SceneView($('view'), { keepPicture: renderRequest() !== null });
    this.probes = null;
  }

  load(index) {
    if (!this.cache.has(index)) {
      const parts = this.frames[index].parts;
      this.cache.set(index, Promise.all(parts.map(async ({ part, file }) => {
        const data = readVtk(await fetchOk(this.base + file), file);
        return [part, { name: objectName(file), data }];
      })).then((entries) => new Map(entries)));
      // Keep the frames near the one shown; drop the rest so long runs fit in memory.
      for (const k of this.cache.keys()) if (Math.abs(k - index) > 8) this.cache.delete(k);
    }
    return this.cache.get(index);
  }

  async show(index) {
    this.index = index;
    const files = await this.load(index);
    if (this.index !== index) return;  // a later request won
    if (this.shown < 0) {
      // The camera frames the first frame, whichever is shown first, so views of a run agree.
      const first = index === 0 ? files : await this.load(0);
      this.view.frame(first);
      this.fillArrayChoices(first);
    }
    this.colouring = this.colourRange(files);
    this.view.show(files, this.colouring);
    this.shown = index;
    const time = this.frames[index].time;
    $('slider').value = String(index);
    $('time').textContent = `t = ${time.toPrecision(4)} s  (frame ${index + 1} of ${this.frames.length})`;
    if (this.probes) this.probes.mark(time);
    this.load(Math.min(index + 1, this.frames.length - 1));  // the next one, while this one is looked at
  }

  // The point arrays of the first frame's objects, for the "colour by" list.
  fillArrayChoices(files) {
    const names = new Set();
    for (const { data } of files.values()) for (const n of Object.keys(data.pointData)) names.add(n);
    const select = $('colour-by');
    for (const n of [...names].sort()) select.add(new Option(n, n));
  }

  // The chosen array's range over the frame's objects that have it, planes aside (the colour
  // bar's ends).
  colourRange(files) {
    if (!this.colourArray) {
      $('colour-bar-box').hidden = true;
      return null;
    }
    let min = Infinity, max = -Infinity;
    for (const { data } of files.values()) {
      const array = data.pointData[this.colourArray];
      if (!array || isPlaneSquare(data)) continue;  // planes are drawn grey
      for (const s of pointScalars(array)) {
        min = Math.min(min, s);
        max = Math.max(max, s);
      }
    }
    if (!(min <= max)) min = max = 0;
    $('colour-bar-box').hidden = false;
    $('colour-min').textContent = min.toPrecision(3);
    $('colour-max').textContent = max.toPrecision(3);
    $('colour-name').textContent = this.colourArray;
    return { array: this.colourArray, min, max };
  }

  async play() {
    this.playing = !this.playing;
    $('play').textContent = this.playing ? 'Pause' : 'Play';
    if (this.playing && this.index >= this.frames.length - 1) await this.show(0);
    while (this.playing && this.index < this.frames.length - 1) {
      const started = performance.now();
      await this.show(this.index + 1);
      const wait = 1000 / 30 - (performance.now() - started);
      if (wait > 0) await new Promise((r) => setTimeout(r, wait));
    }
    this.playing = false;
    $('play').textContent = 'Play';
  }

  // The world position of the point of object `name` where point array `array` is largest (or
  // smallest) in the frame shown.
  async extremePoint(name, array, which = 'max') {
    const files = await this.load(this.shown);
    for (const { name: n, data } of files.values()) {
      if (n !== name || !data.pointData[array]) continue;
      const s = pointScalars(data.pointData[array]);
      let best = 0;
      for (let i = 1; i < s.length; ++i) if (which === 'max' ? s[i] > s[best] : s[i] < s[best]) best = i;
      return [data.points[best * 3], data.points[best * 3 + 1], data.points[best * 3 + 2]];
    }
    throw new Error(`no object '${name}' with array '${array}' in frame ${this.shown}`);
  }
}

async function start() {
  const manifest = await fetchOk('/manifest.json', 'json');
  document.title = `${manifest.scene} — moreau`;
  $('scene').textContent = manifest.scene;
  $('directory').textContent = manifest.directory;
  if (manifest.collections.length === 0) throw new Error(`${manifest.directory} has no .pvd collection`);
  const collection = manifest.collections[0];
  const frames = readPvd(await fetchOk('/data/' + collection, 'text'), collection);
  if (frames.length === 0) throw new Error(`${collection} lists no frames yet`);
  const player = new Player(manifest, collection, frames);

  const slider = $('slider');
  slider.max = String(frames.length - 1);
  slider.addEventListener('input', () => player.show(Number(slider.value)).catch(report));
  $('play').addEventListener('click', () => player.play().catch(report));
  $('colour-by').addEventListener('change', (e) => {
    player.colourArray = e.target.value;
    player.show(player.index).catch(report);
  });
  paintColourBar($('colour-bar'));
  const render = renderRequest();
  if (render) return renderFrames(player, render);
  if (manifest.probes) {
    const probes = readProbesCsv(await fetchOk('/data/' + manifest.probes, 'text'));
    if (probes.names.length > 1) player.probes = new ProbePlot($('probes'), probes);
  }
  await player.show(0);

  window.moreauViewer = {
    frameCount: frames.length,
    get shownFrame() { return player.shown; },
    get time() { return frames[player.shown].time; },
    get colouring() { return player.colouring; },
    project: (x, y, z) => player.view.project(x, y, z),
    extremePoint: (name, array, which) => player.extremePoint(name, array, which),
    objectColour: (name) => [...player.view.parts.values()].find((v) => v.name === name)?.baseColour,
    showFrame: (index) => player.show(index),
  };
  document.body.dataset.state = 'ready';
}

// moreau render opens the page as /?render=last|all|N&width=W&height=H[&colour=ARRAY]: the page
// then draws those frames alone, W x H pixels, and posts each picture to /render/frame_NNNNNN, then /render/done (or
// /render/bad_input and /render/error with the message).
function renderRequest() {
  const params = new URLSearchParams(location.search);
  return params.has('render') ? {
    frames: params.get('render'), colour: params.get('colour') || '',
    width: Number(params.get('width') || 1280), height: Number(params.get('height') || 720),
  } : null;
}

async function post(name, body) {
  const response = await fetch(`/render/${name}`, { method: 'POST', body });
  if (!response.ok) throw new Error(`posting ${name}: ${response.status}`);
}

// The view as PNG with a caption: the scene and the time at the bottom left and, when coloured by
// an array, its colour bar with its range at the bottom right.
function captionedPicture(player) {
  const view = player.view.renderer.domElement;
  player.view.render();
  const canvas = document.createElement('canvas');
  canvas.width = view.width;
  canvas.height = view.height;
  const context = canvas.getContext('2d');
  context.drawImage(view, 0, 0);
  context.font = '14px system-ui, sans-serif';
  context.fillStyle = '#e0e0e0';
  context.textBaseline = 'bottom';
  const time = player.frames[player.shown].time;
  context.fillText(`${player.manifest.scene}   t = ${time.toPrecision(4)} s`, 12, canvas.height - 10);
  if (player.colouring) {
    const { array, min, max } = player.colouring;
    const bar = $('colour-bar');
    const right = canvas.width - 12, top = canvas.height - 22;
    const maxLabel = max.toPrecision(3);
    const x = right - context.measureText(maxLabel).width - 6 - bar.width;
    context.drawImage(bar, x, top, bar.width, 10);
    context.fillText(maxLabel, x + bar.width + 6, canvas.height - 10);
    context.textAlign = 'right';
    context.fillText(`${array}  ${min.toPrecision(3)}`, x - 6, canvas.height - 10);
  }
  return new Promise((resolve) => canvas.toBlob(resolve, 'image/png'));
}

async function renderFrames(player, request) {
  document.body.classList.add('render');
  player.view.fixSize(request.width, request.height);
  const count = player.frames.length;
  let indices;
  if (request.frames === 'all') indices = [...Array(count).keys()];
  else if (request.frames === 'last') indices = [count - 1];
  else indices = [Number(request.frames)];
  if (!indices.every((i) => Number.isInteger(i) && i >= 0 && i < count))
    return post('bad_input', `frame ${request.frames}: the run has ${count} frames, 0 to ${count - 1}`);
  await player.show(indices[0]);
  if (request.colour) {
    const choices = [...$('colour-by').options].map((o) => o.value).filter((v) => v);
    if (!choices.includes(request.colour))
      return post('bad_input', `--colour-by ${request.colour}: no object has that point array; the arrays are ${choices.join(', ')}`);
    player.colourArray = request.colour;
  }
  for (const i of indices) {
    await player.show(i);
    await post(`frame_${String(i).padStart(6, '0')}`, await captionedPicture(player));
  }
  await post('done', '');
  document.body.dataset.state = 'rendered';
}

function report(error) {
  if (renderRequest()) post('error', String(error.message || error));
  console.error(error);
  $('error').textContent = String(error.message || error);
  $('error').hidden = false;
  document.body.dataset.state = 'error';
}

start().catch(report);
