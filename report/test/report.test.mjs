// Browser test of report.html: Debian's chromium (headless, driven by playwright-core; no
// browser download) opens the report from file:// and checks that nothing leaves the file,
// nothing logs an error, the charts were drawn and every section is there; it saves screenshots.
//
//   node report/test/report.test.mjs REPORT.html SCREENSHOT_DIR
//
// Exit 0: passed; 1: failed; 77: skipped (no chromium or no playwright-core: run
// scripts/install-deps.sh).
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { pathToFileURL } from 'node:url';

const SKIP = 77;
const [reportPath, screenshotDir] = process.argv.slice(2);
if (!reportPath || !screenshotDir) {
  console.error('usage: node report.test.mjs REPORT.html SCREENSHOT_DIR');
  process.exit(1);
}
const chromiumPath = process.env.CHROMIUM || '/usr/bin/chromium';
if (!fs.existsSync(chromiumPath)) {
  console.log(`SKIP: ${chromiumPath} is missing (scripts/install-deps.sh installs Debian's chromium)`);
  process.exit(SKIP);
}
let chromium;
try {
  ({ chromium } = await import('playwright-core'));
} catch {
  console.log('SKIP: report/node_modules/playwright-core is missing (run scripts/install-deps.sh)');
  process.exit(SKIP);
}

const failures = [];
const check = (ok, what) => {
  console.log(`${ok ? 'ok  ' : 'FAIL'} ${what}`);
  if (!ok) failures.push(what);
};

const profile = fs.mkdtempSync(path.join(os.tmpdir(), 'floorgrid-report-chromium-'));
const args = ['--headless', '--disable-gpu', '--no-first-run', '--disable-background-networking',
              '--disable-component-update', '--disable-sync', '--disable-dev-shm-usage'];
if (process.getuid && process.getuid() === 0) args.push('--no-sandbox');
const context = await chromium.launchPersistentContext(profile, {
  executablePath: chromiumPath, headless: true, args, viewport: { width: 1280, height: 900 },
});
try {
  const page = await context.newPage();
  const requests = [];
  const errors = [];
  page.on('request', (request) => requests.push(request.url()));
  page.on('console', (message) => {
    if (message.type() === 'error') errors.push(message.text());
  });
  page.on('pageerror', (error) => errors.push(String(error)));
  const url = pathToFileURL(path.resolve(reportPath)).href;
  await page.goto(url, { waitUntil: 'load', timeout: 20000 });

  const outside = requests.filter((u) => !u.startsWith('file://') && !u.startsWith('data:'));
  check(outside.length === 0, `no request leaves the file (${outside.join(', ') || 'none'})`);
  check(errors.length === 0, `no console error (${errors.join(' | ') || 'none'})`);

  for (const id of ['summary', 'models', 'histograms', 'pairs', 'localization', 'heatmaps',
                    'overlays', 'back-and-forth', 'timings', 'dataset']) {
    check(await page.locator(`section#${id}`).count() === 1, `section #${id} present`);
  }
  for (const id of ['chart-histogram', 'chart-cumulative', 'chart-localization',
                  'chart-scan-pairs']) {
    const size = await page.evaluate((chartId) => {
      const canvas = document.querySelector(`#${chartId} canvas`);
      return canvas ? [canvas.width, canvas.height] : [0, 0];
    }, id);
    check(size[0] > 0 && size[1] > 0, `chart #${id} drawn on a canvas (${size[0]} x ${size[1]})`);
  }
  const images = await page.evaluate(() => Array.from(document.images).map((img) => ({
    src: img.src.slice(0, 22), width: img.naturalWidth })));
  check(images.length > 0 && images.every((i) => i.src.startsWith('data:image/png;base64')
                                                 && i.width > 0),
        `${images.length} pictures, every one a decoded data: URL`);

  fs.mkdirSync(screenshotDir, { recursive: true });
  await page.screenshot({ path: path.join(screenshotDir, 'report-top.png') });
  await page.screenshot({ path: path.join(screenshotDir, 'report-full.png'), fullPage: true });
  // The sticky header would cover the sections' own screenshots.
  await page.evaluate(() => { document.querySelector('header').style.position = 'static'; });
  for (const id of ['summary', 'models', 'histograms', 'pairs', 'localization', 'overlays']) {
    await page.locator(`section#${id}`).screenshot({
      path: path.join(screenshotDir, `report-${id}.png`) });
  }
  console.log(`screenshots in ${screenshotDir}`);
} finally {
  await context.close();
  fs.rmSync(profile, { recursive: true, force: true });
}
console.log(`${failures.length === 0 ? 'passed' : 'FAILED'}: ${failures.length} failed`);
process.exit(failures.length === 0 ? 0 : 1);
