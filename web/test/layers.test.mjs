// Browser tests of the viewer's zones and waypoints (issue 33): a zone drawn by clicks on the
// floorplan appears mapped on the gridmap, and its downloaded nav2 mask has the gridmap's
// resolution, origin and size; a named waypoint placed on the floorplan appears on the gridmap,
// and the downloaded nav2 waypoints YAML holds the pose /api/map gives that point; a zones
// GeoJSON file loads; a bad one shows the server's own message. Checked against the server's
// API answers, not against the page's own numbers.
//
//   FLOORGRID_URL=http://127.0.0.1:PORT/ SCREENSHOT_DIR=DIR node --test web/test/layers.test.mjs
//
// web/test/run_browser_tests.sh starts a server and runs this after viewer.test.mjs. The routes
// it calls keep no state on the server. Skipped (not failed) when chromium, playwright-core or
// FLOORGRID_URL is missing.
import assert from 'node:assert/strict';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { after, before, describe, it } from 'node:test';

const baseUrl = process.env.FLOORGRID_URL;
const screenshotDir = process.env.SCREENSHOT_DIR || path.join(os.tmpdir(), 'floorgrid-viewer-screenshots');
const chromiumPath = [process.env.CHROMIUM, '/usr/lib/chromium/chromium', '/usr/bin/chromium']
  .find((candidate) => candidate && fs.existsSync(candidate));

let chromium = null;
try {
  ({ chromium } = await import('playwright-core'));
} catch {
  chromium = null;
}
const skip = !baseUrl ? 'FLOORGRID_URL is not set (web/test/run_browser_tests.sh starts a server and sets it)'
  : !chromiumPath ? 'no chromium at /usr/lib/chromium/chromium or /usr/bin/chromium (scripts/install-deps.sh installs it)'
  : !chromium ? 'web/node_modules/playwright-core is missing (scripts/install-deps.sh runs npm ci in web/)'
  : false;
if (skip) console.log(`SKIP: ${skip}`);

const METRE_TOLERANCE = 1e-6;

/// The server's answer to a request, and its status.
async function send(method, route, body) {
  const response = await fetch(new URL(route, baseUrl), {
    method, headers: body ? { 'Content-Type': 'application/json' } : {},
    body: body ? JSON.stringify(body) : undefined,
  });
  return { status: response.status, answer: await response.json() };
}
async function call(method, route, body) {
  const { status, answer } = await send(method, route, body);
  assert.ok(status >= 200 && status < 300, `${method} ${route}: ${status} ${JSON.stringify(answer)}`);
  return answer;
}
const mapPoints = (from, points) => call('POST', '/api/map', { from, points });
const near = (a, b, tolerance, what) =>
  assert.ok(Math.abs(a - b) <= tolerance, `${what}: ${a} vs ${b} (tolerance ${tolerance})`);
const polygon = (name, ring, properties = {}) => ({
  type: 'Feature', properties: { name, ...properties },
  geometry: { type: 'Polygon', coordinates: [[...ring, ring[0]]] },
});
/// A square of side `side` metres about (x, y), counterclockwise.
const square = (x, y, side) => [[x - side / 2, y - side / 2], [x + side / 2, y - side / 2],
                                [x + side / 2, y + side / 2], [x - side / 2, y + side / 2]];

