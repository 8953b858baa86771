// The page's copy of the command center's state (docs/command_center.md): the
// WebSocket stream's snapshot, then its deltas merged in. Everything the page
// shows is read from here; views subscribe and are called at most once per
// animation frame with the whole store.

/** Trail points kept per drone (the map draws them): bounded, oldest dropped. */
export const TRAIL_POINTS = 300;
/** Alerts kept (newest kept). */
export const ALERTS_KEPT = 500;
/** Entries kept in each of `stats`' arrays (the newest). */
export const STATS_KEPT = 10000;
/** Reconnection delay after the stream closes, ms (doubles up to the max). */
const RECONNECT_MS = 500;
const RECONNECT_MAX_MS = 5000;

export class Store {
  constructor() {
    this.connection = 'connecting'; // connecting | open | closed
    this.source = '';
    this.readOnly = false;
    this.timeS = 0;
    this.mission = null;
    this.radio = null;
    this.refused = 0;
    /** The state's `plan` (what identifies the plan served at /api/plan), if any. */
    this.plan = null;
    /** Receiver ID -> vehicle row (the state's, trail bounded). */
    this.vehicles = new Map();
    /** Track ID -> track. */
    this.tracks = new Map();
    /** Command ID -> command. */
    this.commands = new Map();
    /** Oldest first. */
    this.alerts = [];
    /** The last {"type": "replay"} message, or null when not a replay. */
    this.replay = null;
    this.lastError = '';
    this.listeners_ = [];
    this.frame_ = 0;
    this.ws_ = null;
    this.retryMs_ = RECONNECT_MS;
    this.hasState = false;
    /**
     * Figures of the page (bench/web/command_center_bench.mjs), the newest
     * STATS_KEPT of each, ms: `latency_ms`, per delta applied, the wall clock
     * (Date.now()) once the views have been drawn in the next animation frame
     * minus the delta's `built_unix_ms` (when the server built it); `frame_ms`,
     * the intervals between animation frames; `render_ms`, the time the views
     * took in each frame they drew.
     */
    this.stats = { latency_ms: [], frame_ms: [], render_ms: [], deltas: 0 };
    this.built_ = []; // the built_unix_ms of the deltas applied since the last frame
    this.frameAt_ = 0;
  }

  /** Calls fn(store) after each change (coalesced to one call per frame). */
  subscribe(fn) {
    this.listeners_.push(fn);
  }

  /** Opens the WebSocket stream (same origin) and keeps it open. */
  connect() {
    if (!this.frameAt_) this.countFrames_();
    const scheme = location.protocol === 'https:' ? 'wss' : 'ws';
    const ws = new WebSocket(`${scheme}://${location.host}/ws`);
    this.ws_ = ws;
    ws.onopen = () => {
      this.retryMs_ = RECONNECT_MS;
      this.connection = 'open';
      this.changed_();
    };
    ws.onmessage = (event) => {
      let message;
      try {
        message = JSON.parse(event.data);
      } catch {
        console.warn('fireswarm: a stream message is not JSON');
        return;
      }
      this.apply(message);
    };
    ws.onclose = () => {
      this.ws_ = null;
      this.connection = 'closed';
      this.changed_();
      setTimeout(() => this.connect(), this.retryMs_);
      this.retryMs_ = Math.min(RECONNECT_MAX_MS, this.retryMs_ * 2);
    };
  }

  /** Sends a message to the server over the stream; false when it is not open. */
  send(message) {
    if (!this.ws_ || this.ws_.readyState !== WebSocket.OPEN) return false;
    this.ws_.send(JSON.stringify(message));
    return true;
  }

  /** Merges one stream message (snapshot, delta, replay, error). */
  apply(message) {
    switch (message.type) {
      case 'snapshot':
        this.applySnapshot(message.state || {});
        break;
      case 'delta':
        if (!this.hasState) break;
        this.applyDelta_(message);
        this.stats.deltas += 1;
        if (typeof message.built_unix_ms === 'number') this.built_.push(message.built_unix_ms);
        break;
      case 'replay':
        this.replay = message;
        this.timeS = message.time_s ?? this.timeS;
        break;
      case 'error':
        this.lastError = message.error || 'error';
        console.warn('fireswarm: server says', this.lastError);
        break;
      default:
        return;
    }
    this.changed_();
  }

