// A server picture (a PNG filling its map's bounds, one pixel per cell) on a map view, drawn in
// the view's display frame: the PNG itself over the bounds when the view is unturned; else the
// PNG drawn onto a canvas turned like the view (nearest cell, at 2x the picture's pixels so the
// cells stay crisp), shown as an image over the turned picture's bounding box.
const L = window.L;

const CANVAS_SCALE = 2;             // canvas pixels per picture pixel
const MAX_CANVAS_PIXELS = 32e6;     // a larger map gets a smaller scale (memory, encoding time)

function loadImage(url) {
  const image = new Image();
  image.src = url;
  return image.decode().then(() => image, () => { throw new Error(`${url} did not load`); });
}

/// A blob: URL of `image` turned by `angle` (radians, counterclockwise in the map's y-up frame)
/// about its centre, on a canvas just holding the turned picture.
async function turnedPictureUrl(image, angle) {
  const width = image.naturalWidth;
  const height = image.naturalHeight;
  const cos = Math.abs(Math.cos(angle));
  const sin = Math.abs(Math.sin(angle));
  const boxWidth = width * cos + height * sin;   // the turned picture's box, in picture pixels
  const boxHeight = width * sin + height * cos;
  const scale = Math.min(CANVAS_SCALE, Math.sqrt(MAX_CANVAS_PIXELS / (boxWidth * boxHeight)));
  const canvas = document.createElement('canvas');
  canvas.width = Math.ceil(boxWidth * scale);
  canvas.height = Math.ceil(boxHeight * scale);
  const context = canvas.getContext('2d');
  context.imageSmoothingEnabled = false;
  // The box fills the canvas exactly (the rounding up stretches it by under a pixel), as the
  // image overlay stretches the canvas over the box's metres.
  context.setTransform(canvas.width / boxWidth, 0, 0, canvas.height / boxHeight, 0, 0);
  context.translate(boxWidth / 2, boxHeight / 2);
  context.rotate(-angle);  // the canvas's y points down: a counterclockwise turn is negative
  context.drawImage(image, -width / 2, -height / 2);
  const blob = await new Promise((resolve) => canvas.toBlob(resolve, 'image/png'));
  if (!blob) throw new Error('the turned picture could not be encoded');
  return URL.createObjectURL(blob);
}

export class Picture {
  /// Not drawn until draw(). `view`: a MapView (its turn, its picture bounds, its map).
  constructor(view, url, { pane, className = 'fg-pixelated', opacity = 1 } = {}) {
    this.view = view;
    this.url = url;
    this.options = { pane, className, interactive: false };
    this.opacity = opacity;
    this.layer = null;     // the L.imageOverlay on the map
    this.source = null;    // the PNG, decoded once for turning
    this.turned = null;    // {turn, url}: the last turned canvas (kept to turn back at once)
    this.generation = 0;
    this.drawn = Promise.resolve();
  }

  setOpacity(opacity) {
    this.opacity = opacity;
    this.layer?.setOpacity(opacity);
  }

  /// (Re)draws for the view's frame now; resolves once the picture is on the map (an earlier
  /// draw still running is dropped), rejects when it does not load.
  draw() {
    this.drawn = this.render(++this.generation);
    return this.drawn;
  }

  async render(generation) {
    const stale = () => generation !== this.generation;
    const turn = this.view.turn;  // the view shows its map turned by -turn
    let src = this.url;
    let replaced = null;          // a turned canvas to let go once the new one is shown
    if (turn !== 0 && this.turned?.turn === turn) {
      src = this.turned.url;
    } else if (turn !== 0) {
      this.source ??= loadImage(this.url);
      const image = await this.source.catch((error) => {
        this.source = null;  // try again next time
        throw error;
      });
      src = await turnedPictureUrl(image, -turn);
      if (stale()) {
        URL.revokeObjectURL(src);
        return;
      }
      replaced = this.turned;
      this.turned = { turn, url: src };
    }
    if (stale()) return;
    const layer = L.imageOverlay(src, this.view.pictureBounds(), { ...this.options, opacity: this.opacity });
    await new Promise((resolve, reject) => {
      layer.once('load', resolve);
      layer.once('error', () => {
        layer.remove();
        reject(new Error(`${this.url} did not load`));
      });
      layer.addTo(this.view.map);
    });
    if (stale()) {
      layer.remove();
      return;
    }
    // The new picture is in place: the old one goes.
    this.layer?.remove();
    this.layer = layer;
    if (replaced) URL.revokeObjectURL(replaced.url);
  }

  remove() {
    this.generation++;
    this.layer?.remove();
    this.layer = null;
    if (this.turned) URL.revokeObjectURL(this.turned.url);
    this.turned = null;
    this.view.pictures.delete(this);
  }
}
