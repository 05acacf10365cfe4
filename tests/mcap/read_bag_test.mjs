// run.mcap read back with the reference readers: Foxglove's @mcap/core (the indexed reader, which
// checks the footer, the summary CRC and each chunk's CRC, and the stream reader, which checks the
// records front to back), @mcap/support (zstd), @foxglove/rosmsg (the ros2msg schemas) and
// @foxglove/rosmsg2-serialization (CDR). floornav writes bags of a lone robot with an IR ring, a
// lidar robot on a ROS map, a fleet with people and forklifts, and a robot with one sonar; the
// tests check that every schema is ROS 2's own definition, every message decodes to its last
// byte and encodes back to the same bytes, the odometry is trajectory.csv, the chunk and message
// indexes point at the right messages, and the statistics count what is there.
//
// Environment: FLOORNAV_BINARY (the floornav executable), FLOORNAV_SOURCE_DIR (the repository).
// Exits 77 (ctest: skipped) when node_modules is missing (`npm ci` in tests/mcap), unless
// FLOORNAV_REQUIRE_BROWSER=1 (CI), when that fails.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { createRequire } from 'node:module';

const binary = process.env.FLOORNAV_BINARY;
const source = process.env.FLOORNAV_SOURCE_DIR || path.resolve(import.meta.dirname, '../..');
const required = process.env.FLOORNAV_REQUIRE_BROWSER === '1';

function skip(reason) {
  if (required) {
    console.error(`mcap reader test: ${reason} (FLOORNAV_REQUIRE_BROWSER=1: failing)`);
    process.exit(1);
  }
  console.log(`skipped: ${reason}`);
  process.exit(77);
}

let mcap, support, rosmsg, ros2, common;
try {
  mcap = await import('@mcap/core');
  support = await import('@mcap/support');
  rosmsg = await import('@foxglove/rosmsg');
  ros2 = await import('@foxglove/rosmsg2-serialization');
  common = createRequire(import.meta.url)('@foxglove/rosmsg-msgs-common');
} catch (e) {
  skip(`the reference readers are not installed (run \`npm ci\` in tests/mcap): ${e.message}`);
}
if (!binary || !fs.existsSync(binary)) skip('FLOORNAV_BINARY does not name the floornav executable');

const work = fs.mkdtempSync(path.join(os.tmpdir(), 'floornav-mcap-'));
const decompressHandlers = await support.loadDecompressHandlers();

function run(scenario, out, ...args) {
  const file = path.isAbsolute(scenario) ? scenario : path.join(source, 'scenarios', scenario);
  execFileSync(binary, ['run', file, '--out', out, '--quiet', '--mcap', ...args], {
    stdio: ['ignore', 'pipe', 'pipe'],
  });
  return out;
}

/// The bag, read whole: header, schemas, channels, messages (decoded), statistics, indexes.
async function readBag(file) {
  const bytes = new Uint8Array(fs.readFileSync(file));
  const readable = {
    size: async () => BigInt(bytes.length),
    read: async (offset, size) => bytes.subarray(Number(offset), Number(offset + size)),
  };
  const reader = await mcap.McapIndexedReader.Initialize({ readable, decompressHandlers });
  const readers = new Map();
  const messages = [];
  for await (const m of reader.readMessages({ validateCrcs: true })) {
    const channel = reader.channelsById.get(m.channelId);
    let r = readers.get(channel.id);
    if (!r) {
      const schema = reader.schemasById.get(channel.schemaId);
      const defs = rosmsg.parse(new TextDecoder().decode(schema.data), { ros2: true });
      r = { reader: new ros2.MessageReader(defs), writer: new ros2.MessageWriter(defs) };
      readers.set(channel.id, r);
    }
    const value = r.reader.readMessage(m.data);
    assert.equal(r.reader.lastReadHadTrailingBytes(), false, `${channel.topic}: trailing bytes`);
    // The reference encoder writes the same bytes (alignment, padding, lengths).
    assert.deepEqual(r.writer.writeMessage(value), m.data, `${channel.topic}: re-encoded bytes`);
    messages.push({ topic: channel.topic, logTime: m.logTime, publishTime: m.publishTime, value });
  }
  for (const m of messages) seenTopics.add(m.topic);
  return { bytes, reader, messages };
}
const seenTopics = new Set();

function csv(file) {
  const [head, ...rows] = fs.readFileSync(file, 'utf8').trim().split('\n');
  const cols = head.split(',');
  return rows.map((l) => Object.fromEntries(l.split(',').map((v, i) => [cols[i], v])));
}

