// The fleet table: one row per receiver ID, sortable by any column, updated in
// place (cells are rewritten only when their text changes, rows moved only when
// the order changes) so that 250 drones stay cheap. A row is keyed by its
// receiver ID (data-vehicle): sorting or a lost link never changes which drone a
// selected row means.
import { fixed, swatch } from './format.js';

const LINK_ORDER = { ok: 0, degraded: 1, lost: 2, never: 3 };

/** Sort key of a vehicle for a column. */
function sortValue(vehicle, key) {
  if (key === 'link') return LINK_ORDER[vehicle.link] ?? 4;
  const value = vehicle[key];
  return value === null || value === undefined ? -Infinity : value;
}

/** The link and the seconds since the last telemetry, at the state's time. */
function linkText(vehicle, timeS) {
  const heard = Number.isFinite(vehicle.heard_s) && Number.isFinite(timeS);
  const ago = heard ? ` ${Math.max(0, timeS - vehicle.heard_s).toFixed(1)} s` : '';
  return `${vehicle.link || '–'}${vehicle.link === 'never' ? '' : ago}`;
}

/** The text of each column after the first (the ID cell has a swatch): (vehicle, time_s). */
const COLUMNS = [
  (v) => v.mode || '–',
  (v) => fixed(v.battery_percent, 0),
  (v) => fixed(v.altitude_m, 0),
  (v) => fixed(v.speed_mps, 1),
  linkText,
  (v) => fixed(v.telemetry_hz, 1),
  (v) => (Number.isFinite(v.progress) ? `${Math.round(100 * v.progress)} %` : '–'),
  (v) => v.task_text || v.task || '',
];

export class FleetTable {
  /** `table`: the #fleet element; onSelect(id) is called when a row is clicked. */
  constructor(table, onSelect) {
    this.body_ = table.tBodies[0];
    this.headers_ = [...table.tHead.rows[0].cells];
    this.rows_ = new Map(); // receiver ID -> {tr, cells, texts}
    this.sortKey_ = 'id';
    this.ascending_ = true;
    this.selected_ = null;
    this.order_ = '';
    this.onSelect_ = onSelect;
    for (const th of this.headers_) {
      th.addEventListener('click', () => this.sortBy(th.dataset.key));
    }
    this.body_.addEventListener('click', (event) => {
      const tr = event.target.closest('tr[data-vehicle]');
      if (tr) this.onSelect_(Number(tr.dataset.vehicle));
    });
    this.last_ = null;
  }

  /** Sorts by `key` (a vehicle field); the same key again reverses the order. */
  sortBy(key) {
    if (this.sortKey_ === key) this.ascending_ = !this.ascending_;
    else [this.sortKey_, this.ascending_] = [key, true];
    for (const th of this.headers_) {
      th.removeAttribute('aria-sort');
      if (th.dataset.key === this.sortKey_) {
        th.setAttribute('aria-sort', this.ascending_ ? 'ascending' : 'descending');
      }
    }
    if (this.last_) this.render(this.last_);
  }

  /** Marks the row of receiver ID `id` (or none) as selected. */
  select(id) {
    this.selected_ = id;
    for (const [rowId, row] of this.rows_) {
      row.tr.classList.toggle('selected', rowId === id);
      row.tr.setAttribute('aria-selected', String(rowId === id));
    }
  }

  render(store) {
    this.last_ = store;
    const seen = new Set();
    for (const vehicle of store.vehicles.values()) {
      seen.add(vehicle.id);
      let row = this.rows_.get(vehicle.id);
      if (!row) row = this.addRow_(vehicle);
      this.updateRow_(row, vehicle, store.timeS);
    }
    for (const [id, row] of this.rows_) {
      if (!seen.has(id)) {
        row.tr.remove();
        this.rows_.delete(id);
      }
    }
    this.reorder_(store);
  }

  addRow_(vehicle) {
    const tr = document.createElement('tr');
    tr.dataset.vehicle = String(vehicle.id);
    tr.setAttribute('aria-selected', String(vehicle.id === this.selected_));
    tr.classList.toggle('selected', vehicle.id === this.selected_);
    const idCell = document.createElement('td');
    const sw = swatch(vehicle.colour);
    idCell.append(sw, String(vehicle.id));
    tr.append(idCell);
    const cells = COLUMNS.map(() => tr.appendChild(document.createElement('td')));
    const row = { tr, cells, texts: COLUMNS.map(() => null), swatch: sw, link: null };
    this.rows_.set(vehicle.id, row);
    this.order_ = ''; // a new row: place it
    return row;
  }

  updateRow_(row, vehicle, timeS) {
    COLUMNS.forEach((column, i) => {
      const text = column(vehicle, timeS);
      if (row.texts[i] !== text) {
        row.texts[i] = text;
        row.cells[i].textContent = text;
      }
    });
    if (row.link !== vehicle.link) {
      row.link = vehicle.link;
      row.tr.dataset.link = vehicle.link || '';
      row.tr.classList.toggle('lost', vehicle.link === 'lost' || vehicle.link === 'never');
      row.cells[4].className = `link-${vehicle.link}`;
    }
    row.swatch.style.background = vehicle.colour || '#888';
    const low = Number.isFinite(vehicle.battery_percent) && vehicle.battery_percent < 25;
    row.cells[1].classList.toggle('low', low);
  }

  reorder_(store) {
    const key = this.sortKey_;
    const sign = this.ascending_ ? 1 : -1;
    const ids = [...store.vehicles.values()]
      .sort((a, b) => {
        const x = sortValue(a, key);
        const y = sortValue(b, key);
        if (x < y) return -sign;
        if (x > y) return sign;
        return a.id - b.id; // ties by receiver ID, so the order is stable
      })
      .map((v) => v.id);
    const order = ids.join(',');
    if (order === this.order_) return;
    this.order_ = order;
    for (const id of ids) this.body_.appendChild(this.rows_.get(id).tr);
  }
}