describe('floorgrid viewer: zones and waypoints', { skip }, () => {
  let context;
  let page;
  let profile;
  let info;
  const errors = [];

  before(async () => {
    fs.mkdirSync(screenshotDir, { recursive: true });
    info = await call('GET', '/api/info');
    profile = fs.mkdtempSync(path.join(os.tmpdir(), 'floorgrid-layers-chromium-'));
    const args = ['--disable-gpu', '--no-first-run', '--disable-dev-shm-usage',
                  '--disable-background-networking', '--disable-component-update', '--disable-sync'];
    if (process.getuid && process.getuid() === 0) args.push('--no-sandbox');
    context = await chromium.launchPersistentContext(profile, {
      executablePath: chromiumPath, headless: true, args, viewport: { width: 1400, height: 900 },
      acceptDownloads: true,
    });
    page = await context.newPage();
    page.on('console', (message) => { if (message.type() === 'error') errors.push(message.text()); });
    page.on('pageerror', (error) => errors.push(String(error)));
    await page.goto(baseUrl, { waitUntil: 'load', timeout: 20000 });
    await page.evaluate(() => window.floorgridViewer.ready);
  });

  after(async () => {
    await context?.close();
    if (profile) fs.rmSync(profile, { recursive: true, force: true });
  });

  const shot = (name) => page.screenshot({ path: path.join(screenshotDir, name) });
  const state = (expression) => page.evaluate(expression);
  /// Client coordinates of a point at fractions (fx, fy) of a map's image box.
  async function pointInImage(which, fx, fy) {
    return page.evaluate(([w, fx_, fy_]) => {
      const rect = document.querySelector(`#${w}-map img.fg-base-image`).getBoundingClientRect();
      return [Math.round(rect.left + fx_ * rect.width), Math.round(rect.top + fy_ * rect.height)];
    }, [which, fx, fy]);
  }
  /// The map point under client (cx, cy), as Leaflet and the view convert it.
  async function pointAt(which, [cx, cy]) {
    return page.evaluate(([w, x, y]) => {
      const hook = window.floorgridViewer;
      const map = hook[w];
      const ll = map.containerPointToLatLng(map.mouseEventToContainerPoint({ clientX: x, clientY: y }));
      const p = hook[`${w}View`].fromLatLng(ll);
      return [p.x, p.y];
    }, [which, cx, cy]);
  }
  /// Saves what a download link gives: its suggested name and bytes.
  async function download(selector) {
    const [file] = await Promise.all([page.waitForEvent('download', { timeout: 5000 }), page.click(selector)]);
    return { name: file.suggestedFilename(), bytes: fs.readFileSync(await file.path()) };
  }

  it('draws a zone by clicks: mapped on the gridmap, its nav2 mask on the gridmap\'s grid', async () => {
    await page.fill('#zone-name', 'loading bay');
    await page.click('#draw-zone');
    assert.match(await page.textContent('#status'), /Draw zone/);
    const corners = [[0.30, 0.30], [0.45, 0.30], [0.45, 0.50], [0.30, 0.50]];
    const clicks = [];
    for (const [fx, fy] of corners) clicks.push(await pointInImage('plan', fx, fy));
    const ring = [];
    for (const at of clicks) {
      ring.push(await pointAt('plan', at));
      await page.mouse.click(at[0], at[1]);
    }
    assert.equal(await page.isDisabled('#close-zone'), false, 'Close zone enabled after 3 corners');
    await page.mouse.click(clicks[0][0], clicks[0][1]);  // the first corner again closes it
    await page.waitForFunction(() => window.floorgridViewer.state.zones?.count === 1, null, { timeout: 10000 });
    await page.evaluate(() => window.floorgridViewer.zones.idle);

    // The server's own answer for the zone under the clicks.
    const expected = await call('POST', '/api/zones', {
      kind: 'keepout', margin_sigma: 2, geojson: { type: 'FeatureCollection', features: [polygon('loading bay', ring)] } });
    const [zone] = expected.zones;
    assert.ok(zone.cells > 0 && zone.cells >= zone.cells_inside, `the zone covers cells (${zone.cells})`);
    const shown = await state(() => window.floorgridViewer.state.zones);
    assert.equal(shown.cells, expected.mask.cells, 'the mask cells the page shows are the API\'s');
    const row = await page.textContent('#zones-list tr[data-zone-index="0"]');
    assert.ok(row.includes('loading bay') && row.includes(zone.cells.toLocaleString('en')), row);
    // The plan polygon at the clicked corners, the mapped boundary where the API puts it.
    const drawn = await page.evaluate(() => {
      const { zones, gridView } = window.floorgridViewer;
      const [planPolygon] = zones.layers.plan.getLayers();
      const [gridPolygon] = zones.layers.grid.getLayers();
      const flat = (lls) => lls.flat(3).map((ll) => [ll.lng, ll.lat]);
      return { plan: flat(planPolygon.getLatLngs()), grid: flat(gridPolygon.getLatLngs()).map(([lng, lat]) => {
        const p = gridView.fromLatLng(window.L.latLng(lat, lng));
        return [p.x, p.y];
      }) };
    });
    ring.forEach(([x, y], i) => {
      near(drawn.plan[i][0], x, METRE_TOLERANCE, `plan corner ${i} x`);
      near(drawn.plan[i][1], y, METRE_TOLERANCE, `plan corner ${i} y`);
    });
    assert.equal(drawn.grid.length, zone.rings[0].length, 'the mapped ring\'s points');
    const corner = (await mapPoints('plan', [ring[0]])).points[0];
    near(drawn.grid[0][0], corner.x, METRE_TOLERANCE, 'mapped boundary starts at the corner /api/map maps (x)');
    near(drawn.grid[0][1], corner.y, METRE_TOLERANCE, 'mapped boundary starts at the corner /api/map maps (y)');
    assert.equal(await page.locator('#grid-map path.fg-zone-mapped').count(), 1);
    // The mask's picture on the gridmap: tinted at the zone's mapped centre, clear far off it.
    const centre = ring.reduce(([sx, sy], [x, y]) => [sx + x / 4, sy + y / 4], [0, 0]);
    const [c] = (await mapPoints('plan', [centre])).points;
    const { resolution, bounds: [[xmin], [, ymax]] } = info.grid;
    const cell = [Math.floor((c.x - xmin) / resolution), Math.floor((ymax - c.y) / resolution)];
    const alpha = await page.evaluate(async ([[i, j], url]) => {
      const img = new Image();
      img.src = url;
      await img.decode();
      const canvas = document.createElement('canvas');
      canvas.width = img.naturalWidth;
      canvas.height = img.naturalHeight;
      const context_ = canvas.getContext('2d');
      context_.drawImage(img, 0, 0);
      const at = (u, v) => context_.getImageData(u, v, 1, 1).data[3];
      return { inside: at(i, j), corner: at(0, 0), size: [img.naturalWidth, img.naturalHeight],
               onMap: window.floorgridViewer.zones.mask.layer !== null };
    }, [cell, expected.mask.png]);
    assert.deepEqual(alpha.size, [info.grid.width, info.grid.height], 'the mask picture is the gridmap\'s size');
    assert.ok(alpha.inside > 0, 'the mask is tinted at the zone\'s centre');
    assert.equal(alpha.corner, 0, 'the mask is clear at the gridmap\'s corner');
    assert.ok(alpha.onMap, 'the mask picture is on the gridmap');
    await shot('viewer-zone-drawn.png');

    // The nav2 files: the mask YAML with the gridmap's resolution and origin, the PGM its size.
    await page.click('#download-mask');
    await page.waitForFunction(() => document.querySelectorAll('#mask-downloads a').length === 4, null, { timeout: 10000 });
    const names = await page.locator('#mask-downloads a').allTextContents();
    assert.deepEqual(names, ['keepout.yaml', 'keepout.pgm', 'keepout_filter_info.yaml', 'keepout_zones_gridmap.geojson']);
    const yaml = (await download('#mask-downloads a[download="keepout.yaml"]')).bytes.toString();
    assert.match(yaml, /^image: keepout\.pgm$/m);
    assert.match(yaml, /^mode: trinary$/m);
    assert.equal(Number(/^resolution: (.*)$/m.exec(yaml)[1]), info.grid.resolution, yaml);
    const origin = /^origin: \[(.*)\]$/m.exec(yaml)[1].split(',').map(Number);
    origin.forEach((v, i) => near(v, info.grid.origin[i], 1e-9, `mask origin ${i}`));
    const pgm = (await download('#mask-downloads a[download="keepout.pgm"]')).bytes;
    const header = `P5\n${info.grid.width} ${info.grid.height}\n255\n`;
    assert.equal(pgm.subarray(0, header.length).toString('latin1'), header, 'the PGM is the gridmap\'s size');
    assert.equal(pgm.length, header.length + info.grid.width * info.grid.height);
    const black = pgm.subarray(header.length).filter((v) => v === 0).length;
    assert.equal(black, expected.mask.cells, 'the PGM\'s black cells are the zone\'s mask cells');
    const params = (await download('#mask-downloads a[download="keepout_filter_info.yaml"]')).bytes.toString();
    assert.match(params, /type: 0/);
    assert.match(params, /yaml_filename: .*keepout\.yaml/);
  });

  it('places a named waypoint: on the gridmap with its std_m, the nav2 YAML holds /api/map\'s pose', async () => {
    await page.fill('#waypoint-name', 'dock');
    await page.fill('#waypoint-heading', '90');
    await page.click('#place-waypoint');
    const at = await pointInImage('plan', 0.62, 0.40);
    const point = await pointAt('plan', at);
    await page.mouse.click(at[0], at[1]);
    await page.waitForFunction(() => window.floorgridViewer.state.waypoints?.length === 1, null, { timeout: 10000 });
    const [expected] = (await mapPoints('plan', [[point[0], point[1], Math.PI / 2]])).points;
    assert.ok(expected.x !== null, `the waypoint maps (${expected.flag})`);
    const [shown] = await state(() => window.floorgridViewer.state.waypoints);
    assert.equal(shown.name, 'dock');
    near(shown.x, expected.x, METRE_TOLERANCE, 'waypoint grid x');
    near(shown.y, expected.y, METRE_TOLERANCE, 'waypoint grid y');
    near(shown.theta, expected.theta, 1e-6, 'waypoint grid heading');
    near(shown.std_m, expected.std_m, 1e-9, 'waypoint std_m');
    // Drawn where toLatLng puts the API's grid point, its circle of radius std_m.
    const drawn = await page.evaluate(() => {
      const { waypoints, gridView } = window.floorgridViewer;
      const layers = waypoints.layers.grid.getLayers();
      const circle = layers.find((l) => l instanceof window.L.Circle);
      const marker = layers.find((l) => l instanceof window.L.Marker);
      const p = gridView.fromLatLng(marker.getLatLng());
      return { x: p.x, y: p.y, radius: circle ? circle.getRadius() : null };
    });
    near(drawn.x, expected.x, METRE_TOLERANCE, 'marker x');
    near(drawn.y, expected.y, METRE_TOLERANCE, 'marker y');
    near(drawn.radius, expected.std_m, 1e-12, 'std_m circle radius');

    const yaml = (await download('#waypoint-downloads a[download="waypoints.yaml"]')).bytes.toString();
    assert.match(yaml, /# dock: std_m/);
    assert.ok(yaml.includes(`position: {x: ${expected.x.toFixed(4)}, y: ${expected.y.toFixed(4)}, z: 0.0}`), yaml);
    const z = Number(/orientation: \{x: 0\.0, y: 0\.0, z: (-?[0-9.]+), w: (-?[0-9.]+)\}/.exec(yaml)[1]);
    near(Math.abs(z), Math.abs(Math.sin(expected.theta / 2)), 1e-6, 'the YAML\'s quaternion z is the mapped heading\'s');
    assert.match(yaml, /frame_id: "map"/);
    const geojson = JSON.parse((await download('#waypoint-downloads a[download="waypoints_gridmap.geojson"]')).bytes.toString());
    const [feature] = geojson.features;
    near(feature.geometry.coordinates[0], expected.x, 1e-6, 'gridmap GeoJSON x');
    near(feature.geometry.coordinates[1], expected.y, 1e-6, 'gridmap GeoJSON y');

    // A second one at the plan's corner, far from the pairs: marked extrapolated on the gridmap.
    await page.click('#place-waypoint');
    const corner = await pointInImage('plan', 0.01, 0.01);
    const cornerPoint = await pointAt('plan', corner);
    await page.mouse.click(corner[0], corner[1]);
    await page.waitForFunction(() => window.floorgridViewer.state.waypoints?.length === 2, null, { timeout: 10000 });
    const [far] = (await mapPoints('plan', [cornerPoint])).points;
    assert.ok(far.extrapolated, `the plan's corner is extrapolated (${far.flag})`);
    if (far.x !== null) {
      assert.equal(await page.locator('#grid-map .fg-waypoint-mapped.fg-extrapolated').count(), 1, 'marked extrapolated');
    }
    assert.match(await page.textContent('#waypoints-list tr[data-waypoint-index="1"]'), new RegExp(far.flag));
    await shot('viewer-waypoints.png');
  });

  it('loads a zones GeoJSON file: its zones join the drawn one on both maps', async () => {
    const [[x0, y0], [x1, y1]] = info.plan.bounds;
    const a = [x0 + 0.6 * (x1 - x0), y0 + 0.6 * (y1 - y0)];
    const b = [x0 + 0.75 * (x1 - x0), y0 + 0.4 * (y1 - y0)];
    const file = { type: 'FeatureCollection', features: [polygon('printer', square(...a, 2)), polygon('lab', square(...b, 3))] };
    await page.setInputFiles('#zones-file', {
      name: 'zones.geojson', mimeType: 'application/geo+json', buffer: Buffer.from(JSON.stringify(file)) });
    await page.waitForFunction(() => window.floorgridViewer.state.zones?.count === 3, null, { timeout: 10000 });
    await page.evaluate(() => window.floorgridViewer.zones.idle);
    const names = await page.locator('#zones-list td.name').allTextContents();
    assert.deepEqual(names, ['loading bay', 'printer', 'lab']);
    assert.equal(await page.locator('#grid-map path.fg-zone-mapped').count(), 3, 'three zones mapped on the gridmap');
    assert.equal(await page.locator('#plan-map path.fg-zone').count(), 3, 'three zones on the floorplan');
    const alone = await call('POST', '/api/zones', { geojson: file });
    const listed = await page.locator('#zones-list tr[data-zone-index="2"] td.num').first().textContent();
    assert.equal(listed, alone.zones[1].cells.toLocaleString('en'), 'the loaded zone\'s cells as the API maps it');
    assert.equal(await page.isHidden('#zones-error'), true);
    await shot('viewer-zones-loaded.png');
  });

  it('shows the server\'s message for a bad zones file, and keeps the zones it had', async () => {
    const [[x0, y0], [x1, y1]] = info.plan.bounds;
    const [cx, cy] = [(x0 + x1) / 2, (y0 + y1) / 2];
    // A bow tie: its edges cross at the centre.
    const text = JSON.stringify({ type: 'FeatureCollection', features: [
      polygon('bow tie', [[cx - 1, cy - 1], [cx + 1, cy + 1], [cx + 1, cy - 1], [cx - 1, cy + 1]])] });
    const { status, answer } = await send('POST', '/api/zones', { geojson: text, file: 'bad.geojson' });
    assert.equal(status, 400);
    assert.match(answer.error, /bad\.geojson.*self-intersecting/);
    await page.setInputFiles('#zones-file', { name: 'bad.geojson', mimeType: 'application/geo+json', buffer: Buffer.from(text) });
    await page.waitForSelector('#zones-error:not([hidden])', { timeout: 10000 });
    const shown = await page.textContent('#zones-error');
    assert.ok(shown.includes(answer.error), `the page shows the server's message: ${shown}`);
    assert.ok((await page.textContent('#status')).includes(answer.error), 'and in the status line');
    assert.equal(await state(() => window.floorgridViewer.state.zones.count), 3, 'the zones before are kept');

    // Not JSON at all, and degrees instead of metres: the server's words again.
    await page.setInputFiles('#zones-file', { name: 'notes.geojson', mimeType: 'application/geo+json', buffer: Buffer.from('{"type": ') });
    await page.waitForFunction(() => document.querySelector('#zones-error').textContent.includes('notes.geojson'), null, { timeout: 10000 });
    assert.match(await page.textContent('#zones-error'), /not JSON/);
    const degrees = JSON.stringify({ type: 'FeatureCollection', features: [polygon('wgs84', square(13.4, 52.5, 0.0001))] });
    await page.setInputFiles('#zones-file', { name: 'wgs84.geojson', mimeType: 'application/geo+json', buffer: Buffer.from(degrees) });
    await page.waitForFunction(() => document.querySelector('#zones-error').textContent.includes('wgs84.geojson'), null, { timeout: 10000 });
    assert.match(await page.textContent('#zones-error'), /degrees/);
    await shot('viewer-zones-bad-file.png');
  });

  it('logged no console or page error but the three refused files\' 400s', () => {
    const refused = errors.filter((e) => /status of 400/.test(e));
    assert.equal(refused.length, 3, 'the bow tie, the text that is not JSON, the degrees');
    assert.deepEqual(errors.filter((e) => !refused.includes(e)), []);
  });
});
