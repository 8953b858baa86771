// Starts a real `fireswarm run SCENARIO --http 127.0.0.1:0 --pace K
// --operator-token-file F --keys DIR --report R` for the browser tests (DIR a
// key store with one operator, `ann`) and tells its URL
// (the `http: listening on http://HOST:PORT/` line it prints). The binary is
// $FIRESWARM, or ../build/bin/fireswarm from web/.
import { spawn } from 'node:child_process';
import crypto from 'node:crypto';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

const here = path.dirname(fileURLToPath(import.meta.url));
export const REPO = path.resolve(here, '..', '..');
export const FIRESWARM = process.env.FIRESWARM || path.join(REPO, 'build', 'bin', 'fireswarm');
/** How long the run may take to print its URL, ms. */
const LISTEN_TIMEOUT_MS = 60_000;

/**
 * A small, quick mission: three drones over a 1.5 km x 0.8 km block, one fire
 * near the launch site (first seen ~75 simulated s, the whole mission ~850 s).
 */
export const SCENARIO = `name: web_mission
seed: 3
duration_s: 1800
area:
  polygon: [[-74.50521, 46.29775], [-74.485707, 46.29775], [-74.485707, 46.304936], [-74.50521, 46.304936]]
fleet:
  count: 3
  launch: {lat: 46.297211, lon: -74.50495}
fires:
  - {lat: 46.2985, lon: -74.5000, start_s: 0, radius_m: 10}
`;
export const DRONES = [1, 2, 3];

/**
 * Starts `fireswarm ARGS` (which include `--http 127.0.0.1:0`) and resolves,
 * once it prints the URL it listens on, to {url, exited, output(), stop()};
 * `exited` resolves to the exit code (or signal).
 */
export async function startProcess(args, { cwd = os.tmpdir() } = {}) {
  if (!fs.existsSync(FIRESWARM)) {
    throw new Error(`fireswarm binary not found at ${FIRESWARM} (build it, or set FIRESWARM)`);
  }
  const child = spawn(FIRESWARM, args, { cwd, stdio: ['ignore', 'pipe', 'pipe'] });
  let out = '';
  child.stdout.on('data', (d) => (out += d));
  child.stderr.on('data', (d) => (out += d));
  const exited = new Promise((resolve) => child.on('exit', (code, signal) => resolve(code ?? signal)));
  const url = await new Promise((resolve, reject) => {
    const timer = setTimeout(() => reject(new Error(`fireswarm printed no URL within ${LISTEN_TIMEOUT_MS} ms:\n${out}`)), LISTEN_TIMEOUT_MS);
    const look = () => {
      const match = /http: listening on (http:\/\/[^\s/]+\/)/.exec(out);
      if (match) {
        clearTimeout(timer);
        resolve(match[1]);
      }
    };
    child.stdout.on('data', look);
    exited.then((code) => {
      clearTimeout(timer);
      reject(new Error(`fireswarm ${args.join(' ')} exited (${code}) before listening:\n${out}`));
    });
  });
  return {
    url, exited,
    output: () => out,
    async stop() {
      if (child.exitCode === null && child.signalCode === null) child.kill('SIGTERM');
      await exited;
    },
  };
}

/**
 * Starts the mission: `fireswarm run SCENARIO --http 127.0.0.1:0 --pace K
 * --operator-token-file F --keys DIR --report R` in a temporary directory.
 * Resolves to {url, token, operator, key, report, dir, exited, output(), stop()}
 * once it listens; `key` is the operator's key as hex (its .key file's line).
 */
export async function startRun({ scenario = SCENARIO, pace = Number(process.env.FIRESWARM_PACE || 10), token = 'test-operator-token' } = {}) {
  const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'fireswarm-web-'));
  const operator = 'ann';
  const key = crypto.randomBytes(32).toString('hex');
  const keys = path.join(dir, 'keys');
  fs.mkdirSync(path.join(keys, 'operators'), { recursive: true, mode: 0o700 });
  fs.writeFileSync(path.join(keys, 'operators', `${operator}.key`), `${key}\n`, { mode: 0o600 });
  const scenarioFile = path.join(dir, 'scenario.yaml');
  fs.writeFileSync(scenarioFile, scenario);
  const tokenFile = path.join(dir, 'operator.token');
  fs.writeFileSync(tokenFile, `${token}\n`, { mode: 0o600 });
  const report = path.join(dir, 'report.json');
  const process_ = await startProcess(['run', scenarioFile, '--http', '127.0.0.1:0', '--pace', String(pace),
    '--operator-token-file', tokenFile, '--keys', keys, '--report', report], { cwd: dir });
  return {
    ...process_, token, operator, key, report, dir,
    async stop() {
      await process_.stop();
      fs.rmSync(dir, { recursive: true, force: true });
    },
  };
}

/**
 * Fails on any request that leaves 127.0.0.1 (and aborts it): `offsite` collects
 * their URLs for the test to assert empty.
 */
export async function guardOrigin(context, offsite) {
  await context.route('**/*', (route) => {
    const url = new URL(route.request().url());
    if (url.hostname === '127.0.0.1') return route.continue();
    offsite.push(route.request().url());
    return route.abort('blockedbyclient');
  });
}
