// Pairs: the alignment's own (dots on both maps), the operator's manual pairs (numbered, listed,
// added by a click on each map, deleted) and a refit of a chosen model on all of them. Pairs are
// kept in the maps' own frames and drawn through each view's toLatLng.
import { fixed } from './geometry.js';

const L = window.L;

const xy = (p) => `${fixed(p[0], 2)}, ${fixed(p[1], 2)}`;

export class PairsPanel {
  constructor({ views, api, status, state, onRefit }) {
    this.views = views;
    this.api = api;
    this.status = status;
    this.state = state;
    this.onRefit = onRefit;
    this.mode = null;  // null, 'plan' (waiting for the floorplan click) or 'grid'
    this.first = null;
    this.baseOn = document.getElementById('base-pairs-on');
    this.baseCount = document.getElementById('base-pairs-count');
    this.list = document.getElementById('pairs-list');
    this.addButton = document.getElementById('add-pair');
    this.modelSelect = document.getElementById('model-select');
    this.refitButton = document.getElementById('refit');
    this.fitResult = document.getElementById('fit-result');
    this.base = null;        // the alignment's pairs, [[plan_x, plan_y, grid_x, grid_y], ...]
    this.baseLayers = null;  // their dots, per map
    this.manual = [];        // the manual pairs, as GET /api/pairs lists them
    this.manualLayers = { plan: L.layerGroup().addTo(views.plan.map), grid: L.layerGroup().addTo(views.grid.map) };
    this.pendingMarker = null;
    this.baseOn.addEventListener('change', () => this.showBase(this.baseOn.checked));
    this.addButton.addEventListener('click', () => (this.mode ? this.cancelAdd() : this.startAdd()));
    this.refitButton.addEventListener('click', () => this.refit());
    document.addEventListener('keydown', (event) => {
      if (event.key === 'Escape' && this.mode) this.cancelAdd();
    });
  }

  setInfo(info) {
    const models = Array.isArray(info.models) && info.models.length ? info.models : [info.model];
    this.modelSelect.replaceChildren(...models.map((name) => {
      const option = document.createElement('option');
      option.value = option.textContent = name;
      return option;
    }));
    this.modelSelect.value = info.model;
  }

  // ---- the alignment's pairs ----

  async showBase(on) {
    if (!on) {
      for (const name of ['plan', 'grid']) this.baseLayers?.[name].remove();
      return;
    }
    if (!this.baseLayers) {
      let answer;
      try {
        answer = await this.api.pairs(true);
      } catch (error) {
        this.status(error.message, 'error');
        return;
      }
      this.base = answer.base;
      this.baseLayers = { plan: this.dots('plan'), grid: this.dots('grid') };
      const drawn = answer.base.length;
      this.baseCount.textContent = drawn < answer.base_pairs
        ? `${answer.base_pairs.toLocaleString('en')} pairs, ${drawn.toLocaleString('en')} drawn (evenly thinned)`
        : `${answer.base_pairs.toLocaleString('en')} pairs`;
      this.state.baseDrawn = drawn;
    }
    if (this.baseOn.checked) {
      for (const name of ['plan', 'grid']) this.baseLayers[name].addTo(this.views[name].map);
    }
  }

  /// Thousands of dots on one map: one canvas renderer, nothing interactive.
  dots(name) {
    const view = this.views[name];
    const offset = name === 'plan' ? 0 : 2;
    const renderer = L.canvas({ padding: 0.3 });
    const style = { renderer, radius: 1.2, stroke: false, fillColor: '#2ca25f', fillOpacity: 0.55, interactive: false };
    return L.layerGroup(this.base.map((row) => L.circleMarker(view.toLatLng([row[offset], row[offset + 1]]), style)));
  }

  /// Draws the pairs on map `name` again (its view's frame changed).
  redraw(name) {
    if (this.baseLayers) {
      this.baseLayers[name].remove();
      this.baseLayers[name] = this.dots(name);
      if (this.baseOn.checked) this.baseLayers[name].addTo(this.views[name].map);
    }
    this.drawManual(name);
    if (this.pendingMarker && name === 'plan') this.pendingMarker.setLatLng(this.views.plan.toLatLng(this.first));
  }

  drawManual(name) {
    const layer = this.manualLayers[name];
    layer.clearLayers();
    for (const pair of this.manual) {
      layer.addLayer(L.marker(this.views[name].toLatLng(pair[name]), {
        icon: L.divIcon({ className: 'fg-pair', html: String(pair.id), iconSize: [20, 20], iconAnchor: [10, 10] }),
        interactive: false, keyboard: false, zIndexOffset: 300,
      }));
    }
  }

