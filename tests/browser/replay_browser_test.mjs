// trajectory.html in a real browser: Debian's chromium, headless, driven by puppeteer-core.
// floornav writes the pages (a lone robot, a fleet, a map with unknown cells); the tests check that
// a page loads with no console error and no network request, that seek(t) then state() matches
// trajectory.csv for every robot, that play advances time, that a screenshot shows the robot
// where the CSV says (pixels), and that the keyboard and the URL hash work.
//
// Environment: FLOORNAV_BINARY (the floornav executable), FLOORNAV_SOURCE_DIR (the repository),
// CHROMIUM (default /usr/bin/chromium). Exits 77 (ctest: skipped) when chromium or
// node_modules/puppeteer-core is missing, unless FLOORNAV_REQUIRE_BROWSER=1 (CI), when that fails.
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import zlib from 'node:zlib';
import { pathToFileURL } from 'node:url';
import { CHROMIUM, launchChromium } from './launch.mjs';

const chromium = CHROMIUM;
const binary = process.env.FLOORNAV_BINARY;
const source = process.env.FLOORNAV_SOURCE_DIR || path.resolve(import.meta.dirname, '../..');
const required = process.env.FLOORNAV_REQUIRE_BROWSER === '1';

function skip(reason) {
  if (required) {
    console.error(`replay browser test: ${reason} (FLOORNAV_REQUIRE_BROWSER=1: failing)`);
    process.exit(1);
  }
  console.log(`skipped: ${reason}`);
  process.exit(77);
}

let puppeteer;
try {
  puppeteer = (await import('puppeteer-core')).default;
} catch (e) {
  skip('puppeteer-core is not installed (run `npm ci` in tests/browser)');
}
if (!fs.existsSync(chromium)) skip(`no chromium at ${chromium} (apt-get install chromium)`);
if (!binary || !fs.existsSync(binary)) skip('FLOORNAV_BINARY does not name the floornav executable');

const POSITION_TOLERANCE = 0.01; // m: the replay is exact to 1 cm at recorded times
const HEADING_TOLERANCE = 0.02; // rad

const work = fs.mkdtempSync(path.join(os.tmpdir(), 'floornav-replay-'));
let browser;

function run(scenario, out, ...sets) {
  const file = path.isAbsolute(scenario) ? scenario : path.join(source, 'scenarios', scenario);
  const args = ['run', file, '--out', out, '--quiet'];
  for (const s of sets) args.push('--set', s);
  execFileSync(binary, args, { stdio: 'inherit' });
  return out;
}

/**
 * A ROS map_server map (4 x 3 m at 0.1 m: walls round the edge, a 1 x 1 m block of unknown cells
 * with its lower-left corner at (2.5, 1.5)) and a scenario on it; returns the scenario's path.
 */
function writeMapScenario() {
  const w = 40;
  const h = 30;
  const pixels = Buffer.alloc(w * h, 254); // free
  for (let row = 0; row < h; row++) {
    for (let col = 0; col < w; col++) {
      const y = h - 1 - row; // image rows run top down, the map's y up
      if (col === 0 || row === 0 || col === w - 1 || row === h - 1) pixels[row * w + col] = 0;
      else if (col >= 25 && col < 35 && y >= 15 && y < 25) pixels[row * w + col] = 205; // unknown
    }
  }
  fs.writeFileSync(path.join(work, 'room.pgm'), Buffer.concat([Buffer.from(`P5\n${w} ${h}\n255\n`), pixels]));
  fs.writeFileSync(path.join(work, 'room.yaml'),
    'image: room.pgm\nresolution: 0.1\norigin: [0, 0, 0]\nnegate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n');
  const scenario = path.join(work, 'room_run.yaml');
  fs.writeFileSync(scenario, 'name: room\nworld: {map: room.yaml}\n' +
    'robot: {preset: quickbot, start: [0.6, 0.6, 0]}\ngoal: [1.6, 0.6]\nsim: {t_max: 20}\n');
  return scenario;
}

