// Zones: polygons drawn on the floorplan by clicks (or loaded from a GeoJSON file), mapped by the
// server onto the gridmap with their margin (K x std_m along the boundary) and drawn there as the
// nav2 mask's cells and the mapped boundary; the mask's nav2 files offered for download. Zones
// are kept in plan metres; the server's answer is drawn through each view's toLatLng.
import { fixed } from './geometry.js';
import { showDownloads } from './files.js';

const L = window.L;
const CLOSE_PX = 10;  // a click this near the first vertex closes the polygon

export class ZonesTool {
  constructor({ views, api, status, state }) {
    this.views = views;
    this.api = api;
    this.status = status;
    this.state = state;
    this.zones = [];       // {name, outer: [[x, y]...], holes: [...], speed_percent}, plan metres
    this.drawing = null;   // vertices of the zone being drawn, plan metres
    this.answer = null;    // the last POST /api/zones answer
    this.mask = null;      // its mask's Picture on the gridmap
    this.request = 0;
    this.idle = Promise.resolve();
    this.layers = { plan: L.layerGroup().addTo(views.plan.map), grid: L.layerGroup().addTo(views.grid.map) };
    this.sketch = L.layerGroup().addTo(views.plan.map);
    const $ = (id) => document.getElementById(id);
    this.el = {
      draw: $('draw-zone'), close: $('close-zone'), name: $('zone-name'), kind: $('zone-kind'),
      speed: $('zone-speed'), margin: $('zone-margin'), list: $('zones-list'), file: $('zones-file'),
      clear: $('clear-zones'), download: $('download-mask'), downloads: $('mask-downloads'),
      error: $('zones-error'),
    };
    this.el.draw.addEventListener('click', () => (this.drawing ? this.cancel() : this.start()));
    this.el.close.addEventListener('click', () => this.closeZone());
    this.el.clear.addEventListener('click', () => { this.zones = []; this.update(); });
    this.el.kind.addEventListener('change', () => this.update());
    this.el.margin.addEventListener('change', () => this.update());
    this.el.file.addEventListener('change', () => this.loadFile(this.el.file.files[0]));
    this.el.download.addEventListener('click', () => this.download());
    document.addEventListener('keydown', (event) => {
      if (event.key === 'Escape' && this.drawing) this.cancel();
    });
    this.render();
  }

  /// The request's common fields: the mask's kind, margin and default speed.
  options() {
    const margin = Number(this.el.margin.value);
    return { kind: this.el.kind.value, margin_sigma: Number.isFinite(margin) ? margin : 2 };
  }

  /// The zones as a GeoJSON FeatureCollection in plan metres (rings closed).
  geojson() {
    const closed = (ring) => [...ring, ring[0]];
    return {
      type: 'FeatureCollection',
      features: this.zones.map((zone) => ({
        type: 'Feature',
        properties: { name: zone.name, ...(zone.speed_percent ? { speed_percent: zone.speed_percent } : {}) },
        geometry: { type: 'Polygon', coordinates: [closed(zone.outer), ...zone.holes.map(closed)] },
      })),
    };
  }

  // ---- drawing ----

  start() {
    this.drawing = [];
    this.el.draw.textContent = 'Cancel';
    this.el.draw.classList.add('active');
    document.body.classList.add('fg-picking');
    this.status('Draw zone: click its corners on the floorplan; click the first one again or Close zone to finish (Esc cancels)', 'prompt');
    this.drawSketch();
  }

  cancel(message = 'zone drawing cancelled') {
    this.drawing = null;
    this.el.draw.textContent = 'Draw zone';
    this.el.draw.classList.remove('active');
    document.body.classList.remove('fg-picking');
    this.el.close.disabled = true;
    this.sketch.clearLayers();
    if (message) this.status(message, 'info');
  }

  /// Takes a map click while drawing; false when not drawing (the click goes elsewhere).
  handleClick(from, latlng) {
    if (!this.drawing) return false;
    if (from !== 'plan') {
      this.status('Draw zone: zones are drawn on the floorplan', 'prompt');
      return true;
    }
    const view = this.views.plan;
    if (this.drawing.length >= 3) {
      const first = view.map.latLngToContainerPoint(view.toLatLng(this.drawing[0]));
      if (first.distanceTo(view.map.latLngToContainerPoint(latlng)) <= CLOSE_PX) {
        this.closeZone();
        return true;
      }
    }
    const p = view.fromLatLng(latlng);
    this.drawing.push([p.x, p.y]);
    this.drawSketch();
    return true;
  }

  drawSketch() {
    this.sketch.clearLayers();
    this.el.close.disabled = !this.drawing || this.drawing.length < 3;
    if (!this.drawing || this.drawing.length === 0) return;
    const lls = this.drawing.map((p) => this.views.plan.toLatLng(p));
    this.sketch.addLayer(L.polyline(lls, { className: 'fg-zone-sketch', interactive: false }));
    lls.forEach((ll, i) => this.sketch.addLayer(L.circleMarker(ll, {
      className: i === 0 ? 'fg-zone-vertex fg-zone-first' : 'fg-zone-vertex', radius: i === 0 ? 6 : 4, interactive: false })));
  }

  closeZone() {
    if (!this.drawing || this.drawing.length < 3) return;
    const name = this.el.name.value.trim() || `zone ${this.zones.length + 1}`;
    const speed = Number(this.el.speed.value);
    const zone = { name, outer: this.drawing, holes: [], speed_percent: speed > 0 && speed <= 100 ? speed : null };
    this.zones.push(zone);
    this.el.name.value = '';
    this.cancel(null);
    return this.update().then((ok) => {
      if (ok) this.status(`zone '${name}' mapped onto the gridmap`, 'info');
      if (ok === false) this.dropRefused(zone);
    });
  }