const stampNs = (s) => BigInt(s.sec) * 1000000000n + BigInt(s.nanosec);
const yaw = (q) => 2 * Math.atan2(q.z, q.w);
const wrap = (a) => Math.atan2(Math.sin(a), Math.cos(a));

/// The chunk indexes and the message indexes after each chunk point at the messages.
function checkIndexes(bag) {
  const { bytes, reader } = bag;
  const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
  let indexed = 0n;
  assert.ok(reader.chunkIndexes.length > 0);
  for (const ci of reader.chunkIndexes) {
    const at = Number(ci.chunkStartOffset);
    assert.equal(bytes[at], 0x06, 'a chunk index points at a chunk record');
    assert.equal(view.getBigUint64(at + 1, true) + 9n, ci.chunkLength);
    // The chunk record, read by hand (the reader's own record parser is internal).
    const compression = new TextDecoder().decode(bytes.subarray(at + 41, at + 41 + view.getUint32(at + 37, true)));
    assert.equal(compression, 'zstd');
    const after = at + 41 + compression.length;
    const compressedSize = view.getBigUint64(after, true);
    assert.equal(compressedSize, ci.compressedSize);
    const uncompressedSize = view.getBigUint64(at + 25, true);
    assert.equal(uncompressedSize, ci.uncompressedSize);
    const records = decompressHandlers.zstd(bytes.subarray(after + 8, after + 8 + Number(compressedSize)),
      uncompressedSize);
    const rv = new DataView(records.buffer, records.byteOffset, records.byteLength);
    let length = 0n;
    for (const [channelId, offset] of ci.messageIndexOffsets) {
      const o = Number(offset);
      assert.equal(bytes[o], 0x07, 'a message index record');
      assert.equal(view.getUint16(o + 9, true), channelId);
      const entries = view.getUint32(o + 11, true) / 16;
      length += 9n + view.getBigUint64(o + 1, true);
      for (let e = 0; e < entries; ++e) {
        const time = view.getBigUint64(o + 15 + 16 * e, true);
        const mo = Number(view.getBigUint64(o + 23 + 16 * e, true));
        assert.equal(records[mo], 0x05, 'the entry points at a message record');
        assert.equal(rv.getUint16(mo + 9, true), channelId);
        assert.equal(rv.getBigUint64(mo + 15, true), time);
        assert.ok(time >= ci.messageStartTime && time <= ci.messageEndTime);
        ++indexed;
      }
    }
    assert.equal(length, ci.messageIndexLength);
  }
  assert.equal(indexed, reader.statistics.messageCount, 'every message is indexed once');
}

/// What every bag must be: ros2 profile, ROS 2 schemas, CDR, log = publish = header time, order.
function checkCommon(bag) {
  const { reader, messages } = bag;
  assert.equal(reader.header.profile, 'ros2');
  assert.match(reader.header.library, /^floornav /);
  const jazzy = common.ros2jazzy;
  for (const schema of reader.schemasById.values()) {
    assert.equal(schema.encoding, 'ros2msg');
    // Each type the schema defines is ROS 2's own (fields, types, arrays, constants, defaults).
    const defs = rosmsg.parse(new TextDecoder().decode(schema.data), { ros2: true });
    assert.ok(defs.length > 0);
    for (const def of defs) {
      const name = def.name ?? schema.name.replace('/msg/', '/');
      const ref = jazzy[name];
      assert.ok(ref, `${name} is a ROS 2 type`);
      const shape = (d) => d.definitions.map((f) => [f.type, f.name, !!f.isArray, f.arrayLength,
        !!f.isConstant, f.value, f.defaultValue]);
      assert.deepEqual(shape(def), shape(ref), `${schema.name}: ${name}`);
    }
    assert.match(new TextDecoder().decode(schema.data).split('\n').filter((l) => l.startsWith('MSG:'))
      .join('\n') || 'MSG: -', /^(MSG: [a-z0-9_]+\/[A-Za-z0-9]+\n?)+$|^MSG: -$/);
  }
  for (const channel of reader.channelsById.values()) {
    assert.equal(channel.messageEncoding, 'cdr');
    assert.ok(channel.metadata.has('offered_qos_profiles'));
  }
  let last = 0n;
  for (const m of messages) {
    assert.equal(m.logTime, m.publishTime);
    assert.ok(m.logTime >= last, 'messages in log-time order');
    last = m.logTime;
    const stamp = m.value.header?.stamp ?? m.value.clock;
    if (stamp) assert.equal(stampNs(stamp), m.logTime, `${m.topic}: header stamp = log time`);
  }
  const counts = new Map();
  for (const m of messages) counts.set(m.topic, (counts.get(m.topic) ?? 0n) + 1n);
  for (const [id, n] of reader.statistics.channelMessageCounts)
    assert.equal(counts.get(reader.channelsById.get(id).topic) ?? 0n, n);
  assert.equal(BigInt(messages.length), reader.statistics.messageCount);
  checkIndexes(bag);
}