/**
 * A walled 10 x 6 m hall: a QuickBot crossing it low, a person walking across the top and a
 * forklift driving the middle; returns the scenario's path.
 */
function writeCrowdScenario() {
  const scenario = path.join(work, 'crowd_run.yaml');
  fs.writeFileSync(scenario, [
    'name: crowd',
    'world: {bounds: [0, 0, 10, 6]}',
    'robot: {preset: quickbot, start: [1, 0.8, 0]}',
    'goal: [9, 0.8]',
    'people:',
    '  - {name: ann, start: [1.5, 5], waypoints: [[8.5, 5]], speed: 1.0, cyclic: false}',
    'forklifts:',
    '  - {name: fork1, route: [[1.5, 3], [8.5, 3]], speed: 0.8, size: [1.2, 0.6], cyclic: false}',
    'sim: {t_max: 60}',
    '',
  ].join('\n'));
  return scenario;
}

/** crowd.csv -> {name: [{t, kind, x, y, theta}]}. */
function readCrowdCsv(file) {
  const lines = fs.readFileSync(file, 'utf8').trim().split('\n');
  assert.equal(lines[0], 't,kind,name,x,y,theta');
  const byName = {};
  for (const line of lines.slice(1)) {
    const [t, kind, name, x, y, theta] = line.split(',');
    (byName[name] ??= []).push({ t: +t, kind, x: +x, y: +y, theta: +theta });
  }
  return byName;
}

/** trajectory.csv -> {robot name: [{t, x, y, theta, mode}]} (a lone robot is named ''). */
function readCsv(file) {
  const lines = fs.readFileSync(file, 'utf8').trim().split('\n');
  const header = lines[0].split(',');
  const col = (name) => header.indexOf(name);
  const [it, ix, iy, ith, im, ir] = ['t', 'x', 'y', 'theta', 'mode', 'robot'].map(col);
  const byRobot = {};
  for (const line of lines.slice(1)) {
    const f = line.split(',');
    const name = ir >= 0 ? f[ir] : '';
    (byRobot[name] ??= []).push({ t: +f[it], x: +f[ix], y: +f[iy], theta: +f[ith], mode: f[im] });
  }
  return byRobot;
}

/** The row of `rows` in force at time t (the last at or before it). */
function rowAt(rows, t) {
  let best = rows[0];
  for (const r of rows) {
    if (r.t <= t + 1e-9) best = r;
    else break;
  }
  return best;
}

function angleGap(a, b) {
  return Math.abs(Math.atan2(Math.sin(a - b), Math.cos(a - b)));
}

/** Opens a page, recording console errors, page errors and every request. */
async function open(file, hash = '') {
  const page = await browser.newPage();
  await page.setViewport({ width: 1200, height: 800 });
  const problems = [];
  const requests = [];
  page.on('console', (m) => {
    if (m.type() === 'error' || m.type() === 'warning') problems.push(`console ${m.type()}: ${m.text()}`);
  });
  page.on('pageerror', (e) => problems.push(`page error: ${e.message}`));
  page.on('requestfailed', (r) => problems.push(`request failed: ${r.url()}`));
  page.on('request', (r) => requests.push(r.url()));
  const url = pathToFileURL(file).href + hash;
  const started = Date.now();
  await page.goto(url, { waitUntil: 'load' });
  await page.waitForFunction(() => window.floornavReplay !== undefined);
  const openMs = Date.now() - started;
  return { page, problems, requests, url, openMs };
}

/** Waits until the page has drawn two more frames (seek(t) draws at the next one). */
function nextFrames(page) {
  return page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));
}