  /// Takes back a zone the server refused (its message stays shown), so the others still map.
  dropRefused(zone) {
    const message = this.el.error.textContent;
    this.zones = this.zones.filter((z) => z !== zone);
    return this.update().then(() => this.showError(`${message} (zone '${zone.name}' not added)`));
  }

  // ---- a zones file ----

  async loadFile(file) {
    if (!file) return;
    let text;
    try {
      text = await file.text();
    } catch (error) {
      this.showError(`${file.name}: ${error.message}`);
      return;
    }
    this.el.file.value = '';
    try {
      const answer = await this.api.zones({ ...this.options(), geojson: text, file: file.name });
      this.zones.push(...answer.zones.map((z) => ({
        name: z.name, outer: z.plan.outer, holes: z.plan.holes, speed_percent: z.speed_percent })));
      this.status(`${file.name}: ${answer.zones.length} zones loaded`, 'info');
    } catch (error) {
      this.showError(error.message);
      return;
    }
    await this.update();
  }

  showError(message) {
    this.el.error.textContent = message;
    this.el.error.hidden = false;
    this.status(message, 'error');
  }

  // ---- the server's mapping ----

  /// Maps the zones again (after a change or a refit); resolves true when they are drawn, false
  /// when the server refused them (its message shown), null when a newer change took over.
  update() {
    this.idle = this.run(++this.request);
    return this.idle;
  }

  async run(id) {
    this.el.downloads.replaceChildren();
    if (this.zones.length === 0) {
      this.answer = null;
      this.render();
      return true;
    }
    let answer;
    try {
      answer = await this.api.zones({ ...this.options(), geojson: this.geojson() });
    } catch (error) {
      if (id !== this.request) return null;
      this.showError(error.message);
      return false;
    }
    if (id !== this.request) return null;  // a newer change is being mapped
    this.el.error.hidden = true;
    this.answer = answer;
    this.render();
    for (const warning of answer.warnings) this.status(`zones: ${warning}`, 'warn');
    await this.mask?.drawn;
    return true;
  }

  /// Draws the zones again (a view's frame changed: the mask's picture turns by itself).
  redraw() {
    this.drawSketch();
    this.drawZones();
  }

  render() {
    this.mask?.remove();
    this.mask = null;
    if (this.answer) {
      this.mask = this.views.grid.addPicture(this.answer.mask.png, { pane: 'fg-layers', opacity: 1 });
      this.mask.draw().catch((error) => this.status(`zone mask: ${error.message}`, 'error'));
    }
    this.drawZones();
    this.renderList();
    this.el.download.disabled = !this.answer;
    this.state.zones = this.answer ? { count: this.answer.zones.length, cells: this.answer.mask.cells } : null;
  }

  drawZones() {
    for (const layer of Object.values(this.layers)) layer.clearLayers();
    const kind = this.el.kind.value;
    for (const zone of this.zones) {
      const rings = [zone.outer, ...zone.holes].map((r) => r.map((p) => this.views.plan.toLatLng(p)));
      this.layers.plan.addLayer(L.polygon(rings, { className: `fg-zone fg-zone-${kind}`, interactive: false })
        .bindTooltip(zone.name, { permanent: true, direction: 'center', className: 'fg-label' }));
    }
    for (const zone of this.answer?.zones ?? []) {
      const rings = zone.rings.map((r) => r.map((p) => this.views.grid.toLatLng(p)));
      const extrapolated = zone.extrapolated_points > 0 ? 'fg-extrapolated' : '';
      this.layers.grid.addLayer(L.polygon(rings, { className: `fg-zone-mapped ${extrapolated}`, interactive: false, fill: false }));
    }
  }

  renderList() {
    const zones = this.answer?.zones ?? [];
    const rows = zones.map((z) => {
      const row = document.createElement('tr');
      row.dataset.zoneIndex = z.index;
      const flags = [z.clipped ? 'clipped' : '', z.extrapolated_points ? `${z.extrapolated_points} extrapolated` : '']
        .filter(Boolean).join(', ');
      row.innerHTML = '<td class="name"></td>' +
        `<td class="num">${z.cells.toLocaleString('en')}</td>` +
        `<td class="num">${z.has_std ? fixed(z.margin_m, 3) : '—'}</td>` +
        `<td class="${flags ? 'fg-bad' : 'muted'}">${flags || 'ok'}</td>` +
        '<td><button type="button" class="icon-button delete-zone" title="delete this zone">×</button></td>';
      row.querySelector('.name').textContent = z.name + (z.speed_percent && this.el.kind.value === 'speed' ? ` (${z.speed_percent}%)` : '');
      row.querySelector('button').addEventListener('click', () => {
        this.zones.splice(z.index, 1);
        this.update();
      });
      return row;
    });
    if (rows.length === 0) {
      const row = document.createElement('tr');
      row.innerHTML = '<td colspan="5" class="muted">none yet</td>';
      rows.push(row);
    }
    this.el.list.replaceChildren(...rows);
  }

  // ---- nav2 files ----

  async download() {
    this.el.download.disabled = true;
    try {
      const answer = await this.api.zonesNav2({ ...this.options(), geojson: this.geojson() });
      showDownloads(this.el.downloads, answer.files);
      this.status(`nav2 ${answer.kind} mask: ${answer.files.length} files ready, click each to save`, 'info');
    } catch (error) {
      this.showError(error.message);
    } finally {
      this.el.download.disabled = !this.answer;
    }
  }
}
