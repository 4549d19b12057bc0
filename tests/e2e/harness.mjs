// Shared set-up for the browser end-to-end specs: serves web/dist, drives
// headless Chromium through playwright-core, and offers helpers that click
// map cells the way a person would (real mouse events on the canvas).
//
// Environment:
//   SERVE_CMD   command that serves web/dist; `{port}` is replaced by a free
//               port (default: `target/release/planlab serve` when that binary
//               has `serve`, else `npx vite preview`).
//   CHROMIUM    browser executable (default /usr/bin/chromium).

import assert from 'node:assert/strict';
import { spawn, spawnSync } from 'node:child_process';
import { createRequire } from 'node:module';
import fs from 'node:fs';
import net from 'node:net';
import os from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

export const REPO = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '../..');
export const WEB = path.join(REPO, 'web');
export const DIST = path.join(WEB, 'dist');
// Real map files (Moving AI, TurtleBot3) kept in the repository.
export const DATA = path.join(REPO, 'tests/data');
export const SCREENSHOTS = path.join(REPO, 'tests/e2e/screenshots');

// playwright-core is a devDependency of web/, not of the repo root.
const require = createRequire(path.join(WEB, 'package.json'));
const { chromium } = require('playwright-core');

export const CHROME_ARGS = [
  '--headless=new',
  '--no-sandbox',
  '--disable-gpu',
  '--disable-dev-shm-usage',
  '--disable-background-networking',
  '--disable-component-update',
  '--disable-sync',
  '--no-first-run',
];

/** A free TCP port on 127.0.0.1. */
export async function freePort() {
  return new Promise((resolve, reject) => {
    const srv = net.createServer();
    srv.unref();
    srv.on('error', reject);
    srv.listen(0, '127.0.0.1', () => {
      const { port } = srv.address();
      srv.close(() => resolve(port));
    });
  });
}

function serveCommand(port) {
  if (process.env.SERVE_CMD) {
    return { cmd: process.env.SERVE_CMD.replaceAll('{port}', String(port)), cwd: REPO, shell: true };
  }
  const bin = path.join(REPO, 'target/release/planlab');
  if (fs.existsSync(bin)) {
    const help = spawnSync(bin, ['serve', '--help'], { encoding: 'utf8', timeout: 10_000 });
    if (help.status === 0) {
      return {
        cmd: bin,
        args: ['serve', '--dir', DIST, '--port', String(port), '--host', '127.0.0.1'],
        cwd: REPO,
      };
    }
  }
  return {
    cmd: path.join(WEB, 'node_modules/.bin/vite'),
    args: ['preview', '--port', String(port), '--strictPort', '--host', '127.0.0.1'],
    cwd: WEB,
  };
}

/** Waits until `url` answers 200, failing if `child` (the server) exits. */
export async function waitForHttp(url, child, timeoutMs = 30_000) {
  const deadline = Date.now() + timeoutMs;
  let last = '';
  while (Date.now() < deadline) {
    if (child.exitCode !== null) throw new Error(`server exited with code ${child.exitCode}`);
    try {
      const r = await fetch(url);
      if (r.ok) return;
      last = `HTTP ${r.status}`;
    } catch (e) {
      last = e.message;
    }
    await new Promise((r) => setTimeout(r, 150));
  }
  throw new Error(`server at ${url} did not come up: ${last}`);
}

/** Starts the static server and headless Chromium; `close()` stops both. */
export async function startSession() {
  if (!fs.existsSync(path.join(DIST, 'index.html'))) {
    throw new Error('web/dist is missing: run `npm --prefix web run build:wasm && npm --prefix web run build` first');
  }
  const port = await freePort();
  const sc = serveCommand(port);
  process.stderr.write(`serving web/dist: ${[sc.cmd, ...(sc.args ?? [])].join(' ')}\n`);
  const child = spawn(sc.cmd, sc.args ?? [], {
    cwd: sc.cwd,
    shell: sc.shell ?? false,
    stdio: ['ignore', 'pipe', 'pipe'],
  });
  let serverLog = '';
  child.stdout.on('data', (d) => (serverLog += d));
  child.stderr.on('data', (d) => (serverLog += d));
  const base = `http://127.0.0.1:${port}/`;
  try {
    await waitForHttp(base, child);
  } catch (e) {
    child.kill();
    throw new Error(`${e.message}\n${serverLog}`);
  }
  const userDir = fs.mkdtempSync(path.join(os.tmpdir(), 'planlab-e2e-'));
  const context = await chromium.launchPersistentContext(userDir, {
    executablePath: process.env.CHROMIUM || '/usr/bin/chromium',
    headless: true,
    args: CHROME_ARGS,
    viewport: { width: 1440, height: 900 },
    deviceScaleFactor: 1,
  });
  return {
    base,
    context,
    async close() {
      await context.close().catch(() => {});
      child.kill();
      fs.rmSync(userDir, { recursive: true, force: true });
    },
  };
}

/** A new page whose console errors and page errors collect in `problems`
 *  (which must stay empty). */