/** Compares state() after seek(t) with the CSV, for every robot at each of `times`. */
async function expectMatchesCsv(page, csv, times) {
  const states = await page.evaluate((ts) => ts.map((t) => {
    window.floornavReplay.seek(t);
    return window.floornavReplay.state();
  }), times);
  const names = Object.keys(csv);
  let worst = 0;
  let checked = 0;
  states.forEach((s, i) => {
    assert.ok(Math.abs(s.t - times[i]) < 1e-9, `state().t ${s.t} after seek(${times[i]})`);
    assert.equal(s.robots.length, names.length);
    for (const robot of s.robots) {
      const rows = csv[names.length === 1 && names[0] === '' ? '' : robot.name];
      assert.ok(rows, `robot ${robot.name} is not in the CSV`);
      const row = rowAt(rows, times[i]);
      const gap = Math.hypot(robot.x - row.x, robot.y - row.y);
      worst = Math.max(worst, gap);
      assert.ok(gap <= POSITION_TOLERANCE,
        `${robot.name} at t=${times[i]}: (${robot.x}, ${robot.y}) is ${gap} m from the CSV's (${row.x}, ${row.y})`);
      assert.ok(angleGap(robot.theta, row.theta) <= HEADING_TOLERANCE,
        `${robot.name} at t=${times[i]}: heading ${robot.theta} vs ${row.theta}`);
      assert.equal(robot.mode, row.mode, `${robot.name} at t=${times[i]}`);
      checked++;
    }
  });
  return { worst, checked };
}

// ---- a PNG screenshot's pixels (8-bit RGB/RGBA, not interlaced: what chromium writes) ---------
function decodePng(buffer) {
  let at = 8;
  let width = 0;
  let height = 0;
  let channels = 0;
  const idat = [];
  while (at < buffer.length) {
    const len = buffer.readUInt32BE(at);
    const type = buffer.toString('ascii', at + 4, at + 8);
    const body = buffer.subarray(at + 8, at + 8 + len);
    if (type === 'IHDR') {
      width = body.readUInt32BE(0);
      height = body.readUInt32BE(4);
      assert.equal(body[8], 8, 'bit depth');
      channels = { 2: 3, 6: 4 }[body[9]];
      assert.ok(channels, `colour type ${body[9]}`);
      assert.equal(body[12], 0, 'interlace');
    } else if (type === 'IDAT') {
      idat.push(body);
    }
    at += 12 + len;
  }
  const raw = zlib.inflateSync(Buffer.concat(idat));
  const stride = width * channels;
  const pixels = Buffer.alloc(height * stride);
  for (let y = 0; y < height; y++) {
    const filter = raw[y * (stride + 1)];
    const line = raw.subarray(y * (stride + 1) + 1, (y + 1) * (stride + 1));
    for (let x = 0; x < stride; x++) {
      const a = x >= channels ? pixels[y * stride + x - channels] : 0;
      const b = y > 0 ? pixels[(y - 1) * stride + x] : 0;
      const c = x >= channels && y > 0 ? pixels[(y - 1) * stride + x - channels] : 0;
      let v = line[x];
      if (filter === 1) v += a;
      else if (filter === 2) v += b;
      else if (filter === 3) v += (a + b) >> 1;
      else if (filter === 4) {
        const p = a + b - c;
        const pa = Math.abs(p - a);
        const pb = Math.abs(p - b);
        const pc = Math.abs(p - c);
        v += pa <= pb && pa <= pc ? a : pb <= pc ? b : c;
      }
      pixels[y * stride + x] = v & 255;
    }
  }
  return {
    width,
    height,
    at(x, y) {
      const i = Math.round(y) * stride + Math.round(x) * channels;
      return [pixels[i], pixels[i + 1], pixels[i + 2]];
    },
  };
}

function hexRgb(hex) {
  return [1, 3, 5].map((i) => parseInt(hex.slice(i, i + 2), 16));
}
function colorGap(a, b) {
  return Math.max(...a.map((v, i) => Math.abs(v - b[i])));
}

// ---- the pages ----------------------------------------------------------------------------------
let single;
let fleet;
let map;
let crowd;
before(async () => {
  single = run('rectangle.yaml', path.join(work, 'rectangle'));
  fleet = run('fleet_crossing.yaml', path.join(work, 'fleet'));
  map = run(writeMapScenario(), path.join(work, 'map'));
  crowd = run(writeCrowdScenario(), path.join(work, 'crowd'));
  browser = await launchChromium(puppeteer, work);
});
after(async () => {
  if (browser) await browser.close();
  fs.rmSync(work, { recursive: true, force: true });
});

