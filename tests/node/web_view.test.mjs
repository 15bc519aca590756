// The bridge's built-in web view (services/bridge/web) in headless Chromium: the page must show the digital twin's
// buildings and an estimate trajectory that grows while the pipeline runs. Judged by pixels of two screenshots
// (decoded with pngjs), not by what the page says about itself: window.twinslamView only tells when to look and
// what to print on failure.
//
//   TWINSLAM_VIEW_URL=http://127.0.0.1:PORT/ [TWINSLAM_VIEW_SHOTS=DIR] node --test tests/node/web_view.test.mjs
//   (or run directly: node tests/node/web_view.test.mjs). Without TWINSLAM_VIEW_URL the test is skipped.
// Optional: TWINSLAM_CHROMIUM (default /usr/bin/chromium), TWINSLAM_VIEW_WAIT_S (wait for data, default 60),
// TWINSLAM_VIEW_GAP_S (time between the two screenshots, default 6).
import assert from 'node:assert/strict';
import { mkdirSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import test from 'node:test';
import { chromium } from 'playwright-core';
import { PNG } from 'pngjs';

const URL_ = process.env.TWINSLAM_VIEW_URL;
const SHOTS = process.env.TWINSLAM_VIEW_SHOTS;
const CHROMIUM = process.env.TWINSLAM_CHROMIUM || '/usr/bin/chromium';
const WAIT_S = Number(process.env.TWINSLAM_VIEW_WAIT_S || 60);
const GAP_S = Number(process.env.TWINSLAM_VIEW_GAP_S || 6);
const VIEWPORT = { width: 1280, height: 800 };

// Colours as drawn by the page (services/bridge/web/src/colors.js). The estimate path is an unlit fat line (5 px),
// so its inner pixels are the exact sRGB colour; the tolerance absorbs edge blending and rounding, and no other
// colour on the canvas is near it (truth is green, GNSS blue, buildings grey-blue, background near black).
const ESTIMATE = [0xff, 0x2d, 0x55];
const ESTIMATE_TOLERANCE = 40; // per channel
// Buildings are lit grey-blue (#aab4c6 under ambient + one directional light): faces vary in brightness but stay
// unsaturated with blue >= red. The background (#0d1117, luminance ~17) and the grid (luminance < 45) are darker than
// the lower bound, trajectory and landmark colours are far more saturated than the upper bound on chroma.
function isTile(r, g, b) {
  const lum = 0.2126 * r + 0.7152 * g + 0.0722 * b;
  const chroma = Math.max(r, g, b) - Math.min(r, g, b);
  return lum >= 70 && lum <= 245 && chroma <= 48 && b >= r;
}
function isEstimate(r, g, b) {
  return (
    Math.abs(r - ESTIMATE[0]) <= ESTIMATE_TOLERANCE &&
    Math.abs(g - ESTIMATE[1]) <= ESTIMATE_TOLERANCE &&
    Math.abs(b - ESTIMATE[2]) <= ESTIMATE_TOLERANCE
  );
}
const MIN_TILE_FRACTION = 0.01; // of the counted (non-overlay) pixels: a few buildings in view clear it easily
const MIN_ESTIMATE_PIXELS = 150; // screenshot 2: a path of a few metres at 5 px width
// Growth between the screenshots: at least this many more estimate pixels, and this fraction more. A path that
// stands still differs only by a few edge pixels; GAP_S seconds of driving add hundreds.
const MIN_GROWTH_PIXELS = 60;
const MIN_GROWTH_FRACTION = 0.03;

// Counts pixels outside the overlay rectangles (panel, legend: they hold colour swatches and text).
function countPixels(png, overlays) {
  const inOverlay = (x, y) => overlays.some((o) => x >= o.x && x < o.x + o.w && y >= o.y && y < o.y + o.h);
  let tile = 0;
  let estimate = 0;
  let counted = 0;
  for (let y = 0; y < png.height; ++y) {
    for (let x = 0; x < png.width; ++x) {
      if (inOverlay(x, y)) continue;
      const i = (y * png.width + x) * 4;
      const r = png.data[i];
      const g = png.data[i + 1];
      const b = png.data[i + 2];
      counted += 1;
      if (isTile(r, g, b)) tile += 1;
      else if (isEstimate(r, g, b)) estimate += 1;
    }
  }
  return { tile, estimate, counted, tileFraction: tile / Math.max(1, counted) };
}

async function overlayRects(page) {
  return page.evaluate(() =>
    [...document.querySelectorAll('[data-overlay]')].map((e) => {
      const r = e.getBoundingClientRect();
      return { x: Math.floor(r.left), y: Math.floor(r.top), w: Math.ceil(r.width) + 1, h: Math.ceil(r.height) + 1 };
    }),
  );
}

// Runs in the page: it reports tiles and an estimate path of at least two poses, and a frame has been drawn since.
function ready() {
  const view = window.twinslamView;
  if (!view || view.tiles < 1) return false;
  const hasPath = Object.values(view.poses || {}).some((p) => p.estimate >= 2);
  return hasPath && view.frames > 0 && view.renderedMessages > 0;
}

// Runs in the page: how many estimate poses it holds and how many frames it has drawn.
function progress() {
  const view = window.twinslamView;
  const poses = Object.values(view.poses || {}).reduce((n, p) => n + (p.estimate || 0), 0);
  return { poses, frames: view.frames, state: view.state };
}

// Runs in the page: poses arrived since `before` and a frame has been drawn since they did (or the run is over).
function grown(before) {
  const view = window.twinslamView;
  const poses = Object.values(view.poses || {}).reduce((n, p) => n + (p.estimate || 0), 0);
  return (poses >= before.poses + 3 && view.frames > before.frames) || view.state === 'disconnected';
}

async function shot(page, name) {
  // Two animation frames: the page renders on demand, so let a pending frame land before the capture.
  await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));
  const buffer = await page.screenshot({ type: 'png' });
  if (SHOTS) {
    mkdirSync(SHOTS, { recursive: true });
    writeFileSync(join(SHOTS, name), buffer);
  }
  return PNG.sync.read(buffer);
}

