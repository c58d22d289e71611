// legwork live viewer: wires the UI to the three modes (replay, walk-cycle GLB,
// VR mirror) and exposes numeric state for tests on window.__legwork.
import { Stage } from './scene.js';
import { Replay } from './replay.js';
import { GLBPlayer } from './glb.js';
import { XRMirror } from './xrmode.js';
import { demoXRPose } from './xr.js';
import { parseTrackerCSV } from './trackercsv.js';

const $ = (id) => document.getElementById(id);
const params = new URLSearchParams(location.search);
const base = new URL('.', location.href);
// Software GL (no GPU, e.g. headless CI) renders a few frames a second with shadows and
// antialiasing; ?quality=low|high overrides the guess.
function guessQuality() {
  if (params.get('quality')) return params.get('quality');
  const gl = document.createElement('canvas').getContext('webgl2');
  const ext = gl && gl.getExtension('WEBGL_debug_renderer_info');
  const name = ext ? String(gl.getParameter(ext.UNMASKED_RENDERER_WEBGL)) : '';
  gl?.getExtension('WEBGL_lose_context')?.loseContext();
  return /swiftshader|llvmpipe|software/i.test(name) ? 'low' : 'high';
}
const stage = new Stage($('view'), $('labels'), guessQuality());
const replay = new Replay(stage, base);
const glb = new GLBPlayer(stage);
const mirror = new XRMirror(stage, base);

const state = (window.__legwork = {
  ready: false, mode: 'replay', error: '', info: null, trials: [], trial: '', frame: 0, frames: 0, renderFps: 0,
  posesReceived: 0, lastHandError: NaN, sessions: {}, xr: mirror.stats, glb: glb.info,
});

function fail(msg) {
  state.error = msg;
  $('conn').textContent = msg;
  $('conn').className = 'pill bad';
  console.error(msg);
}

function setMode(mode) {
  state.mode = mode;
  for (const b of document.querySelectorAll('#modes button')) b.classList.toggle('active', b.dataset.mode === mode);
  for (const s of document.querySelectorAll('#panel section[data-for]')) s.hidden = !s.dataset.for.split(' ').includes(mode);
  replay.group.visible = mode === 'replay';
  for (const l of replay.lanes) if (l.label) l.label.visible = mode === 'replay';
  glb.group.visible = mode === 'glb';
  glb.label.visible = mode === 'glb';
  mirror.group.visible = mode === 'xr';
  mirror.label.visible = mode === 'xr';
  if (mode === 'replay') { stage.camera.position.set(0.6, 1.75, 5.6); stage.controls.target.set(0, 0.95, 0); replay.start(); }
  else replay.stop();
  if (mode === 'glb') { stage.camera.position.set(2.8, 1.6, 4.2); stage.controls.target.set(0, 1.0, 0); stage.setGridOffset(0, 0, 0); }
  if (mode === 'xr') { mirror.frameCamera(); stage.setGridOffset(0, 0, 0); }
  else mirror.stopFake();
}

function options(select, methods, value) {
  select.innerHTML = methods.map((m) => `<option${m === value ? ' selected' : ''}>${m}</option>`).join('');
}

function selectedClasses() {
  const boxes = [...document.querySelectorAll('#classes input')];
  const on = boxes.filter((b) => b.checked).map((b) => b.value);
  return on.length === boxes.length ? undefined : on; // undefined = all classes (protocol default)
}

function sessionOptions() {
  const o = { exaggeration: +$('exag').value, format: $('format').value };
  const c = selectedClasses();
  if (c) o.classes = c;
  if (params.get('height')) o.user_height = +params.get('height');
  return o;
}

// (Re)connects the two lane sessions, then plays `getTrial()`'s frames.
async function play(getTrial) {
  const tr = await getTrial();
  replay.options = sessionOptions();
  // A trial carries its subject's standing height: the avatars take it (a
  // recorded session has none and keeps the avatar's own, or ?height=).
  if (replay.options.user_height === undefined && tr.height >= 0.5 && tr.height <= 2.5) replay.options.user_height = tr.height;
  await replay.connect([$('methodA').value, $('methodB').value]);
  state.trial = tr.name;
  state.frames = tr.frames.length;
  $('scrub').max = tr.frames.length - 1;
  replay.setPlaying(true);
  $('play').textContent = 'Pause';
  replay.start();
}

