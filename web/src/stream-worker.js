// The replay's input stream, off the page's render thread (a module Worker).
// It owns the trial's head + hand frames, the replay clock and the lanes' server
// sessions: frames go out at the trial's rate and poses come back whatever the
// page's render rate, so the round trip measured here is the network and the
// server's, not the time a slow frame (software WebGL: ~1-2 fps) kept the page
// busy. The page (replay.js) sends commands and draws the latest pose per lane.
//
// page -> worker: {type:'connect', id, base, methods, options} | {type:'trial', frames, fps}
//                 | {type:'seek', i} | {type:'run', on} | {type:'playing', on} | {type:'speed', s}
//                 | {type:'options', o}
// worker -> page: {type:'connected', id, error?} | {type:'welcome', lane, welcome}
//                 | {type:'pose', lane, gen, i, pose} | {type:'shown', gen, i} | {type:'stats', stats}
import { LiveSession } from './session.js';

export const RESTART_GAP = 6; // seconds forward: more than the server's FrameClock::kMaxGap (5 s) -> restart
const STATS_MS = 100;

// The clock and the sending, with the sessions and the posting injected (tested without a worker).
export class Streamer {
  constructor(post, makeSession = (base, opts, cb) => new LiveSession(base, opts, cb), now = () => performance.now()) {
    this.post = post;
    this.makeSession = makeSession;
    this.now = now;
    this.lanes = [];
    this.frames = null;
    this.gen = 0;          // trial generation: answers to an older trial's frames are dropped by the page
    this.index = 0;        // next frame to send
    this.clockBase = 0;    // added to trial times so the stream's clock only moves forward
    this.lastSentT = -RESTART_GAP; // first stream starts at t = 0
    this.running = false;
    this.playing = true;
    this.speed = 1;
    this.fps = 90;
    this._lastStats = 0;
    this._nextSend = -Infinity;
  }

  connect({ id, base, methods, options }) {
    for (const l of this.lanes) l.session.close();
    this.lanes = methods.map((method, k) => {
      const lane = { method };
      lane.session = this.makeSession(base, { method, ...options }, {
        onWelcome: (w) => this.lanes[k] === lane && this.post({ type: 'welcome', lane: k, welcome: w }),
        onPose: (pose, frame) => this.lanes[k] === lane && frame &&
          this.post({ type: 'pose', lane: k, gen: frame._gen, i: frame._i, pose }),
      });
      return lane;
    });
    this.clockBase = this.lastSentT + RESTART_GAP;
    Promise.all(this.lanes.map((l) => l.session.ready)).then(
      () => this.post({ type: 'connected', id }),
      (e) => this.post({ type: 'connected', id, error: e.message }));
  }

  setTrial(frames, fps) {
    this.frames = frames;
    this.fps = fps;
    this.gen++;
    this.seek(0);
  }

  seek(i) {
    if (!this.frames) return;
    this.index = Math.max(0, Math.min(i, this.frames.length - 1));
    this.clockBase = this.lastSentT + RESTART_GAP - this.frames[this.index].t; // jump = restart
    this._restartClock();
    this.post({ type: 'shown', gen: this.gen, i: this.index });
  }

  setPlaying(on) { this.playing = on; this._restartClock(); }
  setSpeed(s) { this.speed = s; this._restartClock(); }
  setOptions(o) { for (const l of this.lanes) l.session.setOptions(o); }
  _restartClock() { this._playStart = this.now(); this._playFrom = this.index; }

  tick() {
    const now = this.now();
    if (now - this._lastStats >= STATS_MS) {
      this._lastStats = now;
      this.post({ type: 'stats', stats: this.lanes.map((l) => l.session.stats) });
    }
    if (!this.frames || !this.running || !this.playing) return;
    const due = this._playFrom + Math.floor(((now - this._playStart) / 1000) * this.speed * this.fps);
    if (due < this.index || now < this._nextSend) return;
    // Latest wins, as a tracker streams: frames that came due while this thread was held up
    // are skipped, not sent in a burst; and never faster than the server's max_rate_hz.
    this.index = due;
    if (this.index >= this.frames.length) { this.seek(0); return; } // loop: restart the stream
    const gap = this._minGapMs(); // a schedule, not a gap since the last send: the tick's 4 ms steps do not lower the rate
    this._nextSend = Math.max(this._nextSend, now - gap) + gap;
    this._send(this.index++);
  }

  _minGapMs() {
    const rates = this.lanes.map((l) => l.session.stats.maxRateHz).filter((r) => r > 0);
    return rates.length ? 1000 / Math.min(...rates) : 0;
  }

  _send(i) {
    const src = this.frames[i];
    const frame = { ...src, t: this.clockBase + src.t, _i: i, _gen: this.gen };
    let sent = false;
    for (const lane of this.lanes) if (lane.session.send(frame)) sent = true;
    if (sent) this.lastSentT = frame.t;
    else this.post({ type: 'shown', gen: this.gen, i }); // no session answers: the truth alone keeps time
  }

  handle(m) {
    if (m.type === 'connect') this.connect(m);
    else if (m.type === 'trial') this.setTrial(m.frames, m.fps);
    else if (m.type === 'seek') this.seek(m.i);
    else if (m.type === 'run') { this.running = m.on; if (m.on) this._restartClock(); }
    else if (m.type === 'playing') this.setPlaying(m.on);
    else if (m.type === 'speed') this.setSpeed(m.s);
    else if (m.type === 'options') this.setOptions(m.o);
  }
}

// In a worker (not when imported by a test): wire the Streamer to the page.
if (typeof WorkerGlobalScope !== 'undefined' && self instanceof WorkerGlobalScope) {
  const streamer = new Streamer((m) => self.postMessage(m));
  self.onmessage = (ev) => streamer.handle(ev.data);
  setInterval(() => streamer.tick(), 4);
}
