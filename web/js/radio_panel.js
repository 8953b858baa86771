// The radio panel: the shared channel's busy fraction, payload rate, retries,
// timeouts, and each vehicle's telemetry age (old ones highlighted); with several
// radio channels (issue 21) a row per channel, a silent one marked.
import { fixed } from './format.js';

/** Telemetry older than this is shown as stale, s. */
const STALE_S = 3;

export class RadioPanel {
  constructor(element) {
    this.element_ = element;
    this.key_ = '';
  }

  render(store) {
    const radio = store.radio;
    if (!radio) return;
    const ages = Object.entries(radio.telemetry_age_s || {}).sort((a, b) => Number(a[0]) - Number(b[0]));
    const channels = radio.channels || [];
    const key = JSON.stringify([radio.busy_fraction, radio.payload_bytes_per_s, radio.retries, radio.timeouts, ages, channels]);
    if (key === this.key_) return;
    this.key_ = key;
    const busy = Number.isFinite(radio.busy_fraction) ? radio.busy_fraction : 0;
    const chips = ages
      .map(([id, age]) => {
        const colour = store.vehicles.get(Number(id))?.colour || '#888';
        const stale = !Number.isFinite(age) || age > STALE_S ? ' stale' : '';
        return `<span class="age${stale}" data-vehicle="${id}"><span class="swatch" style="background:${colour}"></span>${id}: ${fixed(age, 1)} s</span>`;
      })
      .join('');
    const rows = channels.length < 2 ? '' : channels
      .map((c) => {
        const silent = c.silent ? ' <b class="silent">SILENT</b>' : '';
        return `<div class="channel${c.silent ? ' stale' : ''}" data-channel="${c.channel}">ch ${c.channel}: ` +
          `<meter min="0" max="1" value="${Number.isFinite(c.busy_fraction) ? c.busy_fraction : 0}"></meter> ` +
          `${c.vehicles.length} drones · retries ${c.retries} · timeouts ${c.timeouts}${silent}</div>`;
      })
      .join('');
    this.element_.innerHTML =
      `<div class="busy"><span>${channels.length < 2 ? 'channel' : 'busiest channel'} busy</span><meter min="0" max="1" value="${busy}"></meter> <b id="radio-busy">${Math.round(100 * busy)} %</b></div>` +
      `<div>payload ${fixed(radio.payload_bytes_per_s, 0)} B/s · retries <b id="radio-retries">${radio.retries ?? '–'}</b> · timeouts <b id="radio-timeouts">${radio.timeouts ?? '–'}</b></div>` +
      `<div class="channels">${rows}</div>` +
      `<div class="ages" title="telemetry age per vehicle, s">${chips}</div>`;
  }
}
