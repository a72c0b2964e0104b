// Browser tests of the viewer page of `floorgrid serve`: Debian's chromium (headless, driven by
// playwright-core from web/node_modules; no browser download) opens a running server's page and
// checks what the operator relies on against the server's own API answers.
//
//   FLOORGRID_URL=http://127.0.0.1:PORT/ SCREENSHOT_DIR=DIR node --test web/test/viewer.test.mjs
//
// web/test/run_browser_tests.sh starts a server on a small simulated dataset and runs this.
// The tests change the server's state (a manual pair, a refit) and put both back at the end.
// Skipped (not failed) when chromium, playwright-core or FLOORGRID_URL is missing.
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

async function call(method, route, body) {
  const response = await fetch(new URL(route, baseUrl), {
    method, headers: body ? { 'Content-Type': 'application/json' } : {},
    body: body ? JSON.stringify(body) : undefined,
  });
  const answer = await response.json();
  assert.ok(response.ok, `${method} ${route}: ${response.status} ${JSON.stringify(answer)}`);
  return answer;
}
const mapPoints = (from, points) => call('POST', '/api/map', { from, points });
const fixed3 = (v) => { const t = v.toFixed(3); return /^-0\.0*$/.test(t) ? t.slice(1) : t; };
const near = (a, b, tolerance, what) =>
  assert.ok(Math.abs(a - b) <= tolerance, `${what}: ${a} vs ${b} (tolerance ${tolerance})`);

