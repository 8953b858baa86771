// The command center against a real simulated mission (`fireswarm run --http
// --pace`): the fleet fills the table, the drones move, a fire track appears with
// its ellipse and is confirmed, a command without the token is refused, a signed
// command altered on its way is refused (its MAC no longer matches), and a
// confirmed "return all", signed by the page with the operator's key, seen by a
// second browser, brings the drones home (the run's own report says so). No
// request may leave 127.0.0.1.
import fs from 'node:fs';
import path from 'node:path';
import { test, expect } from '@playwright/test';
import { DRONES, REPO, guardOrigin, startRun } from './fireswarm.js';

test.describe.configure({ mode: 'serial' });

let run;
let operator; // {context, page}: holds the token
const offsite = [];
const pageErrors = [];

async function openPage(browser, url) {
  const context = await browser.newContext();
  await guardOrigin(context, offsite);
  const page = await context.newPage();
  page.on('pageerror', (error) => pageErrors.push(error.message));
  await page.goto(url);
  return { context, page };
}

test.beforeAll(async ({ browser }) => {
  run = await startRun();
  operator = await openPage(browser, run.url);
});

test.afterAll(async () => {
  await operator?.context.close();
  await run?.stop();
});

test.afterEach(() => {
  expect(offsite, 'requests that left 127.0.0.1').toEqual([]);
  expect(pageErrors, 'errors thrown in the page').toEqual([]);
});

test('the fleet table fills with the scenario\'s drones and their markers move', async () => {
  const { page } = operator;
  await expect(page.locator('#connection')).toHaveText('live');
  const rows = page.locator('#fleet tbody tr');
  await expect(rows).toHaveCount(DRONES.length);
  await expect(rows.first()).toHaveAttribute('data-vehicle', '1');
  for (const id of DRONES) {
    await expect(page.locator(`#fleet tr[data-vehicle="${id}"] .swatch`)).toBeVisible();
  }
  // The plan is drawn: the area and each drone's lanes.
  await expect(page.locator('body.plan-loaded')).toHaveCount(1);
  const marker = page.locator('.drone[data-vehicle="1"]');
  await expect(marker).toBeVisible();
  const first = await marker.getAttribute('data-lat') + ',' + await marker.getAttribute('data-lon');
  await expect
    .poll(async () => (await marker.getAttribute('data-lat')) + ',' + (await marker.getAttribute('data-lon')))
    .not.toBe(first);
  // A trail follows it (a polyline of more than one point).
  await expect.poll(() => page.evaluate(() => window.fireswarm.store.vehicles.get(1).trail.length)).toBeGreaterThan(1);
});

test('a fire track appears with its 2-sigma ellipse and becomes confirmed', async () => {
  const { page } = operator;
  const ellipse = page.locator('path.track-ellipse').first();
  await expect(ellipse).toBeAttached({ timeout: 60_000 });
  await expect(ellipse).toHaveAttribute('data-status', 'confirmed', { timeout: 60_000 });
  // The ellipse is a polygon around the track (many vertices once zoomed to it).
  const overview = await page.evaluate(() => {
    const { map, store } = window.fireswarm;
    const view = { center: map.getCenter(), zoom: map.getZoom() };
    const track = [...store.tracks.values()].find((t) => t.status === 'confirmed');
    map.setView(track.position, 19, { animate: false });
    return view;
  });
  await expect.poll(async () => ((await ellipse.getAttribute('d')).match(/L/g) || []).length).toBeGreaterThan(20);
  const box = await ellipse.boundingBox();
  expect(box.width).toBeGreaterThan(4);
  expect(box.height).toBeGreaterThan(4);
  await expect(page.locator('#alerts li[data-kind="fire_confirmed"]')).toHaveCount(1);
  await page.locator('path.track-centre').first().click({ force: true });
  await expect(page.locator('.leaflet-popup-content')).toContainText('confirmed');
  await expect(page.locator('.leaflet-popup-content')).toContainText('views (reports)');
  await page.locator('.leaflet-popup-close-button').click();
  await page.evaluate(({ center, zoom }) => window.fireswarm.map.setView(center, zoom, { animate: false }), overview);
  // The README's picture is refreshed only when asked
  // (FIRESWARM_SCREENSHOT=docs/img/command_center.png): a test run leaves the tree as it was.
  const shot = process.env.FIRESWARM_SCREENSHOT
    ? path.resolve(REPO, process.env.FIRESWARM_SCREENSHOT)
    : path.join(REPO, 'web', 'test-results', 'command_center.png');
  fs.mkdirSync(path.dirname(shot), { recursive: true });
  await page.screenshot({ path: shot });
});

