// VR mirror mode: the headset and controllers drive a live session and the
// avatar stands in a mirror 1.6 m in front of the user. Works with a real
// WebXR immersive-vr session or with window.__legworkFakeXR (emulated input
// through the same XRInput path). Scene objects live in WebXR's frame.
import * as THREE from 'three';
import { Body, DeviceMarkers } from './avatar.js';
import { LiveSession } from './session.js';
import { XRInput, FakeXRSession, demoXRPose, legworkToXRPosition } from './xr.js';

const MIRROR_Z = -1.6; // mirror plane, metres in front of the user's start (WebXR -z)

export class XRMirror {
  constructor(stage, base) {
    this.stage = stage;
    this.base = base;
    this.group = new THREE.Group();
    stage.scene.add(this.group);
    const frame = new THREE.Mesh(new THREE.BoxGeometry(2.2, 2.4, 0.04), new THREE.MeshStandardMaterial({ color: 0x3a4350, roughness: 0.4 }));
    frame.position.set(0, 1.2, MIRROR_Z - 0.02);
    const glass = new THREE.Mesh(new THREE.PlaneGeometry(2.05, 2.25), new THREE.MeshStandardMaterial({ color: 0x9fb8d0, roughness: 0.05, metalness: 0.6, transparent: true, opacity: 0.18 }));
    glass.position.set(0, 1.2, MIRROR_Z + 0.001);
    this.group.add(frame, glass);
    this.markers = new DeviceMarkers();
    this.group.add(this.markers.group);
    this.body = null;
    this.session = null;
    this.xrSession = null;
    this.label = stage.addLabel('Mirror', '#ffd166');
    this.label.at.set(0, 2.55, MIRROR_Z);
    this.label.visible = false;
    this.stats = { active: false, fake: false, framesRead: 0, posesReceived: 0, lastHandError: NaN, lastFrame: null };
    this.input = new XRInput((f) => this._frame(f));
  }

  async _open(method, options) {
    if (this.session) this.session.close();
    if (this.body) this.group.remove(this.body.group);
    this.body = new Body(0xffd166);
    this.group.add(this.body.group);
    this.session = new LiveSession(this.base, { method, ...options }, {
      onWelcome: (w) => this.body.setSkeleton(w.skeleton.names, w.skeleton.parents),
      onPose: (pose) => this._pose(pose),
    });
    this.label.title.textContent = `Mirror · ${method}`;
    await this.session.ready;
  }

  _frame(f) {
    this.stats.framesRead = this.input.framesRead;
    this.stats.lastFrame = f;
    if (this.session) this.session.send(f);
    // the user's own devices, back in WebXR's frame
    const back = (d) => d && { p: legworkToXRPosition(d.p), q: [d.q[0], -d.q[1], d.q[2], -d.q[3]] };
    this.markers.set({ head: back(f.head), left: back(f.left), right: back(f.right) }, new THREE.Vector3());
  }

  // legwork pose -> WebXR frame -> reflected in the mirror plane z = MIRROR_Z.
  _pose(pose) {
    const s = this.session.stats;
    this.stats.posesReceived = s.posesReceived;
    this.stats.lastHandError = s.lastHandError;
    this.stats.medianHandError = s.medianHandError;
    this.stats.rttMs = s.rttAvgMs;
    if (!pose.positions || pose.status === 'rejected' || !this.body.joints.length) return;
    this.body.setPositions(pose.positions.map((p) => {
      const x = legworkToXRPosition(p);
      return [x[0], x[1], 2 * MIRROR_Z - x[2]];
    }));
  }

  async enterVR(method, options) {
    const xr = this.stage.renderer.xr;
    const session = await navigator.xr.requestSession('immersive-vr', { optionalFeatures: ['local-floor'] });
    await this._open(method, options);
    xr.enabled = true;
    xr.setReferenceSpaceType('local-floor');
    await xr.setSession(session);
    const ref = await session.requestReferenceSpace('local-floor').catch(() => session.requestReferenceSpace('local'));
    this.xrSession = session;
    this.stats.active = true;
    this.stage.renderer.setAnimationLoop((time, frame) => {
      if (frame) this.input.onXRFrame(time, frame, ref);
      this.stage.renderer.render(this.stage.scene, this.stage.camera);
    });
    session.addEventListener('end', () => { this.stats.active = false; this.stage.renderer.setAnimationLoop(null); xr.enabled = false; });
  }

  // Emulated XR: the fake session's frames go through XRInput like real ones.
  async startFake(method, options, poseAt = demoXRPose) {
    await this.stopFake();
    await this._open(method, options);
    const session = new FakeXRSession(poseAt);
    const ref = await session.requestReferenceSpace('local-floor');
    this.input.t0 = null;
    const loop = (time, frame) => { this.input.onXRFrame(time, frame, ref); session.requestAnimationFrame(loop); };
    session.requestAnimationFrame(loop);
    this.xrSession = session;
    Object.assign(this.stats, { active: true, fake: true });
  }

  async stopFake() {
    if (this.xrSession && this.stats.fake) await this.xrSession.end();
    this.stats.active = false;
    this.stats.fake = false;
  }

  setOptions(o) { if (this.session) this.session.setOptions(o); }

  // Third-person view for the screen: behind and beside the user, facing the mirror.
  frameCamera() {
    this.stage.camera.position.set(1.6, 1.9, 2.2);
    this.stage.controls.target.set(0, 1.1, -0.7);
  }
}