describe('floorgrid viewer page', { skip }, () => {
  let context;
  let page;
  let profile;
  let info;
  const requests = [];
  const errors = [];
  const addedPairs = new Set();  // deleted again in after(), should a test fail midway

  before(async () => {
    fs.mkdirSync(screenshotDir, { recursive: true });
    info = await call('GET', '/api/info');
    profile = fs.mkdtempSync(path.join(os.tmpdir(), 'floorgrid-viewer-chromium-'));
    const args = ['--disable-gpu', '--no-first-run', '--disable-dev-shm-usage',
                  '--disable-background-networking', '--disable-component-update', '--disable-sync'];
    if (process.getuid && process.getuid() === 0) args.push('--no-sandbox');
    context = await chromium.launchPersistentContext(profile, {
      executablePath: chromiumPath, headless: true, args, viewport: { width: 1400, height: 900 },
    });
    page = await context.newPage();
    page.on('request', (request) => requests.push(request.url()));
    page.on('console', (message) => { if (message.type() === 'error') errors.push(message.text()); });
    page.on('pageerror', (error) => errors.push(String(error)));
  });

  after(async () => {
    try {
      for (const id of addedPairs) await fetch(new URL(`/api/pairs/${id}`, baseUrl), { method: 'DELETE' });
      if (info && (await call('GET', '/api/info')).model !== info.model) await call('POST', '/api/fit', { model: info.model });
    } catch (error) {
      console.log(`could not put the server back: ${error.message}`);
    }
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
  /// What Leaflet makes of a click at client (cx, cy) on a map: containerPointToLatLng of the
  /// container point (Leaflet's own, which divides by the container's CSS scale).
  async function latLngAt(which, [cx, cy]) {
    return page.evaluate(([w, x, y]) => {
      const map = window.floorgridViewer[w];
      const ll = map.containerPointToLatLng(map.mouseEventToContainerPoint({ clientX: x, clientY: y }));
      return { x: ll.lng, y: ll.lat };
    }, [which, cx, cy]);
  }

  it('loads with both maps placed over their bounds, nothing leaving 127.0.0.1', async () => {
    await page.goto(baseUrl, { waitUntil: 'load', timeout: 20000 });
    await page.evaluate(() => window.floorgridViewer.ready);
    assert.equal(await page.textContent('#dataset-name'), info.dataset);
    assert.equal(await page.textContent('#model-name'), info.model);
    for (const which of ['plan', 'grid']) {
      const placed = await page.evaluate((w) => {
        const map = window.floorgridViewer[w];
        const img = document.querySelector(`#${w}-map img.fg-base-image`);
        const box = map.getContainer().getBoundingClientRect();
        const rect = img.getBoundingClientRect();
        const [[xmin, ymin], [xmax, ymax]] = window.floorgridViewer.info[w].bounds;
        const topLeft = map.latLngToContainerPoint([ymax, xmin]);
        const bottomRight = map.latLngToContainerPoint([ymin, xmax]);
        return {
          natural: [img.naturalWidth, img.naturalHeight],
          expected: [topLeft.x, topLeft.y, bottomRight.x, bottomRight.y],
          drawn: [rect.left - box.left, rect.top - box.top, rect.right - box.left, rect.bottom - box.top],
        };
      }, which);
      assert.deepEqual(placed.natural, [info[which].width, info[which].height], `${which} image decoded`);
      placed.expected.forEach((v, i) => near(placed.drawn[i], v, 2, `${which} image corner ${i}`));
    }
    const style = await page.evaluate(() =>
      getComputedStyle(document.querySelector('#plan-map img.fg-base-image')).imageRendering);
    assert.equal(style, 'pixelated');
    const outside = requests.filter((u) => !u.startsWith('data:') && new URL(u).hostname !== '127.0.0.1');
    assert.deepEqual(outside, [], 'requests leaving 127.0.0.1');
    assert.deepEqual(errors, [], 'console or page errors');
    await shot('viewer-loaded.png');
  });

  it('maps a floorplan click to the gridmap exactly as the API does, and turns it', async () => {
    const at = await pointInImage('plan', 0.42, 0.47);
    const clicked = await latLngAt('plan', at);
    await page.mouse.click(at[0], at[1]);
    await page.waitForFunction(() => window.floorgridViewer.state.goal?.grid, null, { timeout: 5000 });
    const s = await state(() => {
      const { click, mapped } = window.floorgridViewer.state;
      return { click: { x: click.latlng.lng, y: click.latlng.lat }, mapped: { x: mapped.latlng.lng, y: mapped.latlng.lat } };
    });
    near(s.click.x, clicked.x, METRE_TOLERANCE, 'clicked x');
    near(s.click.y, clicked.y, METRE_TOLERANCE, 'clicked y');
    const [expected] = (await mapPoints('plan', [[clicked.x, clicked.y]])).points;
    assert.ok(expected.x !== null, `the test point maps (${expected.flag})`);
    near(s.mapped.x, expected.x, METRE_TOLERANCE, 'grid marker x');
    near(s.mapped.y, expected.y, METRE_TOLERANCE, 'grid marker y');

    const screen = await page.evaluate(() => {
      const { grid, state: st } = window.floorgridViewer;
      const box = grid.getContainer().getBoundingClientRect();
      const dot = document.querySelector('#grid-map .fg-goal-mapped .fg-dot').getBoundingClientRect();
      const p = grid.latLngToContainerPoint(st.mapped.latlng);
      return { expected: [p.x, p.y], drawn: [dot.left + dot.width / 2 - box.left, dot.top + dot.height / 2 - box.top] };
    });
    near(screen.drawn[0], screen.expected[0], 1, 'grid marker on screen x');
    near(screen.drawn[1], screen.expected[1], 1, 'grid marker on screen y');
    assert.equal(await page.textContent('#goal-grid-x'), fixed3(expected.x));
    assert.equal(await page.textContent('#goal-grid-y'), fixed3(expected.y));
    const yaml = await page.textContent('#goal-yaml');
    assert.ok(yaml.includes(`position: {x: ${fixed3(expected.x)}, y: ${fixed3(expected.y)}, z: 0.0}`), yaml);
    assert.match(yaml, /frame_id: map/);
    assert.match(await page.textContent('#goal-command'), /^ros2 topic pub --once \/goal_pose geometry_msgs\/msg\/PoseStamped "\{/);

    // Drag the heading handle from the arrow's tip (east) to 40 px east, 50 px north of the point.
    const thetaBefore = await page.textContent('#goal-grid-theta');
    const handle = await page.locator('#plan-map .fg-handle').boundingBox();
    const hx = handle.x + handle.width / 2;
    const hy = handle.y + handle.height / 2;
    await page.mouse.move(hx, hy);
    await page.mouse.down();
    for (let i = 1; i <= 10; i++) await page.mouse.move(hx, hy - 5 * i);
    await page.mouse.up();
    await page.waitForFunction((before_) => document.querySelector('#goal-grid-theta').textContent !== before_
      && !window.floorgridViewer.goal.running, thetaBefore, { timeout: 5000 });
    const planTheta = Number(await page.textContent('#goal-plan-theta'));
    near(planTheta, Math.atan2(50, 40), 0.05, 'plan heading after the drag');
    const goal = await state(() => window.floorgridViewer.state.goal);
    const [turned] = (await mapPoints('plan', [[clicked.x, clicked.y, goal.plan.theta]])).points;
    const wrap = (a) => Math.atan2(Math.sin(a), Math.cos(a));
    near(wrap(goal.grid.theta - turned.theta), 0, 1e-9, 'grid heading as the API maps it');
    assert.equal(await page.textContent('#goal-grid-theta'), fixed3(wrap(turned.theta)));
    const half = wrap(turned.theta) / 2;
    const orientation = `orientation: {x: 0.0, y: 0.0, z: ${Math.sin(half).toFixed(4)}, w: ${Math.cos(half).toFixed(4)}}`;
    assert.ok((await page.textContent('#goal-yaml')).includes(orientation), `YAML has ${orientation}`);
    await shot('viewer-goal-heading.png');

    await page.click('button[data-copy="goal-yaml"]');
    await page.waitForFunction(() => /copied|selected/.test(document.querySelector('#status').textContent),
                               null, { timeout: 3000 });
  });

  it('warns about a goal the mapping extrapolates', async () => {
    const at = await pointInImage('plan', 0.01, 0.01);
    const clicked = await latLngAt('plan', at);
    const [expected] = (await mapPoints('plan', [[clicked.x, clicked.y]])).points;
    assert.ok(expected.extrapolated || expected.x === null, `the plan's corner is outside the pairs (${expected.flag})`);
    await page.mouse.click(at[0], at[1]);
    await page.waitForFunction(() => !document.querySelector('#goal-warning').hidden
      && !window.floorgridViewer.goal.running, null, { timeout: 5000 });
    assert.match(await page.textContent('#goal-warning'), expected.x === null ? /does not map/ : /Extrapolated/);
    assert.match(await page.textContent('#goal-flag'), new RegExp(expected.flag));
    if (expected.x !== null) {
      assert.equal(await page.locator('#grid-map .fg-goal-mapped.fg-extrapolated').count(), 1, 'marked on the gridmap');
    }
  });

  it('draws the robot where the API maps its pose', async () => {
    const { base } = await call('GET', '/api/pairs?base=1');
    assert.ok(Array.isArray(base) && base.length > 0, 'the alignment has pairs');
    const [, , gx, gy] = base[Math.floor(base.length / 2)];
    const { sequence } = await call('POST', '/api/robot_pose', { x: gx, y: gy, theta: 0.5 });
    await page.waitForFunction((seq) => window.floorgridViewer.state.robot?.sequence === seq, sequence, { timeout: 3000 });
    const robot = await state(() => {
      const r = window.floorgridViewer.state.robot;
      return { grid: [r.grid.lng, r.grid.lat], plan: r.plan && [r.plan.lng, r.plan.lat] };
    });
    const [expected] = (await mapPoints('grid', [[gx, gy, 0.5]])).points;
    near(robot.grid[0], gx, METRE_TOLERANCE, 'robot grid x');
    near(robot.grid[1], gy, METRE_TOLERANCE, 'robot grid y');
    assert.ok(robot.plan, 'the robot is drawn on the floorplan');
    near(robot.plan[0], expected.x, METRE_TOLERANCE, 'robot plan x');
    near(robot.plan[1], expected.y, METRE_TOLERANCE, 'robot plan y');
    assert.equal(await page.locator('#plan-map .fg-robot').count(), 1);
    assert.equal(await page.locator('#grid-map .fg-robot').count(), 1);
  });

  it('adds, deletes and refits on a manual pair, and shows pairs and the wall overlay', async () => {
    const startModel = info.model;
    const addPair = async () => {
      const before_ = (await call('GET', '/api/pairs')).pairs.map((p) => p.id);
      await page.click('#add-pair');
      assert.match(await page.textContent('#status'), /floorplan/);
      const planAt = await pointInImage('plan', 0.25, 0.3);
      const gridAt = await pointInImage('grid', 0.6, 0.35);
      const plan = await latLngAt('plan', planAt);
      await page.mouse.click(planAt[0], planAt[1]);
      assert.match(await page.textContent('#status'), /gridmap/);
      const grid = await latLngAt('grid', gridAt);
      await page.mouse.click(gridAt[0], gridAt[1]);
      let added;
      for (let i = 0; i < 50 && !added; i++) {
        added = (await call('GET', '/api/pairs')).pairs.find((p) => !before_.includes(p.id));
        if (!added) await new Promise((r) => setTimeout(r, 100));
      }
      assert.ok(added, 'POST /api/pairs happened');
      addedPairs.add(added.id);
      near(added.plan[0], plan.x, METRE_TOLERANCE, 'pair plan x');
      near(added.plan[1], plan.y, METRE_TOLERANCE, 'pair plan y');
      near(added.grid[0], grid.x, METRE_TOLERANCE, 'pair grid x');
      near(added.grid[1], grid.y, METRE_TOLERANCE, 'pair grid y');
      await page.waitForSelector(`#pairs-list tr[data-pair-id="${added.id}"]`, { timeout: 3000 });
      return added.id;
    };
    const first = await addPair();
    await page.click(`#pairs-list tr[data-pair-id="${first}"] button.delete-pair`);
    await page.waitForSelector(`#pairs-list tr[data-pair-id="${first}"]`, { state: 'detached', timeout: 3000 });
    assert.ok(!(await call('GET', '/api/pairs')).pairs.some((p) => p.id === first), 'pair deleted on the server');
    addedPairs.delete(first);
    const second = await addPair();

    const models = info.models || [info.model];
    const model = models.includes('gt-affine') && startModel !== 'gt-affine' ? 'gt-affine'
      : models.find((m) => m !== startModel);
    assert.ok(model, `another model to refit (${models.join(', ')})`);
    await page.selectOption('#model-select', model);
    await page.click('#refit');
    await page.waitForFunction((m) => document.querySelector('#model-name').textContent === m
      && !document.querySelector('#refit').disabled, model, { timeout: 60000 });
    const fresh = await call('GET', '/api/info');
    assert.equal(fresh.model, model);
    assert.match(await page.textContent('#fit-result'), new RegExp(`${model}.*pairs.*rms.*s`));

    await page.check('#base-pairs-on');
    await page.waitForFunction(() => window.floorgridViewer.state.baseDrawn > 0, null, { timeout: 10000 });
    assert.ok(await page.locator('#plan-map canvas').count() >= 1, 'pairs drawn on a canvas');
    const manual = (await call('GET', '/api/pairs')).pairs.length;
    assert.equal(await page.locator('#plan-map .fg-pair').count(), manual, 'the manual pairs on the floorplan');
    assert.equal(await page.locator('#grid-map .fg-pair').count(), manual, 'the manual pairs on the gridmap');
    assert.equal(await page.locator(`#plan-map .fg-pair:text-is("${second}")`).count(), 1, 'numbered by id');
    if (fresh.layers?.overlay) {
      await page.check('#overlay-on');
      const size = await page.waitForFunction((v) => {
        const img = [...document.querySelectorAll('#grid-map img')].find((i) => i.src.includes(`/api/overlay.png?v=${v}`));
        return img && img.complete && img.naturalWidth > 0 && [img.naturalWidth, img.naturalHeight];
      }, fresh.model_version, { timeout: 10000 });
      assert.deepEqual(await size.jsonValue(), [fresh.grid.width, fresh.grid.height]);
    } else {
      console.log('the server has no wall overlay (info.layers.overlay false): not checked');
    }
    await shot('viewer-pairs-overlay.png');

    // Put the server back as it was.
    await page.click(`#pairs-list tr[data-pair-id="${second}"] button.delete-pair`);
    await page.waitForSelector(`#pairs-list tr[data-pair-id="${second}"]`, { state: 'detached', timeout: 3000 });
    addedPairs.delete(second);
    await page.selectOption('#model-select', startModel);
    await page.click('#refit');
    await page.waitForFunction((m) => document.querySelector('#model-name').textContent === m
      && !document.querySelector('#refit').disabled, startModel, { timeout: 60000 });
    await page.uncheck('#base-pairs-on');
  });

  it('shows the heat map with its legend', async (t) => {
    const fresh = await call('GET', '/api/info');
    if (!fresh.layers?.heatmap) {
      t.skip('the server has no heat map (info.layers.heatmap false)');
      return;
    }
    const { layers } = await call('GET', '/api/heatmap');
    assert.ok(layers.length > 0, 'the server lists heat map layers');
    await page.check('#heatmap-on');
    for (const layer of layers) {
      await page.selectOption('#heatmap-kind', layer.kind);
      const size = await page.waitForFunction((url) => {
        const img = [...document.querySelectorAll('#plan-map img')].find((i) => i.src.endsWith(url));
        return img && img.complete && img.naturalWidth > 0 && [img.naturalWidth, img.naturalHeight];
      }, layer.url, { timeout: 20000 });
      assert.deepEqual(await size.jsonValue(), [fresh.plan.width, fresh.plan.height], `${layer.kind} heat map`);
      const ticks = await page.locator('.fg-legend-ticks span').allTextContents();
      assert.equal(ticks.length, 3);
      assert.equal(ticks[0], '0');
      assert.ok(ticks[2].includes(layer.clip_m.toFixed(2)), `legend clip ${ticks[2]} vs ${layer.clip_m}`);
    }
    await shot('viewer-heatmap.png');
  });

  it('links the views: the gridmap follows the floorplan, with no echo back', async () => {
    const set = await page.evaluate(() => {
      const { plan } = window.floorgridViewer;
      const c = plan.getCenter();
      const target = [c.lat + 1.25, c.lng - 2.5];
      plan.setView(target, plan.getZoom() + 1, { animate: false });
      return { x: target[1], y: target[0], zoom: plan.getZoom() };
    });
    const [centre, east, north] = (await mapPoints('plan', [[set.x, set.y], [set.x + 1, set.y], [set.x, set.y + 1]])).points;
    const scale = (Math.hypot(east.x - centre.x, east.y - centre.y) + Math.hypot(north.x - centre.x, north.y - centre.y)) / 2;
    await page.waitForFunction(([x, y]) => {
      const c = window.floorgridViewer.grid.getCenter();
      return Math.abs(c.lng - x) < 1e-6 && Math.abs(c.lat - y) < 1e-6;
    }, [centre.x, centre.y], { timeout: 5000 });
    const gridZoom = await page.evaluate(() => window.floorgridViewer.grid.getZoom());
    near(gridZoom, set.zoom - Math.log2(scale), 0.3, 'gridmap zoom offset by the local scale');
    await page.waitForTimeout(500);
    const planNow = await page.evaluate(() => {
      const { plan } = window.floorgridViewer;
      return { x: plan.getCenter().lng, y: plan.getCenter().lat, zoom: plan.getZoom() };
    });
    near(planNow.x, set.x, METRE_TOLERANCE, 'the floorplan stays where it was put (x)');
    near(planNow.y, set.y, METRE_TOLERANCE, 'the floorplan stays where it was put (y)');
    assert.equal(planNow.zoom, set.zoom);
  });

  it('stacks the maps on a narrow screen', async () => {
    await page.setViewportSize({ width: 720, height: 1000 });
    await page.waitForTimeout(300);
    const boxes = await page.evaluate(() => ['plan-panel', 'grid-panel'].map((id) => {
      const r = document.getElementById(id).getBoundingClientRect();
      return { top: r.top, bottom: r.bottom, width: r.width };
    }));
    assert.ok(boxes[1].top >= boxes[0].bottom, `gridmap below the floorplan (${JSON.stringify(boxes)})`);
    assert.ok(boxes[0].width > 600, 'the floorplan takes the width');
    await shot('viewer-narrow.png');
    await page.setViewportSize({ width: 1400, height: 900 });
  });

  it('logged no console or page error and stayed on 127.0.0.1 throughout', () => {
    assert.deepEqual(errors, []);
    const outside = requests.filter((u) => !u.startsWith('data:') && new URL(u).hostname !== '127.0.0.1');
    assert.deepEqual(outside, []);
  });
});
