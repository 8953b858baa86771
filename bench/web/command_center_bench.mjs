// The command center's figures, measured in the real browser (issue 15): a
// simulated mission served live (`fireswarm run SCENARIO --http 127.0.0.1:0
// --pace K`), the page opened in Debian's chromium driven by Playwright (from
// web/node_modules, launched as web/playwright.config.js launches it), and, from
// the moment the fleet table holds every drone until the run ends:
//   - state-to-screen latency, per delta: the page's wall clock once the views are
//     drawn in the next animation frame minus the delta's `built_unix_ms` (when
//     the server built it; docs/command_center.md), window.fireswarm.stats;
//   - page frame time: the intervals between animation frames;
//   - the web adapter's share of the server's CPU: the run's last line
//     {"event": "web_cpu", ...} (the feed's own CPU and the web server's io thread
//     against the whole process's, over the whole run);
//   - that it works: rows in the fleet table, markers that moved, page errors.
// Prints one JSON object, then a one-line table; exits 1 when a target is missed:
// with --check full (default) latency p95 <= 250 ms, frame time p95 <= 50 ms,
// share <= 5 %, and what --check works asks; with --check works: every drone's
// row, most markers moved, no page error.
//
// Once: cd web && PLAYWRIGHT_SKIP_BROWSER_DOWNLOAD=1 npm ci; build build/bin/fireswarm. Then:
//   node bench/web/command_center_bench.mjs                        # 100 drones, pace 6 (~100 s)
//   node bench/web/command_center_bench.mjs --scenario bench/scenarios/fleet250.yaml \
//        --pace 2 --check works                                    # 250 drones (~150 s)
// Options: --scenario FILE, --pace K, --check full|works, --fireswarm BINARY
// (default $FIRESWARM or build/bin/fireswarm), --fill-timeout S (default 120).
import { spawn } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';

const REPO = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..', '..');
const WEB = path.join(REPO, 'web');
const TARGETS = { latency_p95_ms: 250, frame_p95_ms: 50, cpu_share: 0.05 };
/** Drones whose markers must have moved during the window, as a fraction of the fleet. */
const MOVED_FRACTION = 0.5;
const SAMPLE_EVERY_MS = 1000;

function parseArgs(argv) {
  const options = {
    scenario: path.join(REPO, 'bench', 'scenarios', 'fleet100.yaml'),
    pace: 6,
    check: 'full',
    fireswarm: process.env.FIRESWARM || path.join(REPO, 'build', 'bin', 'fireswarm'),
    fillTimeoutS: 120,
  };
  const names = { '--scenario': 'scenario', '--pace': 'pace', '--check': 'check', '--fireswarm': 'fireswarm', '--fill-timeout': 'fillTimeoutS' };
  for (let i = 0; i < argv.length; i += 2) {
    const key = names[argv[i]];
    if (!key || argv[i + 1] === undefined) throw new Error(`${argv[i]}: unknown option or missing value (see the file's header)`);
    options[key] = ['pace', 'fillTimeoutS'].includes(key) ? Number(argv[i + 1]) : argv[i + 1];
  }
  if (!(options.pace > 0)) throw new Error(`--pace ${options.pace}: must be > 0`);
  if (!['full', 'works'].includes(options.check)) throw new Error(`--check ${options.check}: must be full or works`);
  if (!fs.existsSync(options.fireswarm)) throw new Error(`fireswarm binary not found at ${options.fireswarm} (build it, or set --fireswarm)`);
  return options;
}

/** The scenario's fleet.count (the rows the table must show). */
function droneCount(scenarioFile) {
  const match = /^fleet:\s*\n(?:\s+.*\n)*?\s+count:\s*(\d+)/m.exec(fs.readFileSync(scenarioFile, 'utf8'));
  if (!match) throw new Error(`${scenarioFile}: no fleet.count found`);
  return Number(match[1]);
}