test('the page loads with no console error and requests nothing but itself', async () => {
  for (const dir of [single, fleet, map, crowd]) {
    const { page, problems, requests, url, openMs } = await open(path.join(dir, 'trajectory.html'));
    // Let a few frames run, so that drawing errors would show.
    await nextFrames(page);
    assert.deepEqual(problems, [], dir);
    assert.deepEqual(requests, [url], `${dir}: every request besides the page itself`);
    const duration = await page.evaluate(() => window.floornavReplay.duration);
    assert.ok(duration > 0);
    console.log(`  ${path.basename(dir)}: ${fs.statSync(path.join(dir, 'trajectory.html')).size} bytes, opened in ${openMs} ms`);
    await page.close();
  }
});

test('seek(t) then state() matches trajectory.csv at every row of a lone robot', async () => {
  const csv = readCsv(path.join(single, 'trajectory.csv'));
  const { page } = await open(path.join(single, 'trajectory.html'));
  const times = csv[''].map((r) => r.t);
  const duration = await page.evaluate(() => window.floornavReplay.duration);
  assert.equal(duration, times[times.length - 1]);
  const { worst, checked } = await expectMatchesCsv(page, csv, times);
  assert.equal(checked, times.length);
  console.log(`  lone robot: ${checked} rows, worst position error ${(worst * 1000).toFixed(2)} mm`);
  await page.close();
});

test('seek(t) then state() matches trajectory.csv for every robot of a fleet', async () => {
  const csv = readCsv(path.join(fleet, 'trajectory.csv'));
  const { page } = await open(path.join(fleet, 'trajectory.html'));
  const duration = await page.evaluate(() => window.floornavReplay.duration);
  // Every 7th row of the longest run, and the very end (robots that finished stay put).
  const longest = Object.values(csv).reduce((a, b) => (a.length >= b.length ? a : b));
  const times = longest.filter((_, i) => i % 7 === 0).map((r) => r.t);
  times.push(duration);
  const { worst, checked } = await expectMatchesCsv(page, csv, times);
  assert.equal(checked, times.length * Object.keys(csv).length);
  console.log(`  fleet: ${checked} robot-times, worst position error ${(worst * 1000).toFixed(2)} mm`);
  await page.close();
});

test('play advances time and stops at the end; pause holds it', async () => {
  const { page } = await open(path.join(single, 'trajectory.html'));
  await page.evaluate(() => {
    window.floornavReplay.seek(0);
    window.floornavReplay.setSpeed(16);
    window.floornavReplay.play();
  });
  await page.waitForFunction(() => window.floornavReplay.state().t > 2, { timeout: 30000 });
  await page.evaluate(() => window.floornavReplay.pause());
  const held = await page.evaluate(() => window.floornavReplay.state().t);
  await page.evaluate(() => new Promise((r) => setTimeout(r, 200)));
  assert.equal(await page.evaluate(() => window.floornavReplay.state().t), held);
  assert.equal(await page.evaluate(() => window.floornavReplay.playing), false);
  // Played to the end, it stops there.
  await page.evaluate(() => window.floornavReplay.play());
  await page.waitForFunction(() => !window.floornavReplay.playing, { timeout: 30000 });
  const end = await page.evaluate(() => [window.floornavReplay.state().t, window.floornavReplay.duration]);
  assert.equal(end[0], end[1]);
  await page.close();
});