  /** Replaces everything with a whole state (GET /api/state or a snapshot). */
  applySnapshot(state) {
    this.hasState = true;
    this.source = state.source || '';
    this.readOnly = !!state.read_only;
    this.timeS = state.time_s ?? 0;
    this.mission = state.mission || null;
    this.radio = state.radio || null;
    this.refused = state.refused ?? 0;
    this.plan = state.plan ?? null;
    // A replay's state holds its timeline, so the page knows it with the snapshot.
    this.replay = state.replay ? { type: 'replay', ...state.replay } : null;
    this.vehicles = new Map();
    for (const v of state.vehicles || []) {
      this.vehicles.set(v.id, { ...v, trail: (v.trail || []).slice(-TRAIL_POINTS) });
    }
    this.tracks = new Map((state.tracks || []).map((t) => [t.id, t]));
    this.commands = new Map((state.commands || []).map((c) => [c.id, c]));
    this.alerts = (state.alerts || []).slice(-ALERTS_KEPT);
  }

  applyDelta_(delta) {
    if (delta.time_s !== undefined && delta.time_s !== null) this.timeS = delta.time_s;
    if (delta.mission) this.mission = { ...this.mission, ...delta.mission };
    if (delta.radio) this.radio = delta.radio;
    if (delta.refused !== undefined) this.refused = delta.refused;
    if (delta.plan !== undefined) this.plan = delta.plan;
    for (const row of delta.vehicles || []) {
      const old = this.vehicles.get(row.id);
      const trail = old ? old.trail.concat(row.trail || []) : row.trail || [];
      if (trail.length > TRAIL_POINTS) trail.splice(0, trail.length - TRAIL_POINTS);
      this.vehicles.set(row.id, { ...old, ...row, trail });
    }
    for (const track of delta.tracks || []) this.tracks.set(track.id, track);
    for (const id of delta.removed_tracks || []) this.tracks.delete(id);
    for (const command of delta.commands || []) this.commands.set(command.id, command);
    if (delta.alerts && delta.alerts.length) {
      this.alerts.push(...delta.alerts);
      if (this.alerts.length > ALERTS_KEPT) this.alerts.splice(0, this.alerts.length - ALERTS_KEPT);
    }
  }

  /** Vehicles in receiver-ID order. */
  vehicleList() {
    return [...this.vehicles.values()].sort((a, b) => a.id - b.id);
  }

  // Records every animation frame's interval in stats.frame_ms, for as long as the page lives.
  countFrames_() {
    this.frameAt_ = performance.now();
    const frame = (at) => {
      keep(this.stats.frame_ms, at - this.frameAt_);
      this.frameAt_ = at;
      requestAnimationFrame(frame);
    };
    requestAnimationFrame(frame);
  }

  changed_() {
    if (this.frame_) return;
    const run = () => {
      this.frame_ = 0;
      const start = performance.now();
      for (const fn of this.listeners_) {
        try {
          fn(this);
        } catch (e) {
          console.error('fireswarm: a view failed', e);
        }
      }
      keep(this.stats.render_ms, performance.now() - start);
      const now = Date.now();
      for (const built of this.built_) keep(this.stats.latency_ms, now - built);
      this.built_ = [];
    };
    // A hidden tab gets no animation frames: it still follows, 5 times a second.
    this.frame_ = document.hidden ? setTimeout(run, 200) : requestAnimationFrame(run);
  }
}

// Appends `value` to `list`, dropping the oldest beyond STATS_KEPT.
function keep(list, value) {
  list.push(value);
  if (list.length > STATS_KEPT) list.splice(0, list.length - STATS_KEPT);
}
