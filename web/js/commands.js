// Operator commands: per drone (hold, resume, return, land, re-task to a point
// clicked on the map), investigate a clicked point, and the fleet's (start, hold
// all, resume all, return all). Each asks for confirmation listing every target
// by receiver ID and colour, then POSTs /api/command with the operator token,
// signed with the operator's key (command_auth.js: HMAC-SHA256 over the command,
// the server's clock and a nonce; name, key and token are kept in sessionStorage
// and the key is never sent), and follows the command's state (queued, sent,
// acknowledged, failed) in the state's `commands`; a refusal shows its error.
// Targets are receiver IDs taken when the dialog opens, never rows or indices.
import { credentialsProblem, signCommand } from './command_auth.js';
import { clock, droneLabel, swatch } from './format.js';

const TOKEN_KEY = 'fireswarm.operatorToken';
const OPERATOR_KEY = 'fireswarm.operatorId';
const SECRET_KEY = 'fireswarm.operatorKey';

const TITLES = {
  hold: 'Hold', resume: 'Resume', return: 'Return to launch', land: 'Land', retask: 'Re-task',
  investigate: 'Investigate point', start: 'Start the mission', hold_all: 'Hold all',
  resume_all: 'Resume all', return_all: 'Return all to launch', abort: 'Abort',
};
const FLEET = new Set(['start', 'hold_all', 'resume_all', 'return_all', 'abort']);

export class Commands {
  /** `store`: the Store; `map`: the Leaflet map (for clicked points). */
  constructor(store, map) {
    this.store_ = store;
    this.map_ = map;
    this.selected_ = null;
    this.picking_ = null; // kind waiting for a map click
    this.pickTarget_ = null; // receiver ID the picked point is for, or null
    this.refusals_ = []; // {time, kind, targets, error}, newest last
    this.listKey_ = '';
    this.dialog_ = document.getElementById('confirm');
    this.error_ = document.getElementById('command-error');
    this.hint_ = document.getElementById('pick-hint');
    this.list_ = document.getElementById('commands');
    this.setUpToken_();
    for (const button of document.querySelectorAll('[data-fleet]')) {
      button.addEventListener('click', () => this.ask_(button.dataset.fleet, this.store_.vehicleList().map((v) => v.id)));
    }
    for (const button of document.querySelectorAll('[data-drone]')) {
      button.addEventListener('click', () => this.drone_(button.dataset.drone));
    }
    document.querySelector('[data-point="investigate"]').addEventListener('click', () => this.pick_('investigate'));
    map.on('click', (event) => this.mapClicked_(event.latlng));
    document.addEventListener('keydown', (event) => {
      if (event.key === 'Escape') this.pick_(null);
    });
  }

  /** The drone per-drone commands go to: a receiver ID, or null. */
  select(id) {
    this.selected_ = id;
    const label = document.getElementById('selected-drone');
    label.replaceChildren();
    if (id === null) label.textContent = 'no drone selected';
    else label.append(droneLabel(this.store_.vehicles.get(id) || { id }));
    label.dataset.vehicle = id === null ? '' : String(id);
    for (const button of document.querySelectorAll('[data-drone]')) button.disabled = id === null;
  }

  setUpToken_() {
    for (const [id, key] of [['token', TOKEN_KEY], ['operator-id', OPERATOR_KEY], ['operator-key', SECRET_KEY]]) {
      const input = document.getElementById(id);
      input.value = sessionStorage.getItem(key) || '';
      input.addEventListener('input', () => sessionStorage.setItem(key, input.value.trim()));
    }
  }

  /**
   * `body` signed with the operator's name and key from the header, at the
   * server's clock (the latest state's time; docs/lcm.md: the window is on it);
   * unsigned (the server refuses it and says why) without them.
   */
  async sign_(body) {
    const operator = document.getElementById('operator-id').value.trim();
    const key = document.getElementById('operator-key').value.trim();
    if (credentialsProblem(operator, key)) return body;
    const utime = this.store_.timeS ? this.store_.timeS * 1e6 : Date.now() * 1000;
    return signCommand(body, operator, key, utime);
  }

  drone_(kind) {
    if (this.selected_ === null) return;
    if (kind === 'retask') this.pick_('retask');
    else this.ask_(kind, [this.selected_]);
  }

