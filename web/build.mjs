// Bundles src/main.js (and the three.js it imports) into dist/app.js, the
// replay's stream worker into dist/stream-worker.js, and copies the static page. `node build.mjs --watch` rebuilds on change.
import * as esbuild from 'esbuild';
import { copyFileSync, mkdirSync } from 'node:fs';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';

const here = dirname(fileURLToPath(import.meta.url));
const dist = join(here, 'dist');
mkdirSync(dist, { recursive: true });
for (const f of ['index.html', 'style.css']) copyFileSync(join(here, 'src', f), join(dist, f));

const options = {
  entryPoints: { app: join(here, 'src', 'main.js'), 'stream-worker': join(here, 'src', 'stream-worker.js') },
  bundle: true,
  format: 'esm',
  target: 'es2020',
  minify: true,
  sourcemap: true,
  outdir: dist,
  logLevel: 'info',
};
if (process.argv.includes('--watch')) {
  const ctx = await esbuild.context(options);
  await ctx.watch();
} else {
  await esbuild.build(options);
}
