// The goal: a click on either map, mapped to the other one with its uncertainty, a heading
// handle to turn it, and the panel with the gridmap pose to send to the robot. The goal and
// the answer are kept in the maps' own frames; each view's toLatLng / toDisplayAngle draws them
// (the gridmap may be drawn turned like the plan).
import {
  degrees, fixed, jacobianFromSteps, poseStampedYaml, preimageEllipse, ros2GoalCommand,
  wrapAngle, yawQuaternion,
} from './geometry.js';
import { metresForPixels, poseIcon } from './maps.js';

const L = window.L;
const ARROW_PX = 40;        // the heading arrow's length on screen
const JACOBIAN_STEP = 0.5;  // metres: finite-difference step of the local Jacobian
const other = (name) => (name === 'plan' ? 'grid' : 'plan');
const isMapped = (p) => p && p.x !== null && p.x !== undefined && p.y !== null && p.y !== undefined;

export class GoalTool {
  constructor({ views, api, status, state }) {
    this.views = views;
    this.api = api;
    this.status = status;
    this.state = state;
    this.goal = null;       // {from, x, y, theta} in the clicked map's frame
    this.answer = null;     // the server's mapped point for the goal
    this.J = null;          // J_target_source at the goal
    this.pending = null;
    this.running = false;
    this.idle = Promise.resolve();
    this.layers = { plan: L.layerGroup().addTo(views.plan.map), grid: L.layerGroup().addTo(views.grid.map) };
    this.dragging = false;
    for (const name of ['plan', 'grid']) {
      views[name].map.on('zoomend', () => {
        if (this.goal && this.goal.from === name && !this.dragging) this.placeHandle();
      });
    }
    this.panel = {
      empty: document.getElementById('goal-empty'),
      body: document.getElementById('goal-body'),
      warning: document.getElementById('goal-warning'),
      source: document.getElementById('goal-source'),
      yaml: document.getElementById('goal-yaml'),
      command: document.getElementById('goal-command'),
    };
  }

  /// A new goal at `latlng` on map `from` (the heading kept from the last goal on that map).
  pick(from, latlng) {
    const p = this.views[from].fromLatLng(latlng);
    this.goal = { from, x: p.x, y: p.y, theta: this.goal?.from === from ? this.goal.theta : 0 };
    this.state.click = { from, latlng: L.latLng(latlng.lat, latlng.lng), point: p };
    this.state.mapped = null;
    this.drawClicked();
    return this.remap(true);
  }

  /// The same goal mapped again (after a refit).
  refresh() {
    return this.goal ? this.remap(true) : Promise.resolve();
  }

  /// Draws the goal again (a view's frame changed).
  redraw() {
    if (!this.goal) return;
    this.drawClicked();
    if (this.answer) this.drawMapped();
  }

  /// Queues a POST /api/map of the goal; a drag sends one request at a time, the latest last.
  remap(withJacobian) {
    this.pending = { withJacobian: withJacobian || Boolean(this.pending?.withJacobian) };
    if (!this.running) this.idle = this.run();
    return this.idle;
  }

  async run() {
    this.running = true;
    while (this.pending) {
      const job = this.pending;
      this.pending = null;
      const goal = this.goal;
      const sent = { x: goal.x, y: goal.y, theta: goal.theta };
      const points = [[sent.x, sent.y, sent.theta]];
      if (job.withJacobian) points.push([sent.x + JACOBIAN_STEP, sent.y], [sent.x, sent.y + JACOBIAN_STEP]);
      let answer;
      try {
        answer = await this.api.map(goal.from, points);
      } catch (error) {
        this.status(error.message, 'error');
        continue;
      }
      if (goal !== this.goal) continue;  // a newer click queued its own request
      this.answer = answer.points[0];
      if (job.withJacobian) {
        this.J = jacobianFromSteps(answer.points[0], answer.points[1], answer.points[2], JACOBIAN_STEP);
      }
      this.drawMapped();
      this.renderPanel(sent);
      if (job.withJacobian && this.answer.extrapolated) {
        this.status(`goal extrapolated (${this.answer.flag}): check it on the gridmap before sending`, 'warn');
      }
    }
    this.running = false;
  }

  /// The heading handle's place: the arrow's tip (turns keep lengths: metres are the view's).
  tip() {
    const view = this.views[this.goal.from];
    const length = metresForPixels(view.map, ARROW_PX);
    const { x, y, theta } = this.goal;
    return view.toLatLng({ x: x + length * Math.cos(theta), y: y + length * Math.sin(theta) });
  }

  clickedIcon() {
    return poseIcon('goal-clicked', this.views[this.goal.from].toDisplayAngle(this.goal.theta), { arrow: ARROW_PX });
  }

  placeHandle() {
    if (this.handle) this.handle.setLatLng(this.tip());
    this.state.handle = this.handle ? this.handle.getLatLng() : null;
  }

  drawClicked() {
    for (const layer of Object.values(this.layers)) layer.clearLayers();
    const { from } = this.goal;
    this.clicked = L.marker(this.views[from].toLatLng(this.goal), {
      icon: this.clickedIcon(), interactive: false, keyboard: false, zIndexOffset: 500 });
    this.handle = L.marker(this.tip(), {
      icon: L.divIcon({ className: 'fg-handle', iconSize: [14, 14], iconAnchor: [7, 7] }),
      draggable: true, keyboard: false, zIndexOffset: 1000, title: 'drag to set the heading',
    });
    this.handle.on('dragstart', () => { this.dragging = true; });
    this.handle.on('drag', () => this.turnTowards(this.handle.getLatLng()));
    this.handle.on('dragend', () => {
      this.dragging = false;
      this.turnTowards(this.handle.getLatLng());
      this.placeHandle();
    });
    this.layers[from].addLayer(this.clicked).addLayer(this.handle);
    this.state.handle = this.handle.getLatLng();
  }

