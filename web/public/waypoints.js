// Waypoints: named poses placed by a click on the floorplan (heading from the field, degrees;
// empty for none), mapped by the server onto the gridmap with their std_m circle and an
// extrapolated mark; the nav2 waypoints YAML and the gridmap GeoJSON offered for download.
// Waypoints are kept in plan metres; the answer is drawn through each view's toLatLng.
import { degrees, fixed, wrapAngle } from './geometry.js';
import { showDownloads } from './files.js';
import { poseIcon } from './maps.js';

const L = window.L;

export class WaypointsTool {
  constructor({ views, api, status, state }) {
    this.views = views;
    this.api = api;
    this.status = status;
    this.state = state;
    this.waypoints = [];   // {name, x, y, theta (radians or null)}, plan metres
    this.placing = false;
    this.answer = null;    // the last POST /api/waypoints answer
    this.request = 0;
    this.idle = Promise.resolve();
    this.layers = { plan: L.layerGroup().addTo(views.plan.map), grid: L.layerGroup().addTo(views.grid.map) };
    const $ = (id) => document.getElementById(id);
    this.el = {
      place: $('place-waypoint'), name: $('waypoint-name'), heading: $('waypoint-heading'),
      list: $('waypoints-list'), downloads: $('waypoint-downloads'), error: $('waypoints-error'),
    };
    this.el.place.addEventListener('click', () => (this.placing ? this.stop() : this.start()));
    document.addEventListener('keydown', (event) => {
      if (event.key === 'Escape' && this.placing) this.stop();
    });
    this.render();
  }

  start() {
    this.placing = true;
    this.el.place.textContent = 'Cancel';
    this.el.place.classList.add('active');
    document.body.classList.add('fg-picking');
    this.status('Place waypoint: click its place on the floorplan (Esc cancels)', 'prompt');
  }

  stop(message = 'waypoint placing cancelled') {
    this.placing = false;
    this.el.place.textContent = 'Place waypoint';
    this.el.place.classList.remove('active');
    document.body.classList.remove('fg-picking');
    if (message) this.status(message, 'info');
  }

  /// Takes a map click while placing; false when not placing (the click goes elsewhere).
  handleClick(from, latlng) {
    if (!this.placing) return false;
    if (from !== 'plan') {
      this.status('Place waypoint: waypoints are placed on the floorplan', 'prompt');
      return true;
    }
    const p = this.views.plan.fromLatLng(latlng);
    const heading = this.el.heading.value.trim();
    const theta = heading === '' || !Number.isFinite(Number(heading)) ? null : wrapAngle((Number(heading) * Math.PI) / 180);
    const name = this.el.name.value.trim() || `waypoint ${this.waypoints.length + 1}`;
    const waypoint = { name, x: p.x, y: p.y, theta };
    this.waypoints.push(waypoint);
    this.el.name.value = '';
    this.stop(null);
    this.update().then((ok) => {
      if (ok) this.status(`waypoint '${name}' mapped onto the gridmap`, 'info');
      if (ok !== false) return;
      // Taken back, so the others still map; the server's message stays shown.
      const message = this.el.error.textContent;
      this.waypoints = this.waypoints.filter((w) => w !== waypoint);
      this.update().then(() => this.showError(`${message} (waypoint '${name}' not added)`));
    });
    return true;
  }

  geojson() {
    return {
      type: 'FeatureCollection',
      features: this.waypoints.map((w) => ({
        type: 'Feature',
        properties: { name: w.name, ...(w.theta === null ? {} : { theta: w.theta }) },
        geometry: { type: 'Point', coordinates: [w.x, w.y] },
      })),
    };
  }

  showError(message) {
    this.el.error.textContent = message;
    this.el.error.hidden = false;
    this.status(message, 'error');
  }

  /// Maps the waypoints again (after a change or a refit); resolves true when they are drawn,
  /// false when the server refused them (its message shown), null when a newer change took over.
  update() {
    this.idle = this.run(++this.request);
    return this.idle;
  }

  async run(id) {
    if (this.waypoints.length === 0) {
      this.answer = null;
      this.render();
      return true;
    }
    let answer;
    try {
      answer = await this.api.waypoints({ geojson: this.geojson() });
    } catch (error) {
      if (id !== this.request) return null;
      this.showError(error.message);
      return false;
    }
    if (id !== this.request) return null;
    this.el.error.hidden = true;
    this.answer = answer;
    this.render();
    if (answer.extrapolated > 0) {
      this.status(`${answer.extrapolated} waypoint(s) extrapolated: check them on the gridmap before sending`, 'warn');
    }
    return true;
  }

  redraw() {
    this.draw();
  }

  render() {
    this.draw();
    this.renderList();
    showDownloads(this.el.downloads, this.answer?.files ?? []);
    this.state.waypoints = this.answer ? this.answer.waypoints : null;
  }

  draw() {
    for (const layer of Object.values(this.layers)) layer.clearLayers();
    const { plan, grid } = this.views;
    for (const w of this.waypoints) {
      this.layers.plan.addLayer(L.marker(plan.toLatLng(w), {
        icon: poseIcon('waypoint', w.theta === null ? null : plan.toDisplayAngle(w.theta), { arrow: 24 }),
        interactive: false, keyboard: false,
      }).bindTooltip(w.name, { permanent: true, direction: 'right', offset: [8, 0], className: 'fg-label' }));
    }
    for (const m of this.answer?.waypoints ?? []) {
      if (m.x === null || m.y === null) continue;
      const at = grid.toLatLng(m);
      if (typeof m.std_m === 'number' && m.std_m > 0) {
        this.layers.grid.addLayer(L.circle(at, { radius: m.std_m, className: 'fg-waypoint-std', interactive: false }));
      }
      this.layers.grid.addLayer(L.marker(at, {
        icon: poseIcon('waypoint-mapped', m.theta === null ? null : grid.toDisplayAngle(m.theta),
                       { arrow: 24, extra: m.extrapolated ? 'fg-extrapolated' : '' }),
        interactive: false, keyboard: false,
      }).bindTooltip(m.name, { permanent: true, direction: 'right', offset: [8, 0], className: 'fg-label' }));
    }
  }

  renderList() {
    const rows = (this.answer?.waypoints ?? []).map((m) => {
      const row = document.createElement('tr');
      row.dataset.waypointIndex = m.index;
      row.innerHTML = '<td class="name"></td>' +
        `<td class="num">${fixed(m.x, 2)}, ${fixed(m.y, 2)}</td>` +
        `<td class="num">${m.theta === null ? '—' : `${fixed(degrees(m.theta), 0)}°`}</td>` +
        `<td class="num">${typeof m.std_m === 'number' ? fixed(m.std_m, 3) : '—'}</td>` +
        `<td class="${m.extrapolated ? 'fg-bad' : 'muted'}">${m.flag}</td>` +
        '<td><button type="button" class="icon-button delete-waypoint" title="delete this waypoint">×</button></td>';
      row.querySelector('.name').textContent = m.name;
      row.querySelector('button').addEventListener('click', () => {
        this.waypoints.splice(m.index, 1);
        this.update();
      });
      return row;
    });
    if (rows.length === 0) {
      const row = document.createElement('tr');
      row.innerHTML = '<td colspan="6" class="muted">none yet</td>';
      rows.push(row);
    }
    this.el.list.replaceChildren(...rows);
  }
}
