// Picture layers the server computes from the current model: the plan's walls warped onto the
// gridmap (/api/overlay.png) and the uncertainty/error heat map on the floorplan (/api/heatmap).
// Each is a view's Picture: drawn in the view's frame (turned with the gridmap), above its map.
import { fixed } from './geometry.js';

const L = window.L;

const QUANTITY_NAMES = {
  std_m: 'predicted std',
  nearest_pair_m: 'distance to the nearest pair',
  error_m: 'error vs. ground truth',
};

/// A picture over `view`'s map, drawn now; a failure goes to `onError`.
function showPicture(view, url, opacity, onError) {
  const picture = view.addPicture(url, { pane: 'fg-layers', opacity });
  picture.draw().catch((error) => onError(error.message));
  return picture;
}

export class WallOverlay {
  constructor({ views, status }) {
    this.views = views;
    this.status = status;
    this.checkbox = document.getElementById('overlay-on');
    this.opacity = document.getElementById('overlay-opacity');
    this.picture = null;
    this.version = 0;
    this.checkbox.addEventListener('change', () => this.update());
    this.opacity.addEventListener('input', () => this.picture?.setOpacity(this.opacity.value / 100));
  }

  setInfo(info) {
    this.available = Boolean(info.layers && info.layers.overlay);
    this.version = info.model_version ?? 0;
    this.checkbox.disabled = !this.available;
    this.opacity.disabled = !this.available;
    this.checkbox.closest('label').title = this.available
      ? "the plan's walls drawn on the gridmap through the model" : 'this server has no wall overlay';
    this.update();
  }

  update() {
    const url = `/api/overlay.png?v=${this.version}`;
    if (!this.available || !this.checkbox.checked) {
      this.picture?.remove();
      this.picture = null;
      return;
    }
    if (this.picture && this.picture.url === url) return;
    this.picture?.remove();
    this.picture = showPicture(this.views.grid, url, this.opacity.value / 100, (m) => this.status(m, 'error'));
  }
}

export class HeatMap {
  constructor({ views, api, status }) {
    this.views = views;
    this.api = api;
    this.status = status;
    this.checkbox = document.getElementById('heatmap-on');
    this.kind = document.getElementById('heatmap-kind');
    this.opacity = document.getElementById('heatmap-opacity');
    this.layers = [];
    this.picture = null;
    this.legend = L.control({ position: 'bottomright' });
    this.legend.onAdd = () => L.DomUtil.create('div', 'fg-legend');
    this.checkbox.addEventListener('change', () => this.update());
    this.kind.addEventListener('change', () => this.update());
    this.opacity.addEventListener('input', () => this.picture?.setOpacity(this.opacity.value / 100));
  }

  /// Reads the layer list again (after a refit); resolves when the picture is in place.
  async setInfo(info) {
    this.available = Boolean(info.layers && info.layers.heatmap);
    for (const control of [this.checkbox, this.kind, this.opacity]) control.disabled = !this.available;
    this.checkbox.closest('label').title = this.available ? '' : 'this server has no heat map';
    if (!this.available) {
      this.layers = [];
      return this.update();
    }
    try {
      const answer = await this.api.heatmap();
      this.layers = answer.layers || [];
    } catch (error) {
      this.layers = [];
      this.status(`heat map: ${error.message}`, 'error');
    }
    const chosen = this.kind.value || 'std';
    this.kind.replaceChildren(...this.layers.map((layer) => {
      const option = document.createElement('option');
      option.value = layer.kind;
      option.textContent = layer.kind === 'std' ? 'uncertainty' : layer.kind === 'error' ? 'error vs. truth' : layer.kind;
      option.title = QUANTITY_NAMES[layer.quantity] || layer.quantity;
      return option;
    }));
    if (this.layers.some((layer) => layer.kind === chosen)) this.kind.value = chosen;
    this.kind.disabled = this.layers.length === 0;
    return this.update();
  }

  current() {
    return this.layers.find((layer) => layer.kind === this.kind.value) || this.layers[0] || null;
  }

  update() {
    const layer = this.current();
    if (!this.checkbox.checked || !layer) {
      this.picture?.remove();
      this.picture = null;
      this.legend.remove();
      return;
    }
    if (!this.picture || this.picture.url !== layer.url) {
      this.picture?.remove();
      this.picture = showPicture(this.views.plan, layer.url, this.opacity.value / 100,
                                 (m) => this.status(m, 'error'));
    }
    this.legend.addTo(this.views.plan.map);
    this.drawLegend(layer);
  }

  drawLegend(layer) {
    const clip = layer.clip_m;
    const element = this.legend.getContainer();
    element.innerHTML =
      `<div class="fg-legend-title">${QUANTITY_NAMES[layer.quantity] || layer.quantity} (m)</div>` +
      '<div class="fg-legend-bar"></div>' +
      `<div class="fg-legend-ticks"><span>0</span><span>${fixed(clip / 2, 2)}</span><span>≥ ${fixed(clip, 2)}</span></div>`;
  }
}
