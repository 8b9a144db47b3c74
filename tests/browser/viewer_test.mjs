// The viewer page in a real headless Chromium (Debian's chromium, driven by puppeteer-core): it
// loads and draws the lit scene, a spot moved through the page's own controls relights it, and
// the picture changes where the beam moved and hardly elsewhere; the page logs no errors.
// Usage: node viewer_test.mjs BINARY WEB_DIR OUT_DIR   (screenshots go to OUT_DIR)
import { execFileSync } from 'node:child_process';
import { mkdirSync, readFileSync, writeFileSync } from 'node:fs';
import path from 'node:path';

import { launchChromium, openTab, pictureBlocks, viewerOutcome } from './headless_chromium.mjs';
import { startServer } from './serve_process.mjs';

const [binary, webDir, outDir] = process.argv.slice(2);
mkdirSync(outDir, { recursive: true });

function fail(message) {
  console.error(`FAIL: ${message}`);
  process.exitCode = 1;
}

const server = await startServer(binary, ['cornell-spot', '--patches', '600', '--cache-dir', 'none',
  '--web-dir', webDir]);
const url = server.url;

const browser = await launchChromium(webDir);
try {
  const { tab: page, errors } = await openTab(browser, 900, 600);
  await page.goto(url);
  await page.waitForFunction(() => window.viewerState && window.viewerState.frames > 3, { timeout: 60000 });

  // The lux meter: a shift-click on the floor reads what `solve --sensors` reads at that point
  // (the same method and settings; the server's relighter against the solve's Gauss-Seidel).
  const box = await page.evaluate(() => {
    const r = document.getElementById('view').getBoundingClientRect();
    return { x: r.left + 0.5 * r.width, y: r.top + 0.85 * r.height };
  });
  await page.keyboard.down('Shift');
  await page.mouse.click(box.x, box.y);
  await page.keyboard.up('Shift');
  await page.waitForFunction(() => window.viewerState.sensor !== null, { timeout: 60000 });
  const sensor = await page.evaluate(() => window.viewerState.sensor);
  const shown = await page.evaluate(() => document.getElementById('sensor-reading').textContent);
  console.log(`lux meter: ${shown}`);
  if (!shown.includes(' lx')) fail(`lux meter shows '${shown}'`);
  const csv = path.join(outDir, 'sensor.csv'), readings = path.join(outDir, 'sensor_read.csv');
  writeFileSync(csv, `${[...sensor.position, ...sensor.normal].join(',')},clicked\n`);
  execFileSync(binary, ['solve', 'cornell-spot', '--method', 'patch', '--patches', '600', '--cache-dir',
    'none', '--sensors', csv, '--sensor-output', readings, '--quiet']);
  const solved = Number(readFileSync(readings, 'utf8').trim().split('\n')[1].split(',')[11]);
  console.log(`the page reads ${sensor.illuminance_lux.toPrecision(5)} lx, solve --sensors ${solved.toPrecision(5)} lx`);
  if (!(Math.abs(sensor.illuminance_lux / solved - 1) < 0.01))
    fail(`the page's ${sensor.illuminance_lux} lx against solve --sensors' ${solved} lx`);

  const blocks = () => pictureBlocks(page);
  const before = await blocks();
  await page.screenshot({ path: path.join(outDir, 'viewer_before.png') });

  // Frames a second on this machine's software WebGL while the light changes, for the notes.
  const fps = await page.evaluate(async () => {
    const inputs = document.querySelectorAll('#light-0 .intensity input');
    const start = performance.now(), frames = window.viewerState.frames;
    for (let k = 0; k < 10; ++k) {
      inputs[0].value = String(200000 + 10000 * k);
      inputs[0].dispatchEvent(new Event('change'));
      await new Promise((resolve) => setTimeout(resolve, 100));
    }
    return (window.viewerState.frames - frames) / ((performance.now() - start) / 1000);
  });
  console.log(`${fps.toFixed(1)} frames a second while relighting`);
  const resetFrom = await page.evaluate(() => {  // back to the spot's own intensity
    const inputs = document.querySelectorAll('#light-0 .intensity input');
    inputs[0].value = '268360';
    inputs[0].dispatchEvent(new Event('change'));
    return window.viewerState.relights;
  });
  // Settled: the reset answered, and no relight for half a second since.
  let seen = -1;
  for (;;) {
    await new Promise((resolve) => setTimeout(resolve, 500));
    const now = await page.evaluate(() => window.viewerState.relights);
    if (now > resetFrom && now === seen) break;
    seen = now;
  }
  const settled = await blocks();

  // Swing the spot toward the green wall through the direction fields of the lights panel.
  const relights = await page.evaluate(() => window.viewerState.relights);
  await page.evaluate(() => {
    const inputs = document.querySelectorAll('#light-0 .direction input');
    inputs[0].value = '-0.8';
    inputs[0].dispatchEvent(new Event('change'));
  });
  await page.waitForFunction((n) => window.viewerState.relights > n, { timeout: 60000 }, relights);
  const frames = await page.evaluate(() => window.viewerState.frames);
  await page.waitForFunction((n) => window.viewerState.frames > n + 3, { timeout: 60000 }, frames);
  const after = await blocks();
  await page.screenshot({ path: path.join(outDir, 'viewer_after.png') });

  const change = settled.map((v, b) => Math.abs(after[b] - v));
  const largest = Math.max(...change);
  const changed = change.filter((c) => c > 0.1).length;
  console.log(`largest block change ${largest.toFixed(3)}, ${changed} of ${change.length} blocks changed by > 0.1`);
  if (!(largest > 0.1)) fail('the picture did not change where the beam moved');
  if (!(changed < change.length / 3)) fail('the picture changed nearly everywhere, not where the beam moved');
  // The false-colour view: irradiance in lux over the Cornell data's millimetres (the unit the
  // scene gives), with its legend.
  const unit = await page.evaluate(() => document.getElementById('unit-metres').value);
  if (unit !== '0.001') fail(`scene unit ${unit} m, expected the Cornell box's millimetres`);
  await page.evaluate(() => {
    const toggle = document.getElementById('false-colour');
    toggle.checked = true;
    toggle.dispatchEvent(new Event('change'));
  });
  await page.waitForFunction(() => document.getElementById('legend-max').textContent.endsWith('lx'),
    { timeout: 60000 });
  const falseFrames = await page.evaluate(() => window.viewerState.frames);
  await page.waitForFunction((n) => window.viewerState.frames > n + 3, { timeout: 60000 }, falseFrames);
  await page.screenshot({ path: path.join(outDir, 'viewer_false_colour.png') });
  const legend = await page.evaluate(() => document.getElementById('legend-max').textContent);
  console.log(`false colour up to ${legend}`);
  if (!(parseFloat(legend) > 0)) fail(`false-colour legend '${legend}'`);
  // Its top: the 98th percentile of the luminance-weighted irradiance, per square millimetre
  // made per square metre, at 179 lm/W (the efficacy candela are read with).
  const expected = await page.evaluate(async () => {
    const h = new Float32Array(await (await fetch('api/irradiance')).arrayBuffer());
    const lux = [];
    for (let v = 0; v < h.length / 3; ++v)
      lux.push(179 * 1e6 * (0.2126 * h[3 * v] + 0.7152 * h[3 * v + 1] + 0.0722 * h[3 * v + 2]));
    lux.sort((a, b) => a - b);
    return lux[Math.floor(0.98 * (lux.length - 1))];
  });
  if (!(Math.abs(parseFloat(legend) / expected - 1) < 0.01))
    fail(`false-colour legend '${legend}', expected ${expected.toPrecision(3)} lx`);
  const { state, problems } = await viewerOutcome(page, errors);
  console.log(`relight ${state.lastRelightMs} ms, ${state.frames} frames, ${state.errors} errors`);
  problems.forEach(fail);
} catch (error) {
  fail(error.stack || String(error));
} finally {
  await browser.close();
  server.stop();
}
