// End-to-end: the viewer in headless Chromium against `legwork serve`
// (LEGWORK_URL=http://127.0.0.1:PORT) or, without it, the dev mock server.
// Checks numerically from the page that poses arrive, the IK avatar's hands
// follow the input, the emulated WebXR input converts frames and produces poses,
// a GLB walk cycle plays, and that the screenshot is not blank.
//   npm test                                   (mock server)
//   LEGWORK_URL=http://127.0.0.1:8080 npm test (a running legwork serve)
// Optional: LEGWORK_TRIAL=walking/07_02, LEGWORK_GLB=path/to/walkcycle.glb.
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { existsSync, mkdirSync, writeFileSync, readFileSync } from 'node:fs';
import { execFileSync } from 'node:child_process';
import { join, dirname } from 'node:path';
import { fileURLToPath } from 'node:url';
import { launch } from './browser.mjs';
import { walkGLB } from './glb-fixture.mjs';

const here = dirname(fileURLToPath(import.meta.url));
const out = join(here, '..', 'test-output');
const TIMEOUT = 90_000; // software WebGL on a loaded machine renders a few frames a second
let url, mock, browser, page;
const pageErrors = [];

before(async () => {
  mkdirSync(out, { recursive: true });
  url = process.env.LEGWORK_URL;
  if (!url) {
    if (!existsSync(join(here, '..', 'dist', 'index.html'))) execFileSync('node', [join(here, '..', 'build.mjs')], { stdio: 'inherit' });
    const { startMock } = await import('./mock-server.mjs');
    mock = await startMock({ port: 0 });
    url = mock.url;
  }
  url = url.replace(/\/$/, '');
  browser = await launch({ width: 1280, height: 720 });
  page = browser.page;
  page.on('pageerror', (e) => pageErrors.push(e.message));
  page.on('console', (m) => { if (m.type() === 'error' && !/favicon|404/.test(m.text())) pageErrors.push(m.text()); });
});

after(async () => {
  if (browser) await browser.close();
  if (mock) await mock.close();
});

const legwork = () => page.evaluate(() => JSON.parse(JSON.stringify(window.__legwork)));

async function pickTrial() {
  const r = await fetch(`${url}/api/trials`);
  assert.equal(r.status, 200, 'GET /api/trials');
  const { trials } = await r.json();
  assert.ok(trials.length > 0, 'the server lists trials');
  return process.env.LEGWORK_TRIAL || trials.find((t) => t === 'walking/07_02') || trials.find((t) => t.startsWith('walking/')) || trials[0];
}

// The second lane's method: accent when the server has a database, else ik again (lane "ik2").
let A = 'accent';

test('replay: poses arrive and the IK avatar\'s hands follow the input', { timeout: TIMEOUT * 2 }, async () => {
  const trial = await pickTrial();
  const info = await (await fetch(`${url}/api/info`)).json();
  assert.ok(info.methods.includes('ik'), `the server offers ik: ${info.methods}`);
  if (!info.methods.includes('accent')) { A = 'ik'; console.log('# the server has no accent method (no --db): both lanes ik'); }
  await page.goto(`${url}/?trial=${encodeURIComponent(trial)}&a=${A}&b=ik`);
  await page.waitForFunction(() => window.__legwork.ready || window.__legwork.error, null, { timeout: TIMEOUT });
  assert.equal((await legwork()).error, '', 'viewer error');
  await page.waitForFunction(() => {
    const s = window.__legwork.sessions;
    const a = s.accent || s.ik2;
    return s.ik && a && s.ik.posesReceived >= 40 && a.posesReceived >= 40;
  }, null, { timeout: TIMEOUT, polling: 250 });
  const st = await legwork();
  assert.equal(st.trial, trial);
  const { ik } = st.sessions, accent = st.sessions.accent || st.sessions.ik2;
  console.log(`# ${trial}: ik ${ik.posesReceived} poses, median hand error ${(ik.medianHandError * 1000).toFixed(3)} mm, ` +
    `rtt ${ik.rttAvgMs.toFixed(1)} ms; accent ${accent.posesReceived} poses, median hand error ${(accent.medianHandError * 1000).toFixed(3)} mm; ` +
    `left hand to right input ${(ik.lastCrossHandError * 100).toFixed(1)} cm; input hands travelled ${ik.inputHandTravel.toFixed(2)} m; ` +
    `poses at ${ik.poseHz} Hz while the page renders at ${st.renderFps.toFixed(1)} fps`);
  for (const s of [ik, accent]) {
    assert.equal(s.state, 'open', `${s.method} session state`);
    assert.equal(s.errors, 0, `${s.method}: server errors: ${s.lastError}`);
    assert.ok(Number.isFinite(s.rttAvgMs) && s.rttAvgMs > 0, `${s.method}: round-trip time measured`);
  }
  // the stream runs in a worker, not in the render loop: poses come faster than the page draws
  // (software WebGL draws 1-5 fps; the trial streams at 90 Hz)
  assert.ok(ik.poseHz > st.renderFps, `poses at ${ik.poseHz} Hz, no faster than rendering (${st.renderFps} fps)`);
  // the input hands moved (a walk swings them), and the IK wrists stayed on them
  assert.ok(ik.inputHandTravel > 0.3, `input hands travelled ${ik.inputHandTravel} m over the answered frames`);
  assert.ok(ik.medianHandError < 0.02, `ik: median hand error ${ik.medianHandError} m (want < 2 cm)`);
  assert.ok(ik.lastCrossHandError > 0.1, `the left hand is ${ik.lastCrossHandError} m from the right input: the measure cannot tell hands apart`);
  // accentuation synthesizes a body from the database: its hands go where the controllers are, not exactly
  assert.ok(accent.medianHandError < 0.3, `accent: median hand error ${accent.medianHandError} m (want < 30 cm)`);
});

