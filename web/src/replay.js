// Replay mode: streams a trial's head + hands to two server sessions at the
// trial's rate and shows their avatars beside the trial's ground truth.
// Display frame: each lane = R(yaw) * (p - anchor) + lane offset, where the
// anchor follows the input head (follow mode) so the walkers stay in view, and
// yaw turns the trial's walking direction towards the camera.
import * as THREE from 'three';
import { Body, DeviceMarkers } from './avatar.js';
import { LiveSession } from './session.js';

const LANE_X = [-1.6, 0, 1.6];
const RESTART_GAP = 6; // seconds forward: more than the server's FrameClock::kMaxGap (5 s) -> restart

export const LANE_COLORS = { accent: 0xff9a3c, ik: 0x4aa3ff, wip: 0xc792ea, combined: 0xffd166, truth: 0xb8c2cc };
export const LANE_TITLES = { accent: 'Accentuated', ik: 'IK baseline', wip: 'Walking in place', combined: 'Combined', truth: 'Ground truth' };
const hex = (c) => `#${c.toString(16).padStart(6, '0')}`;

export class Replay {
  constructor(stage, base) {
    this.stage = stage;
    this.base = base;
    this.group = new THREE.Group();
    stage.scene.add(this.group);
    this.lanes = [0, 1, 2].map((i) => {
      const lane = { offset: new THREE.Vector3(LANE_X[i], 0, 0), body: null, markers: new DeviceMarkers(), label: null, session: null, method: null };
      this.group.add(lane.markers.group);
      return lane;
    });
    this.trial = null;
    this.playing = true;
    this.speed = 1;
    this.follow = true;
    this.index = 0;        // next frame to send
    this.shown = 0;        // frame the truth shows
    this.clockBase = 0;    // added to trial times so the stream's clock only moves forward
    this.lastSentT = -RESTART_GAP; // first stream starts at t = 0
    this.options = { classes: undefined, exaggeration: 1, format: 'json' };
    this._timer = null;
  }

  _setLane(i, method) {
    const lane = this.lanes[i];
    if (lane.body) this.group.remove(lane.body.group);
    lane.method = method;
    lane.body = new Body(LANE_COLORS[method] ?? 0xcccccc);
    this.group.add(lane.body.group);
    if (!lane.label) lane.label = this.stage.addLabel('', '#fff');
    if (lane.disc) this.group.remove(lane.disc);
    lane.disc = new THREE.Mesh(new THREE.RingGeometry(0.5, 0.56, 48), new THREE.MeshBasicMaterial({ color: LANE_COLORS[method] ?? 0xcccccc, transparent: true, opacity: 0.55 }));
    lane.disc.rotation.x = -Math.PI / 2;
    lane.disc.position.set(LANE_X[i], 0.004, 0);
    this.group.add(lane.disc);
    lane.label.title.textContent = LANE_TITLES[method] || method;
    lane.label.el.style.color = hex(LANE_COLORS[method] ?? 0xcccccc);
    lane.label.at.set(LANE_X[i], 2.15, 0);
  }

  // Opens (or reopens) the two method sessions.
  async connect(methods) {
    for (const lane of this.lanes) if (lane.session) lane.session.close();
    const opened = methods.map((method, i) => {
      this._setLane(i, method);
      const lane = this.lanes[i];
      const session = new LiveSession(this.base, { method, ...this.options }, {
        onWelcome: (w) => lane.body.setSkeleton(w.skeleton.names, w.skeleton.parents),
        onPose: (pose, frame) => lane.session === session && this._pose(lane, pose, frame),
      });
      lane.session = session;
      return lane.session.ready;
    });
    this._setLane(2, 'truth');
    if (this.trial?.truth) this.lanes[2].body.setSkeleton(this.trial.truth.names, this.trial.truth.parents);
    this.clockBase = this.lastSentT + RESTART_GAP;
    await Promise.all(opened);
  }

  async load(name, rate = 90) {
    const res = await fetch(new URL(`api/trial?name=${encodeURIComponent(name)}&rate=${rate}`, this.base));
    if (!res.ok) throw new Error(`GET /api/trial ${name}: HTTP ${res.status}`);
    return this.setTrial(await res.json());
  }

  // A trial from /api/trial, or a recorded session (trackercsv.js: truth null).
  setTrial(trial) {
    this.trial = trial;
    const truth = this.lanes[2];
    if (trial.truth) truth.body?.setSkeleton(trial.truth.names, trial.truth.parents);
    else if (truth.body) truth.body.group.visible = false;
    if (truth.label) truth.label.title.textContent = trial.truth ? LANE_TITLES.truth : 'Recorded input';
    this._frameOf(trial);
    this.seek(0);
    return trial;
  }

  _frameOf(trial) {
    const f = trial.frames, head = (k) => f[k].head || f[k]._heldHead, first = head(0).p, last = head(f.length - 1).p;
    const dx = last[0] - first[0], dz = last[2] - first[2];
    let heading;
    if (Math.hypot(dx, dz) > 1) heading = Math.atan2(dx, dz);
    else {
      const [w, x, y, z] = head(0).q || [1, 0, 0, 0]; // forward = q * (0,0,1)
      heading = Math.atan2(2 * (x * z + w * y), 1 - 2 * (x * x + y * y));
    }
    this.yaw = -heading;
    this.fixedAnchor = new THREE.Vector3(first[0], 0, first[2]);
  }

