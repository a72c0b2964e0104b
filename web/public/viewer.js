// floorgrid viewer: the floorplan and the robot's gridmap side by side, the gridmap drawn turned
// like the plan when the two are turned apart (turn.js). A click on either map is mapped to the
// other by the server's model; the gridmap pose is the robot's goal.
// window.floorgridViewer is the browser tests' hook: {ready, plan, grid (the Leaflet maps),
// planView, gridView (their MapViews: toLatLng, fromLatLng, turn), turn (the TurnControl:
// alpha), goal, robot, pairs, overlay, zones, waypoints, state}.
import { api } from './api.js';
import { GoalTool } from './goal.js';
import { HeatMap, WallOverlay } from './layers.js';
import { LinkedViews, MapView } from './maps.js';
import { PairsPanel } from './pairs.js';
import { RobotFeed } from './robot.js';
import { measureTurn, TurnControl } from './turn.js';
import { WaypointsTool } from './waypoints.js';
import { ZonesTool } from './zones.js';

const statusLine = document.getElementById('status');

/// The header's status line: kind 'info', 'prompt', 'warn' or 'error'.
function status(message, kind = 'info') {
  statusLine.textContent = message;
  statusLine.className = `status status-${kind}`;
  statusLine.title = message;
}

function showInfo(info) {
  document.getElementById('dataset-name').textContent = info.dataset;
  document.getElementById('model-name').textContent = info.model;
  document.title = `${info.dataset} · floorgrid viewer`;
}

/// Copy buttons: data-copy names the element whose text goes to the clipboard.
function wireCopyButtons() {
  for (const button of document.querySelectorAll('button[data-copy]')) {
    button.addEventListener('click', async () => {
      const source = document.getElementById(button.dataset.copy);
      try {
        // A browser that asks for permission may never settle: fall back after a second.
        const timeout = new Promise((_, reject) => setTimeout(() => reject(new Error('timeout')), 1000));
        await Promise.race([navigator.clipboard.writeText(source.textContent), timeout]);
        status('copied to the clipboard', 'info');
      } catch {
        // No clipboard (plain http on another host): select the text for Ctrl-C.
        const range = document.createRange();
        range.selectNodeContents(source);
        const selection = window.getSelection();
        selection.removeAllRanges();
        selection.addRange(range);
        status('the clipboard is not available here: the text is selected, press Ctrl-C', 'warn');
      }
    });
  }
}

async function start(hook) {
  const info = await api.info();
  hook.info = info;
  showInfo(info);
  // The turn first: the gridmap's first picture is drawn with it.
  const measured = await measureTurn(api, info);
  const turn = new TurnControl({ api, status, measured });
  const views = {
    plan: new MapView('plan-map', 'plan', info.plan, '/api/maps/plan.png'),
    grid: new MapView('grid-map', 'grid', info.grid, '/api/maps/grid.png', { turn: turn.wanted() }),
  };
  turn.attach(views.grid);
  const state = hook.state;

  const linkBox = document.getElementById('linked-views');
  const linked = new LinkedViews(views, api, { enabled: () => linkBox.checked, onError: status });
  linkBox.addEventListener('change', () => { if (linkBox.checked) linked.follow('plan', 'grid'); });

  const goal = new GoalTool({ views, api, status, state });
  const robot = new RobotFeed({ views, api, status, state });
  const overlay = new WallOverlay({ views, status });
  const heatmap = new HeatMap({ views, api, status });
  const zones = new ZonesTool({ views, api, status, state });
  const waypoints = new WaypointsTool({ views, api, status, state });
  const pairs = new PairsPanel({
    views, api, status, state,
    onRefit: async () => {
      const fresh = await api.info();
      hook.info = fresh;
      showInfo(fresh);
      pairs.setInfo(fresh);
      overlay.setInfo(fresh);
      await Promise.all([heatmap.setInfo(fresh), turn.refresh(fresh), goal.refresh(), robot.refresh(),
                         zones.update(), waypoints.update()]);
    },
  });
  // A new turn redraws all that is drawn on the gridmap, in its new frame.
  views.grid.onTurn(() => {
    goal.redraw();
    robot.redraw();
    pairs.redraw('grid');
    zones.redraw();
    waypoints.redraw();
  });
  Object.assign(hook, { plan: views.plan.map, grid: views.grid.map, planView: views.plan, gridView: views.grid,
                        turn, goal, robot, pairs, overlay, zones, waypoints });

  for (const name of ['plan', 'grid']) {
    views[name].map.on('click', (event) => {
      const taken = pairs.handleClick(name, event.latlng) || zones.handleClick(name, event.latlng)
        || waypoints.handleClick(name, event.latlng);
      if (!taken) goal.pick(name, event.latlng);
    });
  }
  wireCopyButtons();
  pairs.setInfo(info);
  overlay.setInfo(info);
  robot.showReplay(info.replay);
  await Promise.all([views.plan.loaded, views.grid.loaded, pairs.loadManual(), robot.start(),
                     heatmap.setInfo(info)]);
  // Both maps open on the same place, at the same scale (and, turned, at the same angle).
  if (linkBox.checked) await linked.follow('plan', 'grid');
  status('Click either map to set a goal; drag the orange handle to turn it.', 'info');
  // A map origin with a yaw (rare: map_server and most of ROS ignore it) turns the map in its
  // frame; the pictures are drawn without that yaw (the turn like the plan aside), so the
  // picture would not lie under its cells.
  for (const [name, layout] of [['floorplan', info.plan], ['gridmap', info.grid]]) {
    if (layout.origin[2] !== 0) {
      status(`the ${name}'s origin has a yaw of ${(layout.origin[2] * 180 / Math.PI).toFixed(1)}°: ` +
             'its picture is drawn without it, so what you click on it is off (the API is exact)',
             'warn');
    }
  }
}

const hook = { ready: null, isReady: false, plan: null, grid: null, state: {} };
window.floorgridViewer = hook;
hook.ready = start(hook).then(
  () => { hook.isReady = true; },
  (error) => {
    status(`the viewer could not start: ${error.message}`, 'error');
    throw error;
  },
);
