// Recorded sessions (`legwork serve --record`, io/tracker_csv.hpp) as replay input:
// "time,<point>_x,_y,_z[,_qw,_qx,_qy,_qz],..." rows; empty or nan cells = dropped sample.
// Point names are matched to devices like io::frames_from_table does.
const ALIASES = {
  head: ['head', 'hmd', 'headset'],
  left: ['left_hand', 'left', 'lhand', 'left_wrist'],
  right: ['right_hand', 'right', 'rhand', 'right_wrist'],
  left_foot: ['left_foot', 'left_ankle', 'ankle_l', 'l_ankle', 'leftankle', 'leftfoot'],
  right_foot: ['right_foot', 'right_ankle', 'ankle_r', 'r_ankle', 'rightankle', 'rightfoot'],
};

function columns(header, source) {
  const cols = header.split(',').map((c) => c.trim());
  if (cols[0] !== 'time') throw new Error(`${source}:1: the first column must be "time", got "${cols[0]}"`);
  const points = {};
  cols.slice(1).forEach((c, k) => {
    const m = /^(.+)_(x|y|z|qw|qx|qy|qz)$/.exec(c);
    if (!m) throw new Error(`${source}:1:${k + 2}: column "${c}" is not <point>_x|y|z|qw|qx|qy|qz`);
    (points[m[1]] ||= {})[m[2]] = k + 1;
  });
  const devices = {};
  for (const [dev, names] of Object.entries(ALIASES)) {
    const name = Object.keys(points).find((p) => names.includes(p.toLowerCase()));
    if (!name) continue;
    const c = points[name];
    if (c.x === undefined || c.y === undefined || c.z === undefined) throw new Error(`${source}:1: point "${name}" lacks one of _x, _y, _z`);
    devices[dev] = { p: [c.x, c.y, c.z], q: c.qw !== undefined ? [c.qw, c.qx, c.qy, c.qz] : null };
  }
  if (!devices.head) throw new Error(`${source}:1: no head point (one of ${ALIASES.head.join(', ')}); points: ${Object.keys(points).join(', ')}`);
  return { count: cols.length, devices };
}

export function parseTrackerCSV(text, source = 'tracker.csv') {
  const lines = text.split(/\r?\n/);
  const { count, devices } = columns(lines[0] || '', source);
  const frames = [];
  let t0 = null, last = -Infinity;
  for (let i = 1; i < lines.length; ++i) {
    if (!lines[i].trim()) continue;
    const cells = lines[i].split(',');
    if (cells.length !== count) throw new Error(`${source}:${i + 1}: ${cells.length} cells, the header has ${count}`);
    const num = (k) => (cells[k].trim() === '' ? NaN : Number(cells[k]));
    const t = num(0);
    if (!(t > last)) throw new Error(`${source}:${i + 1}: time ${cells[0]} is not after ${last}`);
    last = t;
    if (t0 === null) t0 = t;
    const f = { t: t - t0 };
    for (const [dev, c] of Object.entries(devices)) {
      const p = c.p.map(num);
      const q = c.q ? c.q.map(num) : [1, 0, 0, 0];
      if ([...p, ...q].every(Number.isFinite)) f[dev] = dev.endsWith('foot') ? { p } : { p, q };
    }
    frames.push(f);
  }
  if (frames.length < 2) throw new Error(`${source}: fewer than two samples`);
  const dts = frames.slice(1).map((f, k) => f.t - frames[k].t).sort((a, b) => a - b);
  // Replay needs a head every frame (it anchors the view): hold the last one over dropped samples.
  let head = frames.find((f) => f.head)?.head;
  for (const f of frames) { if (f.head) head = f.head; else f._heldHead = head; }
  return { name: source, fps: Math.round(1 / dts[dts.length >> 1]), frames, truth: null };
}