test('a screenshot at a known time shows the robot where the CSV says', async () => {
  const csv = readCsv(path.join(single, 'trajectory.csv'))[''];
  const html = fs.readFileSync(path.join(single, 'trajectory.html'), 'utf8');
  const modeColors = JSON.parse(html.match(/"mode_colors":(\{[^}]*\})/)[1]);
  const { page } = await open(path.join(single, 'trajectory.html'));
  for (const fraction of [0.3, 0.6]) {
    const row = csv[Math.round(fraction * (csv.length - 1))];
    const first = csv[0];
    await page.evaluate((t) => window.floornavReplay.seek(t), row.t);
    await nextFrames(page);
    const [centre, edge, start] = await page.evaluate((r, f) => [
      window.floornavReplay.toPage(r.x, r.y),
      window.floornavReplay.toPage(r.x + 0.075, r.y),
      window.floornavReplay.toPage(f.x, f.y),
    ], row, first);
    const bodyPx = Math.abs(edge.x - centre.x); // the QuickBot's 0.075 m radius in pixels
    assert.ok(bodyPx > 8, `body ${bodyPx} px`);
    const png = decodePng(Buffer.from(await page.screenshot({ type: 'png' })));
    // Half a radius behind the centre (the heading line runs forward from it): the body's fill,
    // the colour of the CSV's mode at that time, drawn at 90 % over the band.
    const bx = centre.x - 0.5 * bodyPx * Math.cos(row.theta);
    const by = centre.y + 0.5 * bodyPx * Math.sin(row.theta);
    const want = hexRgb(modeColors[row.mode]);
    const got = png.at(bx, by);
    assert.ok(colorGap(got, want) <= 40, `t=${row.t}: pixel ${got} at the robot, want about ${want} (${row.mode})`);
    // Where the robot started (far from here now) there is no body of that colour.
    assert.ok(Math.hypot(start.x - centre.x, start.y - centre.y) > 4 * bodyPx);
    assert.ok(colorGap(png.at(start.x, start.y - 0.5 * bodyPx), want) > 60, 'no body at the start');
  }
  await page.close();
});

test('people and forklifts move as crowd.csv says, and are drawn where they are', async () => {
  const csv = readCrowdCsv(path.join(crowd, 'crowd.csv'));
  assert.deepEqual(Object.keys(csv).sort(), ['ann', 'fork1']);
  const { page, problems } = await open(path.join(crowd, 'trajectory.html'));
  const duration = await page.evaluate(() => window.floornavReplay.duration);
  // Every 50th recorded state of each (the replay keeps them to the millimetre).
  const times = csv.ann.filter((_, i) => i % 50 === 0).map((r) => r.t).filter((t) => t <= duration);
  const states = await page.evaluate((ts) => ts.map((t) => {
    window.floornavReplay.seek(t);
    return window.floornavReplay.state().crowd;
  }), times);
  let worst = 0;
  states.forEach((shown, i) => {
    assert.equal(shown.length, 2);
    for (const c of shown) {
      const row = rowAt(csv[c.name], times[i]);
      assert.equal(c.kind, row.kind);
      const gap = Math.hypot(c.x - row.x, c.y - row.y);
      worst = Math.max(worst, gap);
      assert.ok(gap <= POSITION_TOLERANCE, `${c.name} at t=${times[i]}: ${gap} m from crowd.csv`);
    }
  });
  // Mid-way, the person's disc is drawn in the people's colour where the CSV puts her, and the
  // forklift's rectangle where it is; where the person started there is nobody any more.
  const row = csv.ann[Math.floor(csv.ann.length / 2)];
  const fork = rowAt(csv.fork1, row.t);
  await page.evaluate((t) => window.floornavReplay.seek(t), row.t);
  await nextFrames(page);
  const [at, behind, forkAt, start] = await page.evaluate((r, f, s) => [
    window.floornavReplay.toPage(r.x, r.y),
    window.floornavReplay.toPage(r.x - 0.15 * Math.cos(r.theta), r.y - 0.15 * Math.sin(r.theta)),
    window.floornavReplay.toPage(f.x - 0.3 * Math.cos(f.theta), f.y - 0.3 * Math.sin(f.theta)),
    window.floornavReplay.toPage(s.x, s.y),
  ], row, fork, csv.ann[0]);
  assert.ok(Math.hypot(at.x - start.x, at.y - start.y) > 40, 'the person has moved on screen');
  const png = decodePng(Buffer.from(await page.screenshot({ type: 'png' })));
  assert.ok(colorGap(png.at(behind.x, behind.y), hexRgb('#7b3fa0')) <= 50, `person pixel ${png.at(behind.x, behind.y)}`);
  assert.ok(colorGap(png.at(forkAt.x, forkAt.y), hexRgb('#b35900')) <= 50, `forklift pixel ${png.at(forkAt.x, forkAt.y)}`);
  assert.ok(colorGap(png.at(start.x, start.y), hexRgb('#7b3fa0')) > 80, 'no person at her start any more');
  assert.deepEqual(problems, []);
  console.log(`  crowd: ${states.length} times x 2, worst position error ${(worst * 1000).toFixed(2)} mm`);
  await page.close();
});