// A trial from the server's --trials folder, with its ground truth.
const startReplay = (name = $('trial').value) => play(() => replay.load(name, +(params.get('rate') || 90)));

// A recorded session (`legwork serve --record`): its head and hands replayed like a trial, no ground truth.
const startRecorded = (file) => play(async () => replay.setTrial(parseTrackerCSV(await file.text(), file.name)));

async function init() {
  const get = async (path) => {
    const r = await fetch(new URL(path, base));
    if (!r.ok) throw new Error(`GET ${path}: HTTP ${r.status}`);
    return r.json();
  };
  const info = (state.info = await get('api/info'));
  const methods = info.methods || ['accent', 'ik'];
  options($('methodA'), methods, params.get('a') || (methods.includes('accent') ? 'accent' : methods[0]));
  options($('methodB'), methods, params.get('b') || (methods.includes('ik') ? 'ik' : methods[0]));
  options($('methodXR'), methods, params.get('xr') || $('methodA').value);
  if (params.get('format')) $('format').value = params.get('format');
  const want = params.get('classes') ? params.get('classes').split(',') : null;
  $('classes').innerHTML = (info.classes || []).map((c) =>
    `<label><input type="checkbox" value="${c}"${!want || want.includes(c) ? ' checked' : ''}>${c}</label>`).join('');
  const { trials } = await get('api/trials');
  state.trials = trials;
  $('trial').innerHTML = trials.map((t) => `<option>${t}</option>`).join('');
  const first = params.get('trial') || trials.find((t) => t.startsWith('walking/')) || trials[0];
  if (first) $('trial').value = first;
  $('conn').textContent = `${info.database || 'server'} · v${info.version}`;
  $('conn').className = 'pill ok';
  if (navigator.xr) navigator.xr.isSessionSupported('immersive-vr').then((ok) => {
    $('enterVR').disabled = !ok;
    $('xrInfo').textContent = ok ? 'A headset is available.' : 'No immersive-vr here: use a headset browser, or emulate.';
  }).catch(() => {});
  else $('xrInfo').textContent = 'This browser has no WebXR: open the page in a headset browser, or emulate.';
  const mode = params.get('mode') || 'replay';
  setMode(mode);
  if (mode === 'replay' && first) await startReplay(first);
  if (params.get('glb')) showGLB(await glb.loadURL(params.get('glb')));
  if (mode === 'xr' && params.has('fakexr')) await mirror.startFake($('methodXR').value, sessionOptions());
  state.ready = true;
}

// ---- UI events
for (const b of document.querySelectorAll('#modes button')) b.onclick = () => setMode(b.dataset.mode);
$('trial').onchange = () => startReplay().catch((e) => fail(e.message));
$('methodA').onchange = $('methodB').onchange = $('format').onchange = () => startReplay($('trial').value).catch((e) => fail(e.message));
$('csvFile').onchange = () => $('csvFile').files[0] && startRecorded($('csvFile').files[0]).catch((e) => fail(e.message));
$('follow').onchange = () => { replay.follow = $('follow').checked; };
$('exag').oninput = () => {
  $('exagOut').textContent = (+$('exag').value).toFixed(2);
  replay.setOptions({ exaggeration: +$('exag').value });
  mirror.setOptions({ exaggeration: +$('exag').value });
};
$('classes').onchange = () => {
  const c = selectedClasses() || state.info.classes;
  replay.setOptions({ classes: c });
  mirror.setOptions({ classes: c });
};
$('play').onclick = () => {
  const p = state.mode === 'glb' ? glbPaused = !glbPaused : (replay.setPlaying(!replay.playing), !replay.playing);
  $('play').textContent = p ? 'Play' : 'Pause';
};
let glbPaused = false;
$('speed').onchange = () => replay.setSpeed(+$('speed').value);
$('scrub').oninput = () => {
  if (state.mode === 'glb') glb.seek((+$('scrub').value / 1000) * glb.info.duration);
  else replay.seek(+$('scrub').value);
};
$('glbFile').onchange = () => $('glbFile').files[0] && glb.loadFile($('glbFile').files[0]).then(showGLB).catch((e) => fail(e.message));
$('enterVR').onclick = () => mirror.enterVR($('methodXR').value, sessionOptions()).catch((e) => fail(`VR: ${e.message}`));
$('fakeVR').onclick = () => mirror.startFake($('methodXR').value, sessionOptions()).catch((e) => fail(e.message));

