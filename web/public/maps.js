// The two map views (Leaflet maps in L.CRS.Simple: lat = y metres, lng = x metres), their
// linking, and the screen-sized pose icons drawn on both.
//
// Each view draws its map in a display frame: the floorplan always in its own frame; the gridmap
// in its own frame too, or, "turned like the plan", turned by -turn about its picture's centre
// so that the plan's x axis looks horizontal on both maps. A MapView's toLatLng and fromLatLng
// are the one place where a map's metres become the Leaflet map's LatLng and back: every click,
// marker, pair, picture and linked move goes through them, so what reaches the API is always in
// the map's own frame.
import { jacobianFromSteps, localScale, rotateAbout, turnedBox } from './geometry.js';
import { Picture } from './picture.js';

const L = window.L;

/// Leaflet bounds [[ymin, xmin], [ymax, xmax]] of a box [[xmin, ymin], [xmax, ymax]].
function latLngBounds([[xmin, ymin], [xmax, ymax]]) {
  return L.latLngBounds([ymin, xmin], [ymax, xmax]);
}

export class MapView {
  /// A map showing `imageUrl` over `layout.bounds` (an /api/info map), turned by `turn`;
  /// `loaded` resolves once the picture is drawn.
  constructor(element, name, layout, imageUrl, { turn = 0 } = {}) {
    this.name = name;
    this.layout = layout;
    const [[xmin, ymin], [xmax, ymax]] = layout.bounds;
    this.centre = { x: (xmin + xmax) / 2, y: (ymin + ymax) / 2 };  // of the turn
    this.turn = turn;
    this.pictures = new Set();
    this.turnListeners = [];
    this.quiet = false;  // a move of ours: linked views do not echo it
    // One cell about 32 px at the closest zoom (CRS.Simple: 2^zoom px per metre).
    const maxZoom = Math.ceil(Math.log2(32 / layout.resolution));
    this.map = L.map(element, {
      crs: L.CRS.Simple, zoomSnap: 0.25, zoomDelta: 0.5, wheelPxPerZoomLevel: 90,
      maxZoom, minZoom: -8, attributionControl: false, boxZoom: false, doubleClickZoom: false,
    });
    // Pictures below everything drawn over them: the map's own, then the server's layers.
    for (const [pane, zIndex] of [['fg-base', 250], ['fg-layers', 300]]) {
      this.map.createPane(pane).style.zIndex = zIndex;
    }
    this.image = this.addPicture(imageUrl, { pane: 'fg-base', className: 'fg-pixelated fg-base-image' });
    this.loaded = this.image.draw();
    this.map.fitBounds(this.pictureBounds(), { padding: [12, 12], animate: false });
    this.map.setMinZoom(Math.floor(this.map.getZoom()) - 2);
    L.control.scale({ imperial: false, maxWidth: 120, position: 'bottomleft' }).addTo(this.map);
  }

  /// The Leaflet LatLng of a point {x, y} or [x, y] in the map's own frame.
  toLatLng(p) {
    const [x, y] = Array.isArray(p) ? p : [p.x, p.y];
    const d = rotateAbout({ x, y }, this.centre, -this.turn);
    return L.latLng(d.y, d.x);
  }

  /// The point {x, y} in the map's own frame at a Leaflet LatLng.
  fromLatLng(latlng) {
    return rotateAbout({ x: latlng.lng, y: latlng.lat }, this.centre, this.turn);
  }

  /// A heading in the map's frame as drawn on screen (counterclockwise from east).
  toDisplayAngle(theta) {
    return theta - this.turn;
  }

  /// The LatLng box of the picture as drawn: its bounds, turned.
  pictureBounds() {
    return latLngBounds(this.turn === 0 ? this.layout.bounds : turnedBox(this.layout.bounds, this.centre, -this.turn));
  }

  /// A picture filling the map's bounds, kept in the view's frame; draw() puts it on the map.
  addPicture(url, options) {
    const picture = new Picture(this, url, options);
    this.pictures.add(picture);
    return picture;
  }

  /// Calls `listener(turn)` after each change of the turn (to redraw what it put on the map).
  onTurn(listener) {
    this.turnListeners.push(listener);
  }

  /// Draws the map turned by -`turn` (0: its own frame), centred on the same point of the map;
  /// resolves when the pictures are redrawn.
  setTurn(turn) {
    if (turn === this.turn) return this.loaded;
    const centre = this.fromLatLng(this.map.getCenter());
    this.turn = turn;
    this.setViewQuietly(this.toLatLng(centre));
    this.loaded = Promise.all([...this.pictures].map((picture) => picture.draw()));
    for (const listener of this.turnListeners) listener(turn);
    return this.loaded;
  }

  /// setView that linked views do not follow (moveend fires inside setView when not animated).
  setViewQuietly(latlng, zoom) {
    this.quiet = true;
    try {
      this.map.setView(latlng, zoom ?? this.map.getZoom(), { animate: false });
    } finally {
      this.quiet = false;
    }
  }
}

/// Keeps the other map on the mapped centre of the one the operator moves, zoom offset by
/// the mapping's local scale. Moves made here are not echoed back.
export class LinkedViews {
  constructor(views, api, { enabled, onError }) {
    this.views = views;
    this.api = api;
    this.enabled = enabled;
    this.onError = onError;
    this.request = 0;
    for (const [from, to] of [['plan', 'grid'], ['grid', 'plan']]) {
      views[from].map.on('moveend', () => {
        if (!views[from].quiet && this.enabled()) this.follow(from, to);
      });
    }
  }

  async follow(from, to) {
    const id = ++this.request;
    const source = this.views[from];
    const c = source.fromLatLng(source.map.getCenter());
    const shown = source.map.getBounds();
    const step = Math.min(5, Math.max(0.5, (shown.getEast() - shown.getWest()) / 8));
    let answer;
    try {
      answer = await this.api.map(from, [[c.x, c.y], [c.x + step, c.y], [c.x, c.y + step]]);
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
    const zoom = source.map.getZoom() - (scale > 0 ? Math.log2(scale) : 0);
    const target = this.views[to];
    target.setViewQuietly(target.toLatLng(p0), zoom);
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
