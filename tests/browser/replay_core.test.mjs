// The replay page's own logic (src/render/replay/replay_core.js), with node's test runner:
// decoding, interpolation in time, modes, goals and beam frames, trail thinning, the URL hash.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { createRequire } from 'node:module';

const require = createRequire(import.meta.url);
const C = require('../../src/render/replay/replay_core.js');

const near = (a, b, tol, what) =>
  assert.ok(Math.abs(a - b) <= tol, `${what ?? ''} ${a} is not within ${tol} of ${b}`);

test('undelta sums the deltas', () => {
  assert.deepEqual(Array.from(C.undelta([5, -2, 0, 7])), [5, 3, 3, 10]);
  assert.deepEqual(Array.from(C.undelta([])), []);
});

test('decodeSeries turns millimetres and 1e-4 rad into metres and radians', () => {
  const s = C.decodeSeries({ k: [0, 10, 10], x: [1000, 250, -50], y: [-20, 0, 20], th: [15708, 0, -31416] });
  assert.deepEqual(Array.from(s.k), [0, 10, 20]);
  near(s.x[1], 1.25, 1e-12);
  near(s.x[2], 1.2, 1e-12);
  near(s.y[0], -0.02, 1e-12);
  near(s.th[0], 1.5708, 1e-12);
  near(s.th[2], 1.5708 - 3.1416, 1e-12);
});

test('wrapAngle wraps to (-pi, pi]', () => {
  near(C.wrapAngle(3 * Math.PI), Math.PI, 1e-12);
  near(C.wrapAngle(-Math.PI), Math.PI, 1e-12);
  near(C.wrapAngle(7), 7 - 2 * Math.PI, 1e-12);
  near(C.wrapAngle(0.5), 0.5, 0);
});

test('rows and times: k / rate when 1/dt is whole, k * dt otherwise', () => {
  assert.equal(C.rowTime({ rate: 100, dt: 0.01 }, 60000), 600);
  assert.equal(C.rowTime({ rate: 100, dt: 0.01 }, 3), 0.03);
  assert.equal(C.rowTime({ rate: null, dt: 0.03 }, 3), 3 * 0.03);
  assert.equal(C.timeToRow({ rate: 100, dt: 0.01 }, 12.5), 1250);
});

test('poseAt interpolates linearly in time between kept rows', () => {
  // Kept rows 0 and 10: (0, 0) heading 0 and (1, 2) heading 1.
  const s = { k: [0, 10], x: [0, 1], y: [0, 2], th: [0, 1] };
  const p = C.poseAt(s, 2.5); // a quarter of the way
  near(p.x, 0.25, 1e-12);
  near(p.y, 0.5, 1e-12);
  near(p.theta, 0.25, 1e-12);
  // Exactly on a kept row, before the first, after the last.
  assert.deepEqual(C.poseAt(s, 10), { x: 1, y: 2, theta: 1 });
  assert.deepEqual(C.poseAt(s, -4), { x: 0, y: 0, theta: 0 });
  assert.deepEqual(C.poseAt(s, 99), { x: 1, y: 2, theta: 1 });
});

test('poseAt turns the short way across pi (the stored headings are unwrapped)', () => {
  // 3.1 rad to 3.1 + 0.2 rad (unwrapped): halfway is 3.2, i.e. 3.2 - 2 pi wrapped.
  const s = { k: [0, 2], x: [0, 0], y: [0, 0], th: [3.1, 3.3] };
  near(C.poseAt(s, 1).theta, 3.2 - 2 * Math.PI, 1e-12);
});

test('modeAt: the run holding the last whole row at or before the time', () => {
  const runs = C.decodeRuns([0, 0, 10, 2, 20, 1]);
  assert.deepEqual(runs, { rows: [0, 10, 20], modes: [0, 2, 1] });
  assert.equal(C.modeAt(runs, 0), 0);
  assert.equal(C.modeAt(runs, 9.99), 0);
  assert.equal(C.modeAt(runs, 10), 2);
  assert.equal(C.modeAt(runs, 10 - 1e-9), 2); // rounding of t * rate
  assert.equal(C.modeAt(runs, 19.5), 2);
  assert.equal(C.modeAt(runs, 500), 1);
});

test('goalIndexAt: the first goal not yet reached', () => {
  assert.equal(C.goalIndexAt([100, 250, -1], 0), 0);
  assert.equal(C.goalIndexAt([100, 250, -1], 100), 1);
  assert.equal(C.goalIndexAt([100, 250, -1], 300), 2); // never reached: still the goal
  assert.equal(C.goalIndexAt([100, 250], 300), 2); // all reached
  assert.equal(C.goalIndexAt([], 5), 0);
});

