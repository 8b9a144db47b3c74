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
