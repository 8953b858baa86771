// Fire tracks on the map: each one's 2-sigma ellipse (a polygon from its
// semi-axes and bearing) and centre, coloured by status (tentative, confirmed,
// rejected), with a popup: drones, views (reports) and the first report's time.
/* global L */
import { ellipse } from './geo.js';
import { clock } from './format.js';

const STATUS_COLOUR = { tentative: '#f0a000', confirmed: '#d00000', rejected: '#808080' };

function popupHtml(track) {
  const drones = (track.drones || []).join(', ') || '–';
  return `<b>Fire track ${track.id}</b>: ${track.status}<br>` +
    `drones ${drones} (${(track.drones || []).length})<br>` +
    `views (reports) ${track.reports}<br>` +
    `first report ${clock(track.first_seen_s)} (${Number(track.first_seen_s).toFixed(1)} s)` +
    (track.ellipse ? `<br>2σ ellipse ${track.ellipse.semi_major_m.toFixed(1)} × ${track.ellipse.semi_minor_m.toFixed(1)} m` : '');
}

export class TrackLayer {
  constructor(map) {
    this.map_ = map;
    this.tracks_ = new Map(); // track ID -> {shape, centre, key}
  }

  render(store) {
    for (const [id, t] of this.tracks_) {
      if (store.tracks.has(id)) continue;
      t.shape.remove();
      t.centre.remove();
      this.tracks_.delete(id);
    }
    for (const track of store.tracks.values()) {
      if (!track.position) continue;
      const key = JSON.stringify([track.status, track.position, track.ellipse, track.reports, track.drones]);
      let t = this.tracks_.get(track.id);
      if (t && t.key === key) continue;
      const colour = STATUS_COLOUR[track.status] || '#000';
      const e = track.ellipse; // null when the covariance is not finite: the centre only
      const outline = e ? ellipse(track.position, e.semi_major_m, e.semi_minor_m, e.bearing_deg) : [];
      const style = { color: colour, weight: 2, fillColor: colour, fillOpacity: 0.2, pane: 'tracks', smoothFactor: 0 };
      if (!t) {
        const shape = L.polygon(outline, style).addTo(this.map_);
        const centre = L.circleMarker(track.position, { radius: 4, color: colour, fillOpacity: 1, pane: 'tracks' }).addTo(this.map_);
        shape.bindPopup('');
        centre.bindPopup('');
        t = { shape, centre, key: '' };
        this.tracks_.set(track.id, t);
      }
      t.key = key;
      t.shape.setLatLngs(outline).setStyle(style);
      t.centre.setLatLng(track.position).setStyle({ color: colour });
      t.shape.setPopupContent(popupHtml(track));
      t.centre.setPopupContent(popupHtml(track));
      for (const element of [t.shape.getElement(), t.centre.getElement()]) {
        if (!element) continue;
        element.dataset.track = String(track.id);
        element.dataset.status = track.status;
      }
      t.shape.getElement()?.classList.add('track-ellipse');
      t.centre.getElement()?.classList.add('track-centre');
    }
  }
}