test('replay: scrubbing restarts the stream and poses keep matching their frames', { timeout: TIMEOUT * 2 }, async () => {
  const target = await page.evaluate(() => Math.floor(window.__legwork.frames / 2));
  await page.evaluate((i) => window.__legworkControl.seek(i), target);
  // The time jump (> 5 s forward) restarts the server's clock for this avatar: a restarted pose
  // answers the seek's target frame or a later one (the server's latest-wins queue drops frames
  // while it lags: under ASan on a busy machine the first pose after the seek answered a frame
  // more than 10 past the target). Answers to frames sent before the seek may still be in flight,
  // and the replay's loop restarts too, at frame 0: a restart at the target or later is the seek's.
  const seekRestart = (t) => window.__legwork.sessions.ik.restartFrames.some((i) => i >= t);
  const restarted = await page.waitForFunction(seekRestart, target, { timeout: TIMEOUT, polling: 250 }).then(() => true, () => false);
  const at = (await legwork()).sessions.ik;
  assert.ok(restarted, `no restarted pose for frame ${target} within ${TIMEOUT / 1000} s of the seek: restarted at frames ${JSON.stringify(at.restartFrames)}, statuses ${JSON.stringify(at.statusCounts)}`);
  await page.waitForFunction((n) => window.__legwork.sessions.ik.posesReceived >= n + 20, at.posesReceived, { timeout: TIMEOUT, polling: 250 });
  const ik = (await legwork()).sessions.ik;
  console.log(`# seek to frame ${target}: restarted at frames ${JSON.stringify(at.restartFrames)}; statuses ${JSON.stringify(ik.statusCounts)}, median hand error ${(ik.medianHandError * 1000).toFixed(3)} mm`);
  assert.equal(ik.errors, 0, ik.lastError);
  assert.ok(ik.medianHandError < 0.02, `ik after the seek: median hand error ${ik.medianHandError} m`);
});

// Luminance variance and pixels of each lane's body colour in a PNG (decoded in the page).
const pngStats = (b64) => page.evaluate(async (data) => {
  const img = new Image();
  img.src = `data:image/png;base64,${data}`;
  await img.decode();
  const c = document.createElement('canvas');
  c.width = img.width; c.height = img.height;
  const g = c.getContext('2d');
  g.drawImage(img, 0, 0);
  const d = g.getImageData(0, 0, c.width, c.height).data;
  let sum = 0, sum2 = 0, orange = 0, blue = 0, grey = 0;
  const n = d.length / 4;
  for (let i = 0; i < d.length; i += 4) {
    const [r, gg, b] = [d[i], d[i + 1], d[i + 2]];
    const y = 0.2126 * r + 0.7152 * gg + 0.0722 * b;
    sum += y; sum2 += y * y;
    if (r > 150 && r - b > 70 && gg > 60 && gg < r) orange++;
    if (b > 140 && b - r > 60) blue++;
    if (r > 150 && Math.abs(r - b) < 25 && Math.abs(r - gg) < 25) grey++;
  }
  const mean = sum / n;
  return { width: c.width, height: c.height, variance: sum2 / n - mean * mean, orange, blue, grey };
}, b64);

