// Debian's chromium, headless, driven by puppeteer-core from web/node_modules: what the browser
// tests share. WebGL runs on SwiftShader (no GPU here).
import { createRequire } from 'node:module';
import path from 'node:path';

export async function launchChromium(webDir) {
  const require = createRequire(path.resolve(webDir, 'package.json'));
  const puppeteer = require('puppeteer-core');
  return puppeteer.launch({
    executablePath: process.env.CHROMIUM || '/usr/bin/chromium',
    headless: true,
    args: ['--no-sandbox', '--enable-unsafe-swiftshader', '--use-angle=swiftshader'],
  });
}

// A tab of `width` x `height` whose console errors and uncaught exceptions land in the array
// returned with it.
export async function openTab(browser, width, height) {
  const tab = await browser.newPage();
  await tab.setViewport({ width, height });
  const errors = [];
  tab.on('console', (message) => { if (message.type() === 'error') errors.push(message.text()); });
  tab.on('pageerror', (error) => errors.push(error.message));
  return { tab, errors };
}

// Mean luminance (0..1) of the page's WebGL canvas #view in n x n blocks, read back through a 2D
// canvas: what the browser tests compare before and after a change.
export function pictureBlocks(tab, n = 12) {
  return tab.evaluate((blocksPerSide) => {
    const view = document.getElementById('view');
    const copy = document.createElement('canvas');
    copy.width = view.width; copy.height = view.height;
    const context = copy.getContext('2d');
    context.drawImage(view, 0, 0);
    const pixels = context.getImageData(0, 0, copy.width, copy.height).data;
    const out = new Array(blocksPerSide * blocksPerSide).fill(0), count = out.map(() => 0);
    for (let y = 0; y < copy.height; ++y)
      for (let x = 0; x < copy.width; ++x) {
        const k = 4 * (y * copy.width + x);
        const b = Math.floor((y * blocksPerSide) / copy.height) * blocksPerSide +
          Math.floor((x * blocksPerSide) / copy.width);
        out[b] += (0.2126 * pixels[k] + 0.7152 * pixels[k + 1] + 0.0722 * pixels[k + 2]) / 255;
        count[b] += 1;
      }
    return out.map((v, b) => v / count[b]);
  }, n);
}

// How the viewer page fared: its window.viewerState, and the problems to fail on (errors it
// logged, errors it counted).
export async function viewerOutcome(tab, errors) {
  const state = await tab.evaluate(() => window.viewerState);
  const problems = [];
  if (errors.length) problems.push(`the page logged errors: ${errors.join('; ')}`);
  if (state.errors) problems.push('the page reported errors');
  return { state, problems };
}
