// VR mirror mode: the headset and controllers drive a live session and the
// avatar stands in a mirror 1.6 m in front of the user. Works with a real
// WebXR immersive-vr session or with window.__legworkFakeXR (emulated input
// through the same XRInput path). Scene objects live in WebXR's frame.
import * as THREE from 'three';
import { material } from './materials.js';
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
    // The mirror: a frame around see-through glass; the avatar stands behind it, reflected.
    const metal = material({ color: 0x8a96a8, roughness: 0.3, metalness: 0.7 });
    for (const [w, h, x, y] of [[2.2, 0.06, 0, 2.37], [2.2, 0.06, 0, 0.03], [0.06, 2.4, -1.07, 1.2], [0.06, 2.4, 1.07, 1.2]]) {
      const bar = new THREE.Mesh(new THREE.BoxGeometry(w, h, 0.05), metal);
      bar.position.set(x, y, MIRROR_Z);
      this.group.add(bar);
    }
    const glass = new THREE.Mesh(new THREE.PlaneGeometry(2.1, 2.3), material({ color: 0xb8d4f0, roughness: 0.05, metalness: 0.2, transparent: true, opacity: 0.12, depthWrite: false }));
    glass.position.set(0, 1.2, MIRROR_Z);
    this.group.add(glass);
    // The user's own devices: marker geometry is in legwork's device frame, so they sit in a
    // group turned 180 degrees about y (legwork -> WebXR) and take legwork poses unchanged.
    this.markers = new DeviceMarkers();
    this.userFrame = new THREE.Group();
    this.userFrame.rotation.y = Math.PI;
    this.userFrame.add(this.markers.group);
    this.group.add(this.userFrame);
    this.body = null;
    this.session = null;
    this.xrSession = null;
    this.label = stage.addLabel('Mirror', '#ffd166');
    this.label.at.set(0, 2.5, MIRROR_Z);
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
    this.markers.set(f, new THREE.Vector3());
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
    this.stage.camera.position.set(0.7, 1.7, 3.6);
    this.stage.controls.target.set(0, 1.3, -1.4);
  }
}
