// The two Leaflet maps (L.CRS.Simple: lat = y metres, lng = x metres, each in its own frame),
// their linking, and the screen-sized pose icons drawn on both.
import { jacobianFromSteps, localScale } from './geometry.js';

const L = window.L;

/// Leaflet bounds [[ymin, xmin], [ymax, xmax]] of an /api/info map's "bounds".
export function latLngBounds(layout) {
  const [[xmin, ymin], [xmax, ymax]] = layout.bounds;
  return L.latLngBounds([ymin, xmin], [ymax, xmax]);
}

export const toLatLng = (p) => L.latLng(p.y, p.x);

/// A map showing `imageUrl` exactly over `layout.bounds`; resolves once the picture decoded.
export function createMapView(element, name, layout, imageUrl) {
  const bounds = latLngBounds(layout);
  // One cell about 32 px at the closest zoom (CRS.Simple: 2^zoom px per metre).
  const maxZoom = Math.ceil(Math.log2(32 / layout.resolution));
  const map = L.map(element, {
    crs: L.CRS.Simple, zoomSnap: 0.25, zoomDelta: 0.5, wheelPxPerZoomLevel: 90,
    maxZoom, minZoom: -8, attributionControl: false, boxZoom: false, doubleClickZoom: false,
  });
  const image = L.imageOverlay(imageUrl, bounds, {
    className: 'fg-pixelated fg-base-image', interactive: false,
  });
  const loaded = new Promise((resolve, reject) => {
    image.once('load', resolve);
    image.once('error', () => reject(new Error(`${imageUrl} did not load`)));
  });
  image.addTo(map);
  map.fitBounds(bounds, { padding: [12, 12], animate: false });
  map.setMinZoom(Math.floor(map.getZoom()) - 2);
  L.control.scale({ imperial: false, maxWidth: 120, position: 'bottomleft' }).addTo(map);
  return { name, map, bounds, image, layout, loaded };
}

/// Keeps the other map on the mapped centre of the one the operator moves, zoom offset by
/// the mapping's local scale. Moves made here are not echoed back.
export class LinkedViews {
  constructor(views, api, { enabled, onError }) {
    this.views = views;
    this.api = api;
    this.enabled = enabled;
    this.onError = onError;
    this.quiet = new Set();
    this.request = 0;
    for (const [from, to] of [['plan', 'grid'], ['grid', 'plan']]) {
      views[from].map.on('moveend', () => {
        if (!this.quiet.has(from) && this.enabled()) this.follow(from, to);
      });
    }
  }

  /// setView without linking back (moveend fires inside setView when not animated).
  setViewQuietly(name, latlng, zoom) {
    const map = this.views[name].map;
    this.quiet.add(name);
    try {
      map.setView(latlng, zoom ?? map.getZoom(), { animate: false });
    } finally {
      this.quiet.delete(name);
    }
  }

  async follow(from, to) {
    const id = ++this.request;
    const source = this.views[from].map;
    const c = source.getCenter();
    const viewWidth = source.getBounds().getEast() - source.getBounds().getWest();
    const step = Math.min(5, Math.max(0.5, viewWidth / 8));
    let answer;
    try {
      answer = await this.api.map(from, [[c.lng, c.lat], [c.lng + step, c.lat], [c.lng, c.lat + step]]);
    } catch (error) {
      this.onError(`linked views: ${error.message}`);
      return;
    }
    if (id !== this.request) return;  // the operator moved again meanwhile
    const [p0, px, py] = answer.points;
    const J = jacobianFromSteps(p0, px, py, step);
    if (!J) {
      this.onError(`linked views: the ${from} centre does not map to the ${to} (${p0.flag})`, 'warn');
      return;
    }
    const scale = localScale(J);
    const zoom = source.getZoom() - (scale > 0 ? Math.log2(scale) : 0);
    this.setViewQuietly(to, toLatLng(p0), zoom);
  }
}

const SVG = 'http://www.w3.org/2000/svg';

/// A pose icon of fixed screen size: a dot, and an arrow along `theta` (none when null).
/// `kind` picks colours in viewer.css (goal-clicked, goal-mapped, robot).
export function poseIcon(kind, theta, { arrow = 40, extra = '' } = {}) {
  const size = 2 * (arrow + 8);
  const c = size / 2;
  const rotate = theta === null || theta === undefined ? '' :
    `<g transform="rotate(${(-theta * 180) / Math.PI} ${c} ${c})">` +
    (kind === 'robot'
      ? `<path class="fg-robot-body" d="M ${c + 16} ${c} L ${c - 10} ${c - 11} L ${c - 5} ${c} L ${c - 10} ${c + 11} Z"/>`
      : kind === 'goal-clicked'  // its draggable handle is the arrow's head
        ? `<line class="fg-arrow" x1="${c}" y1="${c}" x2="${c + arrow}" y2="${c}"/>`
        : `<line class="fg-arrow" x1="${c}" y1="${c}" x2="${c + arrow - 6}" y2="${c}"/>` +
          `<path class="fg-arrow-head" d="M ${c + arrow} ${c} l -11 -5.5 l 0 11 Z"/>`) +
    '</g>';
  const dot = kind === 'robot'
    ? `<circle class="fg-dot" cx="${c}" cy="${c}" r="3"/>`
    : `<circle class="fg-dot" cx="${c}" cy="${c}" r="6"/>`;
  return L.divIcon({
    className: `fg-pose fg-${kind} ${extra}`,
    html: `<svg xmlns="${SVG}" width="${size}" height="${size}" viewBox="0 0 ${size} ${size}">` +
      rotate + dot + '</svg>',
    iconSize: [size, size], iconAnchor: [c, c],
  });
}

/// Metres covering `pixels` on screen at the map's zoom (CRS.Simple: 2^zoom px per metre).
export const metresForPixels = (map, pixels) => pixels / Math.pow(2, map.getZoom());