test('replay: the screenshot is not blank and the 3D view shows the three bodies', { timeout: TIMEOUT }, async () => {
  const file = join(out, 'replay.png');
  await page.screenshot({ path: file });
  const m = await pngStats(readFileSync(file).toString('base64'));
  console.log(`# screenshot ${file}: ${m.width}x${m.height}, luminance variance ${m.variance.toFixed(1)}`);
  assert.equal(m.width, 1280);
  assert.ok(m.variance > 100, `luminance variance ${m.variance}: blank screenshot?`);
  // The WebGL canvas alone (no HTML panel or labels, whose text is also coloured): the bodies' colours.
  const canvasPNG = await page.evaluate(() => document.getElementById('view').toDataURL('image/png').split(',')[1]);
  writeFileSync(join(out, 'replay-canvas.png'), Buffer.from(canvasPNG, 'base64'));
  const v = await pngStats(canvasPNG);
  console.log(`# 3D view: luminance variance ${v.variance.toFixed(1)}, body pixels orange ${v.orange} blue ${v.blue} grey ${v.grey}`);
  assert.ok(v.variance > 50, `3D view luminance variance ${v.variance}: nothing rendered?`);
  for (const k of A === 'accent' ? ['orange', 'blue', 'grey'] : ['blue', 'grey']) assert.ok(v[k] > 800, `${k} body pixels in the 3D view: ${v[k]}`);
});

test('replay in the binary format; exaggeration and class options are accepted', { timeout: TIMEOUT * 2 }, async () => {
  const trial = await pickTrial();
  await page.goto(`${url}/?trial=${encodeURIComponent(trial)}&a=${A}&b=ik&format=binary`);
  await page.waitForFunction(() => {
    const s = window.__legwork.sessions, a = s.accent || s.ik2;
    return window.__legwork.error || (s.ik && a && s.ik.posesReceived >= 20 && a.posesReceived >= 20);
  }, null, { timeout: TIMEOUT, polling: 250 });
  assert.equal((await legwork()).error, '', 'viewer error');
  const before = (await legwork()).sessions;
  // the slider sends {"type":"options","exaggeration":1.6}; a class chip sends the remaining classes
  await page.evaluate(() => {
    const e = document.getElementById('exag');
    e.value = '1.6';
    e.dispatchEvent(new Event('input'));
    const chips = [...document.querySelectorAll('#classes input')];
    if (chips.length > 1) { chips[chips.length - 1].checked = false; chips[0].dispatchEvent(new Event('change', { bubbles: true })); }
  });
  const second = (s) => s.accent || s.ik2;
  await page.waitForFunction((n) => { const s = window.__legwork.sessions; return (s.accent || s.ik2).posesReceived >= n + 20; },
    second(before).posesReceived, { timeout: TIMEOUT, polling: 250 });
  const st = (await legwork()).sessions, ik = st.ik, accent = second(st);
  console.log(`# binary: ik ${ik.posesReceived} poses, median hand error ${(ik.medianHandError * 100).toFixed(2)} cm; accent ${accent.posesReceived} poses after options`);
  for (const s of [ik, accent]) assert.equal(s.errors, 0, `${s.method}: server errors: ${s.lastError}`);
  assert.ok(ik.medianHandError < 0.02, `ik (binary): median hand error ${ik.medianHandError} m`);
});

test('replay of a recorded session (tracker CSV, as legwork serve --record writes)', { timeout: TIMEOUT * 2 }, async () => {
  const trial = await pickTrial();
  const tr = await (await fetch(`${url}/api/trial?name=${encodeURIComponent(trial)}&rate=90`)).json();
  const pts = [['head', 'head'], ['left', 'left_hand'], ['right', 'right_hand']];
  const header = ['time', ...pts.flatMap(([, n]) => ['x', 'y', 'z', 'qw', 'qx', 'qy', 'qz'].map((c) => `${n}_${c}`))];
  const rows = tr.frames.slice(0, 180).map((f, i) => [100 + f.t, ...pts.flatMap(([d]) =>
    i === 20 && d === 'right' ? Array(7).fill('') : [...f[d].p, ...f[d].q])].join(','));
  const csv = [header.join(','), ...rows].join('\n') + '\n';
  writeFileSync(join(out, 'recorded-session.csv'), csv);
  await page.goto(`${url}/?a=${A}&b=ik&trial=${encodeURIComponent(trial)}`);
  await page.waitForFunction(() => window.__legwork.ready || window.__legwork.error, null, { timeout: TIMEOUT });
  await page.setInputFiles('#csvFile', { name: 'recorded-session.csv', mimeType: 'text/csv', buffer: Buffer.from(csv) });
  await page.waitForFunction(() => window.__legwork.trial === 'recorded-session.csv' && window.__legwork.sessions.ik?.posesReceived >= 30,
    null, { timeout: TIMEOUT, polling: 250 });
  const st = await legwork();
  assert.equal(st.error, '');
  assert.equal(st.frames, 180);
  const { ik } = st.sessions;
  console.log(`# recorded session: ik ${ik.posesReceived} poses, median hand error ${(ik.medianHandError * 1000).toFixed(3)} mm`);
  assert.equal(ik.errors, 0, ik.lastError);
  assert.ok(ik.medianHandError < 0.02, `ik: median hand error ${ik.medianHandError} m`);
});

