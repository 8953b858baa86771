// A replay shows what the run published: `fireswarm run --log` writes the LCM
// log and the report, `fireswarm replay LOG --http` serves it read-only; scrubbed
// to the end, the page holds the report's final tracks (same IDs, statuses and
// positions), the commands are hidden and a command is refused.
import { spawnSync } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { test, expect } from '@playwright/test';
import { FIRESWARM, SCENARIO, guardOrigin, startProcess } from './fireswarm.js';

/** Metres between two [lat, lon] points a few metres apart. */
function distance_m([lat1, lon1], [lat2, lon2]) {
  const north = (lat2 - lat1) * 111_320;
  const east = (lon2 - lon1) * 111_320 * Math.cos((lat1 * Math.PI) / 180);
  return Math.hypot(north, east);
}

test('a replay of a run\'s log ends with the run report\'s tracks, read-only', async ({ browser }) => {
  const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'fireswarm-replay-'));
  const scenario = path.join(dir, 'scenario.yaml');
  fs.writeFileSync(scenario, SCENARIO);
  const log = path.join(dir, 'run.lcmlog');
  const reportFile = path.join(dir, 'report.json');
  const flown = spawnSync(FIRESWARM, ['run', scenario, '--log', log, '--report', reportFile], { encoding: 'utf8' });
  expect(flown.status, flown.stdout + flown.stderr).toBe(0);
  const report = JSON.parse(fs.readFileSync(reportFile, 'utf8'));
  expect(report.tracks.length).toBeGreaterThan(0);

  const replay = await startProcess(['replay', log, '--http', '127.0.0.1:0']);
  const offsite = [];
  const context = await browser.newContext();
  await guardOrigin(context, offsite);
  try {
    const page = await context.newPage();
    await page.goto(replay.url);
    await expect(page.locator('#timeline')).toBeVisible();
    await expect(page.locator('button[data-fleet="return_all"]')).toBeHidden();
    const end = await page.locator('#replay-scrub').getAttribute('max');
    expect(Number(end)).toBeGreaterThan(0);
    await page.locator('#replay-scrub').fill(end);
    await expect
      .poll(() => page.evaluate(() => [...window.fireswarm.store.tracks.keys()].sort((a, b) => a - b)), { timeout: 60_000 })
      .toEqual(report.tracks.map((t) => t.track_id).sort((a, b) => a - b));
    const shown = await page.evaluate(() => Object.fromEntries([...window.fireswarm.store.tracks].map(([id, t]) => [id, t])));
    for (const track of report.tracks) {
      const onPage = shown[track.track_id];
      expect(onPage.status, `track ${track.track_id}`).toBe(track.status);
      expect(distance_m(onPage.position, [track.lat, track.lon]), `track ${track.track_id}`).toBeLessThan(1);
    }
    await expect(page.locator('path.track-ellipse')).toHaveCount(report.tracks.length);
    // Read-only: the server refuses a command whatever it carries.
    const refused = await page.request.post(`${replay.url}api/command`, {
      data: { kind: 'hold_all' }, headers: { Authorization: 'Bearer anything' },
    });
    expect(refused.status()).toBe(403);
    expect(offsite).toEqual([]);
  } finally {
    await context.close();
    await replay.stop();
    fs.rmSync(dir, { recursive: true, force: true });
  }
});
