// The viewer's moving objects in a real headless Chromium: the office's chair is drawn where its
// path puts it, moves when the time slider does (the picture changes where it was and where it
// went, not everywhere), and Play advances the time; the page logs no errors.
// Usage: node viewer_objects_test.mjs BINARY WEB_DIR SCENE OUT_DIR   (screenshots go to OUT_DIR)
import { execFileSync } from 'node:child_process';
import { mkdirSync, readFileSync } from 'node:fs';
import path from 'node:path';

import { launchChromium, openTab, pictureBlocks, viewerOutcome } from './headless_chromium.mjs';
import { startServer } from './serve_process.mjs';

const [binary, webDir, sceneFile, outDir] = process.argv.slice(2);
mkdirSync(outDir, { recursive: true });

function fail(message) {
  console.error(`FAIL: ${message}`);
  process.exitCode = 1;
}

const server = await startServer(binary, [sceneFile, '--patches', '1500', '--cache-dir', 'none',
  '--web-dir', webDir]);
const browser = await launchChromium(webDir);
try {
  const { tab: page, errors } = await openTab(browser, 900, 600);
  await page.goto(server.url);
  await page.waitForFunction(() => window.viewerState && window.viewerState.frames > 3 &&
    window.viewerState.objectUpdates > 0, { timeout: 60000 });
  const blocks = () => pictureBlocks(page);
  // Moves the slider to `t` as a user does and waits for the answer and a few frames.
  const showTime = async (t) => {
    const updates = await page.evaluate((value) => {
      const slider = document.getElementById('time');
      slider.value = String(value);
      slider.dispatchEvent(new Event('input'));
      return window.viewerState.objectUpdates;
    }, t);
    await page.waitForFunction((n, value) => window.viewerState.objectUpdates > n &&
      Math.abs(window.viewerState.objectTime - value) < 1e-9, { timeout: 60000 }, updates, t);
    const frames = await page.evaluate(() => window.viewerState.frames);
    await page.waitForFunction((n) => window.viewerState.frames > n + 3, { timeout: 60000 }, frames);
  };
  // The office's sensor sets, drawn and listed: what `solve --sensor-output` reads, within 1%
  // (the server's relighter against the solve's Gauss-Seidel, the chair where t = 0 puts it).
  await page.waitForFunction(() => window.viewerState.sensorSets !== null, { timeout: 60000 });
  const sets = await page.evaluate(() => window.viewerState.sensorSets.sets);
  const listed = await page.evaluate(() => document.getElementById('sensor-sets').textContent);
  console.log(`sensor sets: ${listed.replace(/\n/g, '; ')}`);
  if (!listed.includes('workplane: mean')) fail(`the sensor sets are listed as '${listed}'`);
  const readings = path.join(outDir, 'office_sensors.csv');
  execFileSync(binary, ['solve', sceneFile, '--method', 'patch', '--patches', '1500', '--cache-dir', 'none',
    '--sensor-output', readings, '--quiet']);
  const rows = readFileSync(readings, 'utf8').trim().split('\n').slice(1).map((row) => row.split(','));
  const solvedMean = rows.filter((r) => r[0] === 'workplane').reduce((sum, r) => sum + Number(r[11]), 0) /
    sets.workplane.points.length;
  console.log(`workplane: the page ${sets.workplane.mean_lux.toPrecision(4)} lx, solve ${solvedMean.toPrecision(4)} lx`);
  if (!(Math.abs(sets.workplane.mean_lux / solvedMean - 1) < 0.01))
    fail(`the page's workplane mean ${sets.workplane.mean_lux} lx against solve's ${solvedMean} lx`);
  const hidden = await page.evaluate(() => document.getElementById('time-section').hidden);
  if (hidden) fail('the time controls are hidden for a scene with a moving object');
  await showTime(0);
  const before = await blocks();
  await page.screenshot({ path: path.join(outDir, 'objects_t0.png') });
  await showTime(3);
  const after = await blocks();
  await page.screenshot({ path: path.join(outDir, 'objects_t3.png') });
  const change = before.map((v, b) => Math.abs(after[b] - v));
  const changed = change.filter((c) => c > 0.05).length;
  console.log(`the chair moved: largest block change ${Math.max(...change).toFixed(3)}, ${changed} of ${change.length} blocks changed by > 0.05`);
  if (!(changed > 0)) fail('the picture did not change where the chair moved');
  if (!(changed < change.length / 4)) fail('the picture changed nearly everywhere, not where the chair moved');

  // Play advances the time by itself.
  await showTime(0);
  await page.click('#play');
  await page.waitForFunction(() => window.viewerState.objectTime > 0.3, { timeout: 60000 });
  await page.click('#play');
  const { state, problems } = await viewerOutcome(page, errors);
  console.log(`${state.objectUpdates} object updates, time ${state.objectTime.toFixed(2)} s, ${state.errors} errors`);
  problems.forEach(fail);
} catch (error) {
  fail(error.stack || String(error));
} finally {
  await browser.close();
  server.stop();
}
