// The live robot pose: GET /api/robot_pose about 4 times a second, redrawn on both maps
// when its sequence number changes (gridmap pose as sent, floorplan pose as the model maps it),
// each drawn through its view's toLatLng / toDisplayAngle.
import { degrees, fixed } from './geometry.js';
import { poseIcon } from './maps.js';

const L = window.L;
const POLL_MS = 225;

export class RobotFeed {
  constructor({ views, api, status, state }) {
    this.views = views;
    this.api = api;
    this.status = status;
    this.state = state;
    this.sequence = 0;
    this.last = null;  // {pose, plan}: the pose drawn
    this.busy = false;
    this.failing = false;
    this.markers = { plan: null, grid: null };
    this.follow = document.getElementById('follow-robot');
    this.text = document.getElementById('robot-text');
    this.follow.addEventListener('change', () => { if (this.follow.checked) this.panTo(); });
  }

  showReplay(replay) {
    const badge = document.getElementById('robot-replay');
    badge.hidden = !replay;
    if (replay) badge.textContent = `replay · ${replay.poses} poses · ${replay.speed}×`;
  }

  start() {
    this.timer = setInterval(() => this.poll(false), POLL_MS);
    return this.poll(false);
  }

  /// Redraws even when the sequence did not change (the model changed).
  refresh() {
    return this.poll(true);
  }

  /// Draws the last pose again (a view's frame changed).
  redraw() {
    if (this.last) this.draw(this.last.pose, this.last.plan);
  }

  async poll(force) {
    if (this.busy) return;
    this.busy = true;
    try {
      const pose = await this.api.robotPose();
      if (this.failing) this.status('robot pose feed back', 'info');
      this.failing = false;
      if (pose.sequence && (force || pose.sequence !== this.sequence)) {
        this.sequence = pose.sequence;
        this.draw(pose, pose.plan);
      }
    } catch (error) {
      if (!this.failing) this.status(`robot pose: ${error.message}`, 'error');
      this.failing = true;
    } finally {
      this.busy = false;
    }
  }

  /// The robot's marker on one map: `point` {x, y} and `theta` in that map's frame (null: none).
  place(name, point, theta) {
    const view = this.views[name];
    const at = point ? view.toLatLng(point) : null;
    const icon = poseIcon('robot', typeof theta === 'number' ? view.toDisplayAngle(theta) : null, { arrow: 16 });
    if (!at) {
      if (this.markers[name]) this.markers[name].remove();
      this.markers[name] = null;
      return null;
    }
    if (this.markers[name]) {
      this.markers[name].setLatLng(at).setIcon(icon);
    } else {
      this.markers[name] = L.marker(at, { icon, interactive: false, keyboard: false, zIndexOffset: 800 })
        .addTo(view.map);
    }
    return at;
  }

  draw(pose, plan) {
    this.last = { pose, plan };
    const planMapped = plan && plan.x !== null && plan.x !== undefined;
    const planTheta = plan && typeof plan.theta === 'number' ? plan.theta : null;
    const grid = this.place('grid', pose, pose.theta);
    const planAt = this.place('plan', planMapped ? plan : null, planTheta);
    // grid, plan: the markers' LatLngs; pose: as sent (grid frame).
    this.state.robot = { sequence: pose.sequence, pose: { x: pose.x, y: pose.y, theta: pose.theta },
                         grid, plan: planAt, theta: pose.theta, planTheta };
    const std = plan && typeof plan.std_m === 'number' ? ` · std ${fixed(plan.std_m, 3)} m` : '';
    const flag = plan && plan.flag && plan.flag !== 'ok' ? ` · ${plan.flag}` : '';
    this.text.innerHTML =
      `<span class="k">grid</span> <span class="num">${fixed(pose.x, 2)}, ${fixed(pose.y, 2)}, ${fixed(degrees(pose.theta), 0)}°</span><br>` +
      `<span class="k">plan</span> <span class="num">${planAt ? `${fixed(plan.x, 2)}, ${fixed(plan.y, 2)}` : 'does not map'}` +
      `${planTheta !== null ? `, ${fixed(degrees(planTheta), 0)}°` : ''}</span>${std}${flag}` +
      ` <span class="muted">#${pose.sequence}</span>`;
    if (this.follow.checked) this.panTo();
  }

  panTo() {
    const robot = this.state.robot;
    if (!robot) return;
    this.views.grid.setViewQuietly(robot.grid);
    if (robot.plan) this.views.plan.setViewQuietly(robot.plan);
  }
}