  /** Waits for a map click for `kind` (null: stop waiting); the drone is fixed now. */
  pick_(kind) {
    this.picking_ = kind;
    document.body.classList.toggle('picking', kind !== null);
    this.hint_.hidden = kind === null;
    if (kind !== null) {
      this.pickTarget_ = this.selected_; // investigate without one: the server picks
      const who = this.pickTarget_ === null ? '' : ` (drone ${this.pickTarget_})`;
      this.hint_.textContent = `Click the map: the point to ${kind === 'retask' ? 're-task to' : 'investigate'}${who}. Esc cancels.`;
    }
  }

  mapClicked_(latlng) {
    if (!this.picking_) return;
    const kind = this.picking_;
    const target = this.pickTarget_;
    this.pick_(null);
    const point = { lat: latlng.lat, lon: latlng.lng };
    this.ask_(kind, target === null ? [] : [target], point);
  }

  /** Opens the confirmation dialog; sends the command when confirmed. */
  ask_(kind, targets, point = null) {
    document.getElementById('confirm-title').textContent = TITLES[kind] || kind;
    const detail = document.getElementById('confirm-detail');
    const count = FLEET.has(kind) ? `the whole fleet, ${targets.length} drone${targets.length === 1 ? '' : 's'}` : targets.length ? `drone ${targets[0]}` : 'the server picks the drone';
    detail.textContent = point ? `${count}; point ${point.lat.toFixed(6)}, ${point.lon.toFixed(6)}` : count;
    const list = document.getElementById('confirm-targets');
    list.replaceChildren(
      ...targets.map((id) => {
        const li = document.createElement('li');
        li.dataset.vehicle = String(id);
        li.append(droneLabel(this.store_.vehicles.get(id) || { id }));
        return li;
      }),
    );
    document.getElementById('confirm-reason').value = 'operator';
    this.dialog_.returnValue = '';
    this.dialog_.dataset.kind = kind;
    this.dialog_.onclose = () => {
      if (this.dialog_.returnValue !== 'ok') return;
      const reason = document.getElementById('confirm-reason').value.trim() || 'operator';
      const body = { kind, reason };
      if (!FLEET.has(kind) && targets.length) body.vehicle = targets[0];
      if (point) Object.assign(body, point);
      this.send_(body, targets);
    };
    this.dialog_.showModal();
  }

  async send_(body, targets) {
    const token = document.getElementById('token').value;
    const headers = { 'Content-Type': 'application/json' };
    if (token) headers.Authorization = `Bearer ${token}`;
    let error = '';
    try {
      const signed = await this.sign_(body);
      const reply = await fetch('/api/command', { method: 'POST', headers, body: JSON.stringify(signed) });
      const answer = await reply.json().catch(() => ({}));
      if (reply.status !== 202) error = `${reply.status}: ${answer.error || reply.statusText}`;
    } catch (e) {
      error = `not sent: ${e.message}`;
    }
    if (error) {
      this.refusals_.push({ time: this.store_.timeS, kind: body.kind, targets, error });
      this.error_.textContent = `${TITLES[body.kind] || body.kind} refused: ${error}`;
      this.error_.hidden = false;
    } else {
      this.error_.hidden = true;
    }
    this.render(this.store_);
  }

  /** The commands list: the state's commands and this page's refusals, newest first. */
  render(store) {
    document.body.classList.toggle('read-only', store.readOnly);
    const commands = [...store.commands.values()].sort((a, b) => b.id - a.id);
    const key = JSON.stringify([commands, this.refusals_.length]);
    if (key === this.listKey_) return;
    this.listKey_ = key;
    const items = this.refusals_.map((r) => {
      const li = document.createElement('li');
      li.className = 'state-refused';
      li.dataset.state = 'refused';
      li.textContent = `${clock(r.time)} ${r.kind} ${r.targets.join(', ')}: refused (${r.error})`;
      return li;
    }).reverse();
    for (const command of commands) {
      const li = document.createElement('li');
      li.className = `state-${command.state}`;
      li.dataset.command = String(command.id);
      li.dataset.kind = command.kind;
      li.dataset.state = command.state;
      li.append(`${clock(command.time_s)} #${command.id} ${command.kind}: ${command.state} `);
      for (const target of command.targets || []) {
        const span = document.createElement('span');
        span.className = `target state-${target.state}`;
        span.dataset.vehicle = String(target.vehicle);
        span.title = target.state;
        span.append(swatch(store.vehicles.get(target.vehicle)?.colour), `${target.vehicle}`);
        li.append(span);
      }
      if (command.reason) li.append(` (${command.reason})`);
      items.push(li);
    }
    this.list_.replaceChildren(...items);
  }
}
