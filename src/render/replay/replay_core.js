// floornav replay: the page's own logic, free of the DOM (decoding the data, interpolating poses
// in time, finding modes, goals and beam frames, thinning trails for drawing, the URL hash).
// The page loads it before replay_app.js; node's test runner loads it as a module
// (tests/browser/replay_core.test.mjs).
(function (root, factory) {
  const api = factory();
  if (typeof module === 'object' && module.exports) module.exports = api;
  else root.FloornavCore = api;
})(typeof globalThis !== 'undefined' ? globalThis : this, function () {
  'use strict';

  const ANGLE_UNIT = 1e-4; // rad per stored heading unit
  const MM = 1e-3; // m per stored length unit
  const ROW_SLACK = 1e-6; // rows: a time within this of a row counts as that row

  /** Running sums of a delta-coded integer list: the values it encodes. */
  function undelta(deltas) {
    const out = new Float64Array(deltas.length);
    let sum = 0;
    for (let i = 0; i < deltas.length; i++) {
      sum += deltas[i];
      out[i] = sum;
    }
    return out;
  }

  /** A pose series {k, x, y, th} as stored (delta-coded mm and 1e-4 rad) -> rows, metres, rad. */
  function decodeSeries(s) {
    const k = undelta(s.k);
    const x = undelta(s.x);
    const y = undelta(s.y);
    const th = undelta(s.th);
    for (let i = 0; i < k.length; i++) {
      x[i] *= MM;
      y[i] *= MM;
      th[i] *= ANGLE_UNIT;
    }
    return { k, x, y, th };
  }

  /** The angle a, wrapped to (-pi, pi]. */
  function wrapAngle(a) {
    let w = a - 2 * Math.PI * Math.round(a / (2 * Math.PI));
    if (w <= -Math.PI) w += 2 * Math.PI;
    if (w > Math.PI) w -= 2 * Math.PI;
    return w;
  }

  /** Time (s) of trajectory row k: k / rate when the step is a whole fraction of a second. */
  function rowTime(data, k) {
    return data.rate ? k / data.rate : k * data.dt;
  }

  /** The (fractional) row shown at time t. */
  function timeToRow(data, t) {
    return data.rate ? t * data.rate : t / data.dt;
  }

  /** Largest i with sorted[i] <= value (+ ROW_SLACK), or -1. */
  function lastAtOrBefore(sorted, value) {
    let lo = 0;
    let hi = sorted.length - 1;
    let found = -1;
    const v = value + ROW_SLACK;
    while (lo <= hi) {
      const mid = (lo + hi) >> 1;
      if (sorted[mid] <= v) {
        found = mid;
        lo = mid + 1;
      } else {
        hi = mid - 1;
      }
    }
    return found;
  }

  /**
   * The pose of a decoded series at (fractional) row: linear in time between the kept rows around
   * it, the heading the short way (the stored headings are unwrapped); the first or last pose
   * outside the series. Returns {x, y, theta} with theta wrapped to (-pi, pi].
   */
  function poseAt(series, row) {
    const n = series.k.length;
    if (n === 0) return { x: 0, y: 0, theta: 0 };
    const i = lastAtOrBefore(series.k, row);
    if (i < 0) return { x: series.x[0], y: series.y[0], theta: wrapAngle(series.th[0]) };
    if (i >= n - 1 || Math.abs(series.k[i] - row) <= ROW_SLACK) {
      return { x: series.x[i], y: series.y[i], theta: wrapAngle(series.th[i]) };
    }
    const f = (row - series.k[i]) / (series.k[i + 1] - series.k[i]);
    return {
      x: series.x[i] + f * (series.x[i + 1] - series.x[i]),
      y: series.y[i] + f * (series.y[i + 1] - series.y[i]),
      theta: wrapAngle(series.th[i] + f * (series.th[i + 1] - series.th[i])),
    };
  }

  /** Mode runs [row, mode, row, mode, ...] -> {rows, modes}. */
  function decodeRuns(flat) {
    const rows = [];
    const modes = [];
    for (let i = 0; i + 1 < flat.length; i += 2) {
      rows.push(flat[i]);
      modes.push(flat[i + 1]);
    }
    return { rows, modes };
  }

  /** The mode index at (fractional) row: the run holding the last whole row at or before it. */
  function modeAt(runs, row) {
    const i = lastAtOrBefore(runs.rows, Math.floor(row + ROW_SLACK));
    return i < 0 ? (runs.modes.length ? runs.modes[0] : 0) : runs.modes[i];
  }

  /**
   * Which goal a robot is heading for at (fractional) row: the first whose reached row is not yet
   * passed (goal_rows[g] is -1 for a goal never reached); goals.length once all are reached.
   */
  function goalIndexAt(goalRows, row) {
    for (let g = 0; g < goalRows.length; g++) {
      if (goalRows[g] < 0 || goalRows[g] > row + ROW_SLACK) return g;
    }
    return goalRows.length;
  }

  /** Index of the beam frame shown at (fractional) row: the last recorded at or before it. */
  function frameAt(frameRows, row) {
    return lastAtOrBefore(frameRows, row);
  }

  /**
   * Thinning a polyline for drawing: indices of the points to draw, the first and the last always,
   * and in between a point only when it is at least minDist from the last one kept (so a trail of
   * 60,000 samples costs what a few hundred pixels need). xs and ys: coordinates in the unit of
   * minDist; `end` (exclusive) limits the points considered.
   */
  function thinPolyline(xs, ys, minDist, end) {
    const n = end === undefined ? xs.length : Math.min(end, xs.length);
    const kept = [];
    if (n === 0) return kept;
    kept.push(0);
    const d2 = minDist * minDist;
    let lx = xs[0];
    let ly = ys[0];
    for (let i = 1; i < n - 1; i++) {
      const dx = xs[i] - lx;
      const dy = ys[i] - ly;
      if (dx * dx + dy * dy >= d2) {
        kept.push(i);
        lx = xs[i];
        ly = ys[i];
      }
    }
    if (n > 1) kept.push(n - 1);
    return kept;
  }

  /** "#t=12.5&follow=bot%202" -> {t: 12.5, follow: "bot 2"}; missing or malformed parts are null. */
  function parseHash(hash) {
    const out = { t: null, follow: null };
    if (typeof hash !== 'string') return out;
    const body = hash.charAt(0) === '#' ? hash.slice(1) : hash;
    for (const part of body.split('&')) {
      const eq = part.indexOf('=');
      if (eq < 0) continue;
      const key = part.slice(0, eq);
      let value;
      try {
        value = decodeURIComponent(part.slice(eq + 1));
      } catch (e) {
        continue;
      }
      if (key === 't') {
        if (/^\s*[+]?(\d+(\.\d*)?|\.\d+)([eE][+-]?\d+)?\s*$/.test(value)) {
          const t = Number(value);
          if (Number.isFinite(t)) out.t = t;
        }
      } else if (key === 'follow' && value.length > 0) {
        out.follow = value;
      }
    }
    return out;
  }

  /** The shortest decimal of t to the millisecond: 12.5 -> "12.5", 600.000000000002 -> "600". */
  function shortTime(t) {
    const ms = Math.round(t * 1000);
    return String(ms / 1000);
  }

  /** The hash that shows time t (and follows a robot, when named). */
  function formatHash(t, follow) {
    let h = '#t=' + shortTime(Math.max(0, t));
    if (follow) h += '&follow=' + encodeURIComponent(follow);
    return h;
  }

  /** A grid's run-length-coded cells [value, count, ...] -> one byte per cell. */
  function decodeGrid(grid) {
    const cells = new Uint8Array(grid.width * grid.height);
    let at = 0;
    for (let i = 0; i + 1 < grid.rle.length; i += 2) {
      const v = grid.rle[i];
      const n = grid.rle[i + 1];
      cells.fill(v, at, Math.min(at + n, cells.length));
      at += n;
    }
    return cells;
  }

  /** Switches [row, from, to, guard, ...] -> [{row, from, to, guard}]. */
  function decodeSwitches(flat) {
    const out = [];
    for (let i = 0; i + 3 < flat.length; i += 4) {
      out.push({ row: flat[i], from: flat[i + 1], to: flat[i + 2], guard: flat[i + 3] });
    }
    return out;
  }

  return {
    ANGLE_UNIT,
    MM,
    undelta,
    decodeSeries,
    wrapAngle,
    rowTime,
    timeToRow,
    lastAtOrBefore,
    poseAt,
    decodeRuns,
    modeAt,
    goalIndexAt,
    frameAt,
    thinPolyline,
    parseHash,
    shortTime,
    formatHash,
    decodeGrid,
    decodeSwitches,
  };
});
