// WebXR input: headset + controllers -> legwork tracker frames, kept small and
// separate. The same XRInput.onXRFrame() reads a real XRFrame or the emulated
// one of FakeXRSession (window.__legworkFakeXR), so the conversion and the send
// path are tested in a browser without a headset.
//
// Frames: WebXR is right-handed, y up, and the user starts facing -z (+x to
// their right). legwork is right-handed, y up, facing +z (+x to their left).
// The two differ by a 180-degree turn about y: (x, y, z) -> (-x, y, -z), and a
// rotation q = (w, x, y, z) -> (w, -x, y, -z) (conjugation by that turn).

export function xrToLegworkPosition(p) {
  return [-p.x, p.y, -p.z];
}
export function xrToLegworkRotation(q) {
  return [q.w, -q.x, q.y, -q.z];
}
// Inverse of the above (the same turn), for showing legwork poses in XR space.
export function legworkToXRPosition(p) {
  return [-p[0], p[1], -p[2]];
}

function device(transform) {
  return transform ? { p: xrToLegworkPosition(transform.position), q: xrToLegworkRotation(transform.orientation) } : null;
}

// Reads one XRFrame (real or fake) into a tracker frame and hands it to onFrame.
export class XRInput {
  constructor(onFrame) {
    this.onFrame = onFrame;
    this.t0 = null;
    this.framesRead = 0;
    this.lastFrame = null;
  }

  onXRFrame(time, frame, refSpace) {
    const viewer = frame.getViewerPose(refSpace);
    if (!viewer) return null;
    if (this.t0 === null) this.t0 = time;
    const out = { t: (time - this.t0) / 1000, head: device(viewer.transform) };
    for (const src of frame.session.inputSources) {
      if (src.handedness !== 'left' && src.handedness !== 'right') continue;
      const space = src.gripSpace || src.targetRaySpace;
      const pose = space ? frame.getPose(space, refSpace) : null;
      out[src.handedness] = pose ? device(pose.transform) : null;
    }
    this.framesRead++;
    this.lastFrame = out;
    this.onFrame(out);
    return out;
  }
}

// An emulated XR session with the subset of the WebXR API XRInput uses.
// poseAt(tSeconds) -> {head, left, right} each {position:{x,y,z}, orientation:{x,y,z,w}} in WebXR's frame.
export class FakeXRSession {
  constructor(poseAt, rateHz = 72) {
    this.poseAt = poseAt;
    this.rateHz = rateHz;
    this.ended = false;
    this.inputSources = [
      { handedness: 'left', gripSpace: { name: 'left' } },
      { handedness: 'right', gripSpace: { name: 'right' } },
    ];
    this._callbacks = [];
    this._start = performance.now();
    this._timer = setInterval(() => this._tick(), 1000 / rateHz);
  }
  async requestReferenceSpace() { return { name: 'local-floor' }; }
  requestAnimationFrame(cb) { this._callbacks.push(cb); return this._callbacks.length; }
  async end() { this.ended = true; clearInterval(this._timer); }
  _tick() {
    if (this.ended) return;
    const time = performance.now() - this._start;
    const poses = this.poseAt(time / 1000);
    const frame = {
      session: this,
      getViewerPose: () => ({ transform: poses.head }),
      getPose: (space) => (poses[space.name] ? { transform: poses[space.name] } : null),
    };
    const cbs = this._callbacks;
    this._callbacks = [];
    for (const cb of cbs) cb(time, frame);
  }
}

// A standing user in WebXR's frame swaying and swinging the controllers.
export function demoXRPose(t) {
  const sway = 0.05 * Math.sin(t * 2.1);
  const swing = 0.18 * Math.sin(t * 3.4);
  const id = { x: 0, y: 0, z: 0, w: 1 };
  return {
    head: { position: { x: sway, y: 1.62 + 0.015 * Math.sin(t * 6.8), z: 0 }, orientation: id },
    left: { position: { x: -0.25 + sway, y: 0.95, z: -0.1 - swing }, orientation: id },
    right: { position: { x: 0.25 + sway, y: 0.95, z: -0.1 + swing }, orientation: id },
  };
}