test('frameAt: the last beam frame at or before the row, none before the first', () => {
  const rows = [0, 5, 10, 15];
  assert.equal(C.frameAt(rows, 0), 0);
  assert.equal(C.frameAt(rows, 4.9), 0);
  assert.equal(C.frameAt(rows, 5), 1);
  assert.equal(C.frameAt(rows, 99), 3);
  assert.equal(C.frameAt([3, 6], 1), -1);
});

test('thinPolyline keeps the ends and points at least minDist apart', () => {
  // 21 points 0.1 apart on a line; at minDist 0.25 every third is kept (0.3 apart).
  const xs = Array.from({ length: 21 }, (_, i) => 0.1 * i);
  const ys = xs.map(() => 0);
  assert.deepEqual(C.thinPolyline(xs, ys, 0.25), [0, 3, 6, 9, 12, 15, 18, 20]);
  // Nothing is dropped when the points are already far apart.
  assert.deepEqual(C.thinPolyline(xs, ys, 0.05), xs.map((_, i) => i));
  // `end` limits the points considered; one and zero points.
  assert.deepEqual(C.thinPolyline(xs, ys, 0.25, 5), [0, 3, 4]);
  assert.deepEqual(C.thinPolyline([1], [1], 1), [0]);
  assert.deepEqual(C.thinPolyline([], [], 1), []);
});

test('thinPolyline drops only points within minDist of the last kept one', () => {
  // A spiral 120 m long in 2,000 points: at minDist 0.2 about 600 are needed, not 2,000.
  const xs = [];
  const ys = [];
  for (let i = 0; i < 2000; i++) {
    xs.push(Math.cos(i / 50) * (1 + i / 500));
    ys.push(Math.sin(i / 50) * (1 + i / 500));
  }
  const kept = C.thinPolyline(xs, ys, 0.2);
  assert.ok(kept.length > 400 && kept.length < 650, `kept ${kept.length}`);
  for (let j = 1; j < kept.length; j++) {
    const a = kept[j - 1];
    const b = kept[j];
    for (let i = a + 1; i < b; i++) {
      assert.ok(Math.hypot(xs[i] - xs[a], ys[i] - ys[a]) < 0.2, `point ${i} dropped too far`);
    }
  }
});

test('parseHash reads the time and the followed robot, and rejects the rest', () => {
  assert.deepEqual(C.parseHash('#t=12.5'), { t: 12.5, follow: null });
  assert.deepEqual(C.parseHash('#t=1e2'), { t: 100, follow: null });
  assert.deepEqual(C.parseHash('#follow=bot%202&t=3'), { t: 3, follow: 'bot 2' });
  assert.deepEqual(C.parseHash('t=.5'), { t: 0.5, follow: null });
  for (const bad of ['', '#', '#t=', '#t=abc', '#t=-3', '#t=1.2.3', '#t=Infinity', '#x=4', '#t=%E0%A4%A']) {
    assert.equal(C.parseHash(bad).t, null, bad);
  }
  assert.equal(C.parseHash(undefined).t, null);
});

test('formatHash writes the time to the millisecond without float drift', () => {
  assert.equal(C.formatHash(12.5), '#t=12.5');
  assert.equal(C.formatHash(600.000000000002), '#t=600');
  assert.equal(C.formatHash(0.30000000000000004), '#t=0.3');
  assert.equal(C.formatHash(-1), '#t=0');
  assert.equal(C.formatHash(3, 'a b'), '#t=3&follow=a%20b');
  // What formatHash writes, parseHash reads back.
  assert.deepEqual(C.parseHash(C.formatHash(41.27, 'north/1')), { t: 41.27, follow: 'north/1' });
});

test('decodeGrid expands the run-length cells', () => {
  const cells = C.decodeGrid({ width: 3, height: 2, rle: [0, 2, 1, 1, 2, 3] });
  assert.deepEqual(Array.from(cells), [0, 0, 1, 2, 2, 2]);
});

test('decodeSwitches', () => {
  assert.deepEqual(C.decodeSwitches([5, 0, 1, 2, 9, 1, 0, -1]), [
    { row: 5, from: 0, to: 1, guard: 2 },
    { row: 9, from: 1, to: 0, guard: -1 },
  ]);
});
