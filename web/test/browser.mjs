// Headless Chromium for the tests and scripts/screenshot.mjs: Debian's
// /usr/bin/chromium (CHROMIUM overrides) driven by playwright-core; nothing is
// downloaded, and every run gets a fresh profile that is removed afterwards.
import { chromium } from 'playwright-core';
import { mkdtempSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';

export const CHROMIUM_ARGS = ['--headless', '--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run',
  '--disable-background-networking', '--disable-component-update', '--disable-sync',
  // WebGL without a GPU: ANGLE on SwiftShader (Chromium refuses the software fallback unless told).
  '--use-angle=swiftshader', '--enable-unsafe-swiftshader'];

// A browser context on a fresh --user-data-dir (playwright passes the directory itself).
export async function launch(viewport = { width: 1280, height: 720 }) {
  const profile = mkdtempSync(join(tmpdir(), 'legwork-chromium-'));
  const context = await chromium.launchPersistentContext(profile, {
    executablePath: process.env.CHROMIUM || '/usr/bin/chromium', headless: true, args: CHROMIUM_ARGS, viewport });
  const page = context.pages()[0] || (await context.newPage());
  return { context, page, close: async () => { await context.close(); rmSync(profile, { recursive: true, force: true }); } };
}
