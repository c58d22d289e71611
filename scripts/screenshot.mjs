#!/usr/bin/env node
// Captures PNGs of the viewer's replay from a running `legwork serve` (or the mock)
// in headless Chromium (Debian's /usr/bin/chromium, driven by web/'s playwright-core).
//   node scripts/screenshot.mjs --url http://127.0.0.1:8080 [--out shot.png] [--trial walking/07_02]
//        [--seq N --interval-ms 100] [--width 1280 --height 720] [--wait-poses 60] [--timeout-ms 120000] [--query "quality=high&a=accent&b=ik"]
// --seq N writes N PNGs (out-000.png, ...) spaced --interval-ms apart instead of one, and out-fps.txt:
// the frames per second they were taken at (for a video at the replay's real speed).
import { mkdirSync, writeFileSync } from 'node:fs';
import { dirname, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import { launch } from '../web/test/browser.mjs'; // needs `npm ci` in web/ (scripts/setup.sh does it)

function args() {
  const a = { url: 'http://127.0.0.1:8080', out: 'legwork-replay.png', trial: '', seq: 0, intervalMs: 100, width: 1280, height: 720, waitPoses: 60, timeoutMs: 120000, query: 'quality=high' };
  const argv = process.argv.slice(2);
  for (let i = 0; i < argv.length; i += 2) {
    const k = argv[i].replace(/^--/, '').replace(/-([a-z])/g, (_, c) => c.toUpperCase());
    if (!(k in a)) throw new Error(`unknown option ${argv[i]} (see the header of ${fileURLToPath(import.meta.url)})`);
    a[k] = typeof a[k] === 'number' ? Number(argv[i + 1]) : argv[i + 1];
  }
  return a;
}

async function main() {
  const a = args();
  const { page, close } = await launch({ width: a.width, height: a.height });
  try {
    page.on('console', (m) => m.type() === 'error' && console.error(`page: ${m.text()}`));
    const q = new URLSearchParams(a.query);
    if (a.trial) q.set('trial', a.trial);
    await page.goto(`${a.url.replace(/\/$/, '')}/?${q}`);
    await page.waitForFunction((n) => window.__legwork && (window.__legwork.error || window.__legwork.posesReceived >= n), a.waitPoses, { timeout: a.timeoutMs, polling: 250 });
    const err = await page.evaluate(() => window.__legwork.error);
    if (err) throw new Error(`viewer: ${err}`);
    const out = resolve(a.out);
    mkdirSync(dirname(out), { recursive: true });
    if (a.seq > 0) {
      // A software-rendered page takes ~1 s per screenshot: the real times are written
      // beside the frames (<out>-fps.txt: frames per second of the page's own clock), so a
      // video made of them plays at the replay's speed, not faster.
      const t0 = Date.now();
      for (let i = 0; i < a.seq; ++i) {
        const f = out.replace(/\.png$/, '') + `-${String(i).padStart(3, '0')}.png`;
        await page.screenshot({ path: f });
        console.log(f);
        if (i + 1 < a.seq) await page.waitForTimeout(a.intervalMs);
      }
      const fps = a.seq > 1 ? (a.seq - 1) / ((Date.now() - t0) / 1000) : 1;
      writeFileSync(out.replace(/\.png$/, '') + '-fps.txt', `${fps.toFixed(3)}\n`);
    } else {
      await page.waitForTimeout(300);
      await page.screenshot({ path: out });
      console.log(out);
    }
  } finally {
    await close();
  }
}

if (resolve(process.argv[1] || '') === fileURLToPath(import.meta.url)) main().catch((e) => { console.error(`screenshot: ${e.message}`); process.exit(1); });
