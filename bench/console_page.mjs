// The console page in headless chromium (Debian's, driven by playwright-core from tests/browser): how many
// stream frames it receives and how many times it redraws the canvas per second. Used by
// bench/console_load as its third viewer; prints one JSON line. Exit 77 when chromium or playwright-core
// is missing.
//
//   node bench/console_page.mjs URL SECONDS
import { createRequire } from 'node:module';
import { existsSync } from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

const [url, secondsText] = process.argv.slice(2);
const seconds = Number(secondsText || 10);
const here = path.dirname(fileURLToPath(import.meta.url));
const require = createRequire(path.join(here, '..', 'tests', 'browser', 'package.json'));
if (!existsSync('/usr/bin/chromium')) process.exit(77);
let chromium;
try {
  ({ chromium } = require('playwright-core'));
} catch {
  process.exit(77);
}
const browser = await chromium.launch({
  executablePath: '/usr/bin/chromium', headless: true,
  args: ['--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run', '--disable-background-networking',
    '--disable-component-update', '--disable-sync'],
});
const page = await browser.newPage({ viewport: { width: 1280, height: 800 } });
await page.goto(url);
await page.waitForFunction(() => window.sslConsole?.frames > 10, null, { timeout: 20_000 });
const sample = () => page.evaluate(() => ({ frames: window.sslConsole.frames, draws: window.sslConsole.draws,
  t: performance.now() }));
const first = await sample();
await page.waitForTimeout(seconds * 1000);
const last = await sample();
const elapsed = (last.t - first.t) / 1000;
console.log(JSON.stringify({ frames_per_s: (last.frames - first.frames) / elapsed,
  draws_per_s: (last.draws - first.draws) / elapsed }));
await browser.close();
