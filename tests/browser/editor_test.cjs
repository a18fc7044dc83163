// The browser editor in a real headless Chromium: load the Superior demo, drag a shore point with the
// mouse; the server applied the move, the page redrew only the change and counts the server's triangles,
// the session's export equals a fresh run on the edited shoreline, undo (Ctrl+Z) returns to the original
// export byte for byte, and the canvas shows a drawn mesh.
'use strict';
const assert = require('assert');
const fs = require('fs');
const os = require('os');
const path = require('path');
const { execFileSync } = require('child_process');
const h = require('./editor_harness.cjs');

h.requireChromium();

// An OFF file's triangles as sorted corner texts: a mesh compared by place, whatever its numbering.
function offTriangles(file) {
  const words = fs.readFileSync(file, 'utf8').split(/\s+/).filter(Boolean);
  const points = Number(words[1]), faces = Number(words[2]);
  let at = 4;
  const corner = [];
  for (let i = 0; i < points; ++i, at += 3) corner.push(`${words[at]} ${words[at + 1]}`);
  const tris = [];
  for (let f = 0; f < faces; ++f, at += 4) tris.push([1, 2, 3].map((k) => corner[Number(words[at + k])]).sort().join('|'));
  return tris.sort();
}

async function main() {
  const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'shoremesh_browser_'));
  fs.mkdirSync(path.join(dir, 'out'));
  const image = path.join(h.env.samples, 'superior', 'superior_watermask_h.png');
  const server = await h.startServer([image, '--largest-water', '--spacing', '4000', '--export-dir', 'out'], dir);
  const browser = await h.launch();
  const checks = [];
  const check = (name, fn) => { fn(); checks.push(name); };
  try {
    const { page, problems } = await h.openEditor(browser, server.url);
    const [start] = await h.post(server.url, 'export before.off');
    assert.ok(start.ok, JSON.stringify(start));

    const edit = await h.dragShorePoint(page, 700);
    check('the drag was accepted', () => assert.ok(edit.ok, `refused: ${JSON.stringify(edit.reply)}`));
    check('the drag moved that point', () => assert.ok(edit.line.startsWith(`move ${edit.id} `), edit.line));

    const [stats] = await h.post(server.url, 'stats');
    const page1 = await page.evaluate(() => ({ triangles: window.shoremesh.triangles, redraws: window.shoremesh.redraws,
                                                version: window.shoremesh.version,
                                                shown: document.getElementById('tri-count').textContent }));
    check('the server applied one edit and the page has its version', () => assert.strictEqual(page1.version, 1));
    check('the page redrew the change once', () => assert.strictEqual(page1.redraws, 1));
    check("the page's triangle count is the server's", () => {
      assert.strictEqual(page1.triangles, stats.elements);
      assert.strictEqual(page1.shown.replace(/,/g, ''), String(stats.elements));
    });

    // A fresh run on the exported shoreline, in the session's box: the same triangles as the session.
    const exported = await h.post(server.url, 'export after.rings\nexport after.off');
    assert.ok(exported.every((r) => r.ok), JSON.stringify(exported));
    const box = JSON.parse(execFileSync(h.env.binary, ['edit', image, '--largest-water', '--spacing', '4000', '--json',
                                                       '--edits', '/dev/null']).toString().split('\n')[0]).box;
    execFileSync(h.env.binary, ['mesh', '-q', path.join(dir, 'out', 'after.rings'), '--box', ...box.map(String),
                                '-o', path.join(dir, 'fresh.off')]);
    const fresh = offTriangles(path.join(dir, 'fresh.off'));
    check('the session equals a fresh run on the edited shoreline',
          () => assert.deepStrictEqual(offTriangles(path.join(dir, 'out', 'after.off')), fresh));
    check("the page's triangle count is the fresh run's", () => assert.strictEqual(page1.triangles, fresh.length));

    // The canvas: a drawn mesh, not a blank one (many pixels away from the background colour).
    await page.screenshot({ path: path.join(dir, 'editor.png') });
    const drawn = await page.evaluate(() => {
      const src = document.querySelector('#view canvas');
      const c = document.createElement('canvas');
      c.width = src.width; c.height = src.height;
      const g = c.getContext('2d');
      g.drawImage(src, 0, 0);
      const px = g.getImageData(0, 0, c.width, c.height).data;
      let painted = 0;
      const colours = new Set();
      for (let i = 0; i < px.length; i += 4) {
        if (Math.abs(px[i] - 0xe9) + Math.abs(px[i + 1] - 0xe4) + Math.abs(px[i + 2] - 0xd8) > 30) ++painted;
        colours.add((px[i] >> 4) * 256 + (px[i + 1] >> 4) * 16 + (px[i + 2] >> 4));
      }
      return { painted: painted / (px.length / 4), colours: colours.size };
    });
    check('the canvas shows a drawn mesh', () => {
      assert.ok(drawn.painted > 0.2, `only ${(drawn.painted * 100).toFixed(1)} % of the canvas is drawn`);
      assert.ok(drawn.colours > 20, `${drawn.colours} colours`);
    });

    // Undo with the keyboard: the inverse move, and the original export byte for byte.
    await page.keyboard.down('Control');
    await page.keyboard.press('z');
    await page.keyboard.up('Control');
    await page.waitForFunction(() => window.shoremesh.edits === 2, { timeout: 60000 });
    const undone = await page.evaluate(() => window.shoremesh.last);
    check('undo is the inverse move', () => assert.ok(undone.ok && undone.line.startsWith(`move ${edit.id} `), undone.line));
    await h.post(server.url, 'export undone.off');
    check('undo returns to the original export byte for byte', () =>
      assert.ok(fs.readFileSync(path.join(dir, 'out', 'before.off')).equals(fs.readFileSync(path.join(dir, 'out', 'undone.off')))));

    // Click a shore edge (a point added after its first vertex), select the new point and Delete it, then
    // undo both: the removed point comes back under a new id, and the second undo must find it by that id.
    const edge = await page.evaluate(async () => {
      const s = window.shoremesh;
      const [id, v] = [...s.verts.entries()].filter(([, p]) => p.ring === 0)[500];
      const n = s.verts.get(v.next);
      await s.zoomTo(id, Math.hypot(n.x - v.x, n.y - v.y) / 200);
      const [ax, ay] = s.screenOf(id), [bx, by] = s.screenOf(v.next);
      return { id, x: (ax + bx) / 2, y: (ay + by) / 2 };
    });
    const lines = [];
    const waitEdit = async (n) => {
      await page.waitForFunction((k) => window.shoremesh.edits === k || (window.shoremesh.last && !window.shoremesh.last.ok),
                                 { timeout: 60000 }, n);
      const last = await page.evaluate(() => window.shoremesh.last);
      lines.push(last.line);
      assert.ok(last.ok, `refused: ${last.line}: ${JSON.stringify(last.reply)}`);
      return last;
    };
    await page.mouse.click(edge.x, edge.y);
    const added = await waitEdit(3);
    const [px, py] = await page.evaluate((id) => window.shoremesh.screenOf(id), added.reply.id);
    await page.mouse.click(px, py);
    await page.keyboard.press('Delete');
    await waitEdit(4);
    for (const n of [5, 6]) {
      await page.keyboard.down('Control');
      await page.keyboard.press('z');
      await page.keyboard.up('Control');
      await waitEdit(n);
    }
    check('a click on a shore edge adds a point after its first vertex',
          () => assert.ok(lines[0].startsWith('add ') && lines[0].endsWith(` after ${edge.id}`), lines[0]));
    check('Delete removes the selected point', () => assert.strictEqual(lines[1], `remove ${added.reply.id}`));
    check('undo of the removal adds it back, undo of the add removes it by its new id',
          () => assert.ok(lines[2].startsWith('add ') && lines[3] === `remove ${added.reply.id + 1}`, lines.join('; ')));
    await h.post(server.url, 'export undone2.off');
    check('after add, remove and two undos the export is the original, byte for byte', () =>
      assert.ok(fs.readFileSync(path.join(dir, 'out', 'before.off')).equals(fs.readFileSync(path.join(dir, 'out', 'undone2.off')))));
    check('the page raised no error', () => assert.deepStrictEqual(problems, []));

    // An island drawn with I, three clicks and Enter; undone, redone (a new ring number) and undone again.
    fs.writeFileSync(path.join(dir, 'square.txt'), '0,0\n100,0\n100,100\n0,100\n0,0\n');
    const square = await h.startServer(['square.txt'], dir);
    try {
      const second = await h.openEditor(browser, square.url);
      const p2 = second.page;
      const corners = await p2.evaluate(() => [[40, 40], [60, 40], [50, 60]].map(([x, y]) => {
        const s = window.shoremesh;
        s.verts.set(-1, { x, y });
        const at = s.screenOf(-1);
        s.verts.delete(-1);
        return at;
      }));
      const before = await p2.evaluate(() => window.shoremesh.triangles);
      await p2.keyboard.press('i');
      for (const [x, y] of corners) await p2.mouse.click(x, y);
      await p2.keyboard.press('Enter');
      const seen = [];
      const wait = async (n) => {
        await p2.waitForFunction((k) => window.shoremesh.edits === k || (window.shoremesh.last && !window.shoremesh.last.ok),
                                 { timeout: 60000 }, n);
        const last = await p2.evaluate(() => ({ ...window.shoremesh.last, triangles: window.shoremesh.triangles }));
        assert.ok(last.ok, `refused: ${last.line}`);
        seen.push(last);
      };
      await wait(1);
      for (const [key, n] of [['z', 2], ['y', 3], ['z', 4]]) {
        await p2.keyboard.down('Control');
        await p2.keyboard.press(key);
        await p2.keyboard.up('Control');
        await wait(n);
      }
      const [islandStats] = await h.post(square.url, 'stats');
      check('an island is drawn, undone, redone under a new ring number and undone again', () => {
        assert.deepStrictEqual(seen.map((e) => e.line.split(' ')[0]), ['add-ring', 'remove-ring', 'add-ring', 'remove-ring']);
        assert.strictEqual(seen[2].line, seen[0].line);
        assert.deepStrictEqual([seen[1].line, seen[3].line], ['remove-ring 2', 'remove-ring 3']);
        assert.ok(seen[0].triangles > before, `${seen[0].triangles} triangles with the island, ${before} without`);
        assert.strictEqual(seen[3].triangles, before);
        assert.strictEqual(islandStats.elements, before);
        assert.deepStrictEqual(second.problems, []);
      });
    } finally {
      square.child.kill('SIGTERM');
    }
    console.log(`drag of shore point ${edit.id}: ${edit.serverMs.toFixed(2)} ms on the server, ` +
                `${edit.roundTripMs.toFixed(1)} ms round trip, ${edit.frameMs.toFixed(1)} ms to the frame (headless, SwiftShader)`);
    for (const c of checks) console.log(`ok: ${c}`);
    console.log(`${checks.length} passed, 0 failed`);
    fs.rmSync(dir, { recursive: true, force: true });
  } finally {
    await browser.close();
    server.child.kill('SIGTERM');
  }
}

main().catch((e) => {
  console.error(`browser editor test failed: ${e.stack || e}`);
  console.log('0 passed, 1 failed');
  process.exit(1);
});
