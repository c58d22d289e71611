// One avatar session on the server's WebSocket (/ws): hello -> welcome, then
// frame -> pose. Keeps the numbers the UI and the tests read: poses received,
// round-trip latency (send -> pose with the same t), pose rate, and how far the
// avatar's hands are from the input hands.
import { helloMessage, frameJSON, frameBinary, decodePoseBinary, findJoint, distance } from './protocol.js';

export function wsURL(base) {
  const u = new URL('ws', base);
  u.protocol = u.protocol === 'https:' ? 'wss:' : 'ws:';
  return u.toString();
}

// The skeleton of the joints each pose carries (welcome.joints: all, or the subset the hello
// asked for, in pose order); a joint's parent is its nearest ancestor that is in the subset.
export function outputSkeleton(welcome) {
  const { names, parents } = welcome.skeleton;
  const joints = welcome.joints;
  if (!joints || (joints.length === names.length && joints.every((n, i) => n === names[i]))) return welcome.skeleton;
  const index = joints.map((n) => names.indexOf(n));
  const out = index.map((j) => {
    for (let p = parents[j]; p >= 0; p = parents[p]) if (index.includes(p)) return index.indexOf(p);
    return -1;
  });
  return { names: joints, parents: out };
}

export class LiveSession {
  // opts: hello options (method, classes, exaggeration, user_height, format, ...)
  constructor(base, opts, { onPose, onError, onWelcome } = {}) {
    this.opts = { format: 'json', ...opts };
    this.onPose = onPose || (() => {});
    this.onError = onError || (() => {});
    this.onWelcome = onWelcome || (() => {});
    this.stats = { method: opts.method, state: 'connecting', posesReceived: 0, framesSent: 0, errors: 0, lastError: '',
      lastHandError: NaN, maxHandError: 0, lastHeadError: NaN, rttMs: NaN, rttAvgMs: NaN, poseHz: 0, statusCounts: {}, restartFrames: [], serverUs: NaN, inputHandTravel: 0, medianHandError: NaN, lastCrossHandError: NaN };
    this.skeleton = null;
    this.hands = [-1, -1];
    this.sent = new Map(); // t -> {sentAt, frame}
    this.lastPose = null;
    this.handErrors = [];
    this._rateWindow = [];
    this.ws = new WebSocket(wsURL(base));
    this.ws.binaryType = 'arraybuffer';
    this.ready = new Promise((resolve, reject) => { this._ready = resolve; this._fail = reject; });
    this.ws.onopen = () => this.ws.send(JSON.stringify(helloMessage(this.opts)));
    this.ws.onmessage = (ev) => this._message(ev.data);
    this.ws.onerror = () => { this.stats.state = 'error'; this._fail(new Error(`WebSocket to ${wsURL(base)} failed`)); };
    this.ws.onclose = (ev) => { this.stats.state = `closed (${ev.code})`; this._fail(new Error(`closed ${ev.code}`)); };
  }

  get open() { return this.ws.readyState === WebSocket.OPEN && this.skeleton !== null; }

  send(frame) {
    if (!this.open) return false;
    // Whole microseconds: JSON poses echo t with 6 decimals, and the echo finds the frame again.
    frame = { ...frame, t: Math.round(frame.t * 1e6) / 1e6 };
    this.sent.set(frame.t, { sentAt: performance.now(), frame });
    if (this.sent.size > 512) this.sent.delete(this.sent.keys().next().value);
    this.ws.send(this.opts.format === 'binary' ? frameBinary(frame) : frameJSON(frame));
    this.stats.framesSent++;
    return true;
  }

  setOptions(o) {
    Object.assign(this.opts, o);
    if (this.open) this.ws.send(JSON.stringify({ type: 'options', ...o }));
  }

  close() { try { this.ws.close(1000); } catch { /* already closed */ } }

