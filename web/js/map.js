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

/** Draws the plan's GeoJSON and fits the map to the area (once). */
export async function loadPlan(map, colourOf) {
  const reply = await fetch('/api/plan');
  if (!reply.ok) throw new Error(`GET /api/plan: ${reply.status}`);
  const plan = await reply.json();
  const features = plan.features || [];
  const byKind = (kind) => ({ type: 'FeatureCollection', features: features.filter((f) => f.properties && f.properties.kind === kind) });
  const area = L.geoJSON(byKind('area'), { style: PLAN_STYLE.area, interactive: false }).addTo(map);
  L.geoJSON(byKind('no_fly'), { style: PLAN_STYLE.no_fly, interactive: false }).addTo(map);
  const lanes = L.geoJSON(byKind('lanes'), {
    pane: 'lanes',
    interactive: false,
    style: (f) => ({ color: colourOf(f.properties.vehicle), weight: 1.5, opacity: 0.55 }),
  }).addTo(map);
  L.geoJSON(byKind('launch'), {
    pointToLayer: (f, latlng) => L.circleMarker(latlng, { radius: 6, color: '#000', weight: 2, fillColor: '#fff', fillOpacity: 1 }),
  }).bindTooltip('launch').addTo(map);
  const bounds = area.getBounds();
  if (bounds.isValid()) map.fitBounds(bounds, { padding: [12, 12] });
  else if (lanes.getBounds().isValid()) map.fitBounds(lanes.getBounds());
  return { lanes, count: features.length };
}
