// Where the editor's frame time goes: one frame drawn and read back (a pixel), median of 8, with layers
// switched off one by one, zoomed in on a shore point (its neighbour 150 pixels away) and with the whole
// mesh in view; zoomed in, the grid's pick against every chunk in view, over the whole view and scissored
// squares, and a clear alone; three.js's counts of what it drew beside each.
//
//   SHOREMESH_BINARY=build/tool/shoremesh SHOREMESH_NODE_MODULES=build/web/node_modules \
//   SHOREMESH_CHROMIUM=/usr/bin/chromium node bench/editor_frame_profile.cjs INPUT [serve options...]
'use strict';
const fs = require('fs');
const os = require('os');
const path = require('path');
const h = require('../tests/browser/editor_harness.cjs');
(async () => {
  const args = process.argv.slice(2).map((a) => (fs.existsSync(a) ? path.resolve(a) : a));
  if (!args.length) throw new Error('usage: editor_frame_profile.cjs INPUT [serve options...]');
  h.requireChromium();
  const server = await h.startServer(args, os.tmpdir());
  const browser = await h.launch();
  try {
    const { page } = await h.openEditor(browser, server.url);
    const r = await page.evaluate(async () => {
      const s = window.shoremesh;
      const out = {};
      const measure = async (name, opts) => {
        const t = [];
        for (let i = 0; i < 8; ++i) t.push(await s.profileFrame(opts));
        t.sort((a, b) => a - b);
        out[name] = t[4].toFixed(1) + ' ' + JSON.stringify(s.drawn);
      };
      const ring = [...s.verts.entries()].filter(([, v]) => v.ring === 0);
      const [id, v] = ring[5000 % ring.length];
      const a = s.verts.get(v.prev);
      await s.zoomTo(id, Math.hypot(a.x - v.x, a.y - v.y) / 150);
      for (const [name, layers] of [['zoomed: all', {}], ['zoomed: no dots/lines', { dots: false }], ['zoomed: triangles only', { dots: false, corners: false }]]) {
        s.layers(layers); await measure(name);
      }
      s.layers({});
      // The drawing paths of an edit's frame at this zoom: every chunk in view, the grid's pick of the view,
      // of a 300 px square and of a 30 px one, and a clear alone (what a frame costs beyond its primitives:
      // the pixels).
      const w = 675, h = 700;
      await measure('zoomed: grid, whole view', { how: 'grid' });
      await measure('zoomed: clear, whole view', { how: 'clear' });
      await measure('zoomed: chunks, 300 px square', { how: 'chunks', rect: [w / 2 - 150, h / 2 - 150, 300, 300] });
      await measure('zoomed: grid, 300 px square', { how: 'grid', rect: [w / 2 - 150, h / 2 - 150, 300, 300] });
      await measure('zoomed: clear, 300 px square', { how: 'clear', rect: [w / 2 - 150, h / 2 - 150, 300, 300] });
      await measure('zoomed: grid, 30 px square', { how: 'grid', rect: [w / 2 - 15, h / 2 - 15, 30, 30] });
      await measure('zoomed: clear, 30 px square', { how: 'clear', rect: [w / 2 - 15, h / 2 - 15, 30, 30] });
      await s.fit();
      for (const [name, layers] of [['fit: all', {}], ['fit: no dots/lines', { dots: false }], ['fit: triangles only', { dots: false, corners: false }], ['fit: nothing', { dots: false, corners: false, triangles: false }]]) {
        s.layers(layers); await measure(name);
      }
      return out;
    });
    console.log(JSON.stringify(r, null, 1));
  } finally { await browser.close(); server.child.kill('SIGTERM'); }
})();
