// The viewer in a real browser: runs a small scene, serves its output with `moreau view`, opens
// the page in headless Chromium (Debian's, driven by playwright-core) and checks what is drawn —
// the crate where free fall puts it and in its colour, the time slider moving it, the flag coloured
// by displacement from blue at its pinned edge to red at its free edge — and that the console has
// no error — and that `moreau render` draws the same picture without a display, as PNG and MP4.
// Run by ctest as external.viewer:
//   MOREAU_BINARY=build/moreau node --test viewer/test/viewer.test.mjs
import assert from 'node:assert/strict';
import { spawn, spawnSync } from 'node:child_process';
import { mkdtempSync, mkdirSync, readFileSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { dirname, join } from 'node:path';
import { after, before, test } from 'node:test';
import { fileURLToPath } from 'node:url';

import { chromium } from 'playwright-core';
import { PNG } from 'pngjs';

const here = dirname(fileURLToPath(import.meta.url));
const moreau = process.env.MOREAU_BINARY || join(here, '../../build/moreau');
const chromiumPath = process.env.CHROMIUM || '/usr/bin/chromium';
const scene = join(here, 'falling_crate_and_flag.json');
const g = 9.81, crateStart = [0.9, 1.5, 0], duration = 0.4;

let work, out, server, url, browser, page;
const consoleErrors = [];

before(async () => {
  work = mkdtempSync(join(tmpdir(), 'moreau-viewer-'));
  out = join(work, 'out');
  const run = spawnSync(moreau, ['run', scene, '--out', out, '--quiet', '--threads', '1'], { encoding: 'utf8' });
  assert.equal(run.status, 0, run.stderr);
  server = spawn(moreau, ['view', out, '--no-browser'], { stdio: ['ignore', 'pipe', 'pipe'] });
  url = await new Promise((resolve, reject) => {
    let text = '';
    server.stdout.on('data', (chunk) => {
      text += chunk;
      const match = text.match(/at (http:\/\/127\.0\.0\.1:\d+\/)/);
      if (match) resolve(match[1]);
    });
    server.on('exit', (code) => reject(new Error(`moreau view exited with ${code}`)));
  });
  // SwiftShader: WebGL in software, as on a machine without a GPU.
  browser = await chromium.launch({ executablePath: chromiumPath, args: ['--use-angle=swiftshader', '--enable-unsafe-swiftshader'] });
  page = await browser.newPage({ viewport: { width: 1000, height: 760 }, deviceScaleFactor: 1 });
  page.on('console', (m) => { if (m.type() === 'error') consoleErrors.push(`${m.text()} (${m.location().url})`); });
  page.on('pageerror', (e) => consoleErrors.push(String(e)));
  await page.goto(url);
  await page.waitForSelector('body[data-state="ready"]', { timeout: 30000 });
});

after(async () => {
  if (browser) await browser.close();
  if (server && server.exitCode === null) {
    const exited = new Promise((resolve) => server.on('exit', resolve));
    server.kill('SIGINT');
    assert.equal(await exited, 0, 'moreau view stops cleanly on Ctrl-C');
  }
  rmSync(work, { recursive: true, force: true });
});

// The view's pixels, in the page's CSS pixels (device scale 1), as RGB in [0, 1].
async function viewPixels() {
  const box = await page.locator('#view canvas').boundingBox();
  const png = PNG.sync.read(await page.screenshot({ clip: box }));
  return (x, y) => {
    const i = (Math.round(y) * png.width + Math.round(x)) * 4;
    return [png.data[i] / 255, png.data[i + 1] / 255, png.data[i + 2] / 255];
  };
}

const project = (p) => page.evaluate(([x, y, z]) => window.moreauViewer.project(x, y, z), p);

// The pixels of a (2r+1)^2 window around (x, y).
function window_(pixel, { x, y }, r = 3) {
  const out = [];
  for (let dy = -r; dy <= r; ++dy) for (let dx = -r; dx <= r; ++dx) out.push(pixel(x + dx, y + dy));
  return out;
}

// Lighting scales a colour's channels alike, so a surface is recognised by its chromaticity (each
// channel's share of the sum), which the shading leaves as it is. `near` allows 0.04 in each share:
// the sRGB curve is not exactly a power law (its linear toe), and 8-bit rounding of dark shades
// moves a share by up to ~0.02; the crate's colour differs from the background's, the floor's and
// the flag's by 0.15 or more in some share.
function chromaticity([r, g, b]) {
  const s = r + g + b || 1;
  return [r / s, g / s, b / s];
}
const near = (a, b, tolerance) => chromaticity(a).every((c, k) => Math.abs(c - chromaticity(b)[k]) <= tolerance);
// The colour map's ends: blue (0.23, 0.30, 0.75), b/r = 3.3, and red (0.71, 0.02, 0.15), r/b = 4.7.
// The thresholds sit halfway (in ratio) between those and the map's grey middle (ratios 1), and
// keep out the bluish background (b/r = 1.36) and a shaded grey floor.
const isBlue = ([r, g, b]) => b > 1.6 * r && b > 1.4 * g;
const isRed = ([r, g, b]) => r > 2.5 * g && r > 2.5 * b;

test('the page loads the run: every frame, the probes and the scene name', async () => {
  const frames = await page.evaluate(() => window.moreauViewer.frameCount);
  assert.equal(frames, 11, '0.4 s at 0.01 s per step, a frame every 4 steps, and the first');
  assert.equal(await page.locator('#scene').textContent(), 'crate_and_flag');
  assert.ok(await page.locator('#probes canvas').count() > 0, 'the probe plot is drawn');
  const legend = await page.locator('#probes').textContent();
  assert.match(legend, /crate_height\.y/);
});

test('the crate is drawn where it starts, in its colour, on the background', async () => {
  const pixel = await viewPixels();
  const crateColour = await page.evaluate(() => window.moreauViewer.objectColour('crate'));
  const centre = await project(crateStart);
  assert.ok(window_(pixel, centre, 2).every((c) => near(c, crateColour, 0.04)), 'crate colour at its centre');
  const background = [0x1d / 255, 0x21 / 255, 0x27 / 255];
  assert.ok(window_(pixel, { x: 6, y: 6 }, 2).every((c) => c.every((v, k) => Math.abs(v - background[k]) < 0.02)),
    'the background in the top left corner');
});

test('the time slider shows the last frame: the crate has fallen g t^2 / 2', async () => {
  const last = (await page.evaluate(() => window.moreauViewer.frameCount)) - 1;
  await page.locator('#slider').fill(String(last));
  await page.waitForFunction((n) => window.moreauViewer.shownFrame === n, last);
  const time = await page.evaluate(() => window.moreauViewer.time);
  assert.ok(Math.abs(time - duration) < 1e-9, `the last frame is at t = ${time} s`);
  assert.match(await page.locator('#time').textContent(), /frame 11 of 11/);
  const pixel = await viewPixels();
  const crateColour = await page.evaluate(() => window.moreauViewer.objectColour('crate'));
  const fallen = [crateStart[0], crateStart[1] - g * time * time / 2, crateStart[2]];
  assert.ok(window_(pixel, await project(fallen), 2).every((c) => near(c, crateColour, 0.04)),
    'the crate at its free-fall height');
  assert.ok(window_(pixel, await project(crateStart), 2).every((c) => !near(c, crateColour, 0.04)),
    'no crate where it started (it fell 0.78 m, more than twice its size)');
});

test('colouring by displacement: blue where the flag is pinned, red where it swings furthest', async () => {
  await page.locator('#colour-by').selectOption('displacement');
  await page.waitForFunction(() => window.moreauViewer.colouring?.array === 'displacement');
  const range = await page.evaluate(() => window.moreauViewer.colouring);
  assert.equal(range.min, 0, 'the pinned edge does not move');
  assert.ok(range.max > 0.3, `the free edge swings down (largest displacement ${range.max} m)`);
  assert.ok(await page.locator('#colour-bar-box').isVisible());
  const pixel = await viewPixels();
  const pinned = await page.evaluate(() => window.moreauViewer.extremePoint('flag', 'displacement', 'min'));
  const free = await page.evaluate(() => window.moreauViewer.extremePoint('flag', 'displacement', 'max'));
  const atPinned = window_(pixel, await project(pinned));
  const atFree = window_(pixel, await project(free));
  assert.ok(atPinned.some(isBlue) && !atPinned.some(isRed), 'blue at the pinned edge');
  assert.ok(atFree.some(isRed) && !atFree.some(isBlue), 'red at the free edge');
});

test('the console has no error', () => {
  assert.deepEqual(consoleErrors, []);
});

test('moreau view refuses a directory without frames, naming it (exit 2)', () => {
  const missing = spawnSync(moreau, ['view', join(work, 'nowhere'), '--no-browser'], { encoding: 'utf8' });
  assert.equal(missing.status, 2);
  assert.match(missing.stderr, /nowhere: no such directory/);
  const empty = join(work, 'empty');
  mkdirSync(empty);
  const noFrames = spawnSync(moreau, ['view', empty, '--no-browser'], { encoding: 'utf8' });
  assert.equal(noFrames.status, 2);
  assert.match(noFrames.stderr, /empty: no \.pvd file/);
});

test('moreau render draws the last frame as the page does: the fallen crate, as PNG', async () => {
  const box = await page.locator('#view canvas').boundingBox();
  const [width, height] = [Math.round(box.width), Math.round(box.height)];
  const file = process.env.KEEP_RENDER || join(work, 'last.png');
  const render = spawnSync(moreau, ['render', out, '--out', file, '--size', `${width}x${height}`, '--quiet'],
    { encoding: 'utf8' });
  assert.equal(render.status, 0, render.stderr);
  const png = PNG.sync.read(readFileSync(file));
  assert.deepEqual([png.width, png.height], [width, height]);
  const pixel = (x, y) => {
    const i = (Math.round(y) * png.width + Math.round(x)) * 4;
    return [png.data[i] / 255, png.data[i + 1] / 255, png.data[i + 2] / 255];
  };
  // The same camera as the page's at the same size: the page's projection locates the crate.
  await page.locator('#colour-by').selectOption('');
  const crateColour = await page.evaluate(() => window.moreauViewer.objectColour('crate'));
  const fallen = [crateStart[0], crateStart[1] - g * duration * duration / 2, crateStart[2]];
  assert.ok(window_(pixel, await project(fallen), 2).every((c) => near(c, crateColour, 0.04)), 'the crate, fallen');
  assert.ok(window_(pixel, await project(crateStart), 2).every((c) => !near(c, crateColour, 0.04)));
});

test('moreau render --video encodes every frame into an MP4', () => {
  const video = join(work, 'run.mp4');
  const render = spawnSync(moreau, ['render', out, '--video', video, '--size', '320x240', '--quiet'], { encoding: 'utf8' });
  assert.equal(render.status, 0, render.stderr);
  const probe = spawnSync('ffprobe', ['-v', 'error', '-count_frames', '-show_entries', 'stream=width,height,nb_read_frames',
    '-of', 'csv=p=0', video], { encoding: 'utf8' });
  assert.equal(probe.stdout.trim(), '320,240,11');
});

test('moreau render refuses a frame the run does not have (exit 2)', () => {
  const render = spawnSync(moreau, ['render', out, '--frame', '11'], { encoding: 'utf8' });
  assert.equal(render.status, 2);
  assert.match(render.stderr, /frame 11: the run has 11 frames, 0 to 10/);
  const colour = spawnSync(moreau, ['render', out, '--colour-by', 'temperature'], { encoding: 'utf8' });
  assert.equal(colour.status, 2);
  assert.match(colour.stderr, /--colour-by temperature: no object has that point array; the arrays are .*displacement/);
});
