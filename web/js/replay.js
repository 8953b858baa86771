// The replay timeline (read-only sources): play/pause, a scrub slider and the
// speed, sent to the server as {"type": "replay", ...} over the stream; the
// server's {"type": "replay"} messages move the slider.
import { clock } from './format.js';

export class Timeline {
  constructor(store) {
    this.store_ = store;
    this.element_ = document.getElementById('timeline');
    this.play_ = document.getElementById('replay-play');
    this.scrub_ = document.getElementById('replay-scrub');
    this.speed_ = document.getElementById('replay-speed');
    this.time_ = document.getElementById('replay-time');
    this.dragging_ = false;
    this.play_.addEventListener('click', () => {
      const playing = this.store_.replay && this.store_.replay.playing;
      this.send_({ action: playing ? 'pause' : 'play' });
    });
    this.scrub_.addEventListener('input', () => {
      this.dragging_ = true;
      this.time_.textContent = clock(Number(this.scrub_.value));
    });
    this.scrub_.addEventListener('change', () => {
      this.dragging_ = false;
      this.send_({ action: 'seek', time_s: Number(this.scrub_.value) });
    });
    this.speed_.addEventListener('change', () => {
      const playing = this.store_.replay && this.store_.replay.playing;
      this.send_({ action: playing ? 'play' : 'pause' });
    });
  }

  send_(fields) {
    this.store_.send({ type: 'replay', speed: Number(this.speed_.value), ...fields });
  }

  render(store) {
    const replay = store.replay;
    this.element_.hidden = !store.readOnly && !replay;
    if (!replay) return;
    this.play_.textContent = replay.playing ? 'Pause' : 'Play';
    this.scrub_.min = String(replay.start_s ?? 0);
    this.scrub_.max = String(replay.end_s ?? 0);
    if (!this.dragging_) {
      this.scrub_.value = String(replay.time_s ?? 0);
      this.time_.textContent = `${clock(replay.time_s)} / ${clock(replay.end_s)}`;
    }
    if (document.activeElement !== this.speed_ && replay.speed) {
      const speed = String(replay.speed);
      if ([...this.speed_.options].some((o) => o.value === speed)) this.speed_.value = speed;
    }
  }
}
