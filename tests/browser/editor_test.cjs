// The browser editor in a real headless Chromium: load the Superior demo, drag a shore point with the
// mouse (the mesh follows while dragging); the page's drawn triangles and the session's export equal a
// fresh run on the edited shoreline, undo (Ctrl+Z) returns to the original export byte for byte, and the
// canvas shows a drawn mesh. Then points, islands and breakwater lines added, removed, undone and redone,
// refused edits changing nothing, and depth colouring on the Salish Sea DEM.
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
// The same triangles as the page draws them: float32 corners relative to the session's origin.
function asDrawn(triangles, origin) {
  return triangles.map((t) => t.split('|').map((c) => {
    const [x, y] = c.split(' ').map(Number);
    return `${Math.fround(x - origin[0])} ${Math.fround(y - origin[1])}`;
  }).sort().join('|')).sort();
}
// fort.14's depth column, sorted.
function fort14Depths(file) {
  const lines = fs.readFileSync(file, 'utf8').split('\n');
  const nodes = Number(lines[1].trim().split(/\s+/)[1]);
  return lines.slice(2, 2 + nodes).map((l) => Number(l.trim().split(/\s+/)[3])).sort((a, b) => a - b);
}
// The canvas as the page left it (partial frames: an edit's rectangles, a pan's shifted pixels and strips)
// against a full redraw of the same view: the pixels that differ (by more than a rounding in any channel).
async function differsFromFullRedraw(page) {
  return page.evaluate(async () => {
    const src = document.querySelector('#view canvas');
    const grab = () => {
      const c = document.createElement('canvas');
      c.width = src.width; c.height = src.height;
      const g = c.getContext('2d');
      g.drawImage(src, 0, 0);
      return g.getImageData(0, 0, c.width, c.height).data;
    };
    const left = grab();
    await window.shoremesh.redrawAll();
    const full = grab();
    let differ = 0, painted = 0;
    for (let i = 0; i < left.length; i += 4) {
      if (Math.abs(left[i] - full[i]) + Math.abs(left[i + 1] - full[i + 1]) + Math.abs(left[i + 2] - full[i + 2]) > 24) ++differ;
      if (Math.abs(left[i] - 0xe9) + Math.abs(left[i + 1] - 0xe4) + Math.abs(left[i + 2] - 0xd8) > 30) ++painted;
    }
    return { differ, pixels: left.length / 4, painted: painted / (left.length / 4) };
  });
}
const ctrl = async (page, key) => {
  await page.keyboard.down('Control');
  await page.keyboard.press(key);
  await page.keyboard.up('Control');
};

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

    // Pauses between the pointer moves, so that moves go to the server while the mouse moves. This drag
    // with the mesh's frames held and the dragged point on the overlay (state.fast.overlay, ?overlay=1),
    // the second one below with the mesh redrawn while dragging (the default).
    const before = await page.evaluate(() => ({ overlay: window.shoremesh.fast.overlay, held: window.shoremesh.heldFrames,
                                                overlayFrames: window.shoremesh.overlayFrames }));
    await page.evaluate(() => { window.shoremesh.fast.overlay = true; });
    const edit = await h.dragShorePoint(page, 700, 1, { steps: 8, pause: 40 });
    check('the drag was accepted', () => assert.ok(edit.ok, `refused: ${JSON.stringify(edit.reply)}`));
    check('the drag moved that point', () => assert.ok(edit.line.startsWith(`move ${edit.id} `), edit.line));
    const overlaid = await page.evaluate(() => ({ held: window.shoremesh.heldFrames, overlayFrames: window.shoremesh.overlayFrames,
                                                  painted: window.shoremesh.overlayPainted() }));
    check('while dragging, the mesh frames waited and the point was drawn on the overlay; after it, the overlay is clear', () => {
      assert.ok(!before.overlay, 'state.fast.overlay is on by default');
      assert.ok(overlaid.held > before.held && overlaid.overlayFrames > before.overlayFrames, JSON.stringify({ before, overlaid }));
      assert.strictEqual(overlaid.painted, 0);
    });

    const [stats] = await h.post(server.url, 'stats');
    const page1 = await page.evaluate(() => ({ triangles: window.shoremesh.triangles, redraws: window.shoremesh.redraws,
                                                version: window.shoremesh.version, live: window.shoremesh.liveMoves,
                                                origin: window.shoremesh.origin, drawn: window.shoremesh.drawnTriangles(),
                                                shown: document.getElementById('tri-count').textContent }));
    check('the mesh moved while dragging (moves sent before the release)', () => assert.ok(page1.live >= 1, `${page1.live}`));
    check("the page has the server's version: each move while dragging and the final one applied once", () => {
      assert.ok(page1.version === page1.live || page1.version === page1.live + 1, `version ${page1.version}, ${page1.live} live`);
      assert.strictEqual(page1.redraws, page1.version);
    });
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
    check("the page's drawn triangles after the drag are the fresh run's, corner for corner",
          () => assert.deepStrictEqual(page1.drawn, asDrawn(fresh, page1.origin)));

    // The drag's frames redrew only the rectangles the edits touched, and left what a full redraw draws.
    const afterHeldDrag = await differsFromFullRedraw(page);
    check('after a drag drawn on the overlay and then in one partial frame, the canvas is what a full redraw draws', () =>
      assert.ok(afterHeldDrag.differ <= 20 && afterHeldDrag.painted > 0.1, JSON.stringify(afterHeldDrag)));
    const zoomedFull = await page.evaluate(async () => { await window.shoremesh.redrawAll(); return window.shoremesh.drawn; });
    // A full frame zoomed in draws what the grid picks (the triangles and points meeting the view), and
    // that is what every chunk in view draws.
    const zoomedGrid = await page.evaluate(async () => { await window.shoremesh.redraw(); return window.shoremesh.drawn; });
    const gridDiff = await differsFromFullRedraw(page);
    check("a full frame from the grid's pick: fewer triangles than the chunks in view, the same pixels", () => {
      assert.ok(zoomedGrid.how === 'full' && zoomedGrid.picked > 0 && zoomedGrid.triangles === zoomedGrid.picked, JSON.stringify(zoomedGrid));
      assert.ok(zoomedGrid.triangles < zoomedFull.triangles, `${zoomedGrid.triangles} against ${zoomedFull.triangles}`);
      assert.ok(gridDiff.differ <= 20 && gridDiff.painted > 0.1, JSON.stringify(gridDiff));
    });
    check("the drag's last frame redrew only the edit's rectangles: a few pixels, no more triangles than a full frame", () => {
      const d = edit.profile.drawn;
      assert.ok(d && d.how === 'partial', JSON.stringify(edit.profile));
      assert.ok(zoomedFull.how === 'full' && d.pixels < zoomedFull.pixels / 4, `${d.pixels} pixels, ${zoomedFull.pixels} in a full frame`);
      assert.ok(d.triangles <= zoomedFull.triangles, `${d.triangles} triangles in the edit's frame, ${zoomedFull.triangles} in a full one`);
    });
    await page.evaluate(() => { window.shoremesh.fast.overlay = false; });
    const held = await page.evaluate(() => window.shoremesh.heldFrames);
    const second = await h.dragShorePoint(page, 900, -1, { steps: 8, pause: 40 });
    const heldAfter = await page.evaluate(() => window.shoremesh.heldFrames);
    check('with the overlay off, no frame waited for the end of the drag', () => assert.strictEqual(heldAfter, held));
    const lastBoxes = await page.evaluate(() => window.shoremesh.lastEditBoxes());
    const changeFrame = await page.evaluate(() => window.shoremesh.changeFrame);
    check("the edit's frame redrew every triangle the edit wrote (those on the screen)", () => {
      assert.ok(second.ok && changeFrame.drawn, JSON.stringify(changeFrame));
      const rects = changeFrame.drawn.rects;
      assert.ok(lastBoxes.length > 0);
      for (const [x0, y0, x1, y1] of lastBoxes) {
        assert.ok(rects.some(([x, y, w, h]) => x0 >= x && y0 >= y && x1 <= x + w && y1 <= y + h),
                  `triangle box ${[x0, y0, x1, y1]} outside the redrawn rectangles ${JSON.stringify(rects)}`);
      }
    });
    const afterDrag = await differsFromFullRedraw(page);
    check('after a drag drawn in partial frames the canvas is what a full redraw draws', () =>
      assert.ok(afterDrag.differ <= 20, `${afterDrag.differ} of ${afterDrag.pixels} pixels differ`));
    await ctrl(page, 'z');
    await page.waitForFunction(() => window.shoremesh.edits === 3, { timeout: 60000 });
    // Panning with the whole mesh in view: each frame shifts the last one's pixels and draws the strip it
    // uncovers (a fraction of the draws and triangles of a full frame), and ends as a full redraw would.
    const panned = await page.evaluate(async () => {
      const s = window.shoremesh;
      await s.fit();
      await s.redrawAll();
      const full = s.drawn, frames = [];
      for (let i = 0; i < 12; ++i) { await s.pan(i < 6 ? 9 : -4, i % 3 === 0 ? 3 : 0); frames.push(s.drawn); }
      return { full, frames };
    });
    const panDiff = await differsFromFullRedraw(page);
    check('a pan frame shifts the last frame and draws only the uncovered strips', () => {
      for (const d of panned.frames) {
        assert.strictEqual(d.how, 'scroll', JSON.stringify(d));
        // Every chunk this small mesh has meets a strip: no fewer triangles here (a large mesh's chunks are
        // small on the screen, bench/RESULTS.md), but a tenth of the pixels (the copy's one triangle aside).
        assert.ok(d.triangles <= panned.full.triangles + 1, `${d.triangles} triangles, ${panned.full.triangles} in a full frame`);
        assert.ok(d.pixels < panned.full.pixels / 10, `${d.pixels} pixels drawn, ${panned.full.pixels} in a full frame`);
      }
    });
    check('after panning the canvas is what a full redraw draws, and shows the mesh', () => {
      assert.ok(panDiff.differ <= 20, `${panDiff.differ} of ${panDiff.pixels} pixels differ`);
      assert.ok(panDiff.painted > 0.1, `only ${(panDiff.painted * 100).toFixed(1)} % of the canvas is drawn`);
    });
    // Zooming with the wheel: the frame before is drawn scaled (one triangle), and once the wheel rests the
    // view is drawn in full.
    const zoomed = await page.evaluate(async () => {
      const s = window.shoremesh, frames = [];
      for (const f of [0.8, 0.8, 0.9]) { await s.zoom(f); frames.push(s.drawn); }
      await new Promise((r) => setTimeout(r, s.zoomRest + 100));
      await s.nextFrame();
      return { frames, rested: s.drawn };
    });
    const zoomDiff = await differsFromFullRedraw(page);
    check('a wheel zoom draws the last frame scaled, and the full view once the wheel rests', () => {
      for (const d of zoomed.frames) assert.ok(d.how === 'zoom' && d.calls === 1 && d.triangles === 1, JSON.stringify(d));
      assert.strictEqual(zoomed.rested.how, 'full');
      assert.ok(zoomDiff.differ === 0 && zoomDiff.painted > 0.1, JSON.stringify(zoomDiff));
    });
    await page.evaluate(async (id) => {  // back where the drag was; the last frame a pan frame, checked below
      const s = window.shoremesh, v = s.verts.get(id), a = s.verts.get(v.prev);
      await s.zoomTo(id, Math.hypot(a.x - v.x, a.y - v.y) / 150);
      await s.pan(-30, -12);
    }, edit.id);

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
    await ctrl(page, 'z');
    await page.waitForFunction(() => window.shoremesh.edits === 4, { timeout: 60000 });
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
    const added = await waitEdit(5);
    const [px, py] = await page.evaluate((id) => window.shoremesh.screenOf(id), added.reply.id);
    await page.mouse.click(px, py);
    await page.keyboard.press('Delete');
    await waitEdit(6);
    for (const n of [7, 8]) {
      await ctrl(page, 'z');
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

    // A square lake: islands and breakwater lines drawn with the mouse, removed, undone and redone, and
    // refused edits that change nothing.
    fs.writeFileSync(path.join(dir, 'square.txt'), '0,0\n100,0\n100,100\n0,100\n0,0\n');
    const square = await h.startServer(['square.txt', '--export-dir', 'out'], dir);
    try {
      const second = await h.openEditor(browser, square.url);
      const p2 = second.page;
      const screen = (pts) => p2.evaluate((pts) => pts.map(([x, y]) => {
        const s = window.shoremesh;
        s.verts.set(-1, { x, y });
        const at = s.screenOf(-1);
        s.verts.delete(-1);
        return at;
      }), pts);
      const clicks = async (pts) => { for (const [x, y] of await screen(pts)) await p2.mouse.click(x, y); };
      const before = await p2.evaluate(() => window.shoremesh.triangles);
      const [sq0] = await h.post(square.url, 'export sq0.off');
      assert.ok(sq0.ok, JSON.stringify(sq0));
      const seen = [];
      const wait = async (n) => {
        await p2.waitForFunction((k) => window.shoremesh.edits === k || (window.shoremesh.last && !window.shoremesh.last.ok),
                                 { timeout: 60000 }, n);
        const last = await p2.evaluate(() => ({ ...window.shoremesh.last, triangles: window.shoremesh.triangles }));
        assert.ok(last.ok, `refused: ${last.line}: ${JSON.stringify(last.reply)}`);
        seen.push(last);
        return last;
      };
      const island = [[40, 40], [60, 40], [50, 60]];
      await p2.keyboard.press('i');
      await clicks(island);
      await p2.keyboard.press('Enter');
      await wait(1);
      for (const [key, n] of [['z', 2], ['y', 3], ['z', 4]]) {
        await ctrl(p2, key);
        await wait(n);
      }
      check('an island is drawn, undone, redone under a new ring number and undone again', () => {
        assert.deepStrictEqual(seen.map((e) => e.line.split(' ')[0]), ['add-ring', 'remove-ring', 'add-ring', 'remove-ring']);
        assert.strictEqual(seen[2].line, seen[0].line);
        assert.deepStrictEqual([seen[1].line, seen[3].line], ['remove-ring 2', 'remove-ring 3']);
        assert.ok(seen[0].triangles > before, `${seen[0].triangles} triangles with the island, ${before} without`);
        assert.strictEqual(seen[3].triangles, before);
      });

      // A breakwater: L, two clicks and Enter; undone, redone, undone.
      seen.length = 0;
      await p2.keyboard.press('l');
      await clicks([[15, 20], [15, 80], [30, 88]]);
      await p2.keyboard.press('Enter');
      const line = await wait(5);
      for (const [key, n] of [['z', 6], ['y', 7], ['z', 8]]) {
        await ctrl(p2, key);
        await wait(n);
      }
      check('a breakwater line is drawn (add-line), undone (remove-ring), redone and undone', () => {
        assert.deepStrictEqual(seen.map((e) => e.line.split(' ')[0]), ['add-line', 'remove-ring', 'add-line', 'remove-ring']);
        assert.strictEqual(line.reply.role, 'line');
        assert.strictEqual(line.reply.points, 3);
        assert.deepStrictEqual([seen[1].line, seen[3].line], ['remove-ring 4', 'remove-ring 5']);
        assert.ok(seen[0].triangles > before && seen[2].triangles === seen[0].triangles);
        assert.strictEqual(seen[3].triangles, before);
      });

      // An island selected by a click inside it and removed with R; undo brings it back, undo again
      // removes the drawn one: the original export, byte for byte.
      seen.length = 0;
      await p2.keyboard.press('i');
      await clicks(island);
      await p2.keyboard.press('Enter');
      await wait(9);
      await clicks([[50, 46]]);
      const picked = await p2.evaluate(() => document.getElementById('selected').textContent);
      await p2.keyboard.press('r');
      await wait(10);
      for (const n of [11, 12]) {
        await ctrl(p2, 'z');
        await wait(n);
      }
      await h.post(square.url, 'export sq1.off');
      check('a click inside an island selects it, R removes it, undo restores it; the export is the original', () => {
        assert.ok(picked.includes('island 6'), picked);
        assert.deepStrictEqual(seen.map((e) => e.line.split(' ')[0]), ['add-ring', 'remove-ring', 'add-ring', 'remove-ring']);
        assert.strictEqual(seen[1].line, 'remove-ring 6');
        assert.strictEqual(seen[2].triangles, seen[0].triangles);
        assert.ok(fs.readFileSync(path.join(dir, 'out', 'sq0.off')).equals(fs.readFileSync(path.join(dir, 'out', 'sq1.off'))));
      });

      // Refused: a crossed island (a bow tie), and a drag of a corner across the far side of the lake.
      const v0 = await p2.evaluate(() => window.shoremesh.version);
      await p2.keyboard.press('i');
      await clicks([[40, 40], [60, 60], [60, 40], [40, 60]]);
      await p2.keyboard.press('Enter');
      await p2.waitForFunction(() => window.shoremesh.last && !window.shoremesh.last.ok, { timeout: 60000 });
      const bowTie = await p2.evaluate(() => ({ last: window.shoremesh.last, version: window.shoremesh.version,
                                                 status: document.getElementById('status').className }));
      const corner = await p2.evaluate(() => [...window.shoremesh.verts.entries()].find(([, v]) => v.x === 0 && v.y === 100)[0]);
      const [[fx, fy]] = await screen([[0, 100]]);
      const [[tx, ty]] = await screen([[100.5, 50]]);  // beyond the edge x = 100: the shore would cross itself
      await p2.mouse.move(fx, fy);
      await p2.mouse.down();
      for (let i = 1; i <= 6; ++i) {
        await p2.mouse.move(fx + ((tx - fx) * i) / 6, fy + ((ty - fy) * i) / 6);
        await new Promise((r) => setTimeout(r, 40));
      }
      await p2.mouse.up();
      await p2.waitForFunction(() => !window.shoremesh.dragging && window.shoremesh.last.line.startsWith('move'), { timeout: 60000 });
      const drag = await p2.evaluate((id) => ({ last: window.shoremesh.last, edits: window.shoremesh.edits,
                                                at: [window.shoremesh.verts.get(id).x, window.shoremesh.verts.get(id).y],
                                                status: document.getElementById('status').className }), corner);
      await h.post(square.url, 'export sq2.off');
      const [squareStats] = await h.post(square.url, 'stats');
      check('a crossed island is refused, shown as refused, and changes nothing', () => {
        assert.ok(!bowTie.last.ok && bowTie.last.line.startsWith('add-ring'), JSON.stringify(bowTie.last));
        assert.strictEqual(bowTie.version, v0);
        assert.strictEqual(bowTie.status, 'refused');
      });
      check('a drag that would make the shore cross itself is refused and the point is back where it was', () => {
        assert.ok(!drag.last.ok, JSON.stringify(drag.last));
        assert.strictEqual(drag.status, 'refused');
        assert.strictEqual(drag.edits, 12);
        assert.deepStrictEqual(drag.at, [0, 100]);
        assert.strictEqual(squareStats.elements, before);
        assert.ok(fs.readFileSync(path.join(dir, 'out', 'sq0.off')).equals(fs.readFileSync(path.join(dir, 'out', 'sq2.off'))));
        assert.deepStrictEqual(second.problems, []);
      });
    } finally {
      square.child.kill('SIGTERM');
    }

    // Depths: the Salish Sea DEM (serve --dem); the page's depth colouring has a legend, and the depths it
    // draws at the nodes are the export's (fort.14), before and after a drag.
    const salish = await h.startServer(['--dem', path.join(h.env.samples, 'salish', 'salish_sea_topobathy.tif'), '--min-area', '1',
                                        '--export-dir', 'out'], dir);
    try {
      const third = await h.openEditor(browser, salish.url);
      const p3 = third.page;
      await p3.evaluate(() => window.shoremesh.setColour(3));
      const shown = await p3.evaluate(() => ({ depths: window.shoremesh.hasDepths, legend: document.getElementById('legend-text').textContent,
                                               enabled: !document.getElementById('colour-depth').disabled,
                                               scale: document.getElementById('scale-text').textContent,
                                               drawn: window.shoremesh.drawnDepths() }));
      await h.post(salish.url, 'export salish0.14');
      const moved = await h.dragShorePoint(p3, 40, 1, { steps: 4, pause: 40 });
      const after = await p3.evaluate(() => window.shoremesh.drawnDepths());
      await h.post(salish.url, 'export salish1.14');
      const near = (a, b) => a.length === b.length && a.every((x, i) => Math.abs(x - b[i]) <= 1e-4 * Math.max(1, Math.abs(b[i])));
      check('with --dem the page colours by depth, with a legend and a scale bar', () => {
        assert.ok(shown.depths && shown.enabled, JSON.stringify(shown));
        assert.ok(/^depth .* m/.test(shown.legend), shown.legend);
        assert.ok(/\d/.test(shown.scale), shown.scale);
      });
      check("the page's node depths are the export's, before and after a drag", () => {
        assert.ok(moved.ok, JSON.stringify(moved.reply));
        assert.ok(near(shown.drawn, fort14Depths(path.join(dir, 'out', 'salish0.14'))), 'before the drag');
        assert.ok(near(after, fort14Depths(path.join(dir, 'out', 'salish1.14'))), 'after the drag');
        assert.deepStrictEqual(third.problems, []);
      });
    } finally {
      salish.child.kill('SIGTERM');
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
