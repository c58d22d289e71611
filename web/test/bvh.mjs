// Minimal BVH reader for the dev mock server: hierarchy, Euler channels,
// forward kinematics, units guessed like legwork's io (CMU units, inches, cm, mm).
// Only what the mock needs to answer /api/trial like `legwork serve` does.
import { readFileSync } from 'node:fs';

const CMU_UNIT = 0.0254 / 0.45;

function qmul(a, b) {
  return [
    a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3],
    a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2],
    a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1],
    a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0],
  ];
}
function qrot(q, v) {
  const p = qmul(qmul(q, [0, v[0], v[1], v[2]]), [q[0], -q[1], -q[2], -q[3]]);
  return [p[1], p[2], p[3]];
}
function axisAngle(axis, deg) {
  const h = (deg * Math.PI) / 360, s = Math.sin(h);
  return [Math.cos(h), axis === 'X' ? s : 0, axis === 'Y' ? s : 0, axis === 'Z' ? s : 0];
}

export function parseBVH(text) {
  const tok = text.split(/\s+/).filter(Boolean);
  let i = 0;
  const joints = [], ends = [];
  const stack = [];
  let nChannels = 0;
  while (i < tok.length && tok[i] !== 'MOTION') {
    const w = tok[i++];
    if (w === 'ROOT' || w === 'JOINT') {
      joints.push({ name: tok[i++], parent: stack.length ? stack[stack.length - 1] : -1, offset: [0, 0, 0], channels: [], first: 0, end: null });
      stack.push(joints.length - 1);
    } else if (w === 'End') {
      i++; // Site
      stack.push(-2);
    } else if (w === 'OFFSET') {
      const o = [+tok[i], +tok[i + 1], +tok[i + 2]];
      i += 3;
      const top = stack[stack.length - 1];
      if (top === -2) joints[stack[stack.length - 2]].end = o;
      else joints[top].offset = o;
    } else if (w === 'CHANNELS') {
      const n = +tok[i++];
      const j = joints[stack[stack.length - 1]];
      j.first = nChannels;
      j.channels = tok.slice(i, i + n);
      i += n;
      nChannels += n;
    } else if (w === '}') {
      stack.pop();
    }
  }
  i++; // MOTION
  i++; const frames = +tok[i++]; // Frames: N
  i += 2; const frameTime = +tok[i++]; // Frame Time: dt
  const values = [];
  for (let f = 0; f < frames; ++f) {
    values.push(tok.slice(i, i + nChannels).map(Number));
    i += nChannels;
  }
  return { joints, ends, fps: 1 / frameTime, values };
}

// World positions and rotations of every joint for one frame's channel values.
export function fk(bvh, vals, scale) {
  const pos = [], rot = [];
  for (let j = 0; j < bvh.joints.length; ++j) {
    const J = bvh.joints[j];
    let t = J.offset.map((x) => x * scale);
    let q = [1, 0, 0, 0];
    J.channels.forEach((c, k) => {
      const v = vals ? vals[J.first + k] : 0;
      if (c.endsWith('position')) t['XYZ'.indexOf(c[0])] = v * scale;
      else if (vals) q = qmul(q, axisAngle(c[0], v));
    });
    if (J.parent < 0) { pos.push(t); rot.push(q); continue; }
    const pq = rot[J.parent], pp = pos[J.parent];
    const d = qrot(pq, t);
    pos.push([pp[0] + d[0], pp[1] + d[1], pp[2] + d[2]]);
    rot.push(qmul(pq, q));
  }
  return { pos, rot };
}

export function guessScale(bvh) {
  const { pos } = fk(bvh, null, 1);
  let lo = Infinity, hi = -Infinity;
  bvh.joints.forEach((J, j) => {
    const ys = [pos[j][1]];
    if (J.end) ys.push(pos[j][1] + J.end[1]);
    for (const y of ys) { lo = Math.min(lo, y); hi = Math.max(hi, y); }
  });
  const h = hi - lo;
  if (h >= 0.5 && h < 3) return 1;
  if (h >= 15 && h < 45) return CMU_UNIT;
  if (h >= 45 && h < 100) return 0.0254;
  if (h >= 100 && h < 300) return 0.01;
  if (h >= 500 && h < 3000) return 0.001;
  throw new Error(`rest height ${h} fits no known unit`);
}

function lerp(a, b, w) { return a.map((x, k) => x + (b[k] - x) * w); }
function nlerp(a, b, w) {
  const s = a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + a[3] * b[3] < 0 ? -1 : 1;
  const q = a.map((x, k) => x + (s * b[k] - x) * w);
  const n = Math.hypot(...q);
  return q.map((x) => x / n);
}

const round = (v) => v.map((x) => Math.round(x * 1e5) / 1e5);

// The /api/trial answer: devices + truth at `rate` Hz (0: the file's own), T-pose frame 0 dropped.
export function trialFromFile(path, name, rate) {
  const bvh = parseBVH(readFileSync(path, 'utf8'));
  const scale = guessScale(bvh);
  const names = bvh.joints.map((j) => j.name);
  const idx = (n) => names.indexOf(n);
  const dev = { head: idx('Head'), left: idx('LeftHand'), right: idx('RightHand'), left_foot: idx('LeftFoot'), right_foot: idx('RightFoot') };
  const poses = bvh.values.slice(1).map((v) => fk(bvh, v, scale));
  const fps = rate > 0 ? rate : bvh.fps;
  const duration = (poses.length - 1) / bvh.fps;
  const n = Math.floor(duration * fps + 1e-9) + 1;
  const frames = [], positions = [];
  for (let f = 0; f < n; ++f) {
    const t = f / fps;
    const x = t * bvh.fps, a = Math.min(Math.floor(x), poses.length - 1), b = Math.min(a + 1, poses.length - 1), w = x - a;
    const P = (j) => round(lerp(poses[a].pos[j], poses[b].pos[j], w));
    const Q = (j) => round(nlerp(poses[a].rot[j], poses[b].rot[j], w));
    const fr = { t: Math.round(t * 1e6) / 1e6 };
    for (const [d, j] of Object.entries(dev)) if (j >= 0) fr[d] = d.endsWith('foot') ? { p: P(j) } : { p: P(j), q: Q(j) };
    frames.push(fr);
    positions.push(names.flatMap((_, j) => P(j)));
  }
  return { name, fps, frames, truth: { names, parents: bvh.joints.map((j) => j.parent), positions } };
}
