// How long trajectory.html pages take to open in headless chromium: for each page given, the time
// from navigation to the first frame drawn (window.floornavReplay.readyMs), median of 5 loads.
// Usage: node measure_open.mjs PAGE.html ...   (CHROMIUM=/usr/bin/chromium by default)
import puppeteer from 'puppeteer-core';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { pathToFileURL } from 'node:url';
import { launchChromium } from './launch.mjs';

const profile = fs.mkdtempSync(path.join(os.tmpdir(), 'floornav-measure-'));
const browser = await launchChromium(puppeteer, profile);
for (const file of process.argv.slice(2)) {
  const times = [];
  for (let i = 0; i < 5; i++) {
    const page = await browser.newPage();
    await page.setViewport({ width: 1200, height: 800 });
    await page.goto(pathToFileURL(path.resolve(file)).href, { waitUntil: 'load' });
    await page.waitForFunction(() => window.floornavReplay && window.floornavReplay.readyMs);
    times.push(await page.evaluate(() => window.floornavReplay.readyMs));
    await page.close();
  }
  times.sort((a, b) => a - b);
  const mb = fs.statSync(file).size / 1e6;
  console.log(`${file}: ${mb.toFixed(2)} MB, opens in ${Math.round(times[2])} ms (median of 5; ` +
    `${Math.round(times[0])}-${Math.round(times[4])} ms)`);
}
await browser.close();
fs.rmSync(profile, { recursive: true, force: true });
