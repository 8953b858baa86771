// The drones on the map: each one's position as an arrow rotated to its heading
// (an SVG in an L.divIcon, in its colour, its receiver ID beside it) and its
// bounded trail. Markers are keyed by receiver ID and updated in place.
/* global L */

const ARROW = 'M0,-9 L6,7 L0,3 L-6,7 Z';
/** Trail points redrawn at every update at most (drawTrail_). */
const HEAD_POINTS = 16;

function iconHtml(vehicle) {
  return `<svg viewBox="-10 -10 20 20" width="22" height="22" style="transform: rotate(${vehicle.heading_deg || 0}deg)">` +
    `<path d="${ARROW}" fill="${vehicle.colour || '#888'}" stroke="#000" stroke-width="1.2"/></svg>` +
    `<span class="drone-id">${vehicle.id}</span>`;
}

export class FleetLayer {
  constructor(map, onSelect) {
    this.map_ = map;
    this.onSelect_ = onSelect;
    this.markers_ = new Map(); // receiver ID -> {marker, trail, heading}
    this.selected_ = null;
  }

  select(id) {
    this.selected_ = id;
    for (const [markerId, m] of this.markers_) {
      const element = m.marker.getElement();
      if (element) element.classList.toggle('selected', markerId === id);
    }
  }

  render(store) {
    for (const vehicle of store.vehicles.values()) {
      let m = this.markers_.get(vehicle.id);
      const trail = vehicle.trail || [];
      if (!vehicle.position) {
        if (m) m.marker.remove();
        continue;
      }
      if (!m) {
        const icon = L.divIcon({ className: 'drone', html: iconHtml(vehicle), iconSize: [22, 22], iconAnchor: [11, 11] });
        const marker = L.marker(vehicle.position, { icon, keyboard: false, title: `drone ${vehicle.id}` });
        marker.on('click', () => this.onSelect_(vehicle.id));
        const style = { color: vehicle.colour, weight: 2, opacity: 0.8, interactive: false };
        const body = L.polyline([], style).addTo(this.map_);
        const head = L.polyline([], style).addTo(this.map_);
        marker.addTo(this.map_);
        m = { marker, body, head, headFrom: 0, heading: vehicle.heading_deg, trailLength: -1, lastPoint: null };
        this.markers_.set(vehicle.id, m);
        this.decorate_(m, vehicle);
      }
      if (!this.map_.hasLayer(m.marker)) m.marker.addTo(this.map_);
      m.marker.setLatLng(vehicle.position);
      const element = m.marker.getElement();
      if (m.heading !== vehicle.heading_deg && element) {
        m.heading = vehicle.heading_deg;
        element.querySelector('svg').style.transform = `rotate(${vehicle.heading_deg || 0}deg)`;
      }
      const last = trail.length ? trail[trail.length - 1] : null;
      if (trail.length !== m.trailLength || last !== m.lastPoint) this.drawTrail_(m, trail);
      this.decorate_(m, vehicle);
    }
  }

  // A trail is two polylines: the body, redrawn once every HEAD_POINTS new points,
  // and the head, the points since, redrawn at every update. A polyline's change
  // projects every point of it again: 100 drones' whole trails at every update
  // were most of the page's script time.
  drawTrail_(m, trail) {
    const last = trail.length ? trail[trail.length - 1] : null;
    // Where the head starts in `trail`: found by its first point (the store's
    // trail drops its oldest points as new ones come).
    let from = m.headPoint ? trail.lastIndexOf(m.headPoint) : -1;
    if (from < 0 || trail.length - from > HEAD_POINTS) {
      m.body.setLatLngs(trail);
      from = Math.max(0, trail.length - 1);
      m.headPoint = trail[from] || null;
    }
    m.head.setLatLngs(trail.slice(from));
    m.trailLength = trail.length;
    m.lastPoint = last;
  }

  // Writes the marker element's attributes, only those that changed (each write
  // costs a style recalculation at 250 drones).
  decorate_(m, vehicle) {
    const element = m.marker.getElement();
    if (!element) return;
    const set = (key, value) => {
      if (element.dataset[key] !== value) element.dataset[key] = value;
    };
    set('vehicle', String(vehicle.id));
    set('lat', String(vehicle.position[0]));
    set('lon', String(vehicle.position[1]));
    set('link', vehicle.link || '');
    const lost = vehicle.link === 'lost';
    if (element.classList.contains('lost') !== lost) element.classList.toggle('lost', lost);
    const selected = vehicle.id === this.selected_;
    if (element.classList.contains('selected') !== selected) element.classList.toggle('selected', selected);
  }
}
