// The browser editor's edit latency as the page sees it, and its frame time while panning: N mouse drags of
// shore points in headless Chromium (the mesh moving while dragging), each timed by the page from the
// mouse release to the frame drawn after the final move's answer, with where that time went (the page's
// profile: Resource Timing of the POST with the server's Server-Timing header, JSON.parse, the buffer
// writes, the wait for the animation frame, three.js's render and, frames being drawn to the end here
// (state.syncFrames: a pixel read back), the rasterizing). Then 60 pan frames (each 7 pixels on), zoomed
// in as the drags are and with the whole mesh in view, timed between frames, with the draw calls and
// triangles/points/segments given to WebGL per frame (which do not depend on the machine).
//
// The drags alternate between columns, each a page on its own server seeing the same load and dragging the
// same shore points: "this page" (its defaults: an edit's rectangles drawn from the grid of slots, the
// mesh redrawn while dragging, the final move posted at the release and drawn when it comes); with
// SHOREMESH_PEER_BINARY (another build of `shoremesh`, e.g. main's), "peer" (that binary's page, its
// defaults); with SHOREMESH_BENCH_ABLATE=overlay also this page with the drag drawn on a 2D overlay and
// the mesh's frames held (state.fast.overlay), =frames this page with the overlay off, =chunks this page
// without the grid or the overlay (the way of drawing before the grid), or a list (=overlay,chunks).
// Then, on this page, pans with every frame drawn in full and with partial frames, and the same moves
// posted from Node.
//
//   SHOREMESH_BINARY=$PWD/build/tool/shoremesh SHOREMESH_NODE_MODULES=$PWD/build/web/node_modules \
//   SHOREMESH_CHROMIUM=/usr/bin/chromium [SHOREMESH_PEER_BINARY=/other/build/tool/shoremesh] \
//   node bench/editor_latency.cjs N INPUT [serve options...]
// N drags per column. SHOREMESH_BENCH_DRAGS_ONLY=1 stops after the drags.
'use strict';
const fs = require('fs');
const os = require('os');
const path = require('path');
const h = require('../tests/browser/editor_harness.cjs');

const modes = { full: { partial: false, scroll: false, index: false, overlay: false },
                partial: { partial: true, scroll: true, index: true } };
const fmt = (x) => (x === undefined || Number.isNaN(x) ? '-' : x.toFixed(x < 10 ? 2 : 1));
const stat = (xs) => {
  const v = xs.filter((x) => typeof x === 'number' && isFinite(x));
  return v.length ? `${fmt(h.median(v))} (${fmt(h.quantile(v, 0.95))})` : '-';
};

