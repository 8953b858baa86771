// The coverage achieved so far as an overlay: GET /api/coverage (a bitset of
// seen cells, row-major from the south-west, bit i = byte i/8, bit i%8 from the
// least significant) drawn one pixel per cell on a canvas, laid over the raster's
// corners' bounds, refreshed every few seconds.
/* global L */

/** Refresh period of the overlay, ms. */
export const COVERAGE_REFRESH_MS = 4000;
const SEEN_RGBA = [40, 120, 255, 110];

function decode(base64) {
  const text = atob(base64 || '');
  const bytes = new Uint8Array(text.length);
  for (let i = 0; i < text.length; i++) bytes[i] = text.charCodeAt(i);
  return bytes;
}

/** Draws the raster into a data: URL (north up). */
export function rasterUrl(raster) {
  const { rows, cols } = raster;
  const canvas = document.createElement('canvas');
  canvas.width = cols;
  canvas.height = rows;
  const context = canvas.getContext('2d');
  const image = context.createImageData(cols, rows);
  const bits = decode(raster.seen);
  for (let r = 0; r < rows; r++) {
    const y = rows - 1 - r; // row 0 is the southernmost
    for (let c = 0; c < cols; c++) {
      const i = r * cols + c;
      if (!(bits[i >> 3] & (1 << (i & 7)))) continue;
      image.data.set(SEEN_RGBA, 4 * (y * cols + c));
    }
  }
  context.putImageData(image, 0, 0);
  return canvas.toDataURL();
}

export class CoverageLayer {
  constructor(map) {
    this.map_ = map;
    this.overlay_ = null;
    this.timer_ = 0;
  }

  start() {
    const tick = async () => {
      try {
        await this.refresh();
      } catch (e) {
        console.warn('fireswarm: coverage', e.message);
      }
      this.timer_ = setTimeout(tick, COVERAGE_REFRESH_MS);
    };
    tick();
  }

  async refresh() {
    const reply = await fetch('/api/coverage');
    if (!reply.ok) return;
    const raster = await reply.json();
    if (!raster || !raster.rows || !raster.cols || !raster.corners) return; // no plan yet
    const bounds = L.latLngBounds(raster.corners);
    const url = rasterUrl(raster);
    if (!this.overlay_) {
      this.overlay_ = L.imageOverlay(url, bounds, { pane: 'coverage', interactive: false, className: 'coverage' }).addTo(this.map_);
    } else {
      this.overlay_.setUrl(url);
      this.overlay_.setBounds(bounds);
    }
  }
}
