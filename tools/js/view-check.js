// Loads a viewer page (viaroad view … -o page.html) from file:// in headless Chromium and
// reports what tests/view_browser.rs asserts: the robot drawn at t = 0 and t = 1 (a render
// with the robot alone gives its mask), how much it moved, and the console's errors.
//
//   node view-check.js PAGE.html OUT_DIR      (CHROMIUM=/usr/bin/chromium by default)
//
// Prints one JSON object on stdout; writes OUT_DIR/t0.png and OUT_DIR/t1.png.
'use strict';
const fs = require('fs');
const path = require('path');
const { chromium } = require('playwright-core');

// the flags that work on this kind of machine (closed network, root, no GPU)
const FLAGS = [
  '--headless',
  '--no-sandbox',
  '--disable-gpu',
  '--disable-quic',
  '--no-first-run',
  '--disable-background-networking',
  '--disable-component-update',
  '--disable-sync',
  '--enable-unsafe-swiftshader',
  '--use-angle=swiftshader',
];

function decode(p) {
  return { width: p.width, height: p.height, rgba: Buffer.from(p.rgba, 'base64') };
}

// pixels that differ from the background colour of the robot-only render
function mask(img, bg) {
  const m = new Uint8Array(img.width * img.height);
  for (let i = 0; i < m.length; i++) {
    const o = 4 * i;
    const d = Math.abs(img.rgba[o] - bg[0]) + Math.abs(img.rgba[o + 1] - bg[1]) + Math.abs(img.rgba[o + 2] - bg[2]);
    m[i] = d > 12 ? 1 : 0;
  }
  return m;
}

function count(m) {
  let n = 0;
  for (const v of m) n += v;
  return n;
}

// pixels of the mask where the robot changes the full render (the render without it differs):
// the robot is drawn there, in front of everything or seen through a translucent wall
function drawn(full, without, m) {
  let n = 0;
  for (let i = 0; i < m.length; i++) {
    if (!m[i]) continue;
    const o = 4 * i;
    const d = Math.abs(full.rgba[o] - without.rgba[o]) + Math.abs(full.rgba[o + 1] - without.rgba[o + 1]) + Math.abs(full.rgba[o + 2] - without.rgba[o + 2]);
    if (d > 12) n++;
  }
  return n;
}

// how many pixels of mask a are not in mask b
function outside(a, b) {
  let n = 0;
  for (let i = 0; i < a.length; i++) if (a[i] && !b[i]) n++;
  return n;
}

// summed colour change of the full renders where the robot was at t = 0
function changed(a, b, m) {
  let n = 0;
  for (let i = 0; i < m.length; i++) {
    if (!m[i]) continue;
    const o = 4 * i;
    const d = Math.abs(a.rgba[o] - b.rgba[o]) + Math.abs(a.rgba[o + 1] - b.rgba[o + 1]) + Math.abs(a.rgba[o + 2] - b.rgba[o + 2]);
    if (d > 12) n++;
  }
  return n;
}

async function main() {
  const [page_file, out_dir] = process.argv.slice(2);
  fs.mkdirSync(out_dir, { recursive: true });
  const user_dir = fs.mkdtempSync(path.join(out_dir, 'profile-'));
  // a fresh, empty profile each run
  const browser = await chromium.launchPersistentContext(user_dir, {
    executablePath: process.env.CHROMIUM || '/usr/bin/chromium',
    headless: true,
    args: FLAGS,
    viewport: { width: 800, height: 600 },
    deviceScaleFactor: 1,
  });
  const errors = [];
  try {
    const page = await browser.newPage();
    page.on('console', (m) => {
      if (m.type() === 'error') errors.push(m.text());
    });
    page.on('pageerror', (e) => errors.push(String(e)));
    page.on('requestfailed', (r) => errors.push('request failed: ' + r.url()));
    await page.goto('file://' + path.resolve(page_file));
    await page.waitForFunction(() => window.viaroad && (window.viaroad.ready || window.viaroad.error), null, { timeout: 120000 });
    const state = await page.evaluate(() => ({ ready: window.viaroad.ready, error: window.viaroad.error, legend: document.getElementById('legend').innerText }));
    if (!state.ready) throw new Error('the page did not load its model: ' + state.error);
    const at = async (t, only, hide) => {
      await page.evaluate(([t, only, hide]) => {
        if (hide) window.viaroad.hide(hide);
        else window.viaroad.only(only);
        window.viaroad.setTime(t);
      }, [t, only, hide]);
      return decode(await page.evaluate(() => window.viaroad.pixels()));
    };
    const full0 = await at(0, null);
    await page.screenshot({ path: path.join(out_dir, 't0.png') });
    const full1 = await at(1, null);
    await page.screenshot({ path: path.join(out_dir, 't1.png') });
    const robot0 = await at(0, ['robot']);
    const robot1 = await at(1, ['robot']);
    const without0 = await at(0, null, ['robot']);
    const without1 = await at(1, null, ['robot']);
    // the background of the robot-only render: the corner pixel (the robot never fills it)
    const bg = [robot0.rgba[0], robot0.rgba[1], robot0.rgba[2]];
    const m0 = mask(robot0, bg);
    const m1 = mask(robot1, bg);
    await at(0, null);
    const report = {
      width: full0.width,
      height: full0.height,
      legend: state.legend,
      robot_pixels_t0: count(m0),
      robot_pixels_t1: count(m1),
      robot_drawn_t0: drawn(full0, without0, m0),
      robot_drawn_t1: drawn(full1, without1, m1),
      moved_pixels: outside(m0, m1) + outside(m1, m0),
      changed_where_robot_was: changed(full0, full1, m0),
      console_errors: errors,
    };
    process.stdout.write(JSON.stringify(report) + '\n');
  } finally {
    await browser.close();
    fs.rmSync(user_dir, { recursive: true, force: true });
  }
}

main().catch((e) => {
  console.error(String(e && e.stack ? e.stack : e));
  process.exit(1);
});
