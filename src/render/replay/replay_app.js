// floornav replay: the page. Reads the data from #floornav-data, draws the floor on a canvas and
// the modes on a timeline, plays, and exposes window.floornavReplay (CONTRACT.md).
(function () {
  'use strict';
  const C = window.FloornavCore;
  const data = JSON.parse(document.getElementById('floornav-data').textContent);
  const SPEEDS = [0.25, 0.5, 1, 2, 4, 8, 16];
  const TRAIL_PX = 1.5; // trail points closer than this on screen are not drawn
  const MAX_NAMED = 40; // fleets up to this size have their robots named on the floor
  const COLORS = {
    floor: '#ffffff',
    outside: '#eceef0',
    obstacle: '#c9ccd1',
    obstacleEdge: '#6b7079',
    wall: '#37474f',
    goal: '#f4b400',
    goalEdge: '#8a6d00',
    band: 'rgba(255, 152, 0, 0.13)',
    beam: 'rgba(120, 120, 120, 0.35)',
    beamHit: 'rgba(214, 39, 40, 0.55)',
    point: '#d62728',
    collided: '#d62728',
    person: '#7b3fa0',
    forklift: '#b35900',
  };
  const GRID_RGBA = { 1: [169, 173, 179, 255], 2: [222, 214, 240, 255] };

  // ---- the data, decoded once ------------------------------------------------------------------
  const fleet = data.robots.length > 1;
  const robots = data.robots.map(function (r, index) {
    const track = C.decodeSeries(r.track);
    const runs = C.decodeRuns(r.mode_runs);
    const beams = r.beams ? C.decodeSeries(r.beams) : null;
    if (beams) beams.r = r.beams.r;
    const lastRow = Math.max(0, r.rows - 1);
    const robot = {
      index,
      name: r.name,
      color: r.color || '#1f77b4',
      radius: r.radius,
      footprint: r.footprint,
      front: 0,
      d_o: r.d_o,
      footprintClearance: r.footprint_clearance,
      epsilon: r.epsilon,
      goals: r.goals,
      goalRows: r.goal_rows,
      status: r.status,
      collided: r.collided,
      parked: r.parked,
      lastRow,
      modes: r.modes,
      guards: r.guards,
      track,
      runs,
      switches: C.decodeSwitches(r.switches),
      sensors: r.sensors,
      beams,
      trail: null,
      trailCache: null,
    };
    if (robot.footprint) {
      for (let i = 0; i < robot.footprint.length; i += 2) {
        robot.front = Math.max(robot.front, robot.footprint[i]);
      }
    }
    if (!(robot.front > 0)) robot.front = robot.radius;
    robot.trail = buildTrail(robot);
    return robot;
  });
  const duration = data.duration;
  const lastRow = Math.round(C.timeToRow(data, duration));
  // People (discs) and forklifts (rectangles): their tracks, as the robots' are stored.
  const crowd = [];
  if (data.crowd) {
    data.crowd.people.forEach(function (p) {
      crowd.push({ kind: 'person', name: p.name, size: p.size, track: C.decodeSeries(p.track) });
    });
    data.crowd.forklifts.forEach(function (f) {
      crowd.push({ kind: 'forklift', name: f.name, size: f.size, track: C.decodeSeries(f.track) });
    });
  }

  // The trail: the kept rows plus a point at every mode change (interpolated), each with its
  // mode, so that a lone robot's trail changes colour exactly where the mode did.
  function buildTrail(robot) {
    const rows = [];
    const add = function (row) {
      rows.push(row);
    };
    let j = 0;
    for (let i = 0; i < robot.track.k.length; i++) {
      while (j < robot.runs.rows.length && robot.runs.rows[j] < robot.track.k[i]) add(robot.runs.rows[j++]);
      if (j < robot.runs.rows.length && robot.runs.rows[j] === robot.track.k[i]) j++;
      add(robot.track.k[i]);
    }
    const n = rows.length;
    const xs = new Float64Array(n);
    const ys = new Float64Array(n);
    const modes = new Int32Array(n);
    for (let i = 0; i < n; i++) {
      const p = C.poseAt(robot.track, rows[i]);
      xs[i] = p.x;
      ys[i] = p.y;
      modes[i] = C.modeAt(robot.runs, rows[i]);
    }
    return { rows: Float64Array.from(rows), xs, ys, modes };
  }

  function modeName(robot, mode) {
    return mode >= 0 && mode < robot.modes.length ? robot.modes[mode] : 'mode_' + mode;
  }
  function modeColor(robot, mode) {
    return data.mode_colors[modeName(robot, mode)] || '#7f7f7f';
  }

  // ---- the page's state -------------------------------------------------------------------------
  const view = document.getElementById('view');
  const ctx = view.getContext('2d');
  const timeline = document.getElementById('timeline');
  const tctx = timeline.getContext('2d');
  const tooltip = document.getElementById('tooltip');
  const scrub = document.getElementById('scrub');
  const playButton = document.getElementById('play');
  const speedSelect = document.getElementById('speed');
  const followSelect = document.getElementById('follow');
  const state = {
    t: 0,
    playing: false,
    speed: 1,
    follow: -1,
    selected: 0,
    cx: 0,
    cy: 0,
    scale: 1,
    width: 1,
    height: 1,
    dpr: 1,
    dirty: true,
    lastFrame: 0,
    lastHash: 0,
  };

  document.getElementById('title').textContent = data.title;
  document.getElementById('numbers').textContent = data.numbers;
  scrub.max = String(duration);
  scrub.step = String(data.dt);
  for (const r of robots) {
    const o = document.createElement('option');
    o.value = r.name;
    o.textContent = r.name;
    followSelect.appendChild(o);
  }
  buildLegend();
  const gridImage = buildGridImage();

  function buildLegend() {
    const legend = document.getElementById('legend');
    const items = [];
    if (fleet) {
      robots.slice(0, 24).forEach(function (r) {
        items.push([r.color, r.name]);
      });
      if (robots.length > 24) items.push(['#999999', '+ ' + (robots.length - 24) + ' more']);
    } else {
      const used = new Set(robots[0].runs.modes);
      used.forEach(function (m) {
        items.push([modeColor(robots[0], m), modeName(robots[0], m)]);
      });
    }
    items.push([COLORS.band, 'd_o band (guard distance)']);
    const people = crowd.filter(function (c) { return c.kind === 'person'; }).length;
    if (people) items.push([COLORS.person, people === 1 ? 'person' : people + ' people']);
    const forklifts = crowd.length - people;
    if (forklifts) items.push([COLORS.forklift, forklifts === 1 ? 'forklift' : forklifts + ' forklifts']);
    if (data.world.grid && data.world.grid.rle.some(function (v, i) { return i % 2 === 0 && v === 2; })) {
      items.push(['rgb(222,214,240)', 'unknown (map)']);
    }
    for (const [color, label] of items) {
      const div = document.createElement('div');
      const swatch = document.createElement('i');
      swatch.style.background = color;
      div.appendChild(swatch);
      div.appendChild(document.createTextNode(label));
      legend.appendChild(div);
    }
    const withBeams = robots.filter(function (r) { return r.beams; });
    const note = document.getElementById('beams-note');
    if (withBeams.length === 0) {
      note.textContent = 'No sensor ranges were recorded: no beams shown.';
    } else {
      const b = withBeams[0].beams.k;
      const every = b.length > 1 ? b[1] - b[0] : 1;
      note.textContent = 'Beams and sensed points as the robots read them' +
        (every > 1 ? ', every ' + C.shortTime(C.rowTime(data, every)) + ' s.' : ', every step.');
    }
  }

  // The occupancy map as an image, one pixel per stored cell (rows from the bottom).
  function buildGridImage() {
    const g = data.world.grid;
    if (!g) return null;
    const cells = C.decodeGrid(g);
    const canvas = document.createElement('canvas');
    canvas.width = g.width;
    canvas.height = g.height;
    const c = canvas.getContext('2d');
    const img = c.createImageData(g.width, g.height);
    for (let i = 0; i < cells.length; i++) {
      const rgba = GRID_RGBA[cells[i]];
      if (!rgba) continue;
      img.data.set(rgba, i * 4);
    }
    c.putImageData(img, 0, 0);
    return canvas;
  }

  // ---- time -------------------------------------------------------------------------------------
  function clampTime(t) {
    if (!Number.isFinite(t)) return 0;
    return Math.min(Math.max(t, 0), duration);
  }
  // Shows time t: drawn at the next frame (state() is right at once).
  function seek(t) {
    state.t = clampTime(Number(t));
    state.dirty = true;
    return state.t;
  }
  function currentRow() {
    return C.timeToRow(data, state.t);
  }
  function stepBy(rows) {
    const row = Math.round(currentRow()) + rows;
    seek(C.rowTime(data, Math.min(Math.max(row, 0), lastRow)));
  }
  function setPlaying(on) {
    if (on && state.t >= duration) state.t = 0;
    state.playing = on;
    state.lastFrame = performance.now();
    playButton.textContent = on ? '❚❚' : '▶';
    if (!on) writeHash(true);
    state.dirty = true;
  }
  function setSpeed(s) {
    const v = Number(s);
    state.speed = SPEEDS.indexOf(v) >= 0 ? v : state.speed;
    speedSelect.value = String(state.speed);
  }
  function changeSpeed(dir) {
    const i = SPEEDS.indexOf(state.speed);
    setSpeed(SPEEDS[Math.min(Math.max(i + dir, 0), SPEEDS.length - 1)]);
  }
  function setFollow(index) {
    state.follow = index;
    if (index >= 0) state.selected = index;
    followSelect.value = index >= 0 ? robots[index].name : '';
    state.dirty = true;
    writeHash(true);
  }

  function writeHash(now) {
    const stamp = performance.now();
    if (!now && stamp - state.lastHash < 1000) return;
    state.lastHash = stamp;
    const hash = C.formatHash(state.t, state.follow >= 0 ? robots[state.follow].name : null);
    if (location.hash === hash) return;
    try {
      history.replaceState(null, '', hash);
    } catch (e) {
      // Some browsers refuse replaceState on file: pages; the hash is then left as it was.
    }
  }
  function readHash() {
    const h = C.parseHash(location.hash);
    if (h.follow !== null) {
      const i = robots.findIndex(function (r) { return r.name === h.follow; });
      if (i >= 0) {
        state.follow = i;
        state.selected = i;
        followSelect.value = robots[i].name;
      }
    }
    if (h.t !== null) seek(h.t);
  }

  // ---- what is shown at a time ------------------------------------------------------------------
  function robotState(robot, row) {
    const r = Math.min(row, robot.lastRow);
    const pose = C.poseAt(robot.track, r);
    const mode = C.modeAt(robot.runs, r);
    return { pose, mode, ended: row > robot.lastRow + 1e-6 };
  }

  function snapshot() {
    const row = currentRow();
    return {
      t: state.t,
      robots: robots.map(function (robot) {
        const s = robotState(robot, row);
        return { name: robot.name, x: s.pose.x, y: s.pose.y, theta: s.pose.theta, mode: modeName(robot, s.mode) };
      }),
      crowd: crowd.map(function (c) {
        const p = C.poseAt(c.track, row);
        return { kind: c.kind, name: c.name, x: p.x, y: p.y, theta: p.theta };
      }),
    };
  }

  // ---- view -------------------------------------------------------------------------------------
  function resize() {
    const dpr = window.devicePixelRatio || 1;
    const w = Math.max(1, view.clientWidth);
    const h = Math.max(1, view.clientHeight);
    if (w !== state.width || h !== state.height || dpr !== state.dpr) {
      const first = state.width === 1;
      state.width = w;
      state.height = h;
      state.dpr = dpr;
      view.width = Math.round(w * dpr);
      view.height = Math.round(h * dpr);
      if (first) fit();
    }
    const tw = Math.max(1, timeline.clientWidth);
    const rowH = timelineRowHeight();
    const th = robots.length * rowH + 14;
    timeline.style.height = th + 'px';
    timeline.width = Math.round(tw * dpr);
    timeline.height = Math.round(th * dpr);
    state.dirty = true;
  }
  function fit() {
    const e = data.extent;
    const w = Math.max(e[2] - e[0], 1e-3);
    const h = Math.max(e[3] - e[1], 1e-3);
    state.cx = 0.5 * (e[0] + e[2]);
    state.cy = 0.5 * (e[1] + e[3]);
    state.scale = 0.94 * Math.min(state.width / w, state.height / h);
    state.dirty = true;
  }
  function toScreen(x, y) {
    return [(x - state.cx) * state.scale + state.width / 2, state.height / 2 - (y - state.cy) * state.scale];
  }
  function toWorld(sx, sy) {
    return [(sx - state.width / 2) / state.scale + state.cx, (state.height / 2 - sy) / state.scale + state.cy];
  }

  // ---- drawing the floor -------------------------------------------------------------------------
  function draw() {
    const started = performance.now();
    state.dirty = false;
    const row = currentRow();
    if (state.follow >= 0) {
      const p = robotState(robots[state.follow], row).pose;
      state.cx = p.x;
      state.cy = p.y;
    }
    const px = 1 / state.scale; // one CSS pixel in metres
    ctx.setTransform(state.dpr, 0, 0, state.dpr, 0, 0);
    const bounds = data.world.bounds;
    ctx.fillStyle = bounds ? COLORS.outside : COLORS.floor;
    ctx.fillRect(0, 0, state.width, state.height);
    ctx.save();
    ctx.translate(state.width / 2, state.height / 2);
    ctx.scale(state.scale, -state.scale);
    ctx.translate(-state.cx, -state.cy);
    ctx.lineJoin = 'round';
    ctx.lineCap = 'round';
    drawWorld(px);
    const states = robots.map(function (r) { return robotState(r, row); });
    for (const r of robots) drawGoals(r, row, px);
    for (const r of robots) drawTrail(r, row, px);
    for (const r of robots) drawBand(r, states[r.index], px);
    for (const r of robots) drawBeams(r, row, px);
    drawCrowd(row, px);
    for (const r of robots) drawBody(r, states[r.index], px);
    ctx.restore();
    drawLabels(states);
    drawTimeline();
    updateReadout(states, row);
    state.drawMs = performance.now() - started;
  }

  function drawWorld(px) {
    const w = data.world;
    if (w.bounds) {
      const b = w.bounds;
      ctx.fillStyle = COLORS.floor;
      ctx.fillRect(b[0], b[1], b[2] - b[0], b[3] - b[1]);
    }
    if (gridImage) {
      const g = w.grid;
      ctx.save();
      ctx.translate(g.origin[0], g.origin[1]);
      ctx.rotate(g.origin[2]);
      ctx.scale(g.resolution, g.resolution);
      ctx.imageSmoothingEnabled = false;
      ctx.drawImage(gridImage, 0, 0, g.width, g.height);
      ctx.restore();
    }
    ctx.fillStyle = COLORS.obstacle;
    ctx.strokeStyle = COLORS.obstacleEdge;
    ctx.lineWidth = 1.5 * px;
    for (const p of w.polygons) {
      ctx.beginPath();
      for (let i = 0; i < p.length; i += 2) ctx.lineTo(p[i], p[i + 1]);
      ctx.closePath();
      ctx.fill();
      ctx.stroke();
    }
    for (const c of w.circles) {
      ctx.beginPath();
      ctx.arc(c[0], c[1], Math.max(c[2], 2 * px), 0, 2 * Math.PI);
      ctx.fill();
      ctx.stroke();
    }
    if (w.bounds) {
      // The wall outside the bounds, so that its inner edge is where a robot collides.
      const b = w.bounds;
      const t = Math.min(Math.max(0.03 * state.scale, 4), 10) * px;
      ctx.strokeStyle = COLORS.wall;
      ctx.lineWidth = t;
      ctx.lineJoin = 'miter';
      ctx.strokeRect(b[0] - t / 2, b[1] - t / 2, b[2] - b[0] + t, b[3] - b[1] + t);
      ctx.lineJoin = 'round';
    }
  }

  function drawGoals(robot, row, px) {
    const current = C.goalIndexAt(robot.goalRows, row);
    const color = fleet ? robot.color : COLORS.goal;
    const edge = fleet ? robot.color : COLORS.goalEdge;
    robot.goals.forEach(function (g, i) {
      const isCurrent = i === current;
      if (fleet && !isCurrent) {
        // A fleet's other goals: a dot each (dashed circles and flags for every stop of every
        // robot would bury the floor, and cost a frame its time).
        ctx.globalAlpha = i < current ? 0.3 : 0.7;
        ctx.fillStyle = color;
        ctx.fillRect(g[0] - 2 * px, g[1] - 2 * px, 4 * px, 4 * px);
        ctx.globalAlpha = 1;
        return;
      }
      ctx.globalAlpha = i < current ? 0.35 : 1;
      ctx.beginPath();
      ctx.arc(g[0], g[1], Math.max(robot.epsilon, 3 * px), 0, 2 * Math.PI);
      ctx.fillStyle = color;
      ctx.globalAlpha *= isCurrent ? 0.35 : 0.15;
      ctx.fill();
      ctx.globalAlpha = i < current ? 0.35 : 1;
      ctx.setLineDash([4 * px, 3 * px]);
      ctx.strokeStyle = edge;
      ctx.lineWidth = (isCurrent ? 2 : 1.2) * px;
      ctx.stroke();
      ctx.setLineDash([]);
      // The flag: a pole and a pennant, bigger for the current goal.
      const s = (isCurrent ? 14 : 10) * px;
      ctx.beginPath();
      ctx.moveTo(g[0], g[1]);
      ctx.lineTo(g[0], g[1] + 1.6 * s);
      ctx.strokeStyle = '#333333';
      ctx.lineWidth = 1.6 * px;
      ctx.stroke();
      ctx.beginPath();
      ctx.moveTo(g[0], g[1] + 1.6 * s);
      ctx.lineTo(g[0] + s, g[1] + 1.3 * s);
      ctx.lineTo(g[0], g[1] + s);
      ctx.closePath();
      ctx.fillStyle = color;
      ctx.fill();
      ctx.strokeStyle = edge;
      ctx.lineWidth = px;
      ctx.stroke();
      ctx.globalAlpha = 1;
    });
  }

  // The trail up to the current time, thinned to what the screen can show (TRAIL_PX), split
  // where the mode changes for a lone robot (those points are never thinned away).
  function trailPoints(robot, px) {
    const tr = robot.trail;
    if (robot.trailCache && robot.trailCache.scale === state.scale) return robot.trailCache.kept;
    let kept = C.thinPolyline(tr.xs, tr.ys, TRAIL_PX * px);
    if (!fleet) {
      const changes = [];
      for (let i = 1; i < tr.modes.length; i++) if (tr.modes[i] !== tr.modes[i - 1]) changes.push(i);
      kept = Array.from(new Set(kept.concat(changes))).sort(function (a, b) { return a - b; });
    }
    robot.trailCache = { scale: state.scale, kept };
    return kept;
  }

  function drawTrail(robot, row, px) {
    const tr = robot.trail;
    if (tr.rows.length === 0) return;
    const kept = trailPoints(robot, px);
    const upto = C.lastAtOrBefore(tr.rows, Math.min(row, robot.lastRow));
    const here = C.poseAt(robot.track, Math.min(row, robot.lastRow));
    ctx.lineWidth = (fleet ? 2 : 2.5) * px;
    ctx.globalAlpha = fleet ? 0.85 : 1;
    let mode = tr.modes[0];
    ctx.beginPath();
    ctx.strokeStyle = fleet ? robot.color : modeColor(robot, mode);
    ctx.moveTo(tr.xs[0], tr.ys[0]);
    for (let j = 0; j < kept.length && kept[j] <= upto; j++) {
      const i = kept[j];
      ctx.lineTo(tr.xs[i], tr.ys[i]);
      if (!fleet && tr.modes[i] !== mode) {
        ctx.stroke();
        mode = tr.modes[i];
        ctx.beginPath();
        ctx.strokeStyle = modeColor(robot, mode);
        ctx.moveTo(tr.xs[i], tr.ys[i]);
      }
    }
    if (upto >= 0) ctx.lineTo(tr.xs[upto], tr.ys[upto]);
    ctx.lineTo(here.x, here.y);
    ctx.stroke();
    ctx.globalAlpha = 1;
  }

  function bodyPath(robot, pose, grow) {
    ctx.beginPath();
    if (robot.footprint) {
      const c = Math.cos(pose.theta);
      const s = Math.sin(pose.theta);
      const f = robot.footprint;
      for (let i = 0; i < f.length; i += 2) {
        ctx.lineTo(pose.x + c * f[i] - s * f[i + 1], pose.y + s * f[i] + c * f[i + 1]);
      }
      ctx.closePath();
    } else {
      ctx.arc(pose.x, pose.y, robot.radius + grow, 0, 2 * Math.PI);
    }
  }

  // The d_o band: where an obstacle point is "met" by the guards (clearance < d_o), measured from
  // the body disc, or from the footprint when the controller measures from it.
  function drawBand(robot, s, px) {
    if (!(robot.d_o > 0) || (s.ended && !robot.parked)) return;
    const p = s.pose;
    ctx.fillStyle = COLORS.band;
    if (robot.footprint && robot.footprintClearance) {
      ctx.save();
      bodyPath(robot, p, 0);
      ctx.strokeStyle = COLORS.band;
      ctx.lineWidth = 2 * robot.d_o;
      ctx.stroke();
      ctx.restore();
      return;
    }
    ctx.beginPath();
    ctx.arc(p.x, p.y, robot.radius + robot.d_o, 0, 2 * Math.PI);
    ctx.arc(p.x, p.y, robot.radius, 0, 2 * Math.PI, true);
    ctx.fill();
    ctx.strokeStyle = 'rgba(255, 152, 0, 0.45)';
    ctx.lineWidth = px;
    ctx.beginPath();
    ctx.arc(p.x, p.y, robot.radius + robot.d_o, 0, 2 * Math.PI);
    ctx.stroke();
  }

  // The beams of the last recorded frame at or before the shown time, from the pose they were
  // read at; a return (range below max) ends in a sensed point.
  function drawBeams(robot, row, px) {
    const b = robot.beams;
    if (!b || row > robot.lastRow + 1e-6) return;
    const f = C.frameAt(b.k, row);
    if (f < 0) return;
    const n = robot.sensors.length;
    const x = b.x[f];
    const y = b.y[f];
    const th = b.th[f];
    const c = Math.cos(th);
    const s = Math.sin(th);
    ctx.lineWidth = px;
    const points = [];
    for (let i = 0; i < n; i++) {
      const m = robot.sensors[i];
      const ox = x + c * m[0] - s * m[1];
      const oy = y + s * m[0] + c * m[1];
      const a = th + m[2];
      const raw = b.r[f * n + i];
      const seen = raw >= 0;
      const range = seen ? raw * C.MM : m[3];
      ctx.strokeStyle = seen ? COLORS.beamHit : COLORS.beam;
      ctx.fillStyle = seen ? 'rgba(214, 39, 40, 0.10)' : 'rgba(120, 120, 120, 0.08)';
      ctx.beginPath();
      if (m[4] > 0) {
        ctx.moveTo(ox, oy);
        ctx.arc(ox, oy, range, a - m[4] / 2, a + m[4] / 2);
        ctx.closePath();
        ctx.fill();
      } else {
        ctx.moveTo(ox, oy);
        ctx.lineTo(ox + range * Math.cos(a), oy + range * Math.sin(a));
      }
      ctx.stroke();
      if (seen) points.push(ox + range * Math.cos(a), oy + range * Math.sin(a));
    }
    ctx.fillStyle = COLORS.point;
    for (let i = 0; i < points.length; i += 2) {
      ctx.beginPath();
      ctx.arc(points[i], points[i + 1], 2.5 * px, 0, 2 * Math.PI);
      ctx.fill();
    }
  }

  // People as discs with a tick in their walking direction, forklifts as their rectangles.
  function drawCrowd(row, px) {
    for (const c of crowd) {
      const p = C.poseAt(c.track, row);
      ctx.beginPath();
      if (c.kind === 'person') {
        ctx.arc(p.x, p.y, Math.max(0.5 * c.size[0], 3 * px), 0, 2 * Math.PI);
      } else {
        const cos = Math.cos(p.theta);
        const sin = Math.sin(p.theta);
        const hl = 0.5 * c.size[0];
        const hw = 0.5 * c.size[1];
        [[hl, hw], [-hl, hw], [-hl, -hw], [hl, -hw]].forEach(function (q, i) {
          const x = p.x + q[0] * cos - q[1] * sin;
          const y = p.y + q[0] * sin + q[1] * cos;
          if (i === 0) ctx.moveTo(x, y);
          else ctx.lineTo(x, y);
        });
        ctx.closePath();
      }
      ctx.fillStyle = c.kind === 'person' ? COLORS.person : COLORS.forklift;
      ctx.globalAlpha = 0.85;
      ctx.fill();
      ctx.globalAlpha = 1;
      ctx.strokeStyle = '#263238';
      ctx.lineWidth = 1.2 * px;
      ctx.stroke();
      drawHeading(p, 0.5 * c.size[0], 1.6 * px);
    }
  }

  // A white tick from pose p's centre, `length` along its heading.
  function drawHeading(p, length, width) {
    ctx.beginPath();
    ctx.moveTo(p.x, p.y);
    ctx.lineTo(p.x + length * Math.cos(p.theta), p.y + length * Math.sin(p.theta));
    ctx.strokeStyle = '#ffffff';
    ctx.lineWidth = width;
    ctx.stroke();
  }

  function drawBody(robot, s, px) {
    const p = s.pose;
    const faded = s.ended && !robot.parked;
    const grow = robot.footprint ? 0 : Math.max(0, 5 * px - robot.radius);
    const endedInCollision = robot.collided && s.ended;
    const atEnd = s.ended || C.timeToRow(data, state.t) >= robot.lastRow - 1e-6;
    ctx.globalAlpha = faded ? 0.3 : 1;
    bodyPath(robot, p, grow);
    if (fleet) {
      // A fleet's robot in its colour, the mode as a thick outline.
      ctx.fillStyle = robot.color;
      ctx.fill();
      ctx.strokeStyle = robot.collided && atEnd ? COLORS.collided : modeColor(robot, s.mode);
      ctx.lineWidth = 3 * px;
      ctx.stroke();
    } else {
      ctx.fillStyle = robot.collided && atEnd ? COLORS.collided : modeColor(robot, s.mode);
      ctx.globalAlpha *= 0.9;
      ctx.fill();
      ctx.globalAlpha = faded ? 0.3 : 1;
      ctx.strokeStyle = '#263238';
      ctx.lineWidth = 1.6 * px;
      ctx.stroke();
    }
    if (endedInCollision || (robot.collided && atEnd)) {
      ctx.strokeStyle = COLORS.collided;
      ctx.lineWidth = 2 * px;
      ctx.stroke();
    }
    // Heading: from the centre to the front of the body.
    drawHeading(p, robot.footprint ? robot.front : robot.radius + grow, 2.2 * px);
    ctx.globalAlpha = 1;
  }

  function drawLabels(states) {
    if (!fleet || robots.length > MAX_NAMED) return;
    ctx.font = '11px Helvetica, Arial, sans-serif';
    ctx.textAlign = 'center';
    ctx.lineWidth = 3;
    ctx.strokeStyle = 'rgba(255, 255, 255, 0.9)';
    for (const r of robots) {
      const p = states[r.index].pose;
      const reach = r.footprint ? Math.max(r.front, r.radius) : r.radius;
      const [sx, sy] = toScreen(p.x, p.y);
      const y = sy - Math.max(reach * state.scale, 5) - 5;
      ctx.fillStyle = r.color;
      ctx.strokeText(r.name, sx, y);
      ctx.fillText(r.name, sx, y);
    }
    ctx.textAlign = 'start';
  }

  function updateReadout(states, row) {
    const r = robots[state.selected];
    const s = states[state.selected];
    document.getElementById('time').textContent =
      state.t.toFixed(2) + ' s / ' + duration.toFixed(2) + ' s';
    document.getElementById('robot-name').textContent = r.name;
    document.getElementById('mode').textContent = modeName(r, s.mode);
    document.getElementById('mode-swatch').style.background = modeColor(r, s.mode);
    const g = C.goalIndexAt(r.goalRows, row);
    document.getElementById('goal').textContent =
      r.goals.length === 0 ? '—' : g < r.goals.length ? (g + 1) + ' of ' + r.goals.length : 'all reached';
    scrub.value = String(state.t);
  }

  // ---- the timeline: each robot's modes, a tick per switch ---------------------------------------
  function timelineRowHeight() {
    return Math.max(2, Math.min(14, Math.floor(160 / robots.length)));
  }
  function timelineX(t, width) {
    return duration > 0 ? (t / duration) * width : 0;
  }
  function drawTimeline() {
    const dpr = state.dpr;
    const width = timeline.width / dpr;
    const rowH = timelineRowHeight();
    tctx.setTransform(dpr, 0, 0, dpr, 0, 0);
    tctx.clearRect(0, 0, width, timeline.height / dpr);
    robots.forEach(function (r, i) {
      const y = i * rowH;
      for (let j = 0; j < r.runs.rows.length; j++) {
        const x0 = timelineX(C.rowTime(data, r.runs.rows[j]), width);
        const end = j + 1 < r.runs.rows.length ? r.runs.rows[j + 1] : r.lastRow;
        const x1 = timelineX(C.rowTime(data, end), width);
        tctx.fillStyle = modeColor(r, r.runs.modes[j]);
        tctx.fillRect(x0, y, Math.max(x1 - x0, 0.5), rowH - (rowH > 4 ? 1 : 0));
      }
      if (rowH >= 6) {
        tctx.fillStyle = 'rgba(0, 0, 0, 0.75)';
        for (const sw of r.switches) {
          const x = timelineX(C.rowTime(data, sw.row), width);
          tctx.fillRect(x - 0.5, y, 1, Math.ceil(rowH / 2));
        }
      }
      if (i === state.selected && robots.length > 1) {
        tctx.strokeStyle = '#222222';
        tctx.lineWidth = 1;
        tctx.strokeRect(0.5, y + 0.5, width - 1, rowH - 1);
      }
    });
    const axisY = robots.length * rowH;
    tctx.fillStyle = '#666666';
    tctx.font = '10px Helvetica, Arial, sans-serif';
    const stepS = niceStep(duration / 8);
    for (let t = 0; t <= duration + 1e-9; t += stepS) {
      const x = timelineX(t, width);
      tctx.fillRect(x, axisY, 1, 3);
      tctx.textAlign = t === 0 ? 'left' : 'center';
      tctx.fillText(C.shortTime(t) + ' s', x, axisY + 12);
    }
    tctx.textAlign = 'left';
    const cx = timelineX(state.t, width);
    tctx.fillStyle = '#d62728';
    tctx.fillRect(cx - 1, 0, 2, axisY + 3);
  }
  function niceStep(raw) {
    if (!(raw > 0)) return 1;
    const e = Math.pow(10, Math.floor(Math.log10(raw)));
    for (const m of [1, 2, 5, 10]) if (m * e >= raw) return m * e;
    return 10 * e;
  }

  function timelineHit(event) {
    const rect = timeline.getBoundingClientRect();
    const x = event.clientX - rect.left;
    const y = event.clientY - rect.top;
    const rowH = timelineRowHeight();
    const i = Math.floor(y / rowH);
    return { x, y, i, width: rect.width, t: clampTime((x / rect.width) * duration) };
  }
  let scrubbing = false;
  timeline.addEventListener('mousedown', function (e) {
    scrubbing = true;
    const h = timelineHit(e);
    if (h.i >= 0 && h.i < robots.length && robots.length > 1) state.selected = h.i;
    seek(h.t);
  });
  window.addEventListener('mouseup', function () {
    if (scrubbing) writeHash(true);
    scrubbing = false;
  });
  timeline.addEventListener('mousemove', function (e) {
    const h = timelineHit(e);
    if (scrubbing) seek(h.t);
    let best = null;
    let bestDx = 5;
    if (h.i >= 0 && h.i < robots.length) {
      const r = robots[h.i];
      for (const sw of r.switches) {
        const dx = Math.abs(timelineX(C.rowTime(data, sw.row), h.width) - h.x);
        if (dx < bestDx) {
          bestDx = dx;
          best = sw;
        }
      }
      if (best) {
        const guard = best.guard >= 0 && best.guard < r.guards.length ? r.guards[best.guard] : 'mode change';
        tooltip.textContent = (fleet ? r.name + ' · ' : '') + 't = ' +
          C.shortTime(C.rowTime(data, best.row)) + ' s · ' + modeName(r, best.from) + ' → ' +
          modeName(r, best.to) + ' · guard: ' + guard;
      } else {
        tooltip.textContent = (fleet ? r.name + ' · ' : '') + 't = ' + h.t.toFixed(2) + ' s · ' +
          modeName(r, C.modeAt(r.runs, C.timeToRow(data, h.t)));
      }
      tooltip.style.left = h.x + 'px';
      tooltip.style.top = (h.i * timelineRowHeight() - 2) + 'px';
      tooltip.hidden = false;
    } else {
      tooltip.hidden = true;
    }
  });
  timeline.addEventListener('mouseleave', function () {
    tooltip.hidden = true;
  });

  // ---- controls ---------------------------------------------------------------------------------
  playButton.addEventListener('click', function () {
    setPlaying(!state.playing);
  });
  document.getElementById('back').addEventListener('click', function () {
    stepBy(-1);
  });
  document.getElementById('forward').addEventListener('click', function () {
    stepBy(1);
  });
  speedSelect.addEventListener('change', function () {
    setSpeed(speedSelect.value);
  });
  followSelect.addEventListener('change', function () {
    setFollow(robots.findIndex(function (r) { return r.name === followSelect.value; }));
  });
  scrub.addEventListener('input', function () {
    seek(Number(scrub.value));
  });
  scrub.addEventListener('change', function () {
    writeHash(true);
  });
  document.addEventListener('keydown', function (e) {
    if (e.target && (e.target.tagName === 'SELECT' || e.target.tagName === 'INPUT') && e.key !== ' ') {
      if (e.target !== scrub) return;
    }
    let handled = true;
    switch (e.key) {
      case ' ':
        setPlaying(!state.playing);
        break;
      case 'ArrowRight':
        stepBy(e.shiftKey ? Math.round(C.timeToRow(data, 1)) : 1);
        writeHash(true);
        break;
      case 'ArrowLeft':
        stepBy(e.shiftKey ? -Math.round(C.timeToRow(data, 1)) : -1);
        writeHash(true);
        break;
      case '+':
      case '=':
        changeSpeed(1);
        break;
      case '-':
      case '_':
        changeSpeed(-1);
        break;
      case 'f':
        setFollow(state.follow + 1 < robots.length ? state.follow + 1 : -1);
        break;
      case 'Home':
        seek(0);
        writeHash(true);
        break;
      case 'End':
        seek(duration);
        writeHash(true);
        break;
      default:
        handled = false;
    }
    if (handled) {
      e.preventDefault();
      state.dirty = true;
    }
  });
  window.addEventListener('hashchange', function () {
    const h = C.parseHash(location.hash);
    if (h.t !== null && Math.abs(h.t - state.t) > 5e-4) seek(h.t);
  });

  // Zoom about the cursor, drag to pan (stops following), double-click to fit.
  let drag = null;
  view.addEventListener('wheel', function (e) {
    e.preventDefault();
    const rect = view.getBoundingClientRect();
    const sx = e.clientX - rect.left;
    const sy = e.clientY - rect.top;
    const [wx, wy] = toWorld(sx, sy);
    const factor = Math.exp(-e.deltaY * 0.0015);
    state.scale = Math.min(Math.max(state.scale * factor, 1e-3), 1e6);
    if (state.follow < 0) {
      state.cx = wx - (sx - state.width / 2) / state.scale;
      state.cy = wy + (sy - state.height / 2) / state.scale;
    }
    state.dirty = true;
  }, { passive: false });
  view.addEventListener('mousedown', function (e) {
    drag = { x: e.clientX, y: e.clientY, cx: state.cx, cy: state.cy, moved: false };
    view.classList.add('dragging');
  });
  window.addEventListener('mousemove', function (e) {
    if (!drag) return;
    const dx = e.clientX - drag.x;
    const dy = e.clientY - drag.y;
    if (Math.abs(dx) + Math.abs(dy) > 3 && !drag.moved) {
      drag.moved = true;
      if (state.follow >= 0) setFollow(-1);
    }
    if (drag.moved) {
      state.cx = drag.cx - dx / state.scale;
      state.cy = drag.cy + dy / state.scale;
      state.dirty = true;
    }
  });
  window.addEventListener('mouseup', function (e) {
    if (drag && !drag.moved) selectAt(e);
    drag = null;
    view.classList.remove('dragging');
  });
  view.addEventListener('dblclick', function () {
    setFollow(-1);
    fit();
  });
  function selectAt(e) {
    const rect = view.getBoundingClientRect();
    const row = currentRow();
    let best = -1;
    let bestD = 20;
    robots.forEach(function (r) {
      const p = robotState(r, row).pose;
      const [sx, sy] = toScreen(p.x, p.y);
      const d = Math.hypot(sx - (e.clientX - rect.left), sy - (e.clientY - rect.top));
      if (d < bestD) {
        bestD = d;
        best = r.index;
      }
    });
    if (best >= 0) {
      state.selected = best;
      state.dirty = true;
    }
  }

  // ---- the loop ---------------------------------------------------------------------------------
  function frame(now) {
    if (state.playing) {
      const dt = Math.min((now - state.lastFrame) / 1000, 0.25);
      state.t = clampTime(state.t + dt * state.speed);
      if (state.t >= duration) setPlaying(false);
      state.dirty = true;
      writeHash(false);
    }
    state.lastFrame = now;
    if (state.dirty) draw();
    requestAnimationFrame(frame);
  }
  window.addEventListener('resize', function () {
    resize();
    draw();
  });

  window.floornavReplay = {
    version: 1,
    duration,
    seek,
    state: snapshot,
    play: function () { setPlaying(true); },
    pause: function () { setPlaying(false); },
    get playing() { return state.playing; },
    get speed() { return state.speed; },
    /** ms the last frame took to draw. */
    get drawMs() { return state.drawMs; },
    setSpeed,
    follow: function (name) {
      setFollow(robots.findIndex(function (r) { return r.name === name; }));
    },
    /** Page (CSS pixel) coordinates of world point (x, y) as drawn now. */
    toPage: function (x, y) {
      const rect = view.getBoundingClientRect();
      const [sx, sy] = toScreen(x, y);
      return { x: rect.left + sx, y: rect.top + sy };
    },
  };

  resize();
  readHash();
  draw();
  // ms from the start of navigation to the first frame drawn: how long the page takes to open.
  window.floornavReplay.readyMs = performance.now();
  requestAnimationFrame(frame);
})();