function percentile(values, p) {
  if (!values.length) return NaN;
  const sorted = [...values].sort((a, b) => a - b);
  return sorted[Math.min(sorted.length - 1, Math.ceil((p / 100) * sorted.length) - 1)];
}

/** Starts the run; resolves to {url, lines(), exited, kill()} once it listens. */
async function startRun(options) {
  const child = spawn(options.fireswarm, ['run', options.scenario, '--http', '127.0.0.1:0', '--pace', String(options.pace)],
    { stdio: ['ignore', 'pipe', 'pipe'] });
  let out = '';
  let err = '';
  child.stdout.on('data', (d) => (out += d));
  child.stderr.on('data', (d) => (err += d));
  const exited = new Promise((resolve) => child.on('exit', (code, signal) => resolve(code ?? signal)));
  const url = await new Promise((resolve, reject) => {
    const look = () => {
      const match = /http: listening on (http:\/\/[^\s/]+\/)/.exec(out);
      if (match) resolve(match[1]);
    };
    child.stdout.on('data', look);
    exited.then((code) => reject(new Error(`fireswarm run exited (${code}) before listening:\n${out}${err}`)));
  });
  return { url, exited, stdout: () => out, stderr: () => err, kill: () => child.kill('SIGTERM') };
}

async function main() {
  const options = parseArgs(process.argv.slice(2));
  const drones = droneCount(options.scenario);
  const { chromium } = await import(pathToFileURL(path.join(WEB, 'node_modules', '@playwright', 'test', 'index.mjs')).href);
  const config = (await import(pathToFileURL(path.join(WEB, 'playwright.config.js')).href)).default;

  const run = await startRun(options);
  const browser = await chromium.launch({ ...config.use.launchOptions, headless: true });
  const failures = [];
  let result;
  try {
    const page = await browser.newPage({ viewport: config.use.viewport });
    // Uncaught exceptions fail the run; console errors are told (without --tiles,
    // the page's GET /tiles/metadata.json is a 404 by design).
    const pageErrors = [];
    const consoleErrors = [];
    page.on('pageerror', (e) => pageErrors.push(String(e)));
    page.on('console', (m) => { if (m.type() === 'error') consoleErrors.push(m.text()); });
    await page.goto(run.url);
    const filledAt = Date.now();
    await page.waitForFunction((n) => document.querySelectorAll('#fleet tbody tr').length >= n, drones,
      { timeout: options.fillTimeoutS * 1000, polling: 200 });
    const fillS = (Date.now() - filledAt) / 1000;
    // The window starts now: the page's figures so far (loading, the snapshot) are dropped.
    await page.evaluate(() => {
      const s = window.fireswarm.stats;
      s.latency_ms.length = 0;
      s.frame_ms.length = 0;
      s.render_ms.length = 0;
      s.deltas = 0;
    });
    const markers = () => page.evaluate(() => Object.fromEntries(
      [...document.querySelectorAll('.drone[data-vehicle]')].map((e) => [e.dataset.vehicle, `${e.dataset.lat},${e.dataset.lon}`])));
    const first = await markers();
    const windowStart = Date.now();
    // Until the run's last line; the page's arrays are drained every second so
    // that none of them overflows its bound on a long run.
    const latency = [];
    const frames = [];
    const renders = [];
    let deltas = 0;
    let rows = 0;
    const drain = async () => {
      const s = await page.evaluate(() => {
        const st = window.fireswarm.stats;
        const taken = { latency: st.latency_ms.splice(0), frames: st.frame_ms.splice(0), render: st.render_ms.splice(0), deltas: st.deltas };
        st.deltas = 0;
        return { ...taken, rows: document.querySelectorAll('#fleet tbody tr').length };
      });
      latency.push(...s.latency);
      frames.push(...s.frames);
      renders.push(...s.render);
      deltas += s.deltas;
      rows = s.rows;
    };
    let exitCode = null;
    run.exited.then((code) => (exitCode = code));
    // A drone's marker moved when its position differs between two samples.
    const movedIds = new Set();
    let last = first;
    while (!/"event":"web_cpu"/.test(run.stdout()) && exitCode === null) {
      await new Promise((r) => setTimeout(r, SAMPLE_EVERY_MS));
      await drain();
      const now = await markers();
      for (const id of Object.keys(now)) if (last[id] !== undefined && last[id] !== now[id]) movedIds.add(id);
      last = now;
    }
    const windowS = (Date.now() - windowStart) / 1000;
    const moved = movedIds.size;
    const consoleErrorsInWindow = [...consoleErrors]; // later ones: the run has ended
    await page.close();
    const code = await run.exited;
    const cpuLine = run.stdout().split('\n').find((l) => l.includes('"event":"web_cpu"'));
    const cpu = cpuLine ? JSON.parse(cpuLine) : null;
    const summary = /fireswarm run: \S+: ([\d.]+) simulated s .* in ([\d.]+) wall s/.exec(run.stdout());
    result = {
      scenario: path.relative(REPO, options.scenario),
      drones,
      pace: options.pace,
      achieved_pace: summary ? Number(summary[1]) / Number(summary[2]) : null,
      fill_s: fillS,
      window_s: windowS,
      deltas,
      latency_ms: { p50: percentile(latency, 50), p95: percentile(latency, 95), max: Math.max(...latency), n: latency.length },
      frame_ms: { p50: percentile(frames, 50), p95: percentile(frames, 95), max: Math.max(...frames), n: frames.length },
      render_ms: { p50: percentile(renders, 50), p95: percentile(renders, 95), max: Math.max(...renders), n: renders.length },
      web_cpu: cpu,
      rows,
      markers_moved: moved,
      page_errors: pageErrors,
      console_errors: consoleErrorsInWindow,
      run_exit: code,
    };
    if (code !== 0) failures.push(`fireswarm run exited ${code}:\n${run.stderr()}`);
    if (rows !== drones) failures.push(`the table has ${rows} rows, not ${drones}`);
    if (moved < MOVED_FRACTION * drones) failures.push(`${moved} of ${drones} markers moved`);
    if (pageErrors.length) failures.push(`page errors: ${pageErrors.slice(0, 5).join('; ')}`);
    if (!cpu) failures.push('no web_cpu line from the run');
    if (options.check === 'full') {
      if (!(result.latency_ms.p95 <= TARGETS.latency_p95_ms)) failures.push(`latency p95 ${result.latency_ms.p95} ms > ${TARGETS.latency_p95_ms}`);
      if (!(result.frame_ms.p95 <= TARGETS.frame_p95_ms)) failures.push(`frame time p95 ${result.frame_ms.p95} ms > ${TARGETS.frame_p95_ms}`);
      if (cpu && !(cpu.share <= TARGETS.cpu_share)) failures.push(`web CPU share ${(100 * cpu.share).toFixed(1)} % > ${100 * TARGETS.cpu_share} %`);
    }
  } finally {
    await browser.close();
    run.kill();
  }
  result.failures = failures;
  console.log(JSON.stringify(result, null, 2));
  const f = (x) => (Number.isFinite(x) ? x.toFixed(0) : '–');
  const share = result.web_cpu ? `${(100 * result.web_cpu.share).toFixed(2)} %` : '–';
  console.log('| drones | latency p50 / p95 (ms) | frame p95 (ms) | web CPU share | rows | markers moved | page errors |');
  console.log(`| ${drones} | ${f(result.latency_ms.p50)} / ${f(result.latency_ms.p95)} | ${f(result.frame_ms.p95)} | ${share} | ${result.rows} | ${result.markers_moved} | ${result.page_errors.length} |`);
  if (failures.length) {
    console.error(`command_center_bench: FAILED: ${failures.join('; ')}`);
    process.exitCode = 1;
  }
}

main().catch((e) => {
  console.error(`command_center_bench: ${e.stack || e}`);
  process.exitCode = 2;
});
