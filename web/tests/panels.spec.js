// The alerts list, the radio panel, the commands' states, fire tracks and a
// refusal's error, on a crafted stream (tests/crafted.js).
import { test, expect } from '@playwright/test';
import { STATE, openCrafted } from './crafted.js';

test('alerts come newest first with their level, the radio panel follows the stream', async ({ page }) => {
  const { stream } = await openCrafted(page);
  const alert = (id, level, kind, text) => ({ id, time_s: 60 + id, level, kind, vehicle: 1, track: 0, text });
  stream.send(JSON.stringify({ type: 'delta', time_s: 61, alerts: [alert(1, 'warning', 'link_degraded', 'drone 1: link degraded')] }));
  stream.send(JSON.stringify({
    type: 'delta', time_s: 62, alerts: [alert(2, 'critical', 'link_lost', 'drone 1: link lost')],
    radio: { busy_fraction: 0.73, payload_bytes_per_s: 1200, retries: 12, timeouts: 5, telemetry_age_s: { 1: 12.5, 2: 0.4, 3: 0.5, 4: 0.3 } },
  }));
  const items = page.locator('#alerts li');
  await expect(items).toHaveCount(2);
  await expect(items.nth(0)).toContainText('link lost');
  await expect(items.nth(0)).toHaveClass('level-critical');
  await expect(items.nth(1)).toHaveClass('level-warning');
  await expect(page.locator('#radio-busy')).toHaveText('73 %');
  await expect(page.locator('#radio-retries')).toHaveText('12');
  await expect(page.locator('#radio-timeouts')).toHaveText('5');
  await expect(page.locator('#radio .age[data-vehicle="1"]')).toHaveClass(/stale/);
  await expect(page.locator('#radio .age[data-vehicle="2"]')).not.toHaveClass(/stale/);
});

test('a command\'s state follows the server: queued, sent, acknowledged, failed per target', async ({ page }) => {
  const { stream } = await openCrafted(page);
  const command = (state, targets) => ({ id: 7, kind: 'hold_all', targets, state, time_s: 70, reason: 'operator' });
  const all = (state) => [1, 2, 3, 4].map((vehicle) => ({ vehicle, state }));
  stream.send(JSON.stringify({ type: 'delta', time_s: 70, commands: [command('queued', all('queued'))] }));
  const item = page.locator('#commands li[data-command="7"]');
  await expect(item).toHaveAttribute('data-state', 'queued');
  await expect(item.locator('.target')).toHaveCount(4);
  stream.send(JSON.stringify({ type: 'delta', time_s: 71, commands: [command('sent', all('sent'))] }));
  await expect(item).toHaveAttribute('data-state', 'sent');
  const mixed = all('acknowledged');
  mixed[2].state = 'failed';
  stream.send(JSON.stringify({ type: 'delta', time_s: 75, commands: [command('failed', mixed)] }));
  await expect(item).toHaveAttribute('data-state', 'failed');
  await expect(item.locator('.target[data-vehicle="3"]')).toHaveClass(/state-failed/);
  await expect(item.locator('.target[data-vehicle="1"]')).toHaveClass(/state-acknowledged/);
});

test('a fire track is drawn by status, and its popup tells drones, views and first report', async ({ page }) => {
  const track = { id: 4, status: 'tentative', position: [46.3025, -74.499], ellipse: { semi_major_m: 30, semi_minor_m: 12, bearing_deg: 45 }, reports: 1, drones: [2], first_seen_s: 40.2 };
  const { stream } = await openCrafted(page, { ...STATE, tracks: [track] });
  await page.evaluate(() => window.fireswarm.map.setView([46.3025, -74.499], 17, { animate: false }));
  const ellipse = page.locator('path.track-ellipse[data-track="4"]');
  await expect(ellipse).toHaveAttribute('data-status', 'tentative');
  const box = await ellipse.boundingBox();
  // 60 m x 24 m at zoom 17 (~0.83 m per pixel at this latitude): tilted 45 degrees.
  expect(box.width).toBeGreaterThan(40);
  expect(box.height).toBeGreaterThan(40);
  stream.send(JSON.stringify({ type: 'delta', time_s: 80, tracks: [{ ...track, status: 'confirmed', reports: 3, drones: [2, 4] }] }));
  await expect(ellipse).toHaveAttribute('data-status', 'confirmed');
  await page.locator('path.track-centre[data-track="4"]').click({ force: true });
  const popup = page.locator('.leaflet-popup-content');
  await expect(popup).toContainText('confirmed');
  await expect(popup).toContainText('drones 2, 4 (2)');
  await expect(popup).toContainText('views (reports) 3');
  await expect(popup).toContainText('first report 0:40');
  // A track the server no longer holds leaves the map.
  stream.send(JSON.stringify({ type: 'delta', time_s: 90, removed_tracks: [4] }));
  await expect(ellipse).toHaveCount(0);
});

test('re-task: the point clicked on the map goes with the selected drone\'s ID', async ({ page }) => {
  const { posted } = await openCrafted(page);
  await page.locator('#token').fill('t');
  await page.locator('#fleet tr[data-vehicle="4"]').click();
  await page.locator('button[data-drone="retask"]').click();
  await expect(page.locator('#pick-hint')).toContainText('drone 4');
  await page.locator('#map').click({ position: { x: 300, y: 300 } });
  await expect(page.locator('#confirm-targets li')).toHaveAttribute('data-vehicle', '4');
  const reply = page.waitForResponse('**/api/command');
  await page.locator('#confirm-ok').click();
  await reply;
  expect(posted).toHaveLength(1);
  expect(posted[0]).toMatchObject({ kind: 'retask', vehicle: 4 });
  expect(Number.isFinite(posted[0].lat) && Number.isFinite(posted[0].lon)).toBe(true);
});