test('WebXR emulated input: frames convert to legwork axes and produce poses', { timeout: TIMEOUT }, async () => {
  await page.evaluate(() => window.__legworkFakeXR.start((t) => {
    const s = 0.04 * Math.sin(t * 3);
    const yaw90 = { x: 0, y: Math.SQRT1_2, z: 0, w: Math.SQRT1_2 }; // WebXR: turned 90 degrees to the left
    const id = { x: 0, y: 0, z: 0, w: 1 };
    return {
      head: { position: { x: 0.1, y: 1.6, z: -0.2 }, orientation: t < 0 ? yaw90 : id },
      left: { position: { x: -0.3, y: 1.0 + s, z: -0.35 }, orientation: id },
      right: { position: { x: 0.3, y: 1.0 - s, z: -0.35 }, orientation: yaw90 },
    };
  }, 'ik'));
  await page.waitForFunction(() => window.__legwork.xr.posesReceived >= 30, null, { timeout: TIMEOUT, polling: 250 });
  const xr = (await legwork()).xr;
  const f = xr.lastFrame;
  const near = (a, b, what) => a.forEach((v, k) => assert.ok(Math.abs(v - b[k]) < 1e-6, `${what}: ${a} vs ${b}`));
  // WebXR (-z forward, +x right) -> legwork (+z forward, +x left): (x, y, z) -> (-x, y, -z)
  near(f.head.p, [-0.1, 1.6, 0.2], 'head position');
  near([f.left.p[0], f.left.p[2]], [0.3, 0.35], 'left hand x,z');
  near([f.right.p[0], f.right.p[2]], [-0.3, 0.35], 'right hand x,z');
  // a 90-degree turn to the left stays a 90-degree turn to the left about +y
  near(f.right.q, [Math.SQRT1_2, 0, Math.SQRT1_2, 0], 'right controller rotation');
  console.log(`# fake XR: ${xr.framesRead} XR frames, ${xr.posesReceived} poses, ik median hand error ${(xr.medianHandError * 100).toFixed(2)} cm`);
  assert.ok(xr.medianHandError < 0.02, `XR ik: median hand error ${xr.medianHandError} m`);
  await page.screenshot({ path: join(out, 'xr-mirror.png') });
  await page.evaluate(() => window.__legworkFakeXR.stop());
});

test('walk-cycle GLB: loads and animates', { timeout: TIMEOUT }, async () => {
  const glb = process.env.LEGWORK_GLB ? readFileSync(process.env.LEGWORK_GLB) : walkGLB();
  const file = join(out, 'walk-fixture.glb');
  if (!process.env.LEGWORK_GLB) writeFileSync(file, glb);
  await page.evaluate(() => window.__legworkControl.setMode('glb'));
  await page.setInputFiles('#glbFile', { name: 'walk.glb', mimeType: 'model/gltf-binary', buffer: glb });
  await page.waitForFunction(() => window.__legwork.glb.loaded || window.__legwork.error, null, { timeout: TIMEOUT });
  const a = (await legwork()).glb;
  assert.ok(a.loaded, `GLB not loaded: ${(await legwork()).error}`);
  assert.ok(a.joints >= 15 && a.duration > 0, `GLB: ${a.joints} joints, ${a.duration} s`);
  // Wait until the clip's time is at least 0.2 s away from a's around the loop: a fixed number of
  // updates can add up to exactly one loop on a slow page (each frame's step is capped at 0.1 s).
  await page.waitForFunction(([t0, d]) => {
    const g = window.__legwork.glb;
    const x = Math.abs(g.time - t0) % d;
    return Math.min(x, d - x) > Math.min(0.2, d / 4);
  }, [a.time, a.duration], { timeout: TIMEOUT, polling: 200 });
  const b = (await legwork()).glb;
  const moved = Math.max(...a.positions.map((p, j) => Math.hypot(...p.map((x, k) => x - b.positions[j][k]))));
  console.log(`# GLB ${a.joints} joints, ${a.duration.toFixed(2)} s loop; largest joint move between samples ${(moved * 100).toFixed(1)} cm`);
  assert.ok(moved > 0.02, 'the GLB animation moves the body');
  await page.screenshot({ path: join(out, 'walkcycle.png') });
});

test('no page errors', () => {
  assert.deepEqual(pageErrors, []);
});
