// The console in a real browser (Debian's chromium, driven by playwright-core), against a real match started
// the way a user starts one: `./ssl up` on a private domain and ports, with the simulator's ground truth
// (--realism none: vision is exact) and sslctl as the independent witness of the bus.
//
//   node tests/browser/console.test.mjs        (ctest: browser_console_test; exit 77 = skipped)
// Environment: SSL_BUILD_DIR (default build), BROWSER_ARTIFACTS (screenshots; default build/tests/browser-artifacts).
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { spawn, spawnSync } from 'node:child_process';
import { existsSync, mkdirSync, mkdtempSync, readFileSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

const here = path.dirname(fileURLToPath(import.meta.url));
const root = path.resolve(here, '..', '..');
const buildDir = process.env.SSL_BUILD_DIR || path.join(root, 'build');
const artifacts = process.env.BROWSER_ARTIFACTS || path.join(buildDir, 'tests', 'browser-artifacts');
const chromiumPath = '/usr/bin/chromium';

// A private match: its own DDS domain and ports, so that it runs beside every other test.
const DOMAIN = 210;
const VISION_PORT = 45020;  // control, blue, yellow, grSim: the four ports above (./ssl up)
const REFEREE_PORT = 45003;
const HTTP_PORT = 45080;
const TOKEN_PORT = 45081;   // a second console, with a token
const TOKEN = 's3cret-token';
const consoleUrl = `http://127.0.0.1:${HTTP_PORT}/`;

function skip(reason) {
  console.log(`SKIP browser tests: ${reason}`);
  process.exit(77);
}

if (!existsSync(chromiumPath)) skip(`${chromiumPath} is missing (./ssl test installs Debian's chromium)`);
let chromium;
try {
  ({ chromium } = await import('playwright-core'));
} catch {
  skip('playwright-core is missing (./ssl test runs npm ci in tests/browser)');
}
if (!existsSync(path.join(buildDir, 'bin', 'console'))) skip(`no console binary in ${buildDir}/bin`);

mkdirSync(artifacts, { recursive: true });
const sslctl = path.join(buildDir, 'bin', 'sslctl');
// Saved run-time parameters go to a directory of this run, never to the user's.
const paramsDir = mkdtempSync(path.join(tmpdir(), 'ssl-browser-params-'));
const env = { ...process.env, SSL_BUILD_DIR: buildDir, SSL_PARAMS_DIR: paramsDir };
const sleep = (ms) => new Promise((resolve) => setTimeout(resolve, ms));

/// Runs `sslctl topic echo TOPIC` and resolves with the first sample for which `accept(sample)` holds.
function waitForSample(topic, accept, { team, timeoutS = 10 } = {}) {
  const args = ['topic', 'echo', topic, '--domain', String(DOMAIN)];
  if (team) args.push('--team', team);
  return new Promise((resolve, reject) => {
    const child = spawn(sslctl, args, { env });
    let buffer = '';
    let last;
    const timer = setTimeout(() => {
      child.kill('SIGTERM');
      reject(new Error(`no ${topic} sample as expected within ${timeoutS} s; last: ${JSON.stringify(last)?.slice(0, 400)}`));
    }, timeoutS * 1000);
    child.stdout.on('data', (chunk) => {
      buffer += chunk;
      let newline;
      while ((newline = buffer.indexOf('\n')) >= 0) {
        const line = buffer.slice(0, newline);
        buffer = buffer.slice(newline + 1);
        if (!line) continue;
        last = JSON.parse(line);
        if (accept(last)) {
          clearTimeout(timer);
          child.kill('SIGTERM');
          resolve(last);
          return;
        }
      }
    });
  });
}

/// Every robot's position (vision frame) over `seconds`, from exact vision: Map "team/id" -> [{t, x, y}].
async function trackRobots(seconds) {
  const tracks = new Map();
  let end;  // counted from the first frame: sslctl's discovery may take a while on a loaded machine
  await waitForSample('vision.detection', (frame) => {
    end ??= Date.now() + seconds * 1000;
    const t = frame.capture_unix_ns / 1e9;
    for (const [team, robots] of [['blue', frame.robots_blue], ['yellow', frame.robots_yellow]]) {
      for (const robot of robots) {
        const key = `${team}/${robot.robot_id}`;
        if (!tracks.has(key)) tracks.set(key, []);
        tracks.get(key).push({ t, x: robot.x, y: robot.y });
      }
    }
    return Date.now() >= end;
  }, { timeoutS: seconds + 10 });
  return tracks;
}

/// The fastest robot's mean speed (m/s) over the tracks.
function fastest(tracks) {
  let best = { key: null, speed: 0 };
  for (const [key, points] of tracks) {
    points.sort((a, b) => a.t - b.t);
    const first = points[0];
    const last = points[points.length - 1];
    if (!first || last.t - first.t < 0.2) continue;
    const speed = Math.hypot(last.x - first.x, last.y - first.y) / (last.t - first.t);
    if (speed > best.speed) best = { key, speed };
  }
  return best;
}

/// Resolves with the first robot whose mean speed (m/s) over a sliding window of `windowS` reaches `minSpeed`;
/// rejects after `timeoutS` with the fastest window seen. Play decides who moves and when, so the test waits
/// for motion rather than sampling one fixed second.
async function waitForMotion(minSpeed, { windowS = 1.0, timeoutS = 10 } = {}) {
  const tracks = new Map();
  let best = { key: null, speed: 0 };
  try {
    await waitForSample('vision.detection', (frame) => {
      const t = frame.capture_unix_ns / 1e9;
      for (const [team, robots] of [['blue', frame.robots_blue], ['yellow', frame.robots_yellow]]) {
        for (const robot of robots) {
          const key = `${team}/${robot.robot_id}`;
          const points = tracks.get(key) ?? [];
          points.push({ t, x: robot.x, y: robot.y });
          while (points.length > 1 && t - points[0].t > windowS) points.shift();
          tracks.set(key, points);
          const span = t - points[0].t;
          if (span < 0.8 * windowS) continue;
          const speed = Math.hypot(robot.x - points[0].x, robot.y - points[0].y) / span;
          if (speed > best.speed) best = { key, speed };
        }
      }
      return best.speed >= minSpeed;
    }, { timeoutS });
  } catch (error) {
    if (best.key === null) throw error;  // no robot seen at all; a slow one is named by the caller's assertion
  }
  return best;
}

let browser;
let page;
let tokenConsole;

before(async () => {
  const up = spawnSync(path.join(root, 'ssl'), ['up', '--robots', '6', '--realism', 'none', '--seed', '3',
    '--domain', String(DOMAIN), '--vision-port', String(VISION_PORT), '--referee-port', String(REFEREE_PORT),
    '--http-port', String(HTTP_PORT)], { env, encoding: 'utf8', timeout: 600_000 });
  assert.equal(up.status, 0, `./ssl up failed:\n${up.stdout}\n${up.stderr}`);
  assert.match(up.stdout, new RegExp(`console: http://127.0.0.1:${HTTP_PORT}`));
  tokenConsole = spawn(path.join(buildDir, 'bin', 'console'), ['--site', 'sim', '--domain', String(DOMAIN),
    '--http-port', String(TOKEN_PORT), '--token', TOKEN, '--set', `simulator_control=127.0.0.1:${VISION_PORT + 1}`],
    { env, stdio: 'ignore' });
  browser = await chromium.launch({
    executablePath: chromiumPath, headless: true,
    args: ['--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run', '--disable-background-networking',
      '--disable-component-update', '--disable-sync'],
  });
  page = await browser.newPage({ viewport: { width: 1280, height: 800 } });
  page.on('pageerror', (error) => console.log(`page error: ${error}`));
  // Both teams' worlds reach the console (the whole stack is up), then the page streams.
  const deadline = Date.now() + 60_000;
  for (;;) {
    try {
      const state = await (await fetch(`${consoleUrl}api/state`)).json();
      const teams = state.frame.teams;
      if (teams.blue?.robots?.length === 12 && teams.yellow?.robots?.length === 12) break;
    } catch {
      // not listening yet
    }
    if (Date.now() > deadline) throw new Error('the console never saw both teams\' worlds with 12 robots');
    await sleep(500);
  }
  await page.goto(consoleUrl);
  await page.waitForFunction(() => window.sslConsole?.frames > 5, null, { timeout: 10_000 });
});

after(async () => {
  await browser?.close();
  tokenConsole?.kill('SIGTERM');
  spawnSync(path.join(root, 'ssl'), ['down', '--domain', String(DOMAIN)], { env, stdio: 'ignore' });
});

test('the page loads and the robots move on the canvas', async () => {
  const canvas = page.locator('canvas#field');
  const first = await canvas.screenshot({ path: path.join(artifacts, 'field-1.png') });
  await sleep(700);
  const second = await canvas.screenshot({ path: path.join(artifacts, 'field-2.png') });
  assert.notDeepEqual(first, second, 'two canvas frames 0.7 s apart are identical');
  const frames = await page.evaluate(() => window.sslConsole.frames);
  assert.ok(frames > 10, `only ${frames} frames streamed`);
  await page.screenshot({ path: path.join(artifacts, 'console.png') });
});

test('a STOP click changes referee.state and the event log shows it', async () => {
  const before = await waitForSample('referee.state', () => true);
  await page.click('[data-command="STOP"]');
  const stopped = await waitForSample('referee.state',
    (state) => state.command === 'COMMAND_STOP' && state.command_counter > before.command_counter, { timeoutS: 5 });
  assert.equal(stopped.command, 'COMMAND_STOP');
  await page.waitForFunction(() => [...document.querySelectorAll('#event-log .log-entry[data-kind="command"]')]
    .some((entry) => entry.querySelector('.txt')?.textContent === 'STOP'), null, { timeout: 5000 });
  await page.screenshot({ path: path.join(artifacts, 'stop.png') });
});

test('robots are drawn where world.state puts them', async () => {
  await page.click('[data-command="HALT"]');
  await waitForSample('referee.state', (state) => state.command === 'COMMAND_HALT', { timeoutS: 5 });
  await sleep(1500);  // robots at rest: the page and sslctl see the same positions
  const world = await waitForSample('world.state', (w) => w.friendly.length === 6, { team: 'blue' });
  const drawn = await page.evaluate(() => window.sslConsole.drawn.filter((item) => item.kind === 'robot' && !item.raw && item.source === 'blue'));
  const sign = world.flipped ? -1 : 1;  // team frame -> vision frame
  for (const robot of world.friendly) {
    const x = sign * robot.pose.x;
    const y = sign * robot.pose.y;
    const match = drawn.find((item) => item.team === 'blue' && item.id === robot.id);
    assert.ok(match, `blue ${robot.id} is not drawn`);
    const error = Math.hypot(match.x - x, match.y - y);
    assert.ok(error < 0.05, `blue ${robot.id} drawn at (${match.x}, ${match.y}), world.state says (${x}, ${y})`);
  }
});

test('dragging the ball moves it in the simulator', async () => {
  const ball = await page.evaluate(() => window.sslConsole.drawn.find((item) => item.kind === 'ball' && !item.raw));
  assert.ok(ball, 'no ball drawn');
  const target = { x: ball.x > 0 ? -1.5 : 1.5, y: -1.0 };
  const box = await page.locator('canvas#field').boundingBox();
  const from = await page.evaluate(([x, y]) => window.sslConsole.toCanvas(x, y), [ball.x, ball.y]);
  const to = await page.evaluate(([x, y]) => window.sslConsole.toCanvas(x, y), [target.x, target.y]);
  await page.mouse.move(box.x + from.x, box.y + from.y);
  await page.mouse.down();
  await page.mouse.move(box.x + (from.x + to.x) / 2, box.y + (from.y + to.y) / 2, { steps: 5 });
  await page.mouse.move(box.x + to.x, box.y + to.y, { steps: 5 });
  await page.mouse.up();
  const seen = await waitForSample('vision.detection', (frame) => frame.balls.some(
    (b) => Math.hypot(b.x - target.x, b.y - target.y) < 0.1), { timeoutS: 5 });
  assert.ok(seen.balls.length > 0);
  await page.screenshot({ path: path.join(artifacts, 'dragged.png') });
});

test('the e-stop button stops every robot, and its release lets them go', async () => {
  await page.click('[data-command="FORCE_START"]');
  await waitForSample('referee.state', (state) => state.command === 'COMMAND_FORCE_START', { timeoutS: 5 });
  const moving = await waitForMotion(0.3);
  assert.ok(moving.speed > 0.3, `nobody moves in play (fastest ${moving.key} at ${moving.speed.toFixed(2)} m/s)`);

  await page.click('#estop');
  await waitForSample('system.estop', (estop) => estop.engaged, { timeoutS: 5 });
  await sleep(1000);  // the links' latch and the robots' braking
  const stopped = fastest(await trackRobots(1.0));
  assert.ok(stopped.speed < 0.02, `${stopped.key} still moves at ${stopped.speed.toFixed(3)} m/s under e-stop`);
  await page.waitForSelector('#estop-release', { state: 'visible', timeout: 5000 });
  await page.screenshot({ path: path.join(artifacts, 'estop.png') });

  await page.click('#estop-release');
  await waitForSample('system.estop', (estop) => !estop.engaged, { timeoutS: 5 });
  const again = await waitForMotion(0.3);
  assert.ok(again.speed > 0.3, `nobody moves after the release (fastest ${again.key} at ${again.speed.toFixed(2)} m/s)`);
});

test('the space bar engages the e-stop and never releases it', async () => {
  await page.locator('canvas#field').click({ position: { x: 5, y: 5 } });  // focus on the page, not an input
  await page.keyboard.press(' ');
  await waitForSample('system.estop', (estop) => estop.engaged, { timeoutS: 5 });
  await page.keyboard.press(' ');
  await sleep(500);
  const state = await waitForSample('system.estop', () => true);
  assert.equal(state.engaged, true, 'a second space released the e-stop');
  await page.click('#estop-release');
  await waitForSample('system.estop', (estop) => !estop.engaged, { timeoutS: 5 });
});

test('a parameter edit reaches the planner, a bad one is refused with the reason, and it saves', async () => {
  const row = page.locator('tr.param-row[data-target="planner/blue"][data-key="planner.limits.max_speed"]');
  await row.waitFor({ timeout: 30_000 });
  await row.locator('.param-value').fill('2.25');
  await row.locator('.param-value').press('Enter');
  await page.waitForFunction(() => document.querySelector(
    'tr.param-row[data-target="planner/blue"][data-key="planner.limits.max_speed"] .param-status')?.textContent?.includes('ok'),
  null, { timeout: 5000 });
  const got = spawnSync(sslctl, ['param', 'get', 'planner/blue', 'planner.limits.max_speed', '--domain', String(DOMAIN)],
    { env, encoding: 'utf8' });
  assert.equal(got.status, 0, got.stderr);
  assert.equal(got.stdout.trim(), '2.25', 'the planner does not report the new value');

  await row.locator('.param-value').fill('99');
  await row.locator('.param-value').press('Enter');
  await page.waitForFunction(() => /out of range/.test(document.querySelector(
    'tr.param-row[data-target="planner/blue"][data-key="planner.limits.max_speed"] .param-status')?.textContent ?? ''),
  null, { timeout: 5000 });
  const kept = spawnSync(sslctl, ['param', 'get', 'planner/blue', 'planner.limits.max_speed', '--domain', String(DOMAIN)],
    { env, encoding: 'utf8' });
  assert.equal(kept.stdout.trim(), '2.25', 'a refused value changed the planner');
  await page.screenshot({ path: path.join(artifacts, 'params.png') });

  await page.click('.param-group[data-target="planner/blue"] .param-save');
  const saved = path.join(paramsDir, 'planner-blue.yaml');
  const deadline = Date.now() + 5000;
  while (!existsSync(saved) && Date.now() < deadline) await sleep(100);
  assert.match(readFileSync(saved, 'utf8'), /max_speed: 2\.25/);
});

test('without the token, operator actions are refused', async () => {
  const guest = await browser.newPage({ viewport: { width: 1280, height: 800 } });
  await guest.goto(`http://127.0.0.1:${TOKEN_PORT}/`);
  await guest.waitForFunction(() => window.sslConsole?.state?.hello, null, { timeout: 10_000 });
  assert.equal(await guest.evaluate(() => window.sslConsole.state.hello.operator), false);
  assert.equal(await guest.locator('[data-command="STOP"]').isDisabled(), true, 'the STOP button is enabled read-only');
  for (const [action, body] of [['referee', { command: 'STOP' }], ['estop', { engaged: true }],
    ['place', { object: 'ball', x: 0, y: 0 }],
    ['params', { target: 'planner/blue', key: 'planner.limits.max_speed', value: '2' }]]) {
    const refused = await guest.request.post(`http://127.0.0.1:${TOKEN_PORT}/api/${action}`, { data: body });
    assert.equal(refused.status(), 403, `/api/${action} without the token answered ${refused.status()}`);
    const wrong = await guest.request.post(`http://127.0.0.1:${TOKEN_PORT}/api/${action}`,
      { data: body, headers: { 'X-Console-Token': 'guess' } });
    assert.equal(wrong.status(), 403, `/api/${action} with a wrong token answered ${wrong.status()}`);
  }
  await guest.screenshot({ path: path.join(artifacts, 'read-only.png') });

  const operator = await browser.newPage({ viewport: { width: 1280, height: 800 } });
  await operator.goto(`http://127.0.0.1:${TOKEN_PORT}/?token=${TOKEN}`);
  await operator.waitForFunction(() => window.sslConsole?.state?.hello?.operator === true, null, { timeout: 10_000 });
  const before = await waitForSample('referee.state', () => true);
  await operator.click('[data-command="STOP"]');
  await waitForSample('referee.state',
    (state) => state.command === 'COMMAND_STOP' && state.command_counter > before.command_counter, { timeoutS: 5 });
  await guest.close();
  await operator.close();
  writeFileSync(path.join(artifacts, 'README.txt'), 'Screenshots of tests/browser/console.test.mjs, newest run.\n');
});
