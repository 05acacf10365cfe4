// The replay screenshots in docs/images: runs the chapter scenarios with floornav, opens each
// trajectory.html in headless chromium at chosen times and saves PNGs (a strip of frames is one
// page of iframes, each the replay at its own #t=).
// Usage (from the repository): node tests/browser/screenshots.mjs build/floornav docs/images
import puppeteer from 'puppeteer-core';
import { execFileSync } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { pathToFileURL } from 'node:url';
import { launchChromium } from './launch.mjs';

const [binary, outDir] = process.argv.slice(2);
if (!binary || !outDir) {
  console.error('usage: node tests/browser/screenshots.mjs FLOORNAV_BINARY OUT_DIR');
  process.exit(2);
}
const source = path.resolve(import.meta.dirname, '../..');
const work = fs.mkdtempSync(path.join(os.tmpdir(), 'floornav-shots-'));

function run(name, scenario, ...sets) {
  const out = path.join(work, name);
  const args = ['run', path.join(source, 'scenarios', scenario), '--out', out, '--quiet'];
  for (const s of sets) args.push('--set', s);
  execFileSync(binary, args, { stdio: 'inherit' });
  return path.join(out, 'trajectory.html');
}

const browser = await launchChromium(puppeteer, work);

async function frame(page, file, hash, out, size) {
  await page.setViewport(size);
  await page.goto(pathToFileURL(file).href + hash, { waitUntil: 'load' });
  await page.waitForFunction(() => window.floornavReplay && window.floornavReplay.readyMs);
  await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));
  await page.screenshot({ path: path.join(outDir, out), type: 'png' });
  console.log(`${out}: ${hash}`);
}

async function strip(page, file, fractions, out) {
  const duration = await (async () => {
    await page.goto(pathToFileURL(file).href, { waitUntil: 'load' });
    return page.evaluate(() => window.floornavReplay.duration);
  })();
  const w = 560;
  const h = 520;
  const frames = fractions.map((f) => `<iframe src="${pathToFileURL(file).href}#t=${(f * duration).toFixed(2)}" ` +
    `width="${w}" height="${h}" style="border:0;margin:0 4px 0 0"></iframe>`).join('');
  const stripFile = path.join(work, `${out}.html`);
  fs.writeFileSync(stripFile, `<!DOCTYPE html><body style="margin:0;display:flex">${frames}</body>`);
  await page.setViewport({ width: fractions.length * (w + 4), height: h });
  await page.goto(pathToFileURL(stripFile).href, { waitUntil: 'load' });
  // The frames are file: pages of their own origin (not readable from here): give them time.
  await page.evaluate(() => new Promise((r) => setTimeout(r, 2000)));
  await page.screenshot({ path: path.join(outDir, out), type: 'png' });
  console.log(`${out}: ${fractions.map((f) => (f * duration).toFixed(2)).join(', ')} s`);
}

const page = await browser.newPage();
const big = { width: 1100, height: 760 };
await frame(page, run('factory', 'factory_delivery.yaml'), '#t=24', 'replay_factory.png', big);
await frame(page, run('rect-hs', 'rectangle.yaml', 'controller.kind=hard_switch'), '#t=9',
  'replay_rectangle_hard_switch.png', big);
await frame(page, run('pocket', 'week7_pocket.yaml'), '#t=12', 'replay_week7_pocket.png', big);
await strip(page, run('crossing', 'fleet_crossing.yaml'), [0.15, 0.4, 0.6, 0.95],
  'replay_fleet_crossing_strip.png');
await browser.close();
fs.rmSync(work, { recursive: true, force: true });
