// Local metres around a point <-> WGS84 degrees, for shapes the page draws (a
// track's ellipse): a spherical approximation, exact enough over a few hundred
// metres.

const EARTH_RADIUS_M = 6378137;
const DEG = Math.PI / 180;

/** [lat, lon] of the point `east_m`, `north_m` from `[lat0, lon0]`. */
export function offset([lat0, lon0], east_m, north_m) {
  const lat = lat0 + north_m / EARTH_RADIUS_M / DEG;
  const lon = lon0 + east_m / (EARTH_RADIUS_M * Math.cos(lat0 * DEG)) / DEG;
  return [lat, lon];
}

/**
 * The outline of an ellipse centred on `centre` ([lat, lon]): semi-axes in m,
 * the major axis `bearing_deg` clockwise from north; `points` vertices.
 */
export function ellipse(centre, semiMajor_m, semiMinor_m, bearing_deg, points = 48) {
  const b = bearing_deg * DEG;
  const major = [Math.sin(b), Math.cos(b)]; // east, north
  const minor = [Math.cos(b), -Math.sin(b)];
  const outline = [];
  for (let i = 0; i < points; i++) {
    const phi = (2 * Math.PI * i) / points;
    const u = semiMajor_m * Math.cos(phi);
    const v = semiMinor_m * Math.sin(phi);
    outline.push(offset(centre, u * major[0] + v * minor[0], u * major[1] + v * minor[1]));
  }
  return outline;
}
