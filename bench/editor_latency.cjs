// The browser editor's edit latency as the page sees it: N mouse drags of shore points in headless
// Chromium (the mesh moving while dragging), each timed by the page from the mouse release to the frame
// drawn after the final move's answer; the final POST's round trip and the server's own time (the edit's
// `ms`) beside them. Then the frame time while panning (60 frames, each a few pixels on): zoomed in as the
// drags are, and with the whole mesh in view. Medians and 95th percentiles.
//
//   SHOREMESH_BINARY=build/tool/shoremesh SHOREMESH_NODE_MODULES=build/web/node_modules \
//   SHOREMESH_CHROMIUM=/usr/bin/chromium node bench/editor_latency.cjs N INPUT [serve options...]
// Then N edits posted from Node with the browser closed, for the server's share of the round trip.
'use strict';
const fs = require('fs');
const os = require('os');
const path = require('path');
const h = require('../tests/browser/editor_harness.cjs');

async function main() {
  const [n, ...serveArgs] = process.argv.slice(2);
  if (!n || !serveArgs.length) throw new Error('usage: editor_latency.cjs N INPUT [serve options...]');
  h.requireChromium();
  const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'shoremesh_latency_'));
  const t0 = Date.now();
  const server = await h.startServer(serveArgs.map((a) => (fs.existsSync(a) ? path.resolve(a) : a)), dir);
  const built = Date.now();
  const browser = await h.launch();
  try {
    const { page } = await h.openEditor(browser, server.url);
    const loaded = Date.now();
    const info = await page.evaluate(() => ({ triangles: window.shoremesh.triangles, points: window.shoremesh.verts.size }));
    console.log(`server built in ${((built - t0) / 1000).toFixed(1)} s; page loaded ${info.triangles} triangles and ` +
                `${info.points} input points in ${((loaded - built) / 1000).toFixed(1)} s`);
    const rows = [];
    let refused = 0;
    for (let i = 0; i < Number(n); ++i) {
      const e = await h.dragShorePoint(page, 101 + i * 997, i % 2 ? 1 : -1);
      if (!e.ok) { ++refused; continue; }
      rows.push(e);
    }
    const show = (name, xs) => console.log(`${name}: median ${h.median(xs).toFixed(2)} ms, p95 ${h.quantile(xs, 0.95).toFixed(2)} ms`);
    console.log(`${rows.length} drags accepted, ${refused} refused`);
    show('server (edit ms)', rows.map((r) => r.serverMs));
    show('POST round trip', rows.map((r) => r.roundTripMs));
    show('release to the updated frame', rows.map((r) => r.frameMs));
    console.log(`moves sent while dragging: ${await page.evaluate(() => window.shoremesh.liveMoves)}`);
    // Panning: frames drawn back to back, each after the view moved 7 pixels (the time between them is what
    // the page can draw: Chromium paces requestAnimationFrame to the compositor).
    const pan = (n) => page.evaluate(async (n) => {
      const s = window.shoremesh, times = [];
      let t = performance.now();
      for (let i = 0; i < n; ++i) {
        const t1 = await s.pan(i % 40 < 20 ? 7 : -7, 0);
        times.push(t1 - t);
        t = t1;
      }
      return times;
    }, n);
    show('frame while panning, zoomed in as the drags', await pan(60));
    await page.evaluate(() => window.shoremesh.fit());
    show(`frame while panning, all ${info.triangles} triangles in view`, await pan(60));
    // The same kind of edit posted from here with the browser closed (no page rendering on the same CPUs):
    // the last drag undone and redone.
    const op = await page.evaluate(() => window.shoremesh.undo[window.shoremesh.undo.length - 1].op);
    await browser.close();
    const lines = [`move ${op.id} ${op.from[0]} ${op.from[1]}`, `move ${op.id} ${op.to[0]} ${op.to[1]}`];
    const direct = [];
    for (let i = 0; i < Number(n); ++i) {
      const t = performance.now();
      const [r] = await h.post(server.url, lines[i % 2]);
      if (r.ok) direct.push(performance.now() - t);
    }
    show('POST round trip from Node (no page)', direct);
  } finally {
    if (browser.connected) await browser.close();
    server.child.kill('SIGTERM');
    fs.rmSync(dir, { recursive: true, force: true });
  }
}

main().catch((e) => { console.error(e.stack || String(e)); process.exit(1); });
