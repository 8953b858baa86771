// A crafted stream for page tests that need exact states: the page is served
// from web/ by the test itself (page.route) at a fake 127.0.0.1 origin, its
// WebSocket is answered by the test (page.routeWebSocket) and POST /api/command
// is recorded and accepted. Every other request is aborted.
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { expect } from '@playwright/test';

const WEB = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..');
const ORIGIN = 'http://127.0.0.1:9';
const TYPES = { '.html': 'text/html', '.js': 'text/javascript', '.css': 'text/css', '.png': 'image/png', '.svg': 'image/svg+xml' };

export function vehicle(id, battery, link = 'ok') {
  return {
    id, colour: ['#1f77b4', '#ff7f0e', '#2ca02c', '#d62728'][id - 1], mode: 'search',
    position: [46.30 + id * 0.001, -74.50], altitude_m: 60, speed_mps: 10, heading_deg: 90 * id,
    battery_percent: battery, link, heard_s: link === 'lost' ? 35.8 : 49.6, // 14.2 s, 0.4 s before time_s 50
    telemetry_hz: 1,
    progress: 0.1 * id, task: 'lane', task_text: `lane ${id} of 12`, track_id: 0, trail: [],
  };
}

export const STATE = {
  source: 'simulated', read_only: false, time_s: 50,
  mission: { state: 'running', mission_id: 1, coverage: 0.1, elapsed_s: 50, vehicles_active: 4, vehicles_lost: 0, fires_tentative: 0, fires_confirmed: 0 },
  // Battery order (ascending) is 3, 1, 4, 2: not the ID order.
  vehicles: [vehicle(1, 60), vehicle(2, 90), vehicle(3, 40), vehicle(4, 75)],
  tracks: [], radio: { busy_fraction: 0.3, payload_bytes_per_s: 900, retries: 0, timeouts: 0, telemetry_age_s: { 1: 0.4, 2: 0.4, 3: 0.4, 4: 0.4 } },
  alerts: [], commands: [], refused: 0,
};

/**
 * Opens the page on `state` (the snapshot). Resolves to {stream, posted}: the
 * mocked WebSocket (stream.send(json)) and the bodies POSTed to /api/command.
 */
export async function openCrafted(page, state = STATE) {
  const posted = [];
  let stream;
  await page.route('**/*', async (route) => {
    const url = new URL(route.request().url());
    if (url.origin !== ORIGIN) return route.abort('blockedbyclient');
    if (url.pathname === '/api/command') {
      posted.push(route.request().postDataJSON());
      return route.fulfill({ status: 202, json: { id: posted.length, state: 'queued' } });
    }
    if (url.pathname === '/api/plan') return route.fulfill({ json: { type: 'FeatureCollection', features: [] } });
    if (url.pathname.startsWith('/api/') || url.pathname.startsWith('/tiles/')) return route.fulfill({ status: 404, body: '' });
    const file = path.join(WEB, url.pathname === '/' ? 'index.html' : url.pathname);
    if (!file.startsWith(WEB) || !fs.existsSync(file)) return route.fulfill({ status: 404, body: '' });
    return route.fulfill({ body: fs.readFileSync(file), contentType: TYPES[path.extname(file)] || 'application/octet-stream' });
  });
  await page.routeWebSocket(`${ORIGIN.replace('http', 'ws')}/ws`, (ws) => {
    stream = ws;
    ws.send(JSON.stringify({ type: 'snapshot', state }));
  });
  await page.goto(`${ORIGIN}/`);
  await expect(page.locator('#fleet tbody tr')).toHaveCount(state.vehicles.length);
  return { stream, posted };
}

