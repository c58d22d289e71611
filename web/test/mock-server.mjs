#!/usr/bin/env node
// Dev mock of `legwork serve` (protocol v1, docs/protocol.md), for developing and
// screenshotting the viewer without the C++ server. It answers every frame with a
// stick body whose wrists are exactly the input hands and whose head is the input
// head; "accent" adds a leg swing scaled by the exaggeration so the UI visibly
// reacts. Not a model of legwork's methods.
//   node test/mock-server.mjs [--port 8090] [--web dist] [--trials ../data/cmu/bvh]
import { createServer } from 'node:http';
import { readFileSync, readdirSync, statSync, existsSync } from 'node:fs';
import { join, resolve, extname, dirname, sep } from 'node:path';
import { fileURLToPath } from 'node:url';
import { WebSocketServer } from 'ws';
import { trialFromFile } from './bvh.mjs';
import { decodeFrameBinary, encodePoseBinary } from '../src/protocol.js';

const here = dirname(fileURLToPath(import.meta.url));
const MIME = { '.html': 'text/html', '.js': 'text/javascript', '.css': 'text/css', '.map': 'application/json', '.glb': 'model/gltf-binary', '.png': 'image/png' };

const NAMES = ['Hips', 'Spine', 'Spine1', 'Neck', 'Head',
  'LeftShoulder', 'LeftArm', 'LeftForeArm', 'LeftHand', 'RightShoulder', 'RightArm', 'RightForeArm', 'RightHand',
  'LeftUpLeg', 'LeftLeg', 'LeftFoot', 'LeftToeBase', 'RightUpLeg', 'RightLeg', 'RightFoot', 'RightToeBase'];
const PARENTS = [-1, 0, 1, 2, 3, 2, 5, 6, 7, 2, 9, 10, 11, 0, 13, 14, 15, 0, 17, 18, 19];

const add = (a, b) => a.map((x, k) => x + b[k]);
const sub = (a, b) => a.map((x, k) => x - b[k]);
const mul = (a, s) => a.map((x) => x * s);
const len = (a) => Math.hypot(...a);
const norm = (a) => mul(a, 1 / (len(a) || 1));
const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];

function rotate(q, v) {
  const [w, x, y, z] = q;
  const u = [x, y, z], t = mul(cross(u, v), 2);
  return add(add(v, mul(t, w)), cross(u, t));
}

// Two-bone chain from a to c with lengths l1, l2 and the elbow/knee pushed towards `pole`.
function middle(a, c, l1, l2, pole) {
  const d = sub(c, a), dl = Math.max(len(d), 1e-6), dir = mul(d, 1 / dl);
  if (dl >= l1 + l2) return add(a, mul(dir, (l1 * dl) / (l1 + l2)));
  const x = (l1 * l1 - l2 * l2 + dl * dl) / (2 * dl), h = Math.sqrt(Math.max(l1 * l1 - x * x, 0));
  const n = norm(sub(pole, mul(dir, dot(pole, dir))));
  return add(add(a, mul(dir, x)), mul(n, h));
}

export function stickPose(frame, opts, seq) {
  const head = frame.head ? frame.head.p : [0, 1.6, 0];
  const hq = frame.head && frame.head.q ? frame.head.q : [1, 0, 0, 0];
  let fwd = rotate(hq, [0, 0, 1]); fwd = norm([fwd[0], 0, fwd[2]]);
  const left = cross([0, 1, 0], fwd);
  const down = [0, -1, 0];
  const P = new Array(NAMES.length);
  P[4] = head;
  P[3] = add(head, [0, -0.12, 0]);
  P[0] = [head[0] - fwd[0] * 0.03, head[1] - 0.62, head[2] - fwd[2] * 0.03];
  P[1] = add(P[0], mul(sub(P[3], P[0]), 0.35));
  P[2] = add(P[0], mul(sub(P[3], P[0]), 0.7));
  for (const [side, s] of [[5, 1], [9, -1]]) {
    P[side] = add(P[2], mul(left, 0.06 * s));
    P[side + 1] = add(add(P[3], mul(left, 0.18 * s)), [0, -0.04, 0]);
    const wrist = frame[s > 0 ? 'left' : 'right'];
    P[side + 3] = wrist ? wrist.p : add(P[side + 1], [0, -0.55, 0]);
    P[side + 2] = middle(P[side + 1], P[side + 3], 0.29, 0.27, add(down, mul(fwd, -0.7)));
  }
  const swing = opts.method === 'accent' ? 0.22 * (opts.exaggeration ?? 1) * Math.sin(frame.t * 2 * Math.PI * 0.9) : 0;
  for (const [hip, s] of [[13, 1], [17, -1]]) {
    P[hip] = add(P[0], add(mul(left, 0.1 * s), [0, -0.07, 0]));
    const foot = frame[s > 0 ? 'left_foot' : 'right_foot'];
    const ank = foot && opts.method !== 'accent' ? foot.p : [P[hip][0] + fwd[0] * swing * s, 0.08, P[hip][2] + fwd[2] * swing * s];
    P[hip + 2] = ank;
    P[hip + 1] = middle(P[hip], ank, 0.44, 0.42, fwd);
    P[hip + 3] = add(ank, add(mul(fwd, 0.14), [0, -0.06, 0]));
  }
  return { type: 'pose', seq, t: frame.t, status: frame.head ? 'ok' : 'degraded', root: P[0],
    rotations: NAMES.map(() => [1, 0, 0, 0]), positions: P.map((p) => p.map((x) => Math.round(x * 1e6) / 1e6)),
    info: { mock: true }, server_us: 5 };
}

