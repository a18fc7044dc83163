// What the browser test and the editor's latency benchmark share: a `shoremesh serve` process, Debian's
// Chromium in headless mode through puppeteer-core (from the build's web/node_modules), and a mouse drag
// of a shore point.
'use strict';
const fs = require('fs');
const path = require('path');
const { spawn } = require('child_process');

const env = {
  binary: process.env.SHOREMESH_BINARY,
  modules: process.env.SHOREMESH_NODE_MODULES,
  chromium: process.env.SHOREMESH_CHROMIUM,
  samples: process.env.SHOREMESH_SAMPLES_DIR,
};

// Chromium, or a clear failure (a skip only when SHOREMESH_SKIP_BROWSER_TEST asks for it).
function requireChromium() {
  if (env.chromium && fs.existsSync(env.chromium)) return;
  if (process.env.SHOREMESH_SKIP_BROWSER_TEST) {
    console.log('browser test skipped: no Chromium, and SHOREMESH_SKIP_BROWSER_TEST is set');
    process.exit(0);
  }
  console.error("no Chromium found (Debian's chromium: scripts/install-deps.sh installs it; " +
                'SHOREMESH_SKIP_BROWSER_TEST=1 skips this test)');
  process.exit(1);
}

// Starts `shoremesh serve ARGS` in `dir` (another build's binary if given); resolves to {url, child} once it
// prints its URL.
function startServer(args, dir, binary = env.binary) {
  return new Promise((resolve, reject) => {
    const child = spawn(binary, ['serve', ...args], { cwd: dir, stdio: ['ignore', 'pipe', 'pipe'] });
    let out = '', err = '';
    child.stdout.on('data', (d) => {
      out += d;
      const m = out.match(/serving (http:\/\/\S+)/);
      if (m) resolve({ url: m[1], child, log: () => out });
    });
    child.stderr.on('data', (d) => { err += d; });
    child.on('exit', (code) => reject(new Error(`shoremesh serve exited (${code}): ${err}`)));
  });
}

async function launch() {
  const puppeteer = require(path.join(env.modules, 'puppeteer-core'));
  return puppeteer.launch({
    executablePath: env.chromium,
    headless: true,
    // WebGL on the CPU (SwiftShader): CI machines have no GPU.
    args: ['--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--window-size=1000,700'],
    defaultViewport: { width: 1000, height: 700 },
  });
}

async function openEditor(browser, url) {
  const page = await browser.newPage();
  const problems = [];
  page.on('pageerror', (e) => problems.push(e.message));
  await page.goto(url);
  await page.waitForFunction(() => window.shoremesh && window.shoremesh.ready && window.shoremesh.frames > 0,
                             { timeout: 120000 });
  return { page, problems };
}

// Drags shore point number `k` of ring 0 (in ring order) a tenth of the way to its neighbours' chord's
// normal, with the mouse (in `steps` pointer moves, `pause` ms apart: the page moves the point on the
// server while the mouse moves), and waits for the page to show the edit's answer. Resolves to the page's
// record of the edit (line, ok, serverMs, roundTripMs, frameMs: from the release, reply).
async function dragShorePoint(page, k, sign = 1, { steps = 6, pause = 0 } = {}) {
  const plan = await page.evaluate(async (k, sign) => {
    const s = window.shoremesh;
    const ring = [...s.verts.entries()].filter(([, v]) => v.ring === 0);
    const [id, v] = ring[k % ring.length];
    const a = s.verts.get(v.prev), b = s.verts.get(v.next);
    const gap = Math.min(Math.hypot(a.x - v.x, a.y - v.y), Math.hypot(b.x - v.x, b.y - v.y));
    await s.zoomTo(id, gap / 150);  // neighbours about 150 pixels away
    const [sx, sy] = s.screenOf(id);
    const tx = b.x - a.x, ty = b.y - a.y, len = Math.hypot(tx, ty);
    const edits = s.edits;
    return { id, sx, sy, dx: (-ty / len) * 15 * sign, dy: -(tx / len) * 15 * sign, edits };
  }, k, sign);
  await page.mouse.move(plan.sx, plan.sy);
  await page.mouse.down();
  for (let i = 1; i <= steps; ++i) {
    await page.mouse.move(plan.sx + (plan.dx * i) / steps, plan.sy + (plan.dy * i) / steps);
    if (pause) await new Promise((r) => setTimeout(r, pause));
  }
  await page.mouse.up();
  // (A final move answered from the event stream has its POST's profile filled in when the answer comes.)
  await page.waitForFunction((n) => !window.shoremesh.dragging && window.shoremesh.last &&
                             window.shoremesh.last.line.startsWith('move') &&
                             (window.shoremesh.edits > n || !window.shoremesh.last.ok) &&
                             !(window.shoremesh.last.profile && window.shoremesh.last.profile.pending), { timeout: 120000 }, plan.edits);
  return { id: plan.id, ...(await page.evaluate(() => window.shoremesh.last)) };
}

async function post(url, body) {
  const res = await fetch(new URL('edit?replies=lines', url), { method: 'POST', body });
  return (await res.text()).trim().split('\n').map((l) => JSON.parse(l));
}

const median = (xs) => { const s = [...xs].sort((a, b) => a - b); return s[Math.floor(s.length / 2)]; };
const quantile = (xs, q) => { const s = [...xs].sort((a, b) => a - b); return s[Math.min(s.length - 1, Math.floor(q * s.length))]; };

module.exports = { env, requireChromium, startServer, launch, openEditor, dragShorePoint, post, median, quantile };