/// Odometry and tf are trajectory.csv, row by row.
function checkOdometry(messages, rows, prefix = '') {
  const odom = messages.filter((m) => m.topic === `${prefix}/odom`);
  const tf = messages.filter((m) => m.topic === `${prefix}/tf`);
  assert.equal(odom.length, rows.length);
  assert.equal(tf.length, rows.length);
  odom.forEach((m, i) => {
    const r = rows[i];
    assert.equal(m.logTime, BigInt(Math.round(Number(r.t) * 1e9)));
    assert.equal(m.value.pose.pose.position.x, Number(r.x));
    assert.equal(m.value.pose.pose.position.y, Number(r.y));
    assert.ok(Math.abs(wrap(yaw(m.value.pose.pose.orientation) - Number(r.theta))) < 1e-12);
    assert.equal(m.value.twist.twist.linear.x, Number(r.v));
    assert.equal(m.value.twist.twist.angular.z, Number(r.omega));
    const t = tf[i].value.transforms[0];
    assert.equal(t.transform.translation.x, Number(r.x));
    assert.equal(t.child_frame_id, m.value.child_frame_id);
  });
}

test('a lone robot with an IR ring: odometry, tf, modes, transitions, goals, ring scans', async () => {
  const out = run('factory_delivery.yaml', path.join(work, 'factory'));
  const bag = await readBag(path.join(out, 'run.mcap'));
  checkCommon(bag);
  const rows = csv(path.join(out, 'trajectory.csv'));
  checkOdometry(bag.messages, rows);
  const topics = new Set(bag.messages.map((m) => m.topic));
  for (const t of ['/clock', '/map', '/world', '/tf_static', '/body', '/mode', '/transition',
    '/goal', '/ring_scan'])
    assert.ok(topics.has(t), t);
  assert.equal(bag.messages.filter((m) => m.topic === '/clock').length, rows.length);
  const map = bag.messages.find((m) => m.topic === '/map');
  assert.equal(map.logTime, 0n);
  assert.equal(map.value.data.length, map.value.info.width * map.value.info.height);
  assert.ok(map.value.data.some((v) => v === 100) && map.value.data.some((v) => v === 0));
  // The mode topic follows trajectory.csv's mode column; each transition is transitions.csv's.
  // The run's last transition (into stop) ends a step that records no row: its mode comes last.
  const transitions = csv(path.join(out, 'transitions.csv'));
  const modes = bag.messages.filter((m) => m.topic === '/mode').map((m) => m.value.data);
  const expected = rows.map((r) => r.mode).filter((m, i, a) => i === 0 || m !== a[i - 1]);
  const last = transitions.at(-1);
  if (last.to !== expected.at(-1)) expected.push(last.to);
  assert.deepEqual(modes, expected);
  assert.equal(modes.at(-1), 'stop');
  const published = bag.messages.filter((m) => m.topic === '/transition');
  assert.equal(published.length, transitions.length);
  published.forEach((m, i) => {
    const tr = transitions[i];
    assert.equal(m.value.data, `${tr.from} -> ${tr.to}${tr.guard ? ': ' + tr.guard : ''}`);
    assert.equal(m.logTime, BigInt(Math.round(Number(tr.t) * 1e9)));
  });
  // The ring: 5 IR sensors, each in its bin, the rest NaN.
  const scan = bag.messages.find((m) => m.topic === '/ring_scan').value;
  assert.equal(scan.ranges.length, 360);
  const used = scan.ranges.filter((r) => !Number.isNaN(r));
  assert.ok(used.length >= 1 && used.length <= 5);
  assert.equal(scan.header.frame_id, 'base_link');
  // The goal: the scenario's first goal at t = 0.
  const goal = bag.messages.find((m) => m.topic === '/goal');
  assert.equal(goal.logTime, 0n);
});

test('a lidar robot on a ROS map: one scan per recorded frame, the map as the grid', async () => {
  const out = run('ros/depot_1.yaml', path.join(work, 'depot'), '--set', 'sim.t_max=20');
  const bag = await readBag(path.join(out, 'run.mcap'));
  checkCommon(bag);
  checkOdometry(bag.messages, csv(path.join(out, 'trajectory.csv')));
  const scans = bag.messages.filter((m) => m.topic === '/scan');
  assert.ok(scans.length > 10);
  const s = scans[0].value;
  assert.equal(s.ranges.length, 360);
  assert.equal(s.header.frame_id, 'lidar');
  assert.ok(Math.abs(s.angle_increment - (2 * Math.PI) / 360) < 1e-6);
  assert.ok(s.ranges.every((r) => r === Infinity || (r >= s.range_min - 1e-6 && r <= s.range_max)));
  const map = bag.messages.find((m) => m.topic === '/map').value;
  assert.deepEqual([map.info.width, map.info.height], [604, 307]);
  const tfStatic = bag.messages.find((m) => m.topic === '/tf_static').value.transforms;
  assert.deepEqual(tfStatic.map((t) => `${t.header.frame_id}->${t.child_frame_id}`),
    ['map->odom', 'base_link->lidar']);
});

