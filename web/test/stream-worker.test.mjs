// The replay's stream worker (src/stream-worker.js) with a fake clock and fake
// sessions: frames go out at the trial's rate, latest wins after a stall (no
// burst), never faster than the server's max_rate_hz, a seek or the loop jumps
// the stream clock forward by more than the server's restart gap, and answers
// carry the trial generation and frame index the page draws them by.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { Streamer, RESTART_GAP } from '../src/stream-worker.js';

function rig({ maxRateHz = 120, frames = 100, fps = 90 } = {}) {
  let now = 0;
  const posted = [];
  const sessions = [];
  const makeSession = (base, opts, cb) => {
    const s = { opts, cb, sent: [], closed: false, ready: Promise.resolve(), stats: { method: opts.method, maxRateHz },
      send(f) { this.sent.push(f); return true; }, setOptions(o) { Object.assign(this.opts, o); }, close() { this.closed = true; } };
    sessions.push(s);
    return s;
  };
  const st = new Streamer((m) => posted.push(m), makeSession, () => now);
  const trial = Array.from({ length: frames }, (_, i) => ({ t: i / fps, head: { p: [0, 1.7, i * 0.01], q: [1, 0, 0, 0] } }));
  st.connect({ id: 1, base: 'http://127.0.0.1:1/', methods: ['accent', 'ik'], options: { format: 'json' } });
  st.setTrial(trial, fps);
  st.handle({ type: 'run', on: true });
  const advance = (ms, stepMs = 4) => { for (let e = 0; e < ms; e += stepMs) { now += stepMs; st.tick(); } };
  const stall = (ms) => { now += ms; st.tick(); };
  return { st, posted, sessions, advance, stall, trial };
}

test('frames go out at the trial rate to every lane, in order, with gen and index', () => {
  const { sessions, advance } = rig();
  advance(500);
  const [a, b] = sessions;
  // 0.5 s at 90 Hz: frames 0..45
  assert.equal(a.sent.length, 46);
  assert.deepEqual(a.sent.map((f) => f._i), b.sent.map((f) => f._i));
  assert.deepEqual(a.sent.map((f) => f._i), [...Array(46).keys()]);
  for (const f of a.sent) assert.equal(f._gen, 1);
  // the stream clock starts RESTART_GAP after t = -RESTART_GAP, i.e. at the trial's own time
  assert.ok(Math.abs(a.sent[10].t - 10 / 90) < 1e-12, `t ${a.sent[10].t}`);
});

test('after a stall the latest frame goes out, not a burst of the missed ones', () => {
  const { sessions, advance, stall } = rig();
  advance(100);
  const before = sessions[0].sent.length;
  stall(400); // the thread was held up for 0.4 s: 36 frames came due
  assert.equal(sessions[0].sent.length, before + 1, 'one frame after the stall');
  const last = sessions[0].sent.at(-1);
  assert.equal(last._i, Math.floor(0.5 * 90), 'the frame due now');
});

test('never faster than the server\'s max_rate_hz, even at 4x speed', () => {
  const { st, sessions, advance } = rig({ maxRateHz: 60, frames: 1000 });
  st.handle({ type: 'speed', s: 4 });
  const n0 = sessions[0].sent.length;
  advance(1000);
  const n = sessions[0].sent.length - n0;
  assert.ok(n <= 61 && n >= 55, `${n} frames in 1 s with max_rate_hz 60`);
  // and they skip ahead through the trial at 4x (360 trial frames per second)
  assert.ok(sessions[0].sent.at(-1)._i >= 340, `at frame ${sessions[0].sent.at(-1)._i}`);
});

test('a seek jumps the stream clock forward by more than the restart gap; the loop restarts too', () => {
  const { st, sessions, advance, posted } = rig({ frames: 30 });
  advance(200);
  const lastT = sessions[0].sent.at(-1).t;
  st.handle({ type: 'seek', i: 5 });
  advance(8);
  const f = sessions[0].sent.at(-1);
  assert.equal(f._i, 5);
  assert.ok(f.t - lastT >= RESTART_GAP, `jump ${f.t - lastT} s`);
  assert.deepEqual(posted.filter((m) => m.type === 'shown').at(-1), { type: 'shown', gen: 1, i: 5 });
  advance(400); // past the end of the 30-frame trial: back to frame 0, clock forward again
  const looped = sessions[0].sent.filter((g) => g._i === 0).at(-1);
  assert.ok(looped && looped.t - f.t >= RESTART_GAP, 'the loop restarts the stream');
  for (let k = 1; k < sessions[0].sent.length; ++k) assert.ok(sessions[0].sent[k].t > sessions[0].sent[k - 1].t, 'time only moves forward');
});

test('answers are posted with lane, generation and frame index; stale lanes are dropped', () => {
  const { st, sessions, advance, posted, trial } = rig();
  advance(50);
  const [a] = sessions;
  a.cb.onPose({ type: 'pose', status: 'ok', positions: [[0, 0, 0]] }, a.sent[2]);
  assert.deepEqual(posted.filter((m) => m.type === 'pose').at(-1), { type: 'pose', lane: 0, gen: 1, i: 2, pose: { type: 'pose', status: 'ok', positions: [[0, 0, 0]] } });
  st.setTrial(trial, 90); // a new trial: generation 2
  st.connect({ id: 2, base: 'http://127.0.0.1:1/', methods: ['ik', 'ik'], options: {} });
  assert.ok(a.closed, 'the old sessions are closed');
  const n = posted.length;
  a.cb.onPose({ type: 'pose', status: 'ok', positions: [] }, a.sent[3]); // a late answer on the closed lane
  assert.equal(posted.length, n, 'nothing posted for a closed session');
  advance(20);
  assert.equal(sessions[2].sent.at(-1)._gen, 2);
});

test('paused or not running: nothing is sent; stats are posted at 10 Hz', () => {
  const { st, sessions, advance, posted } = rig();
  st.handle({ type: 'playing', on: false });
  const n = sessions[0].sent.length;
  advance(1000);
  assert.equal(sessions[0].sent.length, n);
  const stats = posted.filter((m) => m.type === 'stats');
  assert.ok(stats.length >= 9 && stats.length <= 11, `${stats.length} stats messages in 1 s`);
  assert.equal(stats.at(-1).stats.length, 2);
  st.handle({ type: 'playing', on: true });
  st.handle({ type: 'run', on: false });
  advance(200);
  assert.equal(sessions[0].sent.length, n, 'stopped (another mode): nothing sent');
});
