// The command-center page: one store fed by the stream, and the views it drives.
import { Store } from './store.js';
import { FleetTable } from './fleet_table.js';
import { PlanLayer, createMap } from './map.js';
import { FleetLayer } from './map_fleet.js';
import { TrackLayer } from './map_tracks.js';
import { CoverageLayer } from './coverage.js';
import { AlertList } from './alerts.js';
import { RadioPanel } from './radio_panel.js';
import { Commands } from './commands.js';
import { Timeline } from './replay.js';
import { clock, percent } from './format.js';

const store = new Store();
const map = createMap('map');
const commands = new Commands(store, map);
let select = () => {};
const table = new FleetTable(document.getElementById('fleet'), (id) => select(id));
const fleet = new FleetLayer(map, (id) => select(id));
select = (id) => {
  table.select(id);
  fleet.select(id);
  commands.select(id);
};
const plan = new PlanLayer(map, (id) => store.vehicles.get(id)?.colour || '#555');
const tracks = new TrackLayer(map);
const coverage = new CoverageLayer(map);
const alerts = new AlertList(document.getElementById('alerts'));
const radio = new RadioPanel(document.getElementById('radio'));
const timeline = new Timeline(store);

function header(s) {
  const connection = document.getElementById('connection');
  connection.textContent = s.connection === 'open' ? 'live' : s.connection;
  connection.dataset.state = s.connection;
  document.getElementById('source').textContent = s.source + (s.readOnly ? ' (read-only)' : '');
  const m = s.mission;
  const text = m
    ? `${m.state} · t ${clock(s.timeS)} · coverage ${percent(m.coverage)} · drones ${m.vehicles_active} active, ${m.vehicles_lost} lost · fires ${m.fires_confirmed} confirmed, ${m.fires_tentative} tentative · refused ${s.refused}`
    : '';
  const mission = document.getElementById('mission');
  if (mission.textContent !== text) mission.textContent = text;
  mission.dataset.state = m ? m.state : '';
}

let coverageStarted = false;
store.subscribe((s) => {
  header(s);
  plan.render(s);
  table.render(s);
  fleet.render(s);
  tracks.render(s);
  alerts.render(s);
  radio.render(s);
  commands.render(s);
  timeline.render(s);
  if (!coverageStarted && s.hasState) {
    coverageStarted = true;
    coverage.start();
  }
});
store.connect();
window.fireswarm = { store, map, stats: store.stats }; // for the browser tests, the benchmark and the console