  _message(data) {
    let m;
    if (typeof data === 'string') {
      try { m = JSON.parse(data); } catch { return; }
    } else {
      m = decodePoseBinary(data);
      if (!m) return;
    }
    if (m.type === 'welcome') {
      this.skeleton = outputSkeleton(m);
      this.stats.warnings = m.warnings || [];
      this.hands = [findJoint(m.skeleton.names, 'left_hand'), findJoint(m.skeleton.names, 'right_hand')];
      this.headJoint = findJoint(m.skeleton.names, 'head');
      this.stats.state = 'open';
      this.stats.session = m.session;
      this.stats.maxRateHz = m.max_rate_hz;
      this.onWelcome({ ...m, skeleton: this.skeleton });
      this._ready(m);
    } else if (m.type === 'pose') {
      this._pose(m);
    } else if (m.type === 'error') {
      this.stats.errors++;
      this.stats.lastError = `${m.code}: ${m.message}`;
      this.onError(m);
    }
  }

  _pose(m) {
    const now = performance.now();
    const s = this.stats;
    s.posesReceived++;
    s.statusCounts[m.status] = (s.statusCounts[m.status] || 0) + 1;
    if (m.server_us !== undefined) s.serverUs = m.server_us;
    const sent = this.sent.get(m.t) ?? this.sent.get(Math.round(m.t * 1e6) / 1e6);
    if (sent) {
      // The trial frame each restarted pose answers (a seek's target, or 0 when the replay loops): the last 16.
      if (m.status === 'restarted') s.restartFrames = [...s.restartFrames.slice(-15), sent.frame._i];
      const rtt = now - sent.sentAt;
      s.rttMs = rtt;
      s.rttAvgMs = Number.isNaN(s.rttAvgMs) ? rtt : s.rttAvgMs * 0.95 + rtt * 0.05;
      for (const k of this.sent.keys()) { if (k > m.t) break; this.sent.delete(k); }
      if (m.status !== 'rejected' && m.positions) this._errors(m, sent.frame);
    }
    this._rateWindow.push(now);
    while (this._rateWindow.length && now - this._rateWindow[0] > 1000) this._rateWindow.shift();
    s.poseHz = this._rateWindow.length;
    if (m.positions && m.positions.length) this.lastPose = m;
    this.onPose(m, sent ? sent.frame : null);
  }

  _errors(m, frame) {
    // How far the input hands moved over the answered frames: "the hands follow" means something only if they moved.
    // (steps over 25 cm are loops, seeks or skipped frames, not motion)
    if (this._prevHands) for (const side of ['left', 'right']) {
      const step = frame[side] && this._prevHands[side] ? distance(frame[side].p, this._prevHands[side].p) : 0;
      if (step < 0.25) this.stats.inputHandTravel += step;
    }
    this._prevHands = { left: frame.left, right: frame.right };
    const errs = [];
    ['left', 'right'].forEach((side, k) => {
      const j = this.hands[k];
      if (j >= 0 && frame[side] && m.positions[j]) errs.push(distance(m.positions[j], frame[side].p));
    });
    // the same distance to the other side's input: shows the measure tells the hands apart
    if (this.hands[0] >= 0 && frame.right && m.positions[this.hands[0]]) this.stats.lastCrossHandError = distance(m.positions[this.hands[0]], frame.right.p);
    if (errs.length) {
      this.stats.lastHandError = Math.max(...errs);
      this.stats.maxHandError = Math.max(this.stats.maxHandError, this.stats.lastHandError);
      this.handErrors.push(this.stats.lastHandError);
      if (this.handErrors.length > 300) this.handErrors.shift();
      const sorted = [...this.handErrors].sort((a, b) => a - b);
      this.stats.medianHandError = sorted[sorted.length >> 1];
    }
    if (this.headJoint >= 0 && frame.head && m.positions[this.headJoint]) this.stats.lastHeadError = distance(m.positions[this.headJoint], frame.head.p);
  }
}