async function main() {
  const [n, ...serveArgs] = process.argv.slice(2);
  if (!n || !serveArgs.length) throw new Error('usage: editor_latency.cjs N INPUT [serve options...]');
  h.requireChromium();
  const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'shoremesh_latency_'));
  const t0 = Date.now();
  const args = serveArgs.map((a) => (fs.existsSync(a) ? path.resolve(a) : a));
  const server = await h.startServer(args, dir);
  const built = Date.now();
  const peerBinary = process.env.SHOREMESH_PEER_BINARY;
  const peer = peerBinary ? await h.startServer(args, dir, peerBinary) : null;
  const browser = await h.launch();
  try {
    const opened = Date.now();
    const { page } = await h.openEditor(browser, server.url);
    const loaded = Date.now();
    const info = await page.evaluate(() => ({ triangles: window.shoremesh.triangles, points: window.shoremesh.verts.size,
                                              renderer: window.shoremesh.renderer, fast: window.shoremesh.fast }));
    console.log(`server built in ${((built - t0) / 1000).toFixed(1)} s; page loaded ${info.triangles} triangles and ` +
                `${info.points} input points in ${((loaded - opened) / 1000).toFixed(1)} s; WebGL: ${info.renderer}; ` +
                `this page's defaults ${JSON.stringify(info.fast)}`);
    const columns = [{ name: 'this page', page, fast: null }];
    if (peer) columns.unshift({ name: `peer (${path.basename(path.dirname(path.dirname(path.dirname(peerBinary))))})`, page: (await h.openEditor(browser, peer.url)).page, fast: null });
    // Each on a server of its own: a page draws the changes of its session only.
    const ablate = (process.env.SHOREMESH_BENCH_ABLATE || '').split(',').filter(Boolean);
    const variants = { frames: ['this page, mesh frames while dragging (no overlay)', { overlay: false }],
                       overlay: ['this page, drag on the overlay, mesh frames held (?overlay=1)', { overlay: true }],
                       chunks: ['this page, chunks (no grid, no overlay)', { index: false, overlay: false }] };
    for (const k of ablate) {
      if (!variants[k]) throw new Error(`SHOREMESH_BENCH_ABLATE: ${k}? (frames, overlay, chunks)`);
      const other = await h.startServer(args, dir);
      columns.push({ name: variants[k][0], page: (await h.openEditor(browser, other.url)).page, fast: variants[k][1], server: other });
    }
    for (const c of columns) {
      await c.page.evaluate((f) => { window.shoremesh.syncFrames = true; if (f) Object.assign(window.shoremesh.fast, f); }, c.fast);
      c.rows = [];
    }
    // Only the dragged page draws: the others are idle (no frames; their rAF callbacks do nothing). The
    // columns take turns in blocks of SHOREMESH_BENCH_BLOCK drags (5): within a block the drags follow one
    // another as a single page's do, so that the page's summary (GET /stats, asked for once the edits have
    // paused for a second, O(mesh): under the session's lock on main, on a session of its own here, where it
    // still takes CPU from the drags) is not computed at every drag's start.
    const block = Number(process.env.SHOREMESH_BENCH_BLOCK || 5);
    let refused = 0;
    for (let i0 = 0; i0 < Number(n); i0 += block) {
      for (const c of columns) {
        await c.page.bringToFront();
        for (let i = i0; i < Math.min(Number(n), i0 + block); ++i) {
          const e = await h.dragShorePoint(c.page, 101 + i * 997, i % 2 ? 1 : -1);
          if (!e.ok) { ++refused; continue; }
          c.rows.push(e);
        }
      }
    }
    const live = await Promise.all(columns.map((c) => c.page.evaluate(() => window.shoremesh.liveMoves)));
    console.log(`${columns.reduce((k, c) => k + c.rows.length, 0)} drags accepted, ${refused} refused; ` +
                `moves sent while dragging: ${live.join(', ')}`);
    const odd = await Promise.all(columns.map((c) => c.page.evaluate(() => {
      const s = window.shoremesh;
      return `changes that came ahead ${s.changesAhead ?? '-'}, mesh reloads ${s.reloads ?? '-'}, final moves sent again ${s.finalResent ?? '-'}`;
    })));
    columns.forEach((c, i) => console.log(`${c.name}: ${odd[i]}`));
    console.log('medians (p95) in ms; the split is of the final move\'s POST, sent after the release or (some drags) while dragging');
    const split = [
      ['**release to the updated frame** (the page\'s answer to the final move shown: the animation frame after the POST\'s answer, or after the change by the event stream when that came first; frames drawn to the end)', (r) => r.frameMs],
      ['**release to the end of the change\'s own frame** (the mesh updated; < 0: before the release)', (r) => r.profile.changeFrame],
      ['  the change applied, from the release (POST answer or event stream)', (r) => r.profile.changeApplied],
      ['**server: edit `ms`** (engine + mesh)', (r) => r.serverMs],
      ['**final POST round trip** (page)', (r) => r.profile.answerMs ?? r.roundTripMs],
      ['  the page answered from the event stream\'s change, from the release\'s POST', (r) => (r.profile.answerMs !== undefined ? r.roundTripMs : undefined)],
      ['  the final move posted, from the release (< 0: before it, while dragging)', (r) => r.profile.since],
      ['  server: request total', (r) => r.profile.server],
      ['    waiting for the session lock', (r) => r.profile.lock],
      ['    edit + slot bookkeeping', (r) => r.profile.edit],
      ['    JSON of the answer', (r) => r.profile.json],
      ['  network/queue to first byte', (r) => r.profile.network],
      ['  download', (r) => r.profile.download],
      ['  JSON.parse', (r) => r.profile.parse],
      ['  apply (slots, buffers)', (r) => r.profile.apply],
      ['  applied to the change\'s frame: wait for the animation frame', (r) => r.profile.waitFrame],
      ['  render (three.js calls, grid queries)', (r) => r.profile.render],
      ['  **raster of the change\'s frame** (to the end of the frame)', (r) => r.profile.raster],
      ['answer bytes', (r) => r.profile.bytes],
      ['frame: draw calls', (r) => r.profile.drawn?.calls],
      ['frame: triangles given to WebGL', (r) => r.profile.drawn?.triangles],
      ['frame: points', (r) => r.profile.drawn?.points],
      ['frame: pixels drawn', (r) => r.profile.drawn?.pixels],
    ];
    const posted = (xs) => xs.filter((r) => r.profile && r.profile.server !== undefined);
    const after = (xs) => xs.filter((r) => r.profile && r.profile.since >= 0).length;
    console.log(`| | ${columns.map((c) => `${c.name} (${c.rows.length}; ${after(c.rows)} posted after the release)`).join(' | ')} |`);
    console.log(`|---|${columns.map(() => '---|').join('')}`);
    for (const [name, f] of split) {
      const pick = (xs) => (name.startsWith(' ') || name.startsWith('answer') || name.startsWith('frame:') ? posted(xs) : xs).map(f);
      console.log(`| ${name} | ${columns.map((c) => stat(pick(c.rows))).join(' | ')} |`);
    }
    const hows = (xs) => Object.entries(xs.reduce((m, r) => { const k = r.profile.drawn?.how ?? '?'; m[k] = (m[k] || 0) + 1; return m; }, {}))
      .map(([k, v]) => `${k} ${v}`).join(', ');
    console.log(`| the change's frame | ${columns.map((c) => hows(c.rows)).join(' | ')} |`);
    const vias = (xs) => `${xs.filter((r) => r.profile.via === 'events').length} by the event stream first`;
    console.log(`| the change came | ${columns.map((c) => vias(c.rows)).join(' | ')} |`);
    const q = (xs, f) => { const v = xs.map(f).filter((x) => typeof x === 'number' && isFinite(x)); return `median ${fmt(h.median(v))}, p95 ${fmt(h.quantile(v, 0.95))}`; };
    for (const c of columns) {
      console.log(`${c.name}: release to the updated frame ${q(c.rows, (r) => r.frameMs)}; to the change's frame ` +
                  `${q(c.rows, (r) => r.profile.changeFrame)} (targets: median 50, p95 100); server edit ${q(c.rows, (r) => r.serverMs)}; ` +
                  `final POST round trip ${q(c.rows, (r) => r.profile.answerMs ?? r.roundTripMs)}; raster of the change's frame ${q(c.rows.filter((r) => r.profile.raster !== undefined), (r) => r.profile.raster)}`);
    }
    const ratio = (xs, ys) => (h.median(xs.map((r) => r.frameMs)) / h.median(ys.map((r) => r.frameMs))).toFixed(2);
    if (peer) console.log(`release to frame, median: ${columns[0].name} / this page = ${ratio(columns[0].rows, columns[1].rows)}`);
    for (const c of columns) if (c.page !== page) await c.page.close();
    if (peer) peer.child.kill('SIGTERM');
    for (const c of columns) if (c.server) c.server.child.kill('SIGTERM');
    await page.bringToFront();
    const stats = [];
    for (let i = 0; i < 5; ++i) { const t = performance.now(); await h.post(server.url, 'stats'); stats.push(performance.now() - t); }
    console.log(`the stats line (posted from Node; O(mesh) under the session's lock: an edit arriving meanwhile waits): ${stat(stats)}`);
    const got = [];
    for (let i = 0; i < 5; ++i) {
      const t = performance.now();
      await (await fetch(new URL('stats', server.url))).json();
      got.push(performance.now() - t);
    }
    console.log(`the page's summary (GET /stats from Node: on the summary's own session, edits go on meanwhile): ${stat(got)}`);
    if (process.env.SHOREMESH_BENCH_DRAGS_ONLY) { await browser.close(); return; }
    // Panning: frames drawn back to back, each after the view moved 7 pixels (the time between them is what
    // the page can draw: Chromium paces requestAnimationFrame to the compositor), each drawn to the end.
    const pan = (n, mode) => page.evaluate(async (n, m) => {
      const s = window.shoremesh;
      Object.assign(s.fast, m);
      await s.redrawAll();
      const times = [], drawn = [];
      let t = performance.now();
      for (let i = 0; i < n; ++i) {
        const t1 = await s.pan(i % 40 < 20 ? 7 : -7, 0);
        times.push(t1 - t);
        drawn.push(s.drawn);
        t = t1;
      }
      return { times, drawn };
    }, n, modes[mode]);
    const panRow = (name, r) => {
      const d = r.drawn.filter(Boolean);
      console.log(`| ${name} | ${stat(r.times)} | ${stat(d.map((x) => x.calls))} | ${stat(d.map((x) => x.triangles))} | ` +
                  `${stat(d.map((x) => x.points))} | ${stat(d.map((x) => x.lines))} | ${[...new Set(d.map((x) => x.how))].join(', ')} |`);
    };
    console.log('\n| frame | ms | draw calls | triangles | points | line segments | how |\n|---|---|---|---|---|---|---|');
    for (const mode of ['full', 'partial']) panRow(`zoomed in, ${mode}`, await pan(60, mode));
    await page.evaluate(() => window.shoremesh.fit());
    for (const mode of ['full', 'partial']) panRow(`all ${info.triangles} triangles in view, ${mode}`, await pan(60, mode));
    // Twice as close: the mesh fills the view, so that every uncovered strip meets it.
    await page.evaluate(async () => { await window.shoremesh.fit(); await window.shoremesh.zoomTo(null, 0.5); });
    for (const mode of ['full', 'partial']) panRow(`twice as close as the whole mesh, ${mode}`, await pan(60, mode));
    // Zooming with the wheel at the whole mesh: 30 steps in and out, back to back; then, for the partial
    // page, the full frame drawn once the wheel rests (its scaled previews before).
    const zoomRun = (n, mode) => page.evaluate(async (n, m) => {
      const s = window.shoremesh;
      Object.assign(s.fast, m);
      await s.fit();
      const times = [], drawn = [];
      let t = performance.now();
      for (let i = 0; i < n; ++i) {
        const t1 = await s.zoom(i % 10 < 5 ? 0.9 : 1 / 0.9);
        times.push(t1 - t);
        drawn.push(s.drawn);
        t = t1;
      }
      await new Promise((r) => setTimeout(r, s.zoomRest + 50));
      await s.nextFrame();  // the full frame was drawn when the wheel had rested: its own time
      return { times, drawn, rest: { ms: s.frameTiming.renderMs + s.frameTiming.rasterMs, drawn: s.drawn } };
    }, n, modes[mode]);
    for (const mode of ['full', 'partial']) {
      const r = await zoomRun(30, mode);
      panRow(`wheel zoom, whole mesh, ${mode}`, r);
      if (mode === 'partial') panRow('  the full frame once the wheel rests', { times: [r.rest.ms], drawn: [r.rest.drawn] });
    }
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
    console.log(`\nPOST round trip from Node (no page): ${stat(direct)}`);

  } finally {
    if (browser.connected) await browser.close();
    server.child.kill('SIGTERM');
    fs.rmSync(dir, { recursive: true, force: true });
  }
}

main().catch((e) => { console.error(e.stack || String(e)); process.exit(1); });