test('web view shows the twin tiles and a growing estimate trajectory', { skip: !URL_ && 'TWINSLAM_VIEW_URL not set', timeout: (2 * WAIT_S + GAP_S + 60) * 1000 }, async () => {
  const browser = await chromium.launch({
    executablePath: CHROMIUM,
    headless: true,
    // Software WebGL: CI machines have no GPU; SwiftShader must be allowed explicitly in recent Chromium.
    args: ['--use-gl=angle', '--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--ignore-gpu-blocklist'],
  });
  const log = [];
  try {
    const page = await browser.newPage({ viewport: VIEWPORT, deviceScaleFactor: 1 });
    page.on('console', (m) => log.push(`console.${m.type()}: ${m.text()}`));
    page.on('pageerror', (e) => log.push(`pageerror: ${e.message}`));
    // The bridge may not listen yet (the test starts with the run): retry the page until it is served.
    const deadline = Date.now() + WAIT_S * 1000;
    for (;;) {
      const response = await page.goto(URL_, { waitUntil: 'load' }).catch((e) => ({ status: () => e.message }));
      if (response && response.status() === 200) break;
      if (Date.now() > deadline) assert.fail(`${URL_}: no page within ${WAIT_S} s (last: ${response && response.status()})`);
      await new Promise((r) => setTimeout(r, 250));
    }
    try {
      await page.waitForFunction(ready, undefined, { timeout: WAIT_S * 1000, polling: 250 });
    } catch {
      const view = await page.evaluate(() => window.twinslamView).catch(() => null);
      assert.fail(`the page never showed tiles and a trajectory within ${WAIT_S} s: ${JSON.stringify(view)}\n${log.join('\n')}`);
    }
    const first = await shot(page, 'view-1.png');
    const overlays1 = await overlayRects(page);
    // Shot 2 once the page has received more of the path and drawn it, not after a fixed time alone: on a loaded
    // machine SwiftShader draws few frames, and a fixed gap once ended after the run (+0 px, "frames": 4).
    const atFirst = await page.evaluate(progress);
    await page.waitForTimeout(GAP_S * 1000);
    await page
      .waitForFunction(grown, atFirst, { timeout: WAIT_S * 1000, polling: 250 })
      .catch(() => log.push(`no further poses drawn within ${WAIT_S} s of the first shot (at it: ${JSON.stringify(atFirst)})`));
    const second = await shot(page, 'view-2.png');
    // The union of both shots' overlays: the panel may grow (a vehicle appears) between them.
    const overlays = [...overlays1, ...(await overlayRects(page))];
    const c1 = countPixels(first, overlays);
    const c2 = countPixels(second, overlays);
    const view = await page.evaluate(() => window.twinslamView);
    const diag = `shot 1 ${JSON.stringify(c1)}\nshot 2 ${JSON.stringify(c2)}\nview ${JSON.stringify(view)}\n${log.join('\n')}`;
    console.log(`# tiles ${c2.tile} px (${(100 * c2.tileFraction).toFixed(1)} %), estimate ${c1.estimate} -> ${c2.estimate} px`);

    assert.ok(c2.tileFraction >= MIN_TILE_FRACTION, `too few building pixels in view-2.png\n${diag}`);
    assert.ok(c2.estimate >= MIN_ESTIMATE_PIXELS, `too few estimate-trajectory pixels in view-2.png\n${diag}`);
    const growth = c2.estimate - c1.estimate;
    assert.ok(
      growth >= MIN_GROWTH_PIXELS && growth >= MIN_GROWTH_FRACTION * c1.estimate,
      `the estimate trajectory did not grow between the screenshots (+${growth} px)\n${diag}`,
    );
  } finally {
    await browser.close();
  }
});
