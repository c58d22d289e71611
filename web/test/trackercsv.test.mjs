// Recorded-session CSV (io/tracker_csv.hpp layout) -> replay frames.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { parseTrackerCSV } from '../src/trackercsv.js';

const csv = ['time,head_x,head_y,head_z,head_qw,head_qx,head_qy,head_qz,left_hand_x,left_hand_y,left_hand_z,rhand_x,rhand_y,rhand_z',
  '10.0,0,1.7,0,1,0,0,0,0.3,1.0,0.1,-0.3,1.0,0.1',
  '10.011,0,1.71,0,1,0,0,0,0.3,1.01,0.1,,,',
  '10.022,0.01,1.7,0,1,0,0,0,0.3,1.0,0.1,-0.3,nan,0.1', ''].join('\n');

test('devices by alias, times from zero, dropped samples left out, rate from the median step', () => {
  const r = parseTrackerCSV(csv, 'rec.csv');
  assert.equal(r.frames.length, 3);
  assert.equal(r.fps, 91);
  assert.ok(Math.abs(r.frames[1].t - 0.011) < 1e-12);
  assert.deepEqual(r.frames[0].right, { p: [-0.3, 1.0, 0.1], q: [1, 0, 0, 0] });
  assert.equal(r.frames[1].right, undefined);
  assert.equal(r.frames[2].right, undefined);
  assert.deepEqual(r.frames[1].left.p, [0.3, 1.01, 0.1]);
  assert.deepEqual(r.frames[0].head.q, [1, 0, 0, 0]);
  assert.equal(r.truth, null);
});

test('errors name the file, line and problem', () => {
  assert.throws(() => parseTrackerCSV('t,head_x\n', 'a.csv'), /a\.csv:1: the first column must be "time"/);
  assert.throws(() => parseTrackerCSV('time,head_x,head_y\n0,1,2\n', 'b.csv'), /b\.csv:1: point "head" lacks one of _x, _y, _z/);
  assert.throws(() => parseTrackerCSV('time,hand_x,hand_y,hand_z\n', 'c.csv'), /c\.csv:1: no head point .*points: hand/);
  assert.throws(() => parseTrackerCSV('time,head_x,head_y,head_z\n0,0,1,0\n0,0,1,0\n', 'd.csv'), /d\.csv:3: time 0 is not after 0/);
  assert.throws(() => parseTrackerCSV('time,head_x,head_y,head_z\n0,0,1\n', 'e.csv'), /e\.csv:2: 3 cells, the header has 4/);
});
