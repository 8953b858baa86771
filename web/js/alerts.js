// The alerts list, newest first, coloured by level; only new alerts are added
// to the DOM (the list is bounded).
import { clock } from './format.js';

const SHOWN = 200;

export class AlertList {
  constructor(list) {
    this.list_ = list;
    this.shown_ = new Set();
  }

  render(store) {
    for (const alert of store.alerts) {
      if (this.shown_.has(alert.id)) continue;
      this.shown_.add(alert.id);
      const li = document.createElement('li');
      li.className = `level-${alert.level || 'info'}`;
      li.dataset.kind = alert.kind || '';
      li.dataset.alert = String(alert.id);
      const time = document.createElement('time');
      time.textContent = clock(alert.time_s);
      li.append(time, ` ${alert.text || alert.kind}`);
      this.list_.prepend(li);
    }
    while (this.list_.children.length > SHOWN) {
      const last = this.list_.lastElementChild;
      this.shown_.delete(Number(last.dataset.alert));
      last.remove();
    }
  }
}