  get duration() { return this.trial ? (this.trial.frames.length - 1) / this.trial.fps : 0; }

  seek(i) {
    if (!this.trial) return;
    this.index = Math.max(0, Math.min(i, this.trial.frames.length - 1));
    this.shown = this.index;
    this.clockBase = this.lastSentT + RESTART_GAP - this.trial.frames[this.index].t; // jump = restart
    this._playStart = performance.now();
    this._playFrom = this.index;
    this._showTruth(this.index);
  }

  start() {
    if (this._timer) return;
    this._playStart = performance.now();
    this._playFrom = this.index;
    this._timer = setInterval(() => this.tick(), 4);
  }

  stop() { clearInterval(this._timer); this._timer = null; }

  setPlaying(p) {
    this.playing = p;
    this._playStart = performance.now();
    this._playFrom = this.index;
  }

  setSpeed(s) { this.speed = s; this._playStart = performance.now(); this._playFrom = this.index; }

  setOptions(o) {
    Object.assign(this.options, o);
    for (const lane of this.lanes) if (lane.session) lane.session.setOptions(o);
  }

  tick() {
    const tr = this.trial;
    if (!tr || !this.playing) return;
    const due = this._playFrom + Math.floor(((performance.now() - this._playStart) / 1000) * this.speed * tr.fps);
    if (due - this.index > 10) this.index = due - 1; // fell behind (background tab): skip, latest wins
    while (this.index <= due) {
      if (this.index >= tr.frames.length) { this.seek(0); return; } // loop: restart the stream
      this._send(this.index++);
    }
  }

  _send(i) {
    const src = this.trial.frames[i];
    const frame = { ...src, t: this.clockBase + src.t, _i: i, _trial: this.trial };
    let sent = false;
    for (const lane of this.lanes) if (lane.session && lane.session.send(frame)) sent = true;
    if (sent) this.lastSentT = frame.t;
    else this._showTruth(i); // no session answers: the truth alone keeps time
    this.shown = i;
  }

  _anchor(i) {
    if (!this.follow) return this.fixedAnchor;
    const f = this.trial.frames[i];
    const p = (f.head || f._heldHead).p;
    return new THREE.Vector3(p[0], 0, p[2]);
  }

  // world [x,y,z] (legwork frame) -> display point of a lane
  _display(p, anchor, lane, out = []) {
    const c = Math.cos(this.yaw), s = Math.sin(this.yaw);
    const x = p[0] - anchor.x, z = p[2] - anchor.z;
    out[0] = c * x + s * z + lane.offset.x;
    out[1] = p[1];
    out[2] = -s * x + c * z + lane.offset.z;
    return out;
  }

  _devices(frame, anchor, lane) {
    const q = new THREE.Quaternion().setFromAxisAngle(new THREE.Vector3(0, 1, 0), this.yaw);
    const out = {};
    for (const d of ['head', 'left', 'right']) {
      if (!frame[d] || !frame[d].q) continue;
      const r = new THREE.Quaternion(frame[d].q[1], frame[d].q[2], frame[d].q[3], frame[d].q[0]).premultiply(q);
      out[d] = { p: this._display(frame[d].p, anchor, { offset: new THREE.Vector3() }), q: [r.w, r.x, r.y, r.z] };
    }
    lane.markers.set(out, lane.offset);
  }

  _showTruth(i) {
    const tr = this.trial, lane = this.lanes[2];
    if (!tr) return;
    const anchor = this._anchor(i);
    this.stage.setGridOffset(anchor.x, anchor.z, this.yaw);
    this._devices(tr.frames[i], anchor, lane);
    if (!tr.truth || !lane.body || !lane.body.joints.length) return;
    const flat = tr.truth.positions[i], n = flat.length / 3, pts = [];
    for (let j = 0; j < n; ++j) pts.push(this._display([flat[3 * j], flat[3 * j + 1], flat[3 * j + 2]], anchor, lane));
    lane.body.setPositions(pts);
  }

  _pose(lane, pose, frame) {
    // late answers to a previous trial's frames (the lane has reconnected since) are dropped
    if (!frame || frame._trial !== this.trial || pose.status === 'rejected' || !pose.positions || !lane.body.joints.length) return;
    const anchor = this._anchor(frame._i);
    lane.body.setPositions(pose.positions.map((p) => this._display(p, anchor, lane)));
    this._devices(this.trial.frames[frame._i], anchor, lane);
    // the truth shows the frame the middle lane just answered, so all three bodies are in step
    if (lane === this.lanes[1] || !this.lanes[1].session?.open) this._showTruth(frame._i);
  }

  updateLabels() {
    for (const lane of this.lanes.slice(0, 2)) {
      const s = lane.session?.stats;
      if (!s) continue;
      const e = s.lastHandError;
      const err = !Number.isFinite(e) ? '–' : e < 0.01 ? `${(e * 1000).toFixed(1)} mm` : `${(e * 100).toFixed(1)} cm`;
      const rtt = Number.isFinite(s.rttAvgMs) ? `${s.rttAvgMs.toFixed(s.rttAvgMs < 10 ? 1 : 0)} ms` : '–';
      lane.label.stats.textContent = `${lane.method} · hands ${err} · ${rtt}`;
    }
    const tr = this.trial;
    if (tr) this.lanes[2].label.stats.textContent = `${tr.name.split('/').slice(-2).join('/')} · input ${tr.fps} Hz`;
  }
}