test('a fleet with people and forklifts: every robot under its name, the crowd as markers', async () => {
  const out = run('crowd/factory_people.yaml', path.join(work, 'crowd'), '--set', 'sim.t_max=15');
  const bag = await readBag(path.join(out, 'run.mcap'));
  checkCommon(bag);
  const rows = csv(path.join(out, 'trajectory.csv'));
  const robots = [...new Set(rows.map((r) => r.robot))];
  assert.ok(robots.length >= 2);
  for (const name of robots) {
    checkOdometry(bag.messages, rows.filter((r) => r.robot === name), `/${name}`);
    const odom = bag.messages.find((m) => m.topic === `/${name}/odom`).value;
    assert.equal(odom.header.frame_id, `${name}/odom`);
    assert.equal(odom.child_frame_id, `${name}/base_link`);
  }
  const crowd = bag.messages.filter((m) => m.topic === '/crowd');
  assert.ok(crowd.length > 10);
  const people = crowd[0].value.markers.filter((m) => m.ns === 'people');
  const forklifts = crowd[0].value.markers.filter((m) => m.ns === 'forklifts');
  assert.ok(people.length > 0 && forklifts.length > 0);
  // The markers follow crowd.csv: the first person at t = 0.
  const tracks = csv(path.join(out, 'crowd.csv'));
  const first = tracks.find((r) => Number(r.t) === 0);
  const marker = crowd[0].value.markers.find((m) => m.id === 0 && m.ns ===
    (first.kind === 'forklift' ? 'forklifts' : 'people'));
  assert.equal(marker.pose.position.x, Number(first.x));
});

test('a lone sonar: sensor_msgs/msg/Range in its own frame', async () => {
  const file = path.join(work, 'sonar.yaml');
  fs.writeFileSync(file, `name: sonar
world: {bounds: [-1, -1, 4, 2], obstacles: [{circle: {center: [2, 0.5], radius: 0.3}}]}
robot:
  preset: pioneer_p3dx
  start: [0, 0.5, 0]
  sensors: {mounts: [[0.17, 0, 0]], max_range: 3, cone_angle: 0.26}
goal: [3.5, 1.5]
sim: {t_max: 5}
`);
  const out = run(file, path.join(work, 'sonar'));
  const bag = await readBag(path.join(out, 'run.mcap'));
  checkCommon(bag);
  const ranges = bag.messages.filter((m) => m.topic === '/range');
  assert.ok(ranges.length > 10);
  const r = ranges[0].value;
  assert.equal(r.radiation_type, 0); // ULTRASOUND: a cone
  assert.equal(r.header.frame_id, 'range');
  assert.ok(r.range === Infinity || (r.range >= r.min_range && r.range <= r.max_range));
});

test('the stream reader reads the file front to back with every CRC checked', async () => {
  const out = run('rectangle.yaml', path.join(work, 'stream'));
  const bytes = new Uint8Array(fs.readFileSync(path.join(out, 'run.mcap')));
  const reader = new mcap.McapStreamReader({ decompressHandlers, validateCrcs: true });
  reader.append(bytes);
  const kinds = new Map();
  let record;
  while ((record = reader.nextRecord())) kinds.set(record.type, (kinds.get(record.type) ?? 0) + 1);
  assert.ok(reader.done());
  for (const k of ['Header', 'Schema', 'Channel', 'Message', 'DataEnd', 'Statistics',
    'ChunkIndex', 'SummaryOffset', 'Footer'])
    assert.ok(kinds.get(k) > 0, k);
});

test('the Foxglove layout in docs/ shows topics the bags have', () => {
  const layout = JSON.parse(fs.readFileSync(path.join(source, 'docs/foxglove_layout.json'), 'utf8'));
  const topics = new Set(Object.keys(layout.configById['3D!floornav'].topics));
  for (const panel of Object.values(layout.configById))
    for (const p of [...(panel.paths ?? []).map((x) => x.value), panel.topicPath ?? ''])
      if (p) topics.add(p.split('.')[0]);
  for (const t of topics) assert.ok(seenTopics.has(t), `${t} is in no bag`);
});