export async function watchedPage(session) {
  const page = await session.context.newPage();
  const problems = [];
  page.on('console', (m) => {
    if (m.type() === 'error') problems.push(`console.error: ${m.text()}`);
  });
  page.on('pageerror', (e) => problems.push(`pageerror: ${e.message}`));
  return { page, problems };
}

/**
 * Opens the playground and records console errors and page errors; the
 * returned `problems` array must stay empty.
 */
export async function openPage(session, query = '') {
  const { page, problems } = await watchedPage(session);
  await page.goto(session.base + query);
  await page.waitForFunction(() => Number(document.body.dataset.planSeq) > 0, null, { timeout: 30_000 });
  return { page, problems };
}

/** Opens the robot page at `url` (relative to the site), waits until its
 *  episode is built, and checks it shows no error; `problems` collects
 *  console errors and page errors. */
export async function openRobotPage(session, url) {
  const { page, problems } = await watchedPage(session);
  await page.goto(session.base + url);
  await page.waitForFunction(() => ['ready', 'error'].includes(document.body.dataset.state), null, { timeout: 30_000 });
  assert.equal(await errorText(page), null, 'no error after loading');
  return { page, problems };
}

export function screenshot(page, name) {
  fs.mkdirSync(SCREENSHOTS, { recursive: true });
  return page.screenshot({ path: path.join(SCREENSHOTS, name) });
}

/** Client (viewport) coordinates of a cell centre, from the canvas view. */
export async function cellPoint(page, col, row) {
  // Let pending layout (an error box appearing resizes the canvas) and the
  // view update settle first.
  await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));
  return page.evaluate(
    ([c, r]) => {
      const cv = document.getElementById('map-canvas');
      const rect = cv.getBoundingClientRect();
      const s = Number(cv.dataset.scale);
      return {
        x: rect.left + Number(cv.dataset.offsetX) + (c + 0.5) * s,
        y: rect.top + Number(cv.dataset.offsetY) + (r + 0.5) * s,
      };
    },
    [col, row],
  );
}

export const planSeq = (page) => page.evaluate(() => Number(document.body.dataset.planSeq));

/** Runs `action` and waits until the page has re-planned after it. */
export async function afterReplan(page, action) {
  const before = await planSeq(page);
  await action();
  await page.waitForFunction((s) => Number(document.body.dataset.planSeq) > s, before, { timeout: 15_000 });
}

export async function clickCell(page, col, row, opts = {}) {
  const { x, y } = await cellPoint(page, col, row);
  await afterReplan(page, () => page.mouse.click(x, y, opts));
}

export async function chooseTool(page, tool) {
  await page.click(`#tool-${tool}`);
}

export async function setEndpoints(page, start, goal) {
  await chooseTool(page, 'start');
  await clickCell(page, start[0], start[1]);
  await chooseTool(page, 'goal');
  await clickCell(page, goal[0], goal[1]);
}

/**
 * Drags the pointer from one cell to another with the current tool. A stroke
 * re-plans in the next animation frame when it changed a cell (painting over
 * walls changes nothing), so this waits two frames after releasing.
 */
export async function dragCells(page, from, to, steps = 20) {
  const a = await cellPoint(page, from[0], from[1]);
  const b = await cellPoint(page, to[0], to[1]);
  await page.mouse.move(a.x, a.y);
  await page.mouse.down();
  await page.mouse.move(b.x, b.y, { steps });
  await page.mouse.up();
  await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));
}

export async function metric(page, name) {
  const v = await page.getAttribute(`#metric-${name}`, 'data-value');
  return v === null ? null : Number(v);
}

export async function pathCells(page) {
  const s = await page.getAttribute('#map-canvas', 'data-path');
  if (!s) return [];
  const n = s.split(',').map(Number);
  const out = [];
  for (let i = 0; i + 1 < n.length; i += 2) out.push([n[i], n[i + 1]]);
  return out;
}

/** RGBA of the canvas pixel under a cell centre. */
export async function pixelAt(page, col, row) {
  const { x, y } = await cellPoint(page, col, row);
  return page.evaluate(
    ([px, py]) => {
      const cv = document.getElementById('map-canvas');
      const rect = cv.getBoundingClientRect();
      const k = cv.width / rect.width;
      const ctx = cv.getContext('2d');
      return Array.from(ctx.getImageData(Math.floor((px - rect.left) * k), Math.floor((py - rect.top) * k), 1, 1).data);
    },
    [x, y],
  );
}

export async function errorText(page) {
  const hidden = await page.getAttribute('#error', 'hidden');
  if (hidden !== null) return null;
  return page.textContent('#error');
}

/** Rows of a Moving AI .scen as {start, goal, optimal}. */
export function readScen(file) {
  return fs
    .readFileSync(file, 'utf8')
    .split('\n')
    .slice(1)
    .filter((l) => l.trim())
    .map((l) => {
      const f = l.trim().split(/\s+/);
      return { start: [Number(f[4]), Number(f[5])], goal: [Number(f[6]), Number(f[7])], optimal: Number(f[8]) };
    });
}
