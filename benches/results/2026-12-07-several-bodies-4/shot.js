// A still of a viewer page (viaroad view … -o page.html) at a share of its animation, in the
// headless Chromium the browser tests use (playwright-core of tools/js):
//
//   node benches/results/2026-12-07-several-bodies-4/shot.js PAGE.html SHARE OUT.png
'use strict';
const fs = require('fs');
const os = require('os');
const path = require('path');
const { chromium } = require(path.resolve(__dirname, '../../../tools/js/node_modules/playwright-core'));

const FLAGS = ['--headless', '--no-sandbox', '--disable-gpu', '--no-first-run',
  '--enable-unsafe-swiftshader', '--use-angle=swiftshader'];

async function main() {
  const [page_file, share, out] = process.argv.slice(2);
  const user_dir = fs.mkdtempSync(path.join(os.tmpdir(), 'viaroad-shot-'));
  const browser = await chromium.launchPersistentContext(user_dir, {
    executablePath: process.env.CHROMIUM || '/usr/bin/chromium',
    headless: true,
    args: FLAGS,
    viewport: { width: 800, height: 600 },
    deviceScaleFactor: 1,
  });
  try {
    const page = await browser.newPage();
    await page.goto('file://' + path.resolve(page_file));
    await page.waitForFunction(() => window.viaroad && (window.viaroad.ready || window.viaroad.error), null, { timeout: 120000 });
    await page.evaluate((f) => window.viaroad.setTime(f), Number(share));
    await page.screenshot({ path: out });
  } finally {
    await browser.close();
    fs.rmSync(user_dir, { recursive: true, force: true });
  }
}

main().catch((e) => {
  console.error(e);
  process.exit(1);
});