function showGLB(info) {
  $('glbInfo').textContent = `${info.name}: ${info.joints} joints, ${info.duration.toFixed(2)} s`;
  $('scrub').max = 1000;
}

// Test hooks: the emulated XR input and programmatic control.
window.__legworkFakeXR = {
  start: (poseAt = demoXRPose, method = $('methodXR').value) => { setMode('xr'); return mirror.startFake(method, sessionOptions(), poseAt); },
  stop: () => mirror.stopFake(),
};
window.__legworkControl = {
  stage, replay, glb, mirror,
  setMode, startReplay, seek: (i) => replay.seek(i), play: (p) => replay.setPlaying(p),
  loadGLB: async (url) => { setMode('glb'); const i = await glb.loadURL(url); showGLB(i); return i; },
};

// ---- render loop + readouts
let last = performance.now(), frames = 0, fpsStart = last;
function readout() {
  const rows = [];
  const add = (k, v) => rows.push(`<tr><td>${k}</td><td class="v">${v}</td></tr>`);
  const fmt = (x, d = 1, u = '') => (Number.isFinite(x) ? `${x.toFixed(d)}${u}` : '–');
  const sessions = state.mode === 'xr' ? (mirror.session ? [mirror.session] : []) : replay.lanes.map((l) => l.session).filter(Boolean);
  for (const s of sessions) {
    const st = s.stats;
    add(`<b>${st.method}</b>`, st.state);
    add('poses', `${st.posesReceived} @ ${st.poseHz} Hz`);
    add('round trip', `${fmt(st.rttAvgMs, 2, ' ms')} (server ${fmt(st.serverUs, 0, ' µs')})`);
    add('hand error', st.lastHandError < 0.01 ? fmt(st.lastHandError * 1000, 2, ' mm') : fmt(st.lastHandError * 100, 1, ' cm'));
    if (st.errors) add('errors', `${st.errors} ${st.lastError}`);
    for (const w of st.warnings || []) add('warning', w);
  }
  $('readout').innerHTML = rows.join('');
}
function loop(now) {
  requestAnimationFrame(loop);
  if (stage.renderer.xr.isPresenting) return;
  const dt = Math.min((now - last) / 1000, 0.1);
  last = now;
  if (++frames, now - fpsStart > 500) { state.renderFps = (frames * 1000) / (now - fpsStart); frames = 0; fpsStart = now; $('fps').textContent = `${state.renderFps.toFixed(state.renderFps < 10 ? 1 : 0)} fps`; }
  if (state.mode === 'glb' && !glbPaused) {
    glb.update(dt * +$('speed').value);
    if (glb.info.duration) {
      if (document.activeElement !== $('scrub')) $('scrub').value = Math.round((glb.info.time / glb.info.duration) * 1000);
      $('time').textContent = `${glb.info.time.toFixed(2)} / ${glb.info.duration.toFixed(2)} s`;
    }
  }
  if (state.mode === 'replay' && replay.trial) {
    state.frame = replay.shown;
    if (document.activeElement !== $('scrub')) $('scrub').value = replay.shown;
    $('time').textContent = `${(replay.shown / replay.trial.fps).toFixed(2)} / ${replay.duration.toFixed(2)} s · frame ${replay.shown}`;
    replay.update();
  }
  if (state.mode === 'xr') {
    const e = mirror.stats.lastHandError;
    mirror.label.stats.textContent = `${mirror.stats.posesReceived} poses · hands ${!Number.isFinite(e) ? '–' : e < 0.01 ? (e * 1000).toFixed(1) + ' mm' : (e * 100).toFixed(1) + ' cm'}`;
  }
  state.sessions = {};
  for (const l of replay.lanes) if (l.session) state.sessions[l.method in state.sessions ? `${l.method}2` : l.method] = l.session.stats;
  const all = Object.values(state.sessions);
  state.posesReceived = all.reduce((a, s) => a + s.posesReceived, 0);
  state.lastHandError = state.sessions.ik ? state.sessions.ik.lastHandError : NaN;
  if (frames % 10 === 0) readout();
  stage.render();
}
requestAnimationFrame(loop);
init().catch((e) => fail(e.message));
