// The fleet table's rows are keyed by receiver ID: re-sorting it and a drone's
// link going lost never change which drone the selected row, its dialog and the
// command POSTed name. The page is served from web/ by the test and fed a
// crafted stream (docs/command_center.md), so each step is deterministic; the
// mission test drives the same page against a real run.
import { test, expect } from '@playwright/test';
import { STATE, openCrafted, vehicle } from './crafted.js';

let stream;
let posted;

test.beforeEach(async ({ page }) => {
  ({ stream, posted } = await openCrafted(page));
});

const rowIds = (page) => page.locator('#fleet tbody tr').evaluateAll((rows) => rows.map((r) => Number(r.dataset.vehicle)));

test('re-sorting and a lost link keep the selected drone the command\'s target', async ({ page }) => {
  expect(await rowIds(page)).toEqual([1, 2, 3, 4]);
  // Select the second row: drone 2.
  await page.locator('#fleet tbody tr').nth(1).click();
  await expect(page.locator('#fleet tr.selected')).toHaveAttribute('data-vehicle', '2');

  // Sort by battery: the rows move, the selection stays on drone 2 (now last).
  await page.locator('#fleet th[data-key="battery_percent"]').click();
  await expect.poll(() => rowIds(page)).toEqual([3, 1, 4, 2]);
  await expect(page.locator('#fleet tr.selected')).toHaveAttribute('data-vehicle', '2');
  await page.locator('#fleet th[data-key="battery_percent"]').click();
  await expect.poll(() => rowIds(page)).toEqual([2, 4, 1, 3]);

  // Drone 1 loses its link (and so sorts elsewhere by link): its row greys,
  // drone 2 stays selected.
  await page.locator('#fleet th[data-key="link"]').click();
  stream.send(JSON.stringify({ type: 'delta', time_s: 65, vehicles: [vehicle(1, 59, 'lost')] }));
  await expect(page.locator('#fleet tr[data-vehicle="1"]')).toHaveClass(/lost/);
  // Heard last at 35.8 s: its age counts on with the state's time, no row sent.
  await expect(page.locator('#fleet tr[data-vehicle="1"]')).toContainText('lost 29.2 s');
  stream.send(JSON.stringify({ type: 'delta', time_s: 70 }));
  await expect(page.locator('#fleet tr[data-vehicle="1"]')).toContainText('lost 34.2 s');
  await expect.poll(() => rowIds(page)).toEqual([2, 3, 4, 1]);
  await expect(page.locator('#fleet tr.selected')).toHaveAttribute('data-vehicle', '2');
  await expect(page.locator('.drone[data-vehicle="1"]')).toHaveClass(/lost/);

  // The command goes to drone 2, named by its receiver ID.
  await page.locator('#token').fill('t');
  await page.locator('button[data-drone="hold"]').click();
  await expect(page.locator('#confirm-targets li')).toHaveCount(1);
  await expect(page.locator('#confirm-targets li')).toHaveAttribute('data-vehicle', '2');
  const reply = page.waitForResponse('**/api/command');
  await page.locator('#confirm-ok').click();
  await reply;
  expect(posted).toEqual([{ kind: 'hold', vehicle: 2, reason: 'operator' }]);
});

test('a lost drone selected stays the target, and cancelling sends nothing', async ({ page }) => {
  await page.locator('#fleet tr[data-vehicle="3"]').click();
  stream.send(JSON.stringify({ type: 'delta', time_s: 70, vehicles: [vehicle(3, 39, 'lost')] }));
  await expect(page.locator('#fleet tr[data-vehicle="3"]')).toHaveClass(/lost/);
  await page.locator('#fleet th[data-key="link"]').click();
  await expect.poll(() => rowIds(page)).toEqual([1, 2, 4, 3]);
  await page.locator('button[data-drone="return"]').click();
  await expect(page.locator('#confirm-targets li')).toHaveAttribute('data-vehicle', '3');
  await page.locator('#confirm-cancel').click();
  await expect(page.locator('dialog#confirm')).toBeHidden();
  await page.locator('button[data-drone="land"]').click();
  await expect(page.locator('#confirm-targets li')).toHaveAttribute('data-vehicle', '3');
  const reply = page.waitForResponse('**/api/command');
  await page.locator('#confirm-ok').click();
  await reply;
  expect(posted).toEqual([{ kind: 'land', vehicle: 3, reason: 'operator' }]);
});

test('read-only (replay) hides the commands and drives the timeline over the stream', async ({ page }) => {
  const received = [];
  stream.onMessage((m) => received.push(JSON.parse(m)));
  stream.send(JSON.stringify({ type: 'snapshot', state: { ...STATE, source: 'replay', read_only: true } }));
  stream.send(JSON.stringify({ type: 'replay', time_s: 100, start_s: 0, end_s: 900, playing: false, speed: 1 }));
  await expect(page.locator('#timeline')).toBeVisible();
  await expect(page.locator('button[data-fleet="return_all"]')).toBeHidden();
  await expect(page.locator('#drone-commands')).toBeHidden();
  await page.locator('#replay-speed').selectOption('5');
  await page.locator('#replay-play').click();
  await expect.poll(() => received.at(-1)).toEqual({ type: 'replay', action: 'play', speed: 5 });
  await page.locator('#replay-scrub').fill('450');
  await expect.poll(() => received.at(-1)).toEqual({ type: 'replay', action: 'seek', time_s: 450, speed: 5 });
});
