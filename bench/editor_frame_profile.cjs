// Where the editor's frame time goes: one frame drawn and read back (a pixel), median of 8, with layers
// switched off one by one, zoomed in on a shore point (its neighbour 150 pixels away) and with the whole
// mesh in view; three.js's counts of what it drew beside each.
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
      const measure = async (name) => {
        const t = [];
        for (let i = 0; i < 8; ++i) t.push(await s.profileFrame());
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
      await s.fit();
      for (const [name, layers] of [['fit: all', {}], ['fit: no dots/lines', { dots: false }], ['fit: triangles only', { dots: false, corners: false }], ['fit: nothing', { dots: false, corners: false, triangles: false }]]) {
        s.layers(layers); await measure(name);
      }
      return out;
    });
    console.log(JSON.stringify(r, null, 1));
  } finally { await browser.close(); server.child.kill('SIGTERM'); }
})();