test('the map shows unknown cells in their own colour, apart from walls', async () => {
  const { page } = await open(path.join(map, 'trajectory.html'));
  const [unknown, wall, free] = await page.evaluate(() => [
    window.floornavReplay.toPage(3.0, 2.0), // inside the unknown block
    window.floornavReplay.toPage(0.05, 1.5), // the left wall column
    window.floornavReplay.toPage(1.5, 2.0), // free floor
  ]);
  await nextFrames(page);
  const png = decodePng(Buffer.from(await page.screenshot({ type: 'png' })));
  assert.ok(colorGap(png.at(unknown.x, unknown.y), [222, 214, 240]) <= 6, `unknown ${png.at(unknown.x, unknown.y)}`);
  assert.ok(colorGap(png.at(wall.x, wall.y), [169, 173, 179]) <= 6, `wall ${png.at(wall.x, wall.y)}`);
  assert.ok(colorGap(png.at(free.x, free.y), [255, 255, 255]) <= 6, `free ${png.at(free.x, free.y)}`);
  await page.close();
});

test('keyboard: space plays and pauses, arrows step, +/- change speed, home/end, f follows', async () => {
  const { page } = await open(path.join(fleet, 'trajectory.html'));
  await page.evaluate(() => window.floornavReplay.seek(0));
  await page.focus('#view');
  const t = () => page.evaluate(() => window.floornavReplay.state().t);
  await page.keyboard.press('ArrowRight');
  assert.equal(await t(), 0.01);
  await page.keyboard.press('ArrowRight');
  await page.keyboard.press('ArrowLeft');
  assert.equal(await t(), 0.01);
  await page.keyboard.down('Shift');
  await page.keyboard.press('ArrowRight');
  await page.keyboard.up('Shift');
  assert.equal(await t(), 1.01);
  // The URL hash holds the time.
  assert.equal(await page.evaluate(() => location.hash), '#t=1.01');
  await page.keyboard.press('+');
  assert.equal(await page.evaluate(() => window.floornavReplay.speed), 2);
  await page.keyboard.press('-');
  await page.keyboard.press('-');
  assert.equal(await page.evaluate(() => window.floornavReplay.speed), 0.5);
  await page.keyboard.press('Space');
  assert.equal(await page.evaluate(() => window.floornavReplay.playing), true);
  await page.keyboard.press('Space');
  assert.equal(await page.evaluate(() => window.floornavReplay.playing), false);
  await page.keyboard.press('End');
  assert.equal(await t(), await page.evaluate(() => window.floornavReplay.duration));
  await page.keyboard.press('Home');
  assert.equal(await t(), 0);
  await page.keyboard.press('f'); // the first robot, then the next
  await page.keyboard.press('f');
  assert.equal(await page.evaluate(() => document.getElementById('follow').value), 'west');
  assert.match(await page.evaluate(() => location.hash), /follow=west/);
  await page.close();
});

test('a link with #t= opens at that time', async () => {
  const { page, problems } = await open(path.join(fleet, 'trajectory.html'), '#t=5.5&follow=south');
  assert.equal(await page.evaluate(() => window.floornavReplay.state().t), 5.5);
  assert.equal(await page.evaluate(() => document.getElementById('follow').value), 'south');
  assert.deepEqual(problems, []);
  // A malformed hash is ignored: the page opens at 0.
  const other = await open(path.join(fleet, 'trajectory.html'), '#t=banana');
  assert.equal(await other.page.evaluate(() => window.floornavReplay.state().t), 0);
  await page.close();
  await other.page.close();
});