test('a command without the operator token is refused and the error shown', async ({ browser }) => {
  const { context, page } = await openPage(browser, run.url);
  await page.locator('#fleet tr[data-vehicle="2"]').click();
  await expect(page.locator('#selected-drone')).toHaveAttribute('data-vehicle', '2');
  await page.locator('button[data-drone="hold"]').click();
  const dialog = page.locator('dialog#confirm');
  await expect(dialog).toBeVisible();
  await expect(dialog.locator('#confirm-targets li')).toHaveCount(1);
  await expect(dialog.locator('#confirm-targets li')).toHaveAttribute('data-vehicle', '2');
  const reply = page.waitForResponse('**/api/command');
  await dialog.locator('#confirm-ok').click();
  expect((await reply).status()).toBe(401);
  await expect(page.locator('#command-error')).toBeVisible();
  await expect(page.locator('#command-error')).toContainText('refused');
  await expect(page.locator('#commands li[data-state="refused"]')).toHaveCount(1);
  // The server counts it too.
  await expect
    .poll(async () => (await (await page.request.get(`${run.url}api/state`)).json()).refused)
    .toBeGreaterThan(0);
  await context.close();
});

test('a signed command altered on its way is refused, and the key never leaves the page', async () => {
  const { page } = operator;
  await page.locator('#token').fill(run.token);
  await page.locator('#operator-id').fill(run.operator);
  await page.locator('#operator-key').fill(run.key);
  // Kept for the tab only.
  expect(await page.evaluate(() => sessionStorage.getItem('fireswarm.operatorKey'))).toBe(run.key);
  // A man in the middle sends the signed hold for drone 2 to drone 3 instead.
  const sent = [];
  await page.route('**/api/command', (route) => {
    sent.push(JSON.parse(route.request().postData()));
    const body = JSON.parse(route.request().postData());
    body.vehicle = 3;
    return route.continue({ postData: JSON.stringify(body) });
  });
  await page.locator('#fleet tr[data-vehicle="2"]').click();
  await page.locator('button[data-drone="hold"]').click();
  const dialog = page.locator('dialog#confirm');
  await expect(dialog).toBeVisible();
  const reply = page.waitForResponse('**/api/command');
  await dialog.locator('#confirm-ok').click();
  const answer = await reply;
  expect(answer.status()).toBe(401);
  expect((await answer.json()).error).toMatch(/^bad_mac/);
  await expect(page.locator('#command-error')).toContainText('bad_mac');
  await page.unroute('**/api/command');
  // What the page sent: the command, its operator, utime, nonce and MAC; no key.
  expect(sent).toHaveLength(1);
  expect(sent[0].vehicle).toBe(2);
  expect(sent[0].auth.operator).toBe(run.operator);
  expect(sent[0].auth.mac).toMatch(/^[0-9a-f]{64}$/);
  expect(sent[0].auth.nonce).toMatch(/^[0-9a-f]{16}$/);
  expect(JSON.stringify(sent[0])).not.toContain(run.key);
});

test('return all, confirmed, is seen by a second browser and brings the drones home', async ({ browser }) => {
  const { page } = operator;
  const watcher = await openPage(browser, run.url);
  await expect(watcher.page.locator('#fleet tbody tr')).toHaveCount(DRONES.length);

  await page.locator('#token').fill(run.token);
  await page.locator('#operator-id').fill(run.operator);
  await page.locator('#operator-key').fill(run.key);
  await page.locator('button[data-fleet="return_all"]').click();
  const dialog = page.locator('dialog#confirm');
  await expect(dialog).toBeVisible();
  await expect(dialog.locator('#confirm-targets li')).toHaveCount(DRONES.length);
  for (const id of DRONES) await expect(dialog.locator(`li[data-vehicle="${id}"] .swatch`)).toBeVisible();
  const reply = page.waitForResponse('**/api/command');
  await dialog.locator('#confirm-ok').click();
  const answer = await reply;
  expect(answer.status()).toBe(202);
  const { id } = await answer.json();
  await expect(page.locator('#command-error')).toBeHidden();

  // Both browsers follow the command's state from the server.
  for (const p of [page, watcher.page]) {
    const item = p.locator(`#commands li[data-command="${id}"]`);
    await expect(item).toHaveAttribute('data-kind', 'return_all');
    await expect(item).toHaveAttribute('data-state', /sent|acknowledged/);
  }
  await watcher.context.close();

  // The run ends once every drone has landed, and its report says where they are.
  await expect.poll(() => fs.existsSync(run.report), { timeout: 150_000, intervals: [500] }).toBe(true);
  const report = JSON.parse(fs.readFileSync(run.report, 'utf8'));
  for (const id of DRONES) {
    expect(report.vehicles[String(id)].final_state, `drone ${id}`).toBe('landed');
  }
  // Home early: the search was cut short (the whole mission covers the block).
  expect(report.coverage).toBeLessThan(0.9);
  expect(report.sim_seconds).toBeLessThan(800);
});
