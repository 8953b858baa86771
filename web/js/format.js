// Small formatting helpers shared by the views.

/** A number with `digits` decimals, or an en dash when missing/non-finite. */
export function fixed(value, digits = 0) {
  return Number.isFinite(value) ? value.toFixed(digits) : '–';
}

/** A fraction 0..1 as a whole percentage. */
export function percent(fraction) {
  return Number.isFinite(fraction) ? `${Math.round(100 * fraction)} %` : '–';
}

/** Simulated or publisher time, s, as m:ss (h:mm:ss past an hour). */
export function clock(seconds) {
  if (!Number.isFinite(seconds)) return '–';
  const s = Math.max(0, Math.floor(seconds));
  const h = Math.floor(s / 3600);
  const m = Math.floor((s % 3600) / 60);
  const ss = String(s % 60).padStart(2, '0');
  return h > 0 ? `${h}:${String(m).padStart(2, '0')}:${ss}` : `${m}:${ss}`;
}

/** A colour swatch element for a drone. */
export function swatch(colour) {
  const span = document.createElement('span');
  span.className = 'swatch';
  span.style.background = colour || '#888';
  return span;
}

/** "drone 3" with its colour swatch, as a DOM fragment. */
export function droneLabel(vehicle) {
  const fragment = document.createDocumentFragment();
  fragment.append(swatch(vehicle && vehicle.colour), ` drone ${vehicle ? vehicle.id : '?'}`);
  return fragment;
}