function listTrials(dir) {
  const out = [];
  if (!existsSync(dir)) return out;
  for (const c of readdirSync(dir).sort()) {
    if (!statSync(join(dir, c)).isDirectory()) continue;
    for (const f of readdirSync(join(dir, c)).sort()) if (f.endsWith('.bvh')) out.push(`${c}/${f.slice(0, -4)}`);
  }
  return out;
}

function json(res, code, obj) {
  res.writeHead(code, { 'content-type': 'application/json', 'cache-control': 'no-store' });
  res.end(JSON.stringify(obj));
}

export function startMock({ port = 0, host = '127.0.0.1', web = join(here, '..', 'dist'), trials = join(here, '..', '..', 'data', 'cmu', 'bvh') } = {}) {
  const webRoot = resolve(web);
  const server = createServer((req, res) => {
    const url = new URL(req.url, 'http://x');
    if (url.pathname === '/api/info') return json(res, 200, { version: 1, methods: ['accent', 'ik', 'wip', 'combined'], classes: ['walking', 'running', 'boxing', 'basketball'], database: 'mock' });
    if (url.pathname === '/api/trials') return json(res, 200, { trials: listTrials(trials) });
    if (url.pathname === '/api/trial') {
      const name = url.searchParams.get('name') || '';
      if (!listTrials(trials).includes(name)) return json(res, 404, { type: 'error', code: 'bad_value', message: `no trial ${name}` });
      return json(res, 200, trialFromFile(join(trials, `${name}.bvh`), name, +(url.searchParams.get('rate') || 0)));
    }
    const file = resolve(webRoot, '.' + decodeURIComponent(url.pathname === '/' ? '/index.html' : url.pathname));
    if (!file.startsWith(webRoot + sep) || !existsSync(file) || !statSync(file).isFile()) { res.writeHead(404); return res.end('not found'); }
    res.writeHead(200, { 'content-type': MIME[extname(file)] || 'application/octet-stream' });
    res.end(readFileSync(file));
  });
  const wss = new WebSocketServer({ server, path: '/ws', maxPayload: 64 * 1024 });
  let sessions = 0;
  wss.on('connection', (ws) => {
    let opts = null, seq = 0, last = null;
    const id = `m${++sessions}`;
    const error = (code, message) => ws.send(JSON.stringify({ type: 'error', code, message }));
    // FrameClock's rules, minimally: time must increase; a jump over 5 s forward restarts.
    const answer = (frame) => {
      let status = null;
      if (last !== null && !(frame.t > last)) status = 'rejected';
      else if (last !== null && frame.t - last > 5) status = 'restarted';
      if (status !== 'rejected') last = frame.t;
      const pose = stickPose(frame, opts, ++seq);
      if (status) pose.status = status;
      if (status === 'rejected') pose.positions = pose.rotations = [];
      ws.send(opts.format === 'binary' ? Buffer.from(encodePoseBinary(pose)) : JSON.stringify(pose));
    };
    ws.on('message', (data, isBinary) => {
      if (isBinary) {
        const f = opts && decodeFrameBinary(new Uint8Array(data));
        return f ? answer(f) : error('bad_message', 'binary frame before hello or malformed');
      }
      let m;
      try { m = JSON.parse(data.toString()); } catch { return error('bad_json', 'not JSON'); }
      if (m.type === 'hello') {
        if (m.version !== 1) return error('bad_version', `version ${m.version} not supported (1)`);
        opts = { method: 'accent', exaggeration: 1, format: 'json', ...m };
        return ws.send(JSON.stringify({ type: 'welcome', version: 1, session: id, method: opts.method,
          skeleton: { names: NAMES, parents: PARENTS, offsets: NAMES.map(() => [0, 0, 0]) }, max_rate_hz: 120 }));
      }
      if (!opts) return error('bad_message', 'hello first');
      if (m.type === 'options') { Object.assign(opts, m); delete opts.type; return; }
      if (m.type === 'frame') return Number.isFinite(m.t) ? answer(m) : error('bad_value', 't must be finite');
      error('bad_message', `unknown type ${m.type}`);
    });
  });
  return new Promise((ok) => server.listen(port, host, () => ok({ server, wss, url: `http://${host}:${server.address().port}`,
    close: () => new Promise((done) => { for (const c of wss.clients) c.terminate(); wss.close(); server.close(done); }) })));
}

if (process.argv[1] && resolve(process.argv[1]) === fileURLToPath(import.meta.url)) {
  const arg = (k, d) => { const i = process.argv.indexOf(k); return i > 0 ? process.argv[i + 1] : d; };
  const m = await startMock({ port: +arg('--port', 8090), web: arg('--web', join(here, '..', 'dist')), trials: arg('--trials', join(here, '..', '..', 'data', 'cmu', 'bvh')) });
  console.log(`mock legwork server on ${m.url}`);
}
