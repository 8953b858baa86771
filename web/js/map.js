// The map: Leaflet on a plain background (no tile request) unless the server has
// offline tiles (GET /tiles/metadata.json answers: --tiles FILE.mbtiles), the
// plan's layers (GET /api/plan: area with holes, no-fly zones, every drone's
// lanes in its colour, the launch point), a scale bar, fitted to the area once.
/* global L */

const PLAN_STYLE = {
  area: { color: '#2b6e2b', weight: 2, fillColor: '#6fbf6f', fillOpacity: 0.08 },
  no_fly: { color: '#b00020', weight: 2, fillColor: '#b00020', fillOpacity: 0.25, dashArray: '4 3' },
};

/** Creates the map in element `id`; returns {map, panes}. */
export function createMap(id) {
  const map = L.map(id, { zoomControl: true, attributionControl: false, preferCanvas: false });
  map.setView([0, 0], 2);
  L.control.scale({ imperial: false, maxWidth: 160 }).addTo(map);
  map.createPane('coverage').style.zIndex = 350;
  map.createPane('lanes').style.zIndex = 380;
  map.createPane('tracks').style.zIndex = 450;
  addTilesIfServed(map);
  return map;
}

/** Adds /tiles/{z}/{x}/{y}.png when the server serves tiles. */
async function addTilesIfServed(map) {
  let metadata;
  try {
    const reply = await fetch('/tiles/metadata.json');
    if (!reply.ok) return;
    metadata = await reply.json();
  } catch {
    return;
  }
  const options = { maxZoom: 22, maxNativeZoom: Number(metadata.maxzoom) || 19 };
  if (metadata.minzoom !== undefined) options.minNativeZoom = Number(metadata.minzoom);
  L.tileLayer('/tiles/{z}/{x}/{y}.png', options).addTo(map);
  document.body.classList.add('has-tiles');
}

/**
 * The plan's layers (GET /api/plan): drawn on the first state, drawn again when
 * the state's `plan` changes (a new plan, lanes handed over), fitted to the area
 * the first time only.
 */
export class PlanLayer {
  constructor(map, colourOf) {
    this.map_ = map;
    this.colourOf_ = colourOf;
    this.group_ = L.layerGroup().addTo(map);
    this.key_ = null;
    this.fitted_ = false;
    this.loading_ = false;
  }

  render(store) {
    if (!store.hasState) return;
    const key = JSON.stringify(store.plan ?? null);
    if (key === this.key_ || this.loading_) return;
    this.loading_ = true;
    this.load_()
      .then(() => {
        this.key_ = key;
        document.body.classList.add('plan-loaded');
      })
      .catch((e) => console.error('fireswarm: plan', e.message))
      .finally(() => (this.loading_ = false));
  }

  async load_() {
    const reply = await fetch('/api/plan');
    if (!reply.ok) throw new Error(`GET /api/plan: ${reply.status}`);
    const plan = await reply.json();
    const features = (plan && plan.features) || [];
    const byKind = (kind) => ({ type: 'FeatureCollection', features: features.filter((f) => f.properties && f.properties.kind === kind) });
    this.group_.clearLayers();
    const area = L.geoJSON(byKind('area'), { style: PLAN_STYLE.area, interactive: false }).addTo(this.group_);
    L.geoJSON(byKind('no_fly'), { style: PLAN_STYLE.no_fly, interactive: false }).addTo(this.group_);
    const lanes = L.geoJSON(byKind('lanes'), {
      pane: 'lanes',
      interactive: false,
      style: (f) => ({ color: this.colourOf_(f.properties.vehicle), weight: 1.5, opacity: 0.55 }),
    }).addTo(this.group_);
    L.geoJSON(byKind('launch'), {
      pointToLayer: (f, latlng) => L.circleMarker(latlng, { radius: 6, color: '#000', weight: 2, fillColor: '#fff', fillOpacity: 1 }),
    }).bindTooltip('launch').addTo(this.group_);
    if (this.fitted_) return;
    const bounds = area.getBounds().isValid() ? area.getBounds() : lanes.getBounds();
    if (bounds.isValid()) {
      this.map_.fitBounds(bounds, { padding: [12, 12] });
      this.fitted_ = true;
    }
  }
}