  // ---- manual pairs ----

  async loadManual() {
    let answer;
    try {
      answer = await this.api.pairs(false);
    } catch (error) {
      this.status(error.message, 'error');
      return;
    }
    this.state.pairs = answer.pairs;
    this.manual = answer.pairs;
    for (const name of ['plan', 'grid']) this.drawManual(name);
    const rows = answer.pairs.map((pair) => {
      const row = document.createElement('tr');
      row.dataset.pairId = pair.id;
      row.innerHTML = `<td class="id"><span class="fg-pair-chip">${pair.id}</span></td>` +
        `<td class="num">${xy(pair.plan)}</td><td class="num">${xy(pair.grid)}</td>` +
        '<td><button type="button" class="icon-button delete-pair" title="delete this pair">×</button></td>';
      row.querySelector('button').addEventListener('click', () => this.remove(pair.id));
      return row;
    });
    if (rows.length === 0) {
      const row = document.createElement('tr');
      row.innerHTML = '<td colspan="4" class="muted">none yet</td>';
      rows.push(row);
    }
    this.list.replaceChildren(...rows);
  }

  async remove(id) {
    try {
      await this.api.deletePair(id);
      this.status(`pair ${id} deleted; Refit to use the change`, 'info');
    } catch (error) {
      this.status(error.message, 'error');
    }
    await this.loadManual();
  }

  startAdd() {
    this.mode = 'plan';
    this.addButton.textContent = 'Cancel';
    this.addButton.classList.add('active');
    document.body.classList.add('fg-picking');
    this.status('Add pair: click the point on the floorplan (Esc cancels)', 'prompt');
  }

  cancelAdd(message = 'Add pair cancelled') {
    this.mode = null;
    this.first = null;
    this.pendingMarker?.remove();
    this.pendingMarker = null;
    this.addButton.textContent = 'Add pair';
    this.addButton.classList.remove('active');
    document.body.classList.remove('fg-picking');
    if (message) this.status(message, 'info');
  }

  /// Takes a map click while adding a pair; false when not adding (the click sets a goal).
  handleClick(from, latlng) {
    if (!this.mode) return false;
    if (from !== this.mode) {
      this.status(`Add pair: click on the ${this.mode === 'plan' ? 'floorplan' : 'gridmap'} now (Esc cancels)`, 'prompt');
      return true;
    }
    const p = this.views[from].fromLatLng(latlng);
    if (this.mode === 'plan') {
      this.first = [p.x, p.y];
      this.pendingMarker = L.marker(this.views.plan.toLatLng(this.first), {
        icon: L.divIcon({ className: 'fg-pair fg-pair-pending', html: '?', iconSize: [20, 20], iconAnchor: [10, 10] }),
        interactive: false,
      }).addTo(this.views.plan.map);
      this.mode = 'grid';
      this.status(`Add pair: plan ${xy(this.first)} — now click the same point on the gridmap (Esc cancels)`, 'prompt');
      return true;
    }
    const plan = this.first;
    const grid = [p.x, p.y];
    this.cancelAdd(null);
    this.api.addPair(plan, grid).then(
      (answer) => this.status(`pair ${answer.id} added: plan ${xy(plan)} ↔ grid ${xy(grid)}; Refit to use it`, 'info'),
      (error) => this.status(error.message, 'error'),
    ).then(() => this.loadManual());
    return true;
  }

  // ---- refit ----

  async refit() {
    const model = this.modelSelect.value;
    this.refitButton.disabled = true;
    this.fitResult.textContent = `fitting ${model}…`;
    this.status(`fitting ${model}…`, 'info');
    try {
      const fit = await this.api.fit(model);
      this.fitResult.innerHTML = `<b>${fit.model}</b> · ${fit.pairs.toLocaleString('en')} pairs · ` +
        `rms ${fixed(fit.rms_m, 3)} m · ${fixed(fit.seconds, 2)} s`;
      this.status(`refitted ${fit.model} on ${fit.pairs.toLocaleString('en')} pairs`, 'info');
      await this.onRefit(fit);
    } catch (error) {
      this.fitResult.textContent = 'fit failed, model unchanged';
      this.status(error.message, 'error');
    } finally {
      this.refitButton.disabled = false;
    }
  }
}