  /// Heads the goal at the handle's `latlng` (the heading in the clicked map's own frame).
  turnTowards(latlng) {
    const p = this.views[this.goal.from].fromLatLng(latlng);
    const dx = p.x - this.goal.x;
    const dy = p.y - this.goal.y;
    if (Math.hypot(dx, dy) === 0) return;
    this.goal.theta = Math.atan2(dy, dx);
    this.clicked.setIcon(this.clickedIcon());
    this.remap(false);
  }

  drawMapped() {
    const { from } = this.goal;
    const to = other(from);
    const m = this.answer;
    for (const name of ['plan', 'grid']) {
      for (const layer of this.layers[name].getLayers()) {
        if (layer !== this.clicked && layer !== this.handle) this.layers[name].removeLayer(layer);
      }
    }
    if (!isMapped(m)) {
      this.state.mapped = null;
      return;
    }
    const extrapolated = m.extrapolated ? 'fg-extrapolated' : '';
    const target = this.views[to].toLatLng(m);
    const hasStd = typeof m.std_m === 'number';
    const radius = hasStd ? m.std_m : m.nearest_pair_m;
    if (typeof radius === 'number' && radius > 0) {
      const style = { className: `fg-uncertainty ${hasStd ? '' : 'fg-uncertainty-nopair'}`,
                      interactive: false, dashArray: hasStd ? null : '5 4' };
      const circle = L.circle(target, { ...style, radius });
      if (!hasStd) {
        circle.bindTooltip(`no std · circle: nearest pair ${fixed(radius, 2)} m`, {
          permanent: true, direction: 'auto', className: 'fg-label', offset: [0, 0] });
      }
      this.layers[to].addLayer(circle);
      const ellipse = this.J && preimageEllipse(this.goal, this.J, radius);
      if (ellipse) this.layers[from].addLayer(L.polygon(ellipse.map((p) => this.views[from].toLatLng(p)), style));
    }
    const theta = typeof m.theta === 'number' ? m.theta : null;
    this.layers[to].addLayer(L.marker(target, {
      icon: poseIcon('goal-mapped', theta === null ? null : this.views[to].toDisplayAngle(theta),
                     { arrow: ARROW_PX, extra: extrapolated }),
      interactive: false, keyboard: false, zIndexOffset: 500,
    }));
    // latlng: where it is drawn; point and theta: in the target map's own frame.
    this.state.mapped = { to, latlng: target, point: { x: m.x, y: m.y }, theta };
  }

  renderPanel(sent) {
    const { from } = this.goal;
    const m = this.answer;
    const p = this.panel;
    p.empty.hidden = true;
    p.body.hidden = false;
    const clicked = { x: sent.x, y: sent.y, theta: sent.theta };
    const mapped = isMapped(m) ? { x: m.x, y: m.y, theta: typeof m.theta === 'number' ? m.theta : null } : null;
    const grid = from === 'grid' ? clicked : mapped;
    const plan = from === 'plan' ? clicked : mapped;
    this.state.goal = { grid, plan, std_m: m.std_m, flag: m.flag, extrapolated: m.extrapolated };

    const warnings = [];
    if (!mapped) warnings.push(`This point does not map to the ${from === 'plan' ? 'gridmap' : 'floorplan'} (${m.flag}).`);
    else if (m.extrapolated) warnings.push(`Extrapolated (${m.flag}): far from the pairs, the mapping only guesses here.`);
    if (mapped && mapped.theta === null) warnings.push('The heading did not map; the goal below uses θ = 0.');
    p.warning.textContent = warnings.join(' ');
    p.warning.hidden = warnings.length === 0;
    p.source.textContent = from === 'plan' ? 'clicked on the floorplan' : 'clicked on the gridmap';

    const set = (id, text) => { document.getElementById(id).textContent = text; };
    const pose = (prefix, value) => {
      set(`${prefix}-x`, value ? fixed(value.x, 3) : '—');
      set(`${prefix}-y`, value ? fixed(value.y, 3) : '—');
      const theta = value && value.theta !== null ? wrapAngle(value.theta) : null;
      set(`${prefix}-theta`, theta !== null ? fixed(theta, 3) : '—');
      set(`${prefix}-deg`, theta !== null ? `${fixed(degrees(theta), 1)}°` : '');
    };
    pose('goal-grid', grid);
    pose('goal-plan', plan);
    const hasStd = typeof m.std_m === 'number';
    set('goal-std', hasStd ? `${fixed(m.std_m, 3)} m` : `none (nearest pair ${fixed(m.nearest_pair_m, 2)} m)`);
    set('goal-flag', m.flag + (m.extrapolated ? ' · extrapolated' : ''));
    document.getElementById('goal-flag').classList.toggle('fg-bad', Boolean(m.extrapolated) || !mapped);

    if (grid) {
      const goal = { x: grid.x, y: grid.y, theta: grid.theta === null ? 0 : wrapAngle(grid.theta) };
      const q = yawQuaternion(goal.theta);
      set('goal-qz', fixed(q.z, 4));
      set('goal-qw', fixed(q.w, 4));
      p.yaml.textContent = poseStampedYaml(goal);
      p.command.textContent = ros2GoalCommand(goal);
    } else {
      set('goal-qz', '—');
      set('goal-qw', '—');
      p.yaml.textContent = '# no gridmap pose for this point';
      p.command.textContent = '';
    }
  }
}
