// Replay mode: streams a trial's head + hands to two server sessions at the
// trial's rate and shows their avatars beside the trial's ground truth. The
// stream itself (clock, sending, sessions) runs in stream-worker.js, off the
// render thread; this side keeps the latest pose per lane and draws it.
// Display frame: each lane = R(yaw) * (p - anchor) + lane offset, where the
// anchor follows the input head (follow mode) so the walkers stay in view, and
// yaw turns the trial's walking direction towards the camera.
import * as THREE from 'three';
import { Body, DeviceMarkers } from './avatar.js';

const LANE_X = [-1.6, 0, 1.6];

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
    this.gen = 0;          // trial generation, as the worker counts it
    this.playing = true;
    this.follow = true;
    this.shown = 0;        // frame the truth shows
    this.options = { classes: undefined, exaggeration: 1, format: 'json' };
    this._connects = new Map();
    this._connectId = 0;
    this.worker = new Worker(new URL('stream-worker.js', import.meta.url), { type: 'module' });
    this.worker.onmessage = (ev) => this._message(ev.data);
    this.worker.onerror = (e) => { for (const [, c] of this._connects) c.reject(new Error(`stream worker: ${e.message}`)); this._connects.clear(); };
  }

  _post(m) { this.worker.postMessage(m); }

  _message(m) {
    if (m.type === 'pose') { const lane = this.lanes[m.lane]; if (lane?.session) lane.pending = m; }
    else if (m.type === 'shown') { if (m.gen === this.gen) this._pendingShown = m.i; }
    else if (m.type === 'stats') m.stats.forEach((st, k) => { if (this.lanes[k]?.session) this.lanes[k].session.stats = st; });
    else if (m.type === 'welcome') {
      const lane = this.lanes[m.lane];
      lane.session.open = true;
      lane.body.setSkeleton(m.welcome.skeleton.names, m.welcome.skeleton.parents);
    } else if (m.type === 'connected') {
      const c = this._connects.get(m.id);
      this._connects.delete(m.id);
      if (c) (m.error ? c.reject(new Error(m.error)) : c.resolve());
    }
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

  // Opens (or reopens) the two method sessions (in the worker). lane.session is what the
  // page knows of a session: its method, whether it is open, and its stats as last posted.
  async connect(methods) {
    methods.forEach((method, i) => {
      this._setLane(i, method);
      this.lanes[i].session = { method, open: false, stats: { method, state: 'connecting', posesReceived: 0, framesSent: 0, errors: 0, lastError: '' } };
      this.lanes[i].pending = null;
    });
    this._setLane(2, 'truth');
    if (this.trial?.truth) this.lanes[2].body.setSkeleton(this.trial.truth.names, this.trial.truth.parents);
    const id = ++this._connectId;
    const done = new Promise((resolve, reject) => this._connects.set(id, { resolve, reject }));
    this._post({ type: 'connect', id, base: this.base.href, methods, options: this.options });
    await done;
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
    this.gen++;
    for (const lane of this.lanes) lane.pending = null;
    this._post({ type: 'trial', frames: trial.frames, fps: trial.fps });
    this.shown = 0;
    this._showTruth(0);
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
    this.shown = Math.max(0, Math.min(i, this.trial.frames.length - 1));
    this._post({ type: 'seek', i: this.shown });
    this._showTruth(this.shown);
  }

  start() { this._post({ type: 'run', on: true }); }
  stop() { this._post({ type: 'run', on: false }); }
  setPlaying(p) { this.playing = p; this._post({ type: 'playing', on: p }); }
  setSpeed(s) { this._post({ type: 'speed', s }); }

  setOptions(o) {
    Object.assign(this.options, o);
    this._post({ type: 'options', o });
  }

  // Once per rendered frame: the latest pose of each lane, and the truth at the frame the
  // middle lane answered (so all three bodies are in step), or where the stream is.
  update() {
    let truthAt = null;
    this.lanes.slice(0, 2).forEach((lane, k) => {
      const m = lane.pending;
      lane.pending = null;
      if (m && m.gen === this.gen && this._pose(lane, m.pose, m.i) && (k === 1 || !this.lanes[1].session?.open)) truthAt = m.i;
    });
    if (truthAt === null && this._pendingShown !== undefined) truthAt = this._pendingShown;
    this._pendingShown = undefined;
    if (truthAt !== null) { this.shown = truthAt; this._showTruth(truthAt); }
    this.updateLabels();
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

  _pose(lane, pose, i) {
    if (pose.status === 'rejected' || !pose.positions || !lane.body.joints.length || !this.trial.frames[i]) return false;
    const anchor = this._anchor(i);
    lane.body.setPositions(pose.positions.map((p) => this._display(p, anchor, lane)));
    this._devices(this.trial.frames[i], anchor, lane);
    return true;
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
