// legwork live protocol v1 (docs/protocol.md): message encoding shared by the
// viewer and the dev mock server. Pure functions, no DOM, no three.js.

export const PROTOCOL_VERSION = 1;
export const DEVICES = ['head', 'left', 'right', 'left_foot', 'right_foot'];
export const STATUS = ['ok', 'degraded', 'rejected', 'restarted'];
const FRAME_BYTES = 4 + 8 + 1 + 3 + 5 * 7 * 4; // 156

export function helloMessage(opts = {}) {
  const m = { type: 'hello', version: PROTOCOL_VERSION };
  for (const k of ['method', 'classes', 'exaggeration', 'user_height', 'joints', 'format', 'record'])
    if (opts[k] !== undefined && opts[k] !== null) m[k] = opts[k];
  return m;
}

// frame: {t, head:{p,q}, left:{p,q}, right:{p,q}, left_foot:{p}, right_foot:{p}}; missing = untracked.
export function frameJSON(frame) {
  const m = { type: 'frame', t: frame.t };
  for (const d of DEVICES) {
    const dev = frame[d];
    if (!dev) continue;
    m[d] = dev.q ? { p: dev.p, q: dev.q } : { p: dev.p };
  }
  return JSON.stringify(m);
}

export function frameBinary(frame) {
  const buf = new ArrayBuffer(FRAME_BYTES);
  const v = new DataView(buf);
  v.setUint8(0, 0x4c); v.setUint8(1, 0x57); v.setUint8(2, 0x46); v.setUint8(3, 0x31); // "LWF1"
  v.setFloat64(4, frame.t, true);
  let mask = 0;
  DEVICES.forEach((d, i) => {
    const dev = frame[d];
    const o = 16 + i * 28;
    const q = dev && dev.q ? dev.q : [1, 0, 0, 0];
    const p = dev ? dev.p : [0, 0, 0];
    if (dev) mask |= 1 << i;
    for (let k = 0; k < 3; ++k) v.setFloat32(o + 4 * k, p[k], true);
    for (let k = 0; k < 4; ++k) v.setFloat32(o + 12 + 4 * k, q[k], true);
  });
  v.setUint8(12, mask);
  return buf;
}

export function decodeFrameBinary(buf) {
  const v = new DataView(buf.buffer ? buf.buffer : buf, buf.byteOffset || 0, buf.byteLength);
  if (v.byteLength !== FRAME_BYTES || v.getUint32(0, true) !== 0x3146574c) return null;
  const frame = { type: 'frame', t: v.getFloat64(4, true) };
  const mask = v.getUint8(12);
  DEVICES.forEach((d, i) => {
    if (!(mask & (1 << i))) return;
    const o = 16 + i * 28;
    const f = (k) => v.getFloat32(o + 4 * k, true);
    frame[d] = { p: [f(0), f(1), f(2)], q: [f(3), f(4), f(5), f(6)] };
  });
  return frame;
}

// Server pose, binary: "LWP1" | f64 t | u32 seq | u8 status | 3 pad | u32 N | N*4 f32 rot | N*3 f32 pos.
export function decodePoseBinary(buf) {
  const v = new DataView(buf.buffer ? buf.buffer : buf, buf.byteOffset || 0, buf.byteLength);
  if (v.byteLength < 24 || v.getUint32(0, true) !== 0x3150574c) return null;
  const t = v.getFloat64(4, true);
  const seq = v.getUint32(12, true);
  const status = STATUS[v.getUint8(16)] || 'unknown';
  const n = v.getUint32(20, true);
  if (v.byteLength < 24 + n * 28) return null;
  const rotations = [], positions = [];
  for (let j = 0; j < n; ++j) {
    const o = 24 + j * 16;
    rotations.push([0, 1, 2, 3].map((k) => v.getFloat32(o + 4 * k, true)));
  }
  for (let j = 0; j < n; ++j) {
    const o = 24 + n * 16 + j * 12;
    positions.push([0, 1, 2].map((k) => v.getFloat32(o + 4 * k, true)));
  }
  return { type: 'pose', t, seq, status, rotations, positions, root: positions[0] };
}

export function encodePoseBinary(pose) {
  const n = pose.positions.length;
  const buf = new ArrayBuffer(24 + n * 28);
  const v = new DataView(buf);
  v.setUint32(0, 0x3150574c, true);
  v.setFloat64(4, pose.t, true);
  v.setUint32(12, pose.seq, true);
  v.setUint8(16, Math.max(0, STATUS.indexOf(pose.status)));
  v.setUint32(20, n, true);
  for (let j = 0; j < n; ++j) {
    const r = pose.rotations[j] || [1, 0, 0, 0];
    for (let k = 0; k < 4; ++k) v.setFloat32(24 + j * 16 + 4 * k, r[k], true);
    for (let k = 0; k < 3; ++k) v.setFloat32(24 + n * 16 + j * 12 + 4 * k, pose.positions[j][k], true);
  }
  return buf;
}

// Index of the joint playing `role` ('head', 'left_hand', 'right_hand') in a
// skeleton's names; -1 when none matches. Works for CMU, Mixamo and Unity names.
export function findJoint(names, role) {
  const norm = names.map((n) => String(n).toLowerCase().replace(/^mixamorig:/, '').replace(/[^a-z]/g, ''));
  const want = {
    head: [/^head$/],
    left_hand: [/^lefthand$/, /^lhand$/, /^leftwrist$/, /^lwrist$/, /^handl$/, /^handleft$/],
    right_hand: [/^righthand$/, /^rhand$/, /^rightwrist$/, /^rwrist$/, /^handr$/, /^handright$/],
  }[role];
  if (!want) return -1;
  for (const re of want) {
    const i = norm.findIndex((n) => re.test(n));
    if (i >= 0) return i;
  }
  return -1;
}

export function distance(a, b) {
  return Math.hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]);
}
