// Browser tests of the viewer page of `floorgrid serve`: Debian's chromium (headless, driven by
// playwright-core from web/node_modules; no browser download) opens a running server's page and
// checks what the operator relies on against the server's own API answers. The gridmap is drawn
// turned like the plan (on by default on the office dataset): its markers' LatLngs are in the
// turned display frame, so the tests read them through the page's own conversion
// (floorgridViewer.gridView.fromLatLng / toLatLng) and check that conversion against the API.
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
const PIXEL_TOLERANCE = 1;

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
const wrap = (a) => Math.atan2(Math.sin(a), Math.cos(a));
const degrees = (radians) => (radians * 180) / Math.PI;
/// The point {x, y} turned by `angle` about `centre`, computed here, not by the page.
const rotate = (p, centre, angle) => ({
  x: centre.x + Math.cos(angle) * (p.x - centre.x) - Math.sin(angle) * (p.y - centre.y),
  y: centre.y + Math.sin(angle) * (p.x - centre.x) + Math.cos(angle) * (p.y - centre.y),
});
const boxCentre = ([[xmin, ymin], [xmax, ymax]]) => ({ x: (xmin + xmax) / 2, y: (ymin + ymax) / 2 });
/// The turn the page should measure: the plan's x axis in the grid frame at the plan's centre.
async function expectedTurn(plan) {
  const c = boxCentre(plan.bounds);
  const [p0, px, py] = (await mapPoints('plan', [[c.x, c.y], [c.x + 1, c.y], [c.x, c.y + 1]])).points;
  const det = (px.x - p0.x) * (py.y - p0.y) - (py.x - p0.x) * (px.y - p0.y);
  return { alpha: Math.atan2(px.y - p0.y, px.x - p0.x), det };
}
/// The canvas size of a picture of width x height pixels turned by alpha, at 2x.
const turnedSize = (width, height, alpha) => {
  const c = Math.abs(Math.cos(alpha));
  const s = Math.abs(Math.sin(alpha));
  return [Math.ceil(2 * (width * c + height * s)), Math.ceil(2 * (width * s + height * c))];
};
/// The angle (degrees) of the first SVG rotate() inside an element's HTML.
const svgRotation = (html) => Number(/rotate\((-?[0-9.e+-]+)/.exec(html)[1]);
const sameAngleDegrees = (a, b, tolerance, what) =>
  near(((a - b) % 360 + 540) % 360 - 180, 0, tolerance, `${what}: ${a}° vs ${b}°`);

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
  /// The map point under a click at client (cx, cy): Leaflet's containerPointToLatLng of the
  /// container point (Leaflet's own, which divides by the container's CSS scale), then the view's
  /// fromLatLng (the gridmap may be turned). `latlng` is the LatLng itself.
  async function pointAt(which, [cx, cy]) {
    return page.evaluate(([w, x, y]) => {
      const hook = window.floorgridViewer;
      const map = hook[w];
      const ll = map.containerPointToLatLng(map.mouseEventToContainerPoint({ clientX: x, clientY: y }));
      const p = hook[`${w}View`].fromLatLng(ll);
      return { x: p.x, y: p.y, latlng: [ll.lat, ll.lng] };
    }, [which, cx, cy]);
  }
  /// Where the page draws grid points [x, y]: their LatLngs and container (on-screen) points.
  async function gridDrawn(points) {
    return page.evaluate((pts) => pts.map(([x, y]) => {
      const { grid, gridView } = window.floorgridViewer;
      const ll = gridView.toLatLng({ x, y });
      const c = grid.latLngToContainerPoint(ll);
      return { lat: ll.lat, lng: ll.lng, screen: [c.x, c.y] };
    }), points);
  }
  /// Centre of the first element matching `selector`, in its map's container (CSS px).
  async function centreOf(which, selector) {
    return page.evaluate(([w, sel]) => {
      const box = window.floorgridViewer[w].getContainer().getBoundingClientRect();
      const r = document.querySelector(`#${w}-map ${sel}`).getBoundingClientRect();
      return [r.left + r.width / 2 - box.left, r.top + r.height / 2 - box.top];
    }, [which, selector]);
  }
  /// Requests that left the page's server (its own data: and blob: URLs are local).
  const outsideRequests = () => requests.filter((u) => !u.startsWith('data:')
    && !u.startsWith(`blob:${new URL(baseUrl).origin}/`) && new URL(u).hostname !== '127.0.0.1');

  it('loads with both maps placed over their bounds, nothing leaving 127.0.0.1', async () => {
    await page.goto(baseUrl, { waitUntil: 'load', timeout: 20000 });
    await page.evaluate(() => window.floorgridViewer.ready);
    assert.equal(await page.textContent('#dataset-name'), info.dataset);
    assert.equal(await page.textContent('#model-name'), info.model);
    // The floorplan's picture over its bounds; the gridmap's, turned, over the turned bounds' box.
    for (const which of ['plan', 'grid']) {
      const placed = await page.evaluate((w) => {
        const map = window.floorgridViewer[w];
        const img = document.querySelector(`#${w}-map img.fg-base-image`);
        const box = map.getContainer().getBoundingClientRect();
        const rect = img.getBoundingClientRect();
        const bounds = window.floorgridViewer[`${w}View`].pictureBounds();
        const topLeft = map.latLngToContainerPoint(bounds.getNorthWest());
        const bottomRight = map.latLngToContainerPoint(bounds.getSouthEast());
        return {
          natural: [img.naturalWidth, img.naturalHeight],
          expected: [topLeft.x, topLeft.y, bottomRight.x, bottomRight.y],
          drawn: [rect.left - box.left, rect.top - box.top, rect.right - box.left, rect.bottom - box.top],
          turn: window.floorgridViewer[`${w}View`].turn,
        };
      }, which);
      const { width, height } = info[which];
      assert.deepEqual(placed.natural, placed.turn === 0 ? [width, height] : turnedSize(width, height, placed.turn),
                       `${which} image decoded (turned by ${placed.turn})`);
      placed.expected.forEach((v, i) => near(placed.drawn[i], v, 2, `${which} image corner ${i}`));
    }
    const style = await page.evaluate(() =>
      getComputedStyle(document.querySelector('#plan-map img.fg-base-image')).imageRendering);
    assert.equal(style, 'pixelated');
    assert.deepEqual(outsideRequests(), [], 'requests leaving 127.0.0.1');
    assert.deepEqual(errors, [], 'console or page errors');
    await shot('viewer-loaded.png');
  });

  it('turns the gridmap like the plan: the angle the API maps the plan\'s x axis to, on by default', async () => {
    const { alpha, det } = await expectedTurn(info.plan);
    assert.ok(det > 0, 'the mapping does not mirror');
    // On by default past 5 degrees (the office: about 128); a map nearly the plan's way up (fr079:
    // about 2) starts unturned, and is turned here so that the tests below run turned.
    const byDefault = Math.abs(alpha) > (5 * Math.PI) / 180;
    const initially = await page.evaluate(() => document.querySelector('#turn-like-plan').checked);
    assert.equal(initially, byDefault, `on by default iff turned over 5 degrees (${degrees(alpha)}°)`);
    if (!byDefault) {
      await page.click('#turn-like-plan');
      await page.waitForFunction(() => window.floorgridViewer.gridView.turn !== 0);
    }
    const page_ = await page.evaluate(() => {
      const { turn, gridView, planView } = window.floorgridViewer;
      const box = document.querySelector('#turn-like-plan');
      return { alpha: turn.alpha, applied: gridView.turn, planTurn: planView.turn, checked: box.checked,
               disabled: box.disabled, title: box.closest('label').title };
    });
    near(page_.alpha, alpha, 1e-9, 'the measured turn');
    assert.equal(page_.applied, page_.alpha, 'the gridmap is drawn turned');
    assert.equal(page_.planTurn, 0, 'the floorplan is not turned');
    assert.ok(page_.checked && !page_.disabled, '"turned like the plan" on');
    assert.match(page_.title, /turned by/);

    // The conversion: grid points turned by -alpha about the grid picture's centre, and back.
    const centre = boxCentre(info.grid.bounds);
    const samples = [[0, 0], [centre.x, centre.y], [...info.grid.bounds[0]], [...info.grid.bounds[1]], [3.25, -7.5]];
    const drawn = await gridDrawn(samples);
    samples.forEach(([x, y], i) => {
      const d = rotate({ x, y }, centre, -alpha);
      near(drawn[i].lng, d.x, 1e-9, `toLatLng lng of ${x}, ${y}`);
      near(drawn[i].lat, d.y, 1e-9, `toLatLng lat of ${x}, ${y}`);
    });
    const back = await page.evaluate((lls) => lls.map(([lat, lng]) =>
      window.floorgridViewer.gridView.fromLatLng(window.L.latLng(lat, lng))), drawn.map((d) => [d.lat, d.lng]));
    samples.forEach(([x, y], i) => {
      near(back[i].x, x, 1e-9, 'fromLatLng(toLatLng) x');
      near(back[i].y, y, 1e-9, 'fromLatLng(toLatLng) y');
    });

    // The point: the plan's x axis, mapped to the grid, is drawn horizontal (pointing right).
    const c = boxCentre(info.plan.bounds);
    const axis = (await mapPoints('plan', [[c.x - 4, c.y], [c.x + 4, c.y]])).points.map((p) => [p.x, p.y]);
    const [west, east] = await gridDrawn(axis);
    assert.ok(east.screen[0] - west.screen[0] > 0, 'the plan\'s x axis points right on the gridmap');
    near(east.screen[1], west.screen[1], 0.05 * (east.screen[0] - west.screen[0]),
         'the plan\'s x axis is horizontal on the gridmap (5% of its length)');

    // The turned picture lies over the turned box of the grid's bounds.
    const pictureBox = await page.evaluate(() => {
      const b = window.floorgridViewer.gridView.image.layer.getBounds();
      return [[b.getWest(), b.getSouth()], [b.getEast(), b.getNorth()]];
    });
    const [[xmin, ymin], [xmax, ymax]] = info.grid.bounds;
    const corners = [[xmin, ymin], [xmax, ymin], [xmax, ymax], [xmin, ymax]]
      .map(([x, y]) => rotate({ x, y }, centre, -alpha));
    const expectedBox = [[Math.min(...corners.map((p) => p.x)), Math.min(...corners.map((p) => p.y))],
                         [Math.max(...corners.map((p) => p.x)), Math.max(...corners.map((p) => p.y))]];
    pictureBox.flat().forEach((v, i) => near(v, expectedBox.flat()[i], 1e-9, `turned picture box ${i}`));
    assert.equal(await page.locator('#grid-map .fg-axes').count(), 1, 'the grid frame\'s axes key');
  });

  it('maps a floorplan click to the gridmap exactly as the API does, and turns it', async () => {
    const at = await pointInImage('plan', 0.42, 0.47);
    const clicked = await pointAt('plan', at);
    await page.mouse.click(at[0], at[1]);
    await page.waitForFunction(() => window.floorgridViewer.state.goal?.grid, null, { timeout: 5000 });
    const s = await state(() => {
      const { state: { click, mapped }, gridView } = window.floorgridViewer;
      return { click: { x: click.latlng.lng, y: click.latlng.lat }, mapped: gridView.fromLatLng(mapped.latlng),
               point: mapped.point };
    });
    near(s.click.x, clicked.x, METRE_TOLERANCE, 'clicked x');
    near(s.click.y, clicked.y, METRE_TOLERANCE, 'clicked y');
    const [expected] = (await mapPoints('plan', [[clicked.x, clicked.y]])).points;
    assert.ok(expected.x !== null, `the test point maps (${expected.flag})`);
    near(s.mapped.x, expected.x, METRE_TOLERANCE, 'grid marker x (fromLatLng of its LatLng)');
    near(s.mapped.y, expected.y, METRE_TOLERANCE, 'grid marker y (fromLatLng of its LatLng)');
    assert.deepEqual(s.point, { x: expected.x, y: expected.y }, 'the grid point kept as the API answered');

    // On screen where the page draws the API's grid point (and the conversion is checked above).
    const [{ screen: expectedScreen }] = await gridDrawn([[expected.x, expected.y]]);
    const drawnScreen = await centreOf('grid', '.fg-goal-mapped .fg-dot');
    near(drawnScreen[0], expectedScreen[0], PIXEL_TOLERANCE, 'grid marker on screen x');
    near(drawnScreen[1], expectedScreen[1], PIXEL_TOLERANCE, 'grid marker on screen y');
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
    near(wrap(goal.grid.theta - turned.theta), 0, 1e-9, 'grid heading as the API maps it');
    // The gridmap's arrow is drawn at the grid heading less the turn (SVG turns clockwise).
    const gridTurn = await state(() => window.floorgridViewer.gridView.turn);
    const arrow = svgRotation(await page.innerHTML('#grid-map .fg-goal-mapped'));
    sameAngleDegrees(arrow, -degrees(turned.theta - gridTurn), 1e-6, 'the mapped arrow\'s turn on screen');
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
    const clicked = await pointAt('plan', at);
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

  it('sends the API the grid point under a click on the turned gridmap, and its heading in the grid frame', async () => {
    const alpha = await state(() => window.floorgridViewer.gridView.turn);
    assert.notEqual(alpha, 0, 'the gridmap is turned');
    const isGoalRequest = (r) => r.url().endsWith('/api/map') && r.method() === 'POST'
      && r.postDataJSON().from === 'grid' && r.postDataJSON().points[0].length === 3;
    const at = await pointInImage('grid', 0.5, 0.45);
    const under = await pointAt('grid', at);
    const sent = page.waitForRequest(isGoalRequest, { timeout: 5000 });
    await page.mouse.click(at[0], at[1]);
    const body = (await sent).postDataJSON();
    near(body.points[0][0], under.x, METRE_TOLERANCE, 'grid x sent to the API');
    near(body.points[0][1], under.y, METRE_TOLERANCE, 'grid y sent to the API');
    await page.waitForFunction(() => window.floorgridViewer.state.goal?.grid
      && document.querySelector('#goal-source').textContent.includes('gridmap')
      && !window.floorgridViewer.goal.running, null, { timeout: 5000 });
    const goal = await state(() => window.floorgridViewer.state.goal);
    assert.deepEqual([goal.grid.x, goal.grid.y], body.points[0].slice(0, 2), 'the goal panel\'s grid pose is what was sent');
    assert.equal(await page.textContent('#goal-grid-x'), fixed3(under.x));
    assert.equal(await page.textContent('#goal-grid-y'), fixed3(under.y));
    const [onPlan] = (await mapPoints('grid', [[under.x, under.y]])).points;
    assert.equal(await page.textContent('#goal-plan-x'), fixed3(onPlan.x));
    assert.equal(await page.textContent('#goal-plan-y'), fixed3(onPlan.y));
    // The clicked dot under the mouse.
    const box = await page.evaluate(() => {
      const r = window.floorgridViewer.grid.getContainer().getBoundingClientRect();
      return [r.left, r.top];
    });
    const dot = await centreOf('grid', '.fg-goal-clicked .fg-dot');
    near(dot[0], at[0] - box[0], PIXEL_TOLERANCE, 'clicked dot on screen x');
    near(dot[1], at[1] - box[1], PIXEL_TOLERANCE, 'clicked dot on screen y');

    // Drag the handle to 40 px right, 50 px up of the dot: that heading on screen is
    // atan2(50, 40) + alpha in the grid's frame.
    const handle = await page.locator('#grid-map .fg-handle').boundingBox();
    const [hx, hy] = [handle.x + handle.width / 2, handle.y + handle.height / 2];
    const [tx, ty] = [at[0] + 40, at[1] - 50];
    await page.mouse.move(hx, hy);
    await page.mouse.down();
    for (let i = 1; i <= 10; i++) await page.mouse.move(hx + ((tx - hx) * i) / 10, hy + ((ty - hy) * i) / 10);
    const heading = page.waitForRequest((r) => isGoalRequest(r) && r.postDataJSON().points[0][2] !== 0, { timeout: 5000 });
    await page.mouse.up();
    await heading;
    await page.waitForFunction(() => !window.floorgridViewer.goal.running, null, { timeout: 5000 });
    const turned = await state(() => window.floorgridViewer.state.goal.grid.theta);
    near(wrap(turned - (Math.atan2(50, 40) + alpha)), 0, 0.05, 'grid heading after the drag');
    assert.equal(await page.textContent('#goal-grid-theta'), fixed3(wrap(turned)));
    const arrow = svgRotation(await page.innerHTML('#grid-map .fg-goal-clicked'));
    sameAngleDegrees(arrow, -degrees(turned - alpha), 1e-6, 'the clicked arrow drawn at the grid heading less the turn');
    const [planPose] = (await mapPoints('grid', [[under.x, under.y, turned]])).points;
    assert.equal(await page.textContent('#goal-plan-theta'), fixed3(wrap(planPose.theta)));
    await shot('viewer-grid-goal.png');
  });

  it('draws the robot where the API maps its pose', async () => {
    const { base } = await call('GET', '/api/pairs?base=1');
    assert.ok(Array.isArray(base) && base.length > 0, 'the alignment has pairs');
    const [, , gx, gy] = base[Math.floor(base.length / 2)];
    const { sequence } = await call('POST', '/api/robot_pose', { x: gx, y: gy, theta: 0.5 });
    await page.waitForFunction((seq) => window.floorgridViewer.state.robot?.sequence === seq, sequence, { timeout: 3000 });
    const robot = await state(() => {
      const { robot: feed, gridView } = window.floorgridViewer;
      const marker = feed.markers.grid.getLatLng();
      const plan = feed.markers.plan?.getLatLng();
      return { latlng: [marker.lng, marker.lat], grid: gridView.fromLatLng(marker), plan: plan && [plan.lng, plan.lat],
               turn: gridView.turn };
    });
    const [drawn] = await gridDrawn([[gx, gy]]);
    near(robot.latlng[0], drawn.lng, METRE_TOLERANCE, 'robot marker at toLatLng(pose) (lng)');
    near(robot.latlng[1], drawn.lat, METRE_TOLERANCE, 'robot marker at toLatLng(pose) (lat)');
    near(robot.grid.x, gx, METRE_TOLERANCE, 'robot grid x (fromLatLng of the marker)');
    near(robot.grid.y, gy, METRE_TOLERANCE, 'robot grid y (fromLatLng of the marker)');
    const dot = await centreOf('grid', '.fg-robot .fg-dot');
    near(dot[0], drawn.screen[0], PIXEL_TOLERANCE, 'robot on screen x');
    near(dot[1], drawn.screen[1], PIXEL_TOLERANCE, 'robot on screen y');
    sameAngleDegrees(svgRotation(await page.innerHTML('#grid-map .fg-robot')), -degrees(0.5 - robot.turn), 1e-6,
                     'the robot drawn at its heading less the turn');
    const [expected] = (await mapPoints('grid', [[gx, gy, 0.5]])).points;
    assert.ok(robot.plan, 'the robot is drawn on the floorplan');
    near(robot.plan[0], expected.x, METRE_TOLERANCE, 'robot plan x');
    near(robot.plan[1], expected.y, METRE_TOLERANCE, 'robot plan y');
    sameAngleDegrees(svgRotation(await page.innerHTML('#plan-map .fg-robot')), -degrees(expected.theta), 1e-6,
                     'the robot drawn on the floorplan at its mapped heading');
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
      const plan = await pointAt('plan', planAt);
      await page.mouse.click(planAt[0], planAt[1]);
      assert.match(await page.textContent('#status'), /gridmap/);
      const grid = await pointAt('grid', gridAt);
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
    // The turn measured again with the new model, and the gridmap drawn with it.
    const refitTurn = await state(() => ({ alpha: window.floorgridViewer.turn.alpha, applied: window.floorgridViewer.gridView.turn }));
    near(refitTurn.alpha, (await expectedTurn(fresh.plan)).alpha, 1e-9, `the turn under ${model}`);
    assert.equal(refitTurn.applied, refitTurn.alpha);

    await page.check('#base-pairs-on');
    await page.waitForFunction(() => window.floorgridViewer.state.baseDrawn > 0, null, { timeout: 10000 });
    assert.ok(await page.locator('#plan-map canvas').count() >= 1, 'pairs drawn on a canvas');
    const manual = (await call('GET', '/api/pairs')).pairs.length;
    assert.equal(await page.locator('#plan-map .fg-pair').count(), manual, 'the manual pairs on the floorplan');
    assert.equal(await page.locator('#grid-map .fg-pair').count(), manual, 'the manual pairs on the gridmap');
    assert.equal(await page.locator(`#plan-map .fg-pair:text-is("${second}")`).count(), 1, 'numbered by id');
    // The manual pair and the alignment's pairs drawn at toLatLng of their grid points.
    const secondPair = (await call('GET', '/api/pairs')).pairs.find((p) => p.id === second);
    const [pairDrawn] = await gridDrawn([secondPair.grid]);
    const pairScreen = await page.evaluate((id) => {
      const box = window.floorgridViewer.grid.getContainer().getBoundingClientRect();
      const el = [...document.querySelectorAll('#grid-map .fg-pair')].find((e) => e.textContent === String(id));
      const r = el.getBoundingClientRect();
      return [r.left + r.width / 2 - box.left, r.top + r.height / 2 - box.top];
    }, second);
    near(pairScreen[0], pairDrawn.screen[0], PIXEL_TOLERANCE, 'manual pair on the gridmap, screen x');
    near(pairScreen[1], pairDrawn.screen[1], PIXEL_TOLERANCE, 'manual pair on the gridmap, screen y');
    const { base } = await call('GET', '/api/pairs?base=1');
    const dots = await state(() => window.floorgridViewer.pairs.baseLayers.grid.getLayers()
      .filter((_, i) => i % 1000 === 0).map((m) => window.floorgridViewer.gridView.fromLatLng(m.getLatLng())));
    dots.forEach((d, k) => {
      near(d.x, base[k * 1000][2], METRE_TOLERANCE, `alignment pair ${k * 1000} grid x`);
      near(d.y, base[k * 1000][3], METRE_TOLERANCE, `alignment pair ${k * 1000} grid y`);
    });
    if (fresh.layers?.overlay) {
      await page.check('#overlay-on');
      await page.waitForFunction((v) => window.floorgridViewer.overlay.picture?.url.endsWith(`v=${v}`), fresh.model_version);
      await page.evaluate(() => window.floorgridViewer.overlay.picture.drawn);
      const placed = await page.evaluate(() => {
        const { grid, gridView, overlay } = window.floorgridViewer;
        const img = overlay.picture.layer.getElement();
        const box = grid.getContainer().getBoundingClientRect();
        const rect = img.getBoundingClientRect();
        const bounds = gridView.pictureBounds();
        const topLeft = grid.latLngToContainerPoint(bounds.getNorthWest());
        const bottomRight = grid.latLngToContainerPoint(bounds.getSouthEast());
        return {
          natural: [img.naturalWidth, img.naturalHeight], turn: gridView.turn,
          expected: [topLeft.x, topLeft.y, bottomRight.x, bottomRight.y],
          drawn: [rect.left - box.left, rect.top - box.top, rect.right - box.left, rect.bottom - box.top],
        };
      });
      assert.deepEqual(placed.natural, turnedSize(fresh.grid.width, fresh.grid.height, placed.turn), 'the turned overlay');
      placed.expected.forEach((v, i) => near(placed.drawn[i], v, 2, `wall overlay corner ${i}`));
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

  it('draws the turned pictures cell for cell: the plan\'s walls line up on the gridmap', async (t) => {
    const fresh = await call('GET', '/api/info');
    if (!fresh.layers?.overlay) {
      t.skip('the server has no wall overlay (info.layers.overlay false)');
      return;
    }
    await page.check('#overlay-on');
    await page.waitForFunction((v) => window.floorgridViewer.overlay.picture?.url.endsWith(`v=${v}`), fresh.model_version);
    await page.evaluate(() => Promise.all([window.floorgridViewer.overlay.picture.drawn, window.floorgridViewer.gridView.loaded]));
    // Plan wall points (the alignment's pairs' plan points) mapped to the grid by the API.
    const { base } = await call('GET', '/api/pairs?base=1');
    const planPoints = base.filter((_, i) => i % Math.ceil(base.length / 60) === 0).map((row) => [row[0], row[1]]);
    const onGrid = (await mapPoints('plan', planPoints)).points.filter((p) => p.x !== null);
    // Each point's cell: the raw PNGs' pixel, and the turned picture's pixel at the cell's
    // centre as the page draws it (its LatLng through toLatLng, in the picture's bounds).
    const { resolution, bounds: [[xmin], [, ymax]] } = fresh.grid;
    const cells = onGrid.map((p) => [Math.floor((p.x - xmin) / resolution), Math.floor((ymax - p.y) / resolution)]);
    const sampled = await page.evaluate(async ([cellList, res, x0, y1, version]) => {
      const { gridView, overlay } = window.floorgridViewer;
      const pixels = (img) => {
        const canvas = document.createElement('canvas');
        canvas.width = img.naturalWidth;
        canvas.height = img.naturalHeight;
        const context = canvas.getContext('2d');
        context.drawImage(img, 0, 0);
        const { data } = context.getImageData(0, 0, canvas.width, canvas.height);
        return (u, v) => Array.from(data.slice(4 * (v * canvas.width + u), 4 * (v * canvas.width + u) + 4));
      };
      const load = async (url) => { const img = new Image(); img.src = url; await img.decode(); return img; };
      const raw = { base: pixels(await load('/api/maps/grid.png')), overlay: pixels(await load(`/api/overlay.png?v=${version}`)) };
      const turned = {};
      for (const [name, picture] of [['base', gridView.image], ['overlay', overlay.picture]]) {
        const img = picture.layer.getElement();
        const b = picture.layer.getBounds();
        const read = pixels(img);
        turned[name] = (ll) => read(
          Math.floor(((ll.lng - b.getWest()) / (b.getEast() - b.getWest())) * img.naturalWidth),
          Math.floor(((b.getNorth() - ll.lat) / (b.getNorth() - b.getSouth())) * img.naturalHeight));
      }
      return cellList.map(([i, j]) => {
        const ll = gridView.toLatLng({ x: x0 + (i + 0.5) * res, y: y1 - (j + 0.5) * res });
        const wall = [-1, 0, 1].some((di) => [-1, 0, 1].some((dj) => raw.overlay(i + di, j + dj)[3] > 0));
        return { cell: [i, j], wall, raw: raw.overlay(i, j), turned: turned.overlay(ll),
                 rawBase: raw.base(i, j), turnedBase: turned.base(ll) };
      });
    }, [cells, resolution, xmin, ymax, fresh.model_version]);
    assert.ok(sampled.length >= 30, `${sampled.length} wall points sampled`);
    for (const s_ of sampled) {
      assert.deepEqual(s_.turned, s_.raw, `the turned overlay at cell ${s_.cell} is the overlay's pixel`);
      assert.deepEqual(s_.turnedBase, s_.rawBase, `the turned gridmap at cell ${s_.cell} is grid.png's pixel`);
    }
    const walls = sampled.filter((s_) => s_.wall);
    assert.ok(walls.length >= 0.8 * sampled.length, `plan walls on the overlay at ${walls.length} of ${sampled.length} points`);
    assert.ok(walls.every((s_) => s_.turned[3] === 0 || (s_.turned[0] > 200 && s_.turned[1] < 80 && s_.turned[2] < 80)),
              'the overlay is red');
    assert.ok(sampled.some((s_) => s_.turned[3] > 0), 'some sampled cells are opaque red');
    await page.evaluate(() => {
      const { grid, gridView } = window.floorgridViewer;
      grid.fitBounds(gridView.pictureBounds(), { animate: false });
    });
    await page.waitForTimeout(200);
    await shot('viewer-turned-overlay.png');
  });

  it('toggles the turn: off draws the gridmap in its own frame, on turns it back, on the same grid point', async () => {
    const before_ = await page.evaluate(() => {
      const { grid, gridView, turn } = window.floorgridViewer;
      return { centre: gridView.fromLatLng(grid.getCenter()), alpha: turn.alpha, zoom: grid.getZoom() };
    });
    const read = () => page.evaluate(() => {
      const { grid, gridView, robot, state: st } = window.floorgridViewer;
      const ll = (l) => [l.lng, l.lat];
      const base = document.querySelector('#grid-map img.fg-base-image');
      return {
        turn: gridView.turn, centre: gridView.fromLatLng(grid.getCenter()), zoom: grid.getZoom(),
        robot: ll(robot.markers.grid.getLatLng()), pose: st.robot.pose,
        mapped: st.mapped && st.mapped.to === 'grid' ? ll(st.mapped.latlng) : null,
        mappedPoint: st.mapped && st.mapped.to === 'grid' ? st.mapped.point : null,
        clicked: st.click.from === 'grid' ? ll(window.floorgridViewer.goal.clicked.getLatLng()) : null,
        clickedPoint: st.click.from === 'grid' ? st.goal.grid : null,
        pairs: document.querySelectorAll('#grid-map .fg-pair').length,
        natural: [base.naturalWidth, base.naturalHeight], axes: document.querySelectorAll('#grid-map .fg-axes').length,
        image: (() => { const b = gridView.image.layer.getBounds(); return [b.getWest(), b.getSouth(), b.getEast(), b.getNorth()]; })(),
      };
    });
    await page.uncheck('#turn-like-plan');
    await page.evaluate(() => window.floorgridViewer.turn.drawn);
    const off = await read();
    assert.equal(off.turn, 0);
    assert.deepEqual(off.robot, [off.pose.x, off.pose.y], 'the robot marker at the raw grid pose');
    if (off.clicked) assert.deepEqual(off.clicked, [off.clickedPoint.x, off.clickedPoint.y], 'the goal at the raw grid point');
    if (off.mapped) assert.deepEqual(off.mapped, [off.mappedPoint.x, off.mappedPoint.y], 'the mapped goal at the raw grid point');
    assert.ok(off.clicked || off.mapped, 'a goal is drawn on the gridmap');
    assert.deepEqual(off.natural, [info.grid.width, info.grid.height], 'grid.png as it is');
    assert.deepEqual(off.image, info.grid.bounds.flat(), 'grid.png over the grid\'s bounds');
    assert.equal(off.axes, 0, 'no axes key when unturned');
    near(off.centre.x, before_.centre.x, METRE_TOLERANCE, 'same grid point in the middle (x)');
    near(off.centre.y, before_.centre.y, METRE_TOLERANCE, 'same grid point in the middle (y)');
    assert.equal(off.zoom, before_.zoom);
    await shot('viewer-unturned.png');

    await page.check('#turn-like-plan');
    await page.evaluate(() => window.floorgridViewer.turn.drawn);
    const on = await read();
    assert.equal(on.turn, before_.alpha);
    const [robotDrawn] = await gridDrawn([[on.pose.x, on.pose.y]]);
    near(on.robot[0], robotDrawn.lng, 1e-12, 'the robot redrawn turned (lng)');
    near(on.robot[1], robotDrawn.lat, 1e-12, 'the robot redrawn turned (lat)');
    assert.equal(on.pairs, off.pairs, 'the manual pairs kept');
    assert.deepEqual(on.natural, turnedSize(info.grid.width, info.grid.height, on.turn));
    near(on.centre.x, before_.centre.x, METRE_TOLERANCE, 'same grid point in the middle again (x)');
    near(on.centre.y, before_.centre.y, METRE_TOLERANCE, 'same grid point in the middle again (y)');
    assert.equal(on.axes, 1);
    await page.uncheck('#overlay-on');
  });

  it('offers no turn where the mapping mirrors the plan, and turns again when it does not', async () => {
    const alpha = await state(() => window.floorgridViewer.turn.alpha);
    // The same measurement on a mapping that mirrors: a stand-in for the API.
    const mirrored = await page.evaluate(async () => {
      const { turn, gridView } = window.floorgridViewer;
      const box = document.querySelector('#turn-like-plan');
      const api = turn.api;
      turn.api = { map: async () => ({ points: [{ x: 1, y: 1 }, { x: 1, y: 2 }, { x: 2, y: 1 }] }) };
      try {
        await turn.refresh(window.floorgridViewer.info);
      } finally {
        turn.api = api;
      }
      return { alpha: turn.alpha, turn: gridView.turn, checked: box.checked, disabled: box.disabled,
               title: box.closest('label').title };
    });
    assert.equal(mirrored.alpha, null);
    assert.equal(mirrored.turn, 0, 'the gridmap drawn in its own frame');
    assert.ok(mirrored.disabled && !mirrored.checked, 'the checkbox off and disabled');
    assert.match(mirrored.title, /not available: the mapping mirrors the plan/);
    const back = await page.evaluate(async () => {
      const { turn, gridView } = window.floorgridViewer;
      await turn.refresh(window.floorgridViewer.info);
      const box = document.querySelector('#turn-like-plan');
      return { alpha: turn.alpha, turn: gridView.turn, checked: box.checked, disabled: box.disabled };
    });
    near(back.alpha, alpha, 1e-12, 'the turn measured again');
    assert.equal(back.turn, back.alpha, 'turned again');
    assert.ok(back.checked && !back.disabled);
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
      const { grid, gridView } = window.floorgridViewer;
      const c = gridView.fromLatLng(grid.getCenter());
      return Math.abs(c.x - x) < 1e-6 && Math.abs(c.y - y) < 1e-6;
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
    assert.deepEqual(outsideRequests(), []);
  });
});
