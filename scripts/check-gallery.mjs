#!/usr/bin/env node
// Loads a gallery page (legwork gallery DIR -> DIR/index.html) and every page
// it links to inside DIR in headless Chromium (web/test/browser.mjs) and checks
// that every picture decodes, every video loads its metadata, every poster
// exists and no link points to a missing file. Prints what it checked; exits 1
// listing every problem.
//   node scripts/check-gallery.mjs DIR/index.html
import { existsSync, statSync } from 'node:fs';
import { dirname, relative, resolve } from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';
import { launch } from '../web/test/browser.mjs'; // needs `npm ci` in web/ (scripts/setup.sh does it)

const start = process.argv[2];
if (!start || !existsSync(start)) {
  console.error(`usage: node scripts/check-gallery.mjs DIR/index.html (not found: ${start})`);
  process.exit(2);
}
const root = dirname(resolve(start));

// Everything the page refers to, after every image is made eager and every video asked for its metadata.
async function inspect(page, url) {
  await page.goto(url, { waitUntil: 'load' });
  return page.evaluate(async () => {
    const imgs = [...document.images];
    imgs.forEach((i) => { i.loading = 'eager'; });
    await Promise.all(imgs.map((i) => (i.complete ? null : new Promise((r) => { i.onload = i.onerror = r; }))));
    const videos = [...document.querySelectorAll('video')];
    await Promise.all(videos.map((v) => (v.readyState >= 1 ? null : new Promise((r) => {
      v.addEventListener('loadedmetadata', r); v.addEventListener('error', r); v.preload = 'metadata'; v.load();
      setTimeout(r, 15000);
    }))));
    return {
      images: imgs.map((i) => ({ src: i.src, ok: i.complete && i.naturalWidth > 0, width: i.naturalWidth })),
      videos: videos.map((v) => ({ src: v.currentSrc || v.src, ok: v.readyState >= 1 && v.videoWidth > 0, poster: v.poster,
        error: v.error ? v.error.code : 0 })),
      links: [...document.querySelectorAll('a[href]')].map((a) => a.href),
    };
  });
}

const problems = [];
const counts = { pages: 0, images: 0, videos: 0, posters: 0, links: 0 };
const fileOf = (u) => fileURLToPath(u.split('#')[0].split('?')[0]);
const { page, close } = await launch({ width: 1400, height: 900 });
try {
  page.on('console', (m) => m.type() === 'error' && problems.push(`console error on ${page.url()}: ${m.text()}`));
  const queue = [pathToFileURL(resolve(start)).href];
  const seen = new Set(queue);
  while (queue.length) {
    const url = queue.shift();
    const where = relative(root, fileOf(url));
    const r = await inspect(page, url);
    counts.pages += 1;
    for (const i of r.images) {
      counts.images += 1;
      if (!i.ok) problems.push(`${where}: picture does not load: ${relative(root, fileOf(i.src))}`);
    }
    for (const v of r.videos) {
      counts.videos += 1;
      if (!v.ok) problems.push(`${where}: video does not load (error ${v.error}): ${relative(root, fileOf(v.src))}`);
      if (v.poster) {
        counts.posters += 1;
        if (!existsSync(fileOf(v.poster))) problems.push(`${where}: missing poster ${relative(root, fileOf(v.poster))}`);
      }
    }
    for (const l of r.links) {
      if (!l.startsWith('file:')) continue;
      counts.links += 1;
      const f = fileOf(l);
      if (!existsSync(f)) { problems.push(`${where}: broken link ${relative(root, f)}`); continue; }
      if (f.endsWith('.html') && statSync(f).isFile() && !relative(root, f).startsWith('..') && !seen.has(l.split('#')[0])) {
        seen.add(l.split('#')[0]);
        queue.push(l.split('#')[0]);
      }
    }
  }
} finally {
  await close();
}
console.log(`gallery check: ${counts.pages} pages, ${counts.images} pictures, ${counts.videos} videos ` +
  `(${counts.posters} posters), ${counts.links} links`);
if (problems.length) {
  console.error(problems.map((p) => `gallery check: ${p}`).join('\n'));
  process.exit(1);
}
