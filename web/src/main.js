// The browser editor of `shoremesh serve`: the water mesh in WebGL (three.js), shore points to drag, and
// the edit language of `shoremesh edit` over POST /edit. The server keeps every triangle in a slot that
// stays put until the triangle goes, so an edit's change is a few slot writes here (docs/editor.md).
import * as THREE from 'three';

const view = document.getElementById('view');
const $ = (id) => document.getElementById(id);

// What tests and people can read: window.shoremesh.
const state = {
  ready: false, version: 0, triangles: 0, slots: 0, edits: 0, frames: 0, redraws: 0, liveMoves: 0,
  origin: [0, 0], side: 1, units: '', hasDepths: false, liveDrag: true,
  verts: new Map(),  // input point id -> {x, y, ring, prev, next} (x, y exact, in the mesh's units)
  selected: null, last: null, undo: [], redo: [],
  alias: new Map(), firstId: new Map(), ringAlias: new Map(), ringOrigin: new Map(),
};
window.shoremesh = state;

// ---- drawing -------------------------------------------------------------------------------------------
const renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
renderer.setPixelRatio(window.devicePixelRatio || 1);
renderer.setClearColor(0xe9e4d8);
view.prepend(renderer.domElement);
const scene = new THREE.Scene();
const camera = new THREE.OrthographicCamera(-1, 1, 1, -1, -1, 1);
const cam = { cx: 0, cy: 0, scale: 1 };  // centre (relative to origin) and units per CSS pixel

const triVertex = `
  precision highp float;
  uniform mat4 projectionMatrix; uniform mat4 modelViewMatrix; uniform float uVersion;
  in vec2 position; in float kind; in float quality; in float size; in float changed; in float depth;
  out vec3 vBary; out float vQuality; out float vSize; out float vFlash; out float vDepth;
  void main() {
    int c = gl_VertexID % 3;
    vBary = vec3(c == 0, c == 1, c == 2);
    vQuality = quality; vSize = size; vDepth = depth;
    vFlash = abs(changed - uVersion) < 0.5 ? 1.0 : 0.0;  // made by the last edit
    gl_Position = projectionMatrix * modelViewMatrix * vec4(position, 0.0, 1.0);
    if (kind > 254.5) gl_Position = vec4(2.0, 2.0, 2.0, 1.0);  // an empty slot
  }`;
const triFragment = `
  precision highp float;
  uniform int uColour; uniform float uBound; uniform vec2 uSizeRange; uniform vec2 uDepthRange;
  in vec3 vBary; in float vQuality; in float vSize; in float vFlash; in float vDepth;
  out vec4 outColor;
  vec3 ramp(float t) { return mix(mix(vec3(0.93, 0.86, 0.55), vec3(0.45, 0.75, 0.85), clamp(t * 2.0, 0.0, 1.0)),
                                  vec3(0.16, 0.38, 0.72), clamp(t * 2.0 - 1.0, 0.0, 1.0)); }
  // Depth, positive down, interpolated across the triangle: shallow pale to deep navy, on a square-root
  // scale (most water is shallow beside a few deep basins).
  vec3 depthRamp(float t) { t = clamp(t, 0.0, 1.0);
    return mix(mix(vec3(0.80, 0.93, 0.88), vec3(0.30, 0.62, 0.80), clamp(t * 2.0, 0.0, 1.0)),
               vec3(0.05, 0.13, 0.38), clamp(t * 2.0 - 1.0, 0.0, 1.0)); }
  void main() {
    vec3 fill = vec3(0.62, 0.80, 0.90);
    if (uColour == 0) fill = vQuality < uBound ? vec3(0.85, 0.2, 0.15) : ramp((vQuality - uBound) / max(60.0 - uBound, 1.0));
    if (uColour == 1) fill = ramp((vSize - uSizeRange.x) / max(uSizeRange.y - uSizeRange.x, 1e-6));
    if (uColour == 3) fill = depthRamp(sqrt(max(vDepth - uDepthRange.x, 0.0) / max(uDepthRange.y - uDepthRange.x, 1e-6)));
    fill = mix(fill, vec3(1.0, 0.45, 0.0), vFlash * 0.85);
    vec3 d = fwidth(vBary);
    vec3 a = smoothstep(vec3(0.0), d * 1.3, vBary);
    float edge = (1.0 - min(min(a.x, a.y), a.z)) * clamp(1.5 - max(d.x, max(d.y, d.z)) * 12.0, 0.0, 1.0);
    outColor = vec4(mix(fill, vec3(0.12, 0.2, 0.32), edge * 0.75), 1.0);
  }`;
const cornerVertex = `
  precision highp float;
  uniform mat4 projectionMatrix; uniform mat4 modelViewMatrix; uniform float uPointSize;
  in vec2 position; in float kind;
  out vec3 vColour;
  void main() {
    gl_Position = projectionMatrix * modelViewMatrix * vec4(position, 0.0, 1.0);
    gl_PointSize = kind < 0.5 ? uPointSize : kind < 1.5 ? uPointSize * 1.6 : 0.0;  // Steiner, split
    vColour = kind < 0.5 ? vec3(0.45) : vec3(0.09, 0.65, 0.65);
    if (kind > 1.5) gl_Position = vec4(2.0, 2.0, 2.0, 1.0);  // shore and loose points: the point layer
  }`;
const dotVertex = `
  precision highp float;
  uniform mat4 projectionMatrix; uniform mat4 modelViewMatrix; uniform float uPointSize;
  in vec2 position; in vec3 colour; in float big;
  out vec3 vColour;
  void main() {
    gl_Position = projectionMatrix * modelViewMatrix * vec4(position, 0.0, 1.0);
    gl_PointSize = max(uPointSize * 2.0, 4.0) * (1.0 + big);
    vColour = colour;
  }`;
const dotFragment = `
  precision highp float;
  in vec3 vColour; out vec4 outColor;
  void main() { if (length(gl_PointCoord - 0.5) > 0.5) discard; outColor = vec4(vColour, 1.0); }`;
const lineVertex = `
  precision highp float;
  uniform mat4 projectionMatrix; uniform mat4 modelViewMatrix;
  in vec2 position;
  void main() { gl_Position = projectionMatrix * modelViewMatrix * vec4(position, 0.0, 1.0); }`;
const lineFragment = `precision highp float; out vec4 outColor; void main() { outColor = vec4(0.04, 0.24, 0.57, 1.0); }`;

const uniforms = {
  uVersion: { value: -1 }, uColour: { value: 0 }, uBound: { value: 30 }, uSizeRange: { value: new THREE.Vector2(0, 1) },
  uDepthRange: { value: new THREE.Vector2(0, 1) },
  uPointSize: { value: 2 },
};
// Double-sided: a slot's corners come sorted, not counter-clockwise.
const raw = (vertexShader, fragmentShader) =>
  new THREE.RawShaderMaterial({ vertexShader, fragmentShader, uniforms, glslVersion: THREE.GLSL3, side: THREE.DoubleSide });

// The triangles: 3 corners per slot, each with its position, kind, the triangle's min angle and size, and
// the version of the edit that made it (the last edit's triangles are highlighted, as preview-change does;
// a static highlight: no frames drawn between edits).
// The slots are drawn in chunks of kChunk, each a draw of its own with a bounding sphere, so that three.js
// skips the chunks outside the view (the server numbers the first slots along a Z-order curve, so a chunk
// covers one patch of water; a slot an edit reuses lies where the edit freed it). Zoomed in on an edit at a
// million triangles, a frame draws a few chunks instead of all of them.
// Partial frames (an edit's rectangle, a pan's strip) draw from a second set of chunks, of kFine slots, in a
// scene of their own sharing the same buffers: a thin strip meets few of them, where it would meet every
// large chunk in the view (a full frame would pay a draw call per small chunk).
const kChunk = 4096, kFine = 256;
const fineScene = new THREE.Scene();
let chunks = [], fineChunks = [], buffers = null, capacity = 0, layerMask = { d: true, c: true, t: true };
// What lies where: a uniform grid (kGrid cells a side over the mesh's box) of the slots' and the shore
// points' bounding boxes (a shore point's box holds its edge to the next point), so that a frame of a small
// part of the view (an edit's rectangle, a pan's strip, a zoomed-in view) draws the triangles and points
// that meet it, through an index of their slots, instead of every chunk that meets it: SwiftShader's cost
// is mostly per vertex (bench/RESULTS.md), and a chunk of 256 slots meeting a rectangle brings 256
// triangles and 768 corner points where a dozen meet it. Entries are only added: a cleared or moved slot
// (or point) keeps its old cells, and a query keeps what its box really meets. Boxes of more than
// kGridBig cells a side go to one list that every query scans (a few large water triangles).
// The picked primitives are drawn in slot (and point) order, the order of the chunks, so that where
// points overlap the frame is the one the chunks draw (docs/editor.md).
const kGrid = 1024, kGridBig = 16, kPick = 65536, kPickCells = 16384;
const grid = { x0: 0, y0: 0, cell: 1, tri: [], triBig: [], dot: [], dotBig: [], queries: 0 };
const indexScene = new THREE.Scene();
const picked = { mesh: null, corners: null, points: null, segs: null, triangles: 0, dots: 0 };
let triBox = null, triStamp = null, dotBox = new Float32Array(0), dotStamp = new Uint32Array(0);
const pickT = new Uint32Array(kPick), pickD = new Uint32Array(kPick);
function setGrid(lo, hi) {
  grid.cell = Math.max(hi[0] - lo[0], hi[1] - lo[1], 1e-9) / kGrid * (1 + 1e-6);
  grid.x0 = lo[0]; grid.y0 = lo[1];
  grid.tri = new Array(kGrid * kGrid); grid.triBig = [];
}
const cellOf = (v, o) => Math.min(kGrid - 1, Math.max(0, Math.floor((v - o) / grid.cell)));
function gridInsert(cells, big, id, box) {
  const i0 = cellOf(box[id * 4], grid.x0), j0 = cellOf(box[id * 4 + 1], grid.y0);
  const i1 = cellOf(box[id * 4 + 2], grid.x0), j1 = cellOf(box[id * 4 + 3], grid.y0);
  if (i1 - i0 >= kGridBig || j1 - j0 >= kGridBig) { big.push(id); return; }
  for (let j = j0; j <= j1; ++j) {
    for (let i = i0; i <= i1; ++i) {
      const c = j * kGrid + i;
      if (cells[c] === undefined) cells[c] = [id]; else cells[c].push(id);
    }
  }
}
// The ids whose boxes meet [x0, x1] x [y0, y1] (and that `live` keeps), sorted, into `out`; their count, or
// -1 when the rectangle covers more than kPickCells cells or more than kPick ids meet it (then the chunks
// draw: a wide view meets most of the mesh anyway).
function gridQuery(cells, big, box, stamp, x0, y0, x1, y1, live, out) {
  const i0 = cellOf(x0, grid.x0), j0 = cellOf(y0, grid.y0), i1 = cellOf(x1, grid.x0), j1 = cellOf(y1, grid.y0);
  if ((i1 - i0 + 1) * (j1 - j0 + 1) > kPickCells) return -1;
  const q = ++grid.queries;
  let n = 0;
  const take = (id) => {
    if (stamp[id] === q) return true;
    stamp[id] = q;
    if (box[id * 4] > x1 || box[id * 4 + 2] < x0 || box[id * 4 + 1] > y1 || box[id * 4 + 3] < y0 || !live(id)) return true;
    if (n === out.length) return false;
    out[n++] = id;
    return true;
  };
  for (const id of big) if (!take(id)) return -1;
  for (let j = j0; j <= j1; ++j) {
    for (let i = i0; i <= i1; ++i) {
      const list = cells[j * kGrid + i];
      if (list === undefined) continue;
      for (let k = 0; k < list.length; ++k) if (!take(list[k])) return -1;
    }
  }
  out.subarray(0, n).sort();
  return n;
}
const liveSlot = (s) => buffers.kind.array[s * 3] !== 255;
const anyDot = () => true;
// Sets the picked triangles and points to those meeting the rectangle (mesh units relative to the origin);
// false when the grid declines (the chunks draw then).
function pick(x0, y0, x1, y1) {
  if (!fast.index || !picked.mesh || !picked.points) return false;
  const nt = gridQuery(grid.tri, grid.triBig, triBox, triStamp, x0, y0, x1, y1, liveSlot, pickT);
  if (nt < 0) return false;
  const nd = gridQuery(grid.dot, grid.dotBig, dotBox, dotStamp, x0, y0, x1, y1, anyDot, pickD);
  if (nd < 0) return false;
  const ti = picked.mesh.geometry.index;
  for (let i = 0; i < nt; ++i) { const s = pickT[i] * 3; ti.array[3 * i] = s; ti.array[3 * i + 1] = s + 1; ti.array[3 * i + 2] = s + 2; }
  const pi = picked.points.geometry.index, li = picked.segs.geometry.index;
  for (let i = 0; i < nd; ++i) { const d = pickD[i]; pi.array[i] = d; li.array[2 * i] = 2 * d; li.array[2 * i + 1] = 2 * d + 1; }
  for (const [index, n] of [[ti, nt * 3], [pi, nd], [li, nd * 2]]) {
    index.clearUpdateRanges();
    if (n > 0) { index.addUpdateRange(0, n); index.needsUpdate = true; }
  }
  picked.mesh.geometry.setDrawRange(0, nt * 3);
  picked.points.geometry.setDrawRange(0, nd);
  picked.segs.geometry.setDrawRange(0, nd * 2);
  picked.triangles += nt; picked.dots += nd;
  return true;
}
function allocate(slots) {
  capacity = Math.ceil(slots * 1.25) + 1024;
  const old = buffers;
  buffers = {
    position: new THREE.BufferAttribute(new Float32Array(capacity * 6), 2),
    kind: new THREE.BufferAttribute(new Uint8Array(capacity * 3).fill(255), 1),
    quality: new THREE.BufferAttribute(new Float32Array(capacity * 3), 1),
    size: new THREE.BufferAttribute(new Float32Array(capacity * 3), 1),
    changed: new THREE.BufferAttribute(new Float32Array(capacity * 3).fill(-1e9), 1),
    depth: new THREE.BufferAttribute(new Float32Array(capacity * 3), 1),
  };
  if (old) for (const k in old) buffers[k].array.set(old[k].array);
  for (const c of chunks) { scene.remove(c.mesh, c.corners); c.mesh.geometry.dispose(); }
  for (const c of fineChunks) { fineScene.remove(c.mesh, c.corners); c.mesh.geometry.dispose(); }
  const triangles = raw(triVertex, triFragment), points = raw(cornerVertex, dotFragment);
  const oldBox = triBox;
  triBox = new Float32Array(capacity * 4);
  if (oldBox) triBox.set(oldBox);
  triStamp = new Uint32Array(capacity);
  {  // the triangles a grid query picked (see pick()): the same buffers, drawn through an index of their slots
    if (picked.mesh) { indexScene.remove(picked.mesh, picked.corners); picked.mesh.geometry.dispose(); }
    const geometry = new THREE.BufferGeometry();
    for (const k in buffers) geometry.setAttribute(k, buffers[k]);
    geometry.setIndex(new THREE.BufferAttribute(new Uint32Array(kPick * 3), 1).setUsage(THREE.DynamicDrawUsage));
    geometry.setDrawRange(0, 0);
    picked.mesh = new THREE.Mesh(geometry, triangles);
    picked.corners = new THREE.Points(geometry, points);
    picked.mesh.renderOrder = 0; picked.corners.renderOrder = 1;
    picked.mesh.frustumCulled = picked.corners.frustumCulled = false;
    indexScene.add(picked.mesh, picked.corners);
  }
  const make = (size, into) => {
    const out = [];
    for (let start = 0; start < capacity; start += size) {
      const geometry = new THREE.BufferGeometry();
      for (const k in buffers) geometry.setAttribute(k, buffers[k]);  // shared: one GPU buffer per attribute
      geometry.setDrawRange(start * 3, Math.min(size, capacity - start) * 3);
      geometry.boundingSphere = new THREE.Sphere();
      const c = { mesh: new THREE.Mesh(geometry, triangles), corners: new THREE.Points(geometry, points),
                  lo: [Infinity, Infinity], hi: [-Infinity, -Infinity], moved: false };
      c.mesh.renderOrder = 0; c.corners.renderOrder = 1;
      c.mesh.visible = c.corners.visible = false;
      out.push(c);
      into.add(c.mesh, c.corners);
    }
    return out;
  };
  chunks = make(kChunk, scene);
  fineChunks = make(kFine, fineScene);
  if (old) for (let s = 0; s < state.slots; ++s) if (buffers.kind.array[s * 3] !== 255) grow(s);
  updateChunks();
}
function grow(s) {  // chunk bounds only grow: a slot cleared leaves its chunk's bounds as they were
  const p = buffers.position.array;
  for (const c of [chunks[Math.floor(s / kChunk)], fineChunks[Math.floor(s / kFine)]]) {
    for (let k = 0; k < 3; ++k) {
      const x = p[s * 6 + 2 * k], y = p[s * 6 + 2 * k + 1];
      if (x < c.lo[0]) c.lo[0] = x; if (y < c.lo[1]) c.lo[1] = y;
      if (x > c.hi[0]) c.hi[0] = x; if (y > c.hi[1]) c.hi[1] = y;
    }
    c.moved = true;
  }
}
function updateChunks() {
  for (const c of [...chunks, ...fineChunks]) {
    if (!c.moved) continue;
    c.moved = false;
    const sphere = c.mesh.geometry.boundingSphere;
    sphere.center.set((c.lo[0] + c.hi[0]) / 2, (c.lo[1] + c.hi[1]) / 2, 0);
    sphere.radius = Math.hypot(c.hi[0] - c.lo[0], c.hi[1] - c.lo[1]) / 2;
    c.mesh.visible = true;
  }
}

function angleAt(ax, ay, bx, by, cx, cy) {
  const ux = bx - ax, uy = by - ay, vx = cx - ax, vy = cy - ay;
  return Math.abs(Math.atan2(ux * vy - uy * vx, ux * vx + uy * vy)) * 180 / Math.PI;
}
// Writes slot `s` (xy: 6 numbers relative to the origin; kinds: 3; v: the version that made it).
function writeSlot(s, xy, kinds, v) {
  const p = buffers.position.array;
  for (let i = 0; i < 6; ++i) p[s * 6 + i] = xy[i];
  const [ax, ay, bx, by, cx, cy] = xy;
  const q = Math.min(angleAt(ax, ay, bx, by, cx, cy), angleAt(bx, by, cx, cy, ax, ay), angleAt(cx, cy, ax, ay, bx, by));
  const longest = Math.max(Math.hypot(bx - ax, by - ay), Math.hypot(cx - bx, cy - by), Math.hypot(ax - cx, ay - cy));
  const size = Math.log2(longest || 1e-9);
  for (let k = 0; k < 3; ++k) {
    buffers.kind.array[s * 3 + k] = kinds[k];
    buffers.quality.array[s * 3 + k] = q;
    buffers.size.array[s * 3 + k] = size;
    buffers.changed.array[s * 3 + k] = v;
  }
  grow(s);
  triBox[s * 4] = Math.min(ax, bx, cx); triBox[s * 4 + 1] = Math.min(ay, by, cy);
  triBox[s * 4 + 2] = Math.max(ax, bx, cx); triBox[s * 4 + 3] = Math.max(ay, by, cy);
  gridInsert(grid.tri, grid.triBig, s, triBox);
}
function clearSlot(s) {
  buffers.position.array.fill(0, s * 6, s * 6 + 6);
  buffers.kind.array.fill(255, s * 3, s * 3 + 3);
}
function upload(slots) {  // only the slots written: one bufferSubData range per run of slots
  slots.sort((a, b) => a - b);
  for (const k in buffers) {
    const per = k === 'position' ? 6 : 3;
    buffers[k].clearUpdateRanges();
    for (let i = 0; i < slots.length;) {
      let j = i;
      while (j + 1 < slots.length && slots[j + 1] <= slots[j] + 1) ++j;
      buffers[k].addUpdateRange(slots[i] * per, (slots[j] - slots[i] + 1) * per);
      i = j + 1;
    }
    buffers[k].needsUpdate = true;
  }
}

// The shore points (draggable) and loose points, and the shoreline: rebuilt when points come or go,
// written in place when one moves. Drawn in chunks of kChunk points (in ring order, so a chunk is a
// stretch of shore) culled by the view like the triangles.
let dots = null, lines = null, dotChunks = [], fineDotChunks = [], dotIndex = new Map();
function rebuildRings() {
  const ids = [...state.verts.keys()];
  dotIndex = new Map(ids.map((id, i) => [id, i]));
  const pos = new Float32Array(ids.length * 2), colour = new Float32Array(ids.length * 3), big = new Float32Array(ids.length);
  const seg = new Float32Array(ids.length * 4);
  ids.forEach((id, i) => writeDot(pos, colour, big, seg, id, i));
  for (const c of dotChunks) { scene.remove(c.points, c.segs); c.points.geometry.dispose(); c.segs.geometry.dispose(); }
  for (const c of fineDotChunks) { fineScene.remove(c.points, c.segs); c.points.geometry.dispose(); c.segs.geometry.dispose(); }
  dots = { attributes: { position: new THREE.BufferAttribute(pos, 2), colour: new THREE.BufferAttribute(colour, 3),
                         big: new THREE.BufferAttribute(big, 1) } };
  lines = { position: new THREE.BufferAttribute(seg, 2) };
  const dotMaterial = raw(dotVertex, dotFragment), lineMaterial = raw(lineVertex, lineFragment);
  const make = (size, into) => {
    const out = [];
    for (let start = 0; start < ids.length; start += size) {
      const n = Math.min(size, ids.length - start), sphere = new THREE.Sphere();
      const pg = new THREE.BufferGeometry(), lg = new THREE.BufferGeometry();
      for (const k in dots.attributes) pg.setAttribute(k, dots.attributes[k]);
      lg.setAttribute('position', lines.position);
      pg.setDrawRange(start, n); lg.setDrawRange(start * 2, n * 2);
      pg.boundingSphere = lg.boundingSphere = sphere;
      const c = { points: new THREE.Points(pg, dotMaterial), segs: new THREE.LineSegments(lg, lineMaterial),
                  lo: [Infinity, Infinity], hi: [-Infinity, -Infinity], sphere };
      c.segs.renderOrder = 2; c.points.renderOrder = 3;
      out.push(c);
      into.add(c.segs, c.points);
    }
    return out;
  };
  dotChunks = make(kChunk, scene);
  fineDotChunks = make(kFine, fineScene);
  if (picked.points) { indexScene.remove(picked.points, picked.segs); picked.points.geometry.dispose(); picked.segs.geometry.dispose(); }
  const pg = new THREE.BufferGeometry(), lg = new THREE.BufferGeometry();
  for (const k in dots.attributes) pg.setAttribute(k, dots.attributes[k]);
  lg.setAttribute('position', lines.position);
  pg.setIndex(new THREE.BufferAttribute(new Uint32Array(kPick), 1).setUsage(THREE.DynamicDrawUsage));
  lg.setIndex(new THREE.BufferAttribute(new Uint32Array(kPick * 2), 1).setUsage(THREE.DynamicDrawUsage));
  pg.setDrawRange(0, 0); lg.setDrawRange(0, 0);
  picked.points = new THREE.Points(pg, dotMaterial);
  picked.segs = new THREE.LineSegments(lg, lineMaterial);
  picked.segs.renderOrder = 2; picked.points.renderOrder = 3;
  picked.points.frustumCulled = picked.segs.frustumCulled = false;
  indexScene.add(picked.segs, picked.points);
  dotBox = new Float32Array(ids.length * 4);
  dotStamp = new Uint32Array(ids.length);
  grid.dot = new Array(kGrid * kGrid); grid.dotBig = [];
  for (let i = 0; i < ids.length; ++i) growDot(i);
}
function growDot(i) {  // a point's chunks' bounds take in its edge (both ends)
  const seg = lines.position.array;
  for (const c of [dotChunks[Math.floor(i / kChunk)], fineDotChunks[Math.floor(i / kFine)]]) {
    for (let k = 0; k < 4; k += 2) {
      const x = seg[i * 4 + k], y = seg[i * 4 + k + 1];
      if (x < c.lo[0]) c.lo[0] = x; if (y < c.lo[1]) c.lo[1] = y;
      if (x > c.hi[0]) c.hi[0] = x; if (y > c.hi[1]) c.hi[1] = y;
    }
    c.sphere.center.set((c.lo[0] + c.hi[0]) / 2, (c.lo[1] + c.hi[1]) / 2, 0);
    c.sphere.radius = Math.hypot(c.hi[0] - c.lo[0], c.hi[1] - c.lo[1]) / 2;
  }
  dotBox[i * 4] = Math.min(seg[i * 4], seg[i * 4 + 2]); dotBox[i * 4 + 1] = Math.min(seg[i * 4 + 1], seg[i * 4 + 3]);
  dotBox[i * 4 + 2] = Math.max(seg[i * 4], seg[i * 4 + 2]); dotBox[i * 4 + 3] = Math.max(seg[i * 4 + 1], seg[i * 4 + 3]);
  gridInsert(grid.dot, grid.dotBig, i, dotBox);
}
function writeDot(pos, colour, big, seg, id, i) {
  const v = state.verts.get(id);
  const x = v.x - state.origin[0], y = v.y - state.origin[1];
  pos[i * 2] = x; pos[i * 2 + 1] = y;
  const c = id === state.selected ? [0.95, 0.45, 0.0] : v.ring === undefined ? [0.72, 0.19, 0.48] : [0.04, 0.24, 0.57];
  colour.set(c, i * 3);
  big[i] = id === state.selected ? 1 : 0;
  const n = v.ring === undefined ? v : state.verts.get(v.next) || v;
  seg.set([x, y, n.x - state.origin[0], n.y - state.origin[1]], i * 4);
}
function refreshDots(ids) {  // in place: points that moved or whose selection changed, and their edges
  const a = dots.attributes;
  const touched = new Set();
  for (const id of ids) {
    touched.add(id);
    const v = state.verts.get(id);
    if (v && v.prev !== undefined) touched.add(v.prev);
  }
  const seg = lines.position;
  for (const attr of [a.position, a.colour, a.big, seg]) attr.clearUpdateRanges();
  for (const id of touched) {
    if (!dotIndex.has(id) || !state.verts.has(id)) continue;
    const i = dotIndex.get(id);
    const b = emptyBox();  // the point and its edge, before and after
    for (let k = 0; k < 4; k += 2) growBox(b, seg.array[i * 4 + k], seg.array[i * 4 + k + 1]);
    writeDot(a.position.array, a.colour.array, a.big.array, seg.array, id, i);
    for (let k = 0; k < 4; k += 2) growBox(b, seg.array[i * 4 + k], seg.array[i * 4 + k + 1]);
    markBox(b);
    growDot(i);
    // Only these points' entries go to the GPU (a drag rewrites one point 171k times over otherwise).
    for (const attr of [a.position, a.colour, a.big]) attr.addUpdateRange(i * attr.itemSize, attr.itemSize);
    seg.addUpdateRange(i * 4, 4);
  }
  a.position.needsUpdate = a.colour.needsUpdate = a.big.needsUpdate = seg.needsUpdate = true;
}

// ---- the view --------------------------------------------------------------------------------------------
// A frame redraws only what changed: the canvas keeps its pixels between frames (preserveDrawingBuffer),
// so an edit redraws the screen rectangles of its triangles and points (scissored, with a camera of that
// rectangle so that three.js culls every chunk outside it), and a pan by whole pixels shifts the last
// frame (one copy into a texture and one full-screen triangle) and draws only the strips it uncovers.
// A change of scale, size or colouring redraws everything. `fast` switches these off (?full=1), for
// benchmarks and for tests that compare a frame with a full redraw.
const params = new URLSearchParams(window.location.search);
const fast = { partial: !params.has('full'), scroll: !params.has('full'), index: !params.has('full') };
{  // what draws WebGL (for benches: SwiftShader is software)
  const gl = renderer.getContext(), info = gl.getExtension('WEBGL_debug_renderer_info');
  state.renderer = String(gl.getParameter(info ? info.UNMASKED_RENDERER_WEBGL : gl.RENDERER));
  fast.overlay = params.has('overlay') && params.get('overlay') !== '0';
}
state.fast = fast;
let dirty = true;     // the next frame redraws everything
let reference = false;  // and draws every chunk in view (no grid query): the frame the tests compare with
let boxes = [];       // else: these boxes of the mesh (relative to the origin, [x0, y0, x1, y1]) are redrawn
function requestDraw() { dirty = true; }
function markBox(b) { if (b && isFinite(b[0])) boxes.push(b); }
const growBox = (b, x, y) => {
  if (x < b[0]) b[0] = x; if (y < b[1]) b[1] = y;
  if (x > b[2]) b[2] = x; if (y > b[3]) b[3] = y;
};
const emptyBox = () => [Infinity, Infinity, -Infinity, -Infinity];
function resize() {
  renderer.setSize(view.clientWidth, view.clientHeight);
  const dpr = renderer.getPixelRatio();
  overlay.width = Math.round(view.clientWidth * dpr); overlay.height = Math.round(view.clientHeight * dpr);
  overlay.style.width = `${view.clientWidth}px`; overlay.style.height = `${view.clientHeight}px`;
  drag.shown = null;
  requestDraw();
}
function updateCamera() {
  const w = view.clientWidth / 2 * cam.scale, h = view.clientHeight / 2 * cam.scale;
  camera.left = cam.cx - w; camera.right = cam.cx + w; camera.top = cam.cy + h; camera.bottom = cam.cy - h;
  camera.updateProjectionMatrix();
  uniforms.uPointSize.value = Math.min(3, Math.max(0, 2.5 - Math.log10(cam.scale / (state.side / 2e5) + 1e-12)));
  // Split and Steiner points are drawn only once they are big enough to see (their pass costs a vertex
  // per triangle corner).
  for (const c of chunks) c.corners.visible = c.mesh.visible && layerMask.c && uniforms.uPointSize.value > 0.5;
  for (const c of fineChunks) c.corners.visible = c.mesh.visible && layerMask.c && uniforms.uPointSize.value > 0.5;
  // Shore points too dense to pick one out (zoomed out on a large shore) are left to the shoreline.
  const showDots = layerMask.d && (uniforms.uPointSize.value > 0.5 || state.verts.size < 20000);
  for (const c of [...dotChunks, ...fineDotChunks]) { c.points.visible = showDots; c.segs.visible = layerMask.d; }
  if (picked.mesh) {
    picked.mesh.visible = layerMask.t;
    picked.corners.visible = layerMask.t && layerMask.c && uniforms.uPointSize.value > 0.5;
  }
  if (picked.points) { picked.points.visible = showDots; picked.segs.visible = layerMask.d; }
  // The scale bar: a round length near 120 pixels.
  const target = 120 * cam.scale, p = Math.pow(10, Math.floor(Math.log10(target)));
  const len = [5, 2, 1].map((m) => m * p).find((l) => l <= target) || p;
  $('scale-bar').style.width = `${len / cam.scale}px`;
  $('scale-text').textContent = len >= 1000 && state.units === 'metres' ? `${len / 1000} km` : `${len} ${state.units}`;
}
function fit() {
  let lo = [Infinity, Infinity], hi = [-Infinity, -Infinity];
  const p = buffers.position.array;
  for (let i = 0; i < state.slots * 6; i += 2) {
    if (buffers.kind.array[i / 2] === 255) continue;
    lo = [Math.min(lo[0], p[i]), Math.min(lo[1], p[i + 1])];
    hi = [Math.max(hi[0], p[i]), Math.max(hi[1], p[i + 1])];
  }
  if (!isFinite(lo[0])) { lo = [0, 0]; hi = [state.side, state.side]; }
  cam.cx = (lo[0] + hi[0]) / 2; cam.cy = (lo[1] + hi[1]) / 2;
  cam.scale = 1.05 * Math.max((hi[0] - lo[0]) / view.clientWidth, (hi[1] - lo[1]) / view.clientHeight) || 1;
}
const frameWaiters = [];
let zooming = false;  // the camera's scale changed by the wheel (or state.zoom) since the last frame
const drawnView = { cx: NaN, cy: NaN, scale: NaN, w: 0, h: 0 };  // the camera of the pixels on the canvas
const subCamera = new THREE.OrthographicCamera(-1, 1, 1, -1, -1, 1);
// The last frame's pixels, shifted: a copy of the canvas read back with texelFetch (exact, no filtering).
const blit = {
  texture: null,
  shift: { value: new THREE.Vector2(0, 0) },
  scene: new THREE.Scene(),
};
{
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute('position', new THREE.BufferAttribute(new Float32Array([-1, -1, 3, -1, -1, 3]), 2));
  const material = new THREE.RawShaderMaterial({
    glslVersion: THREE.GLSL3, depthTest: false, depthWrite: false,
    uniforms: { uFrame: { value: null }, uShift: blit.shift },
    vertexShader: 'in vec2 position; void main() { gl_Position = vec4(position, 0.0, 1.0); }',
    fragmentShader: `precision highp float; precision highp sampler2D;
      uniform sampler2D uFrame; uniform vec2 uShift; out vec4 outColor;
      void main() {
        ivec2 at = ivec2(floor(gl_FragCoord.xy - uShift));
        ivec2 size = textureSize(uFrame, 0);
        if (at.x < 0 || at.y < 0 || at.x >= size.x || at.y >= size.y) discard;  // uncovered: drawn next
        outColor = texelFetch(uFrame, at, 0);
      }`,
  });
  blit.material = material;
  const quad = new THREE.Mesh(geometry, material);
  quad.frustumCulled = false;
  blit.scene.add(quad);
}
// While the wheel turns, the frame before it is drawn scaled (a preview, filtered), and the view is drawn in
// full once the wheel has rested for kZoomRest ms: zooming a million triangles costs one textured triangle a
// frame and one full frame at the end. Jumps (fit, zoomTo) draw in full at once.
const kZoomRest = 200;
const zoom = { texture: null, view: null, timer: null, map: { value: new THREE.Vector4() }, scene: new THREE.Scene() };
{
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute('position', new THREE.BufferAttribute(new Float32Array([-1, -1, 3, -1, -1, 3]), 2));
  zoom.material = new THREE.RawShaderMaterial({
    glslVersion: THREE.GLSL3, depthTest: false, depthWrite: false,
    uniforms: { uFrame: { value: null }, uMap: zoom.map },
    vertexShader: 'in vec2 position; void main() { gl_Position = vec4(position, 0.0, 1.0); }',
    fragmentShader: `precision highp float; precision highp sampler2D;
      uniform sampler2D uFrame; uniform vec4 uMap; out vec4 outColor;
      void main() {  // this pixel's place in the preview's frame (device pixels): uMap.xy * here + uMap.zw
        vec2 at = uMap.xy * gl_FragCoord.xy + uMap.zw, size = vec2(textureSize(uFrame, 0));
        if (at.x < 0.0 || at.y < 0.0 || at.x >= size.x || at.y >= size.y) discard;
        outColor = texture(uFrame, at / size);
      }`,
  });
  const quad = new THREE.Mesh(geometry, zoom.material);
  quad.frustumCulled = false;
  zoom.scene.add(quad);
}
let previewing = false;  // the canvas holds a zoom preview, not the view: the next frame other than one is full
renderer.info.autoReset = false;  // a frame may be several renders: its counts are their sum
// Redraws the rectangle (CSS pixels, top-left origin) of the view, scissored to it. What the grid picks in
// the rectangle widened by the largest point's radius is drawn through the full frame's camera and
// viewport: the same transform as a full frame, so a long line or edge crossing the rectangle is
// rasterized on the same pixels (a camera of the rectangle alone shifted them by rounding). Without the
// grid, the chunks are culled by a camera of the widened rectangle (a point whose centre is outside the
// viewport is not drawn at all).
function renderRect(x, y, rw, rh, w, h) {
  const m = 16;
  const vx = x - m, vy = y - m, vw = rw + 2 * m, vh = rh + 2 * m;
  subCamera.left = cam.cx + (vx - w / 2) * cam.scale;
  subCamera.right = cam.cx + (vx + vw - w / 2) * cam.scale;
  subCamera.top = cam.cy - (vy - h / 2) * cam.scale;
  subCamera.bottom = cam.cy - (vy + vh - h / 2) * cam.scale;
  renderer.setScissor(x, h - y - rh, rw, rh);
  renderer.setScissorTest(true);
  if (pick(subCamera.left, subCamera.bottom, subCamera.right, subCamera.top)) {
    renderer.setViewport(0, 0, w, h);
    renderer.render(indexScene, camera);
    return;
  }
  subCamera.updateProjectionMatrix();
  renderer.setViewport(vx, h - vy - vh, vw, vh);
  renderer.render(fineScene, subCamera);
}
// The boxes' rectangles on the screen (padded by a point's radius and a pixel of antialiasing), clipped to
// the view, those that overlap or nearly so merged (each rectangle is a render of every chunk it meets);
// null when they cover so much that one full frame is cheaper.
function boxRects(w, h) {
  let rects = [];
  for (const b of boxes) {
    const pad = 9;
    const x0 = Math.max(0, Math.floor((b[0] - cam.cx) / cam.scale + w / 2) - pad);
    const x1 = Math.min(w, Math.ceil((b[2] - cam.cx) / cam.scale + w / 2) + pad);
    const y0 = Math.max(0, Math.floor(h / 2 - (b[3] - cam.cy) / cam.scale) - pad);
    const y1 = Math.min(h, Math.ceil(h / 2 - (b[1] - cam.cy) / cam.scale) + pad);
    if (x1 <= x0 || y1 <= y0) continue;
    rects.push([x0, y0, x1, y1]);
  }
  const area = (r) => (r[2] - r[0]) * (r[3] - r[1]);
  for (let merged = true; merged;) {
    merged = false;
    for (let i = 0; i < rects.length && !merged; ++i) {
      for (let j = i + 1; j < rects.length && !merged; ++j) {
        const a = rects[i], b = rects[j];
        const u = [Math.min(a[0], b[0]), Math.min(a[1], b[1]), Math.max(a[2], b[2]), Math.max(a[3], b[3])];
        if (area(u) <= 1.5 * (area(a) + area(b)) + 4096) {
          rects[i] = u;
          rects.splice(j, 1);
          merged = true;
        }
      }
    }
  }
  // Past 40 % of the view one full frame is cheaper than a pass over the chunks per rectangle; with the
  // grid (pick()) a rectangle costs what it meets, so only a nearly covered view is drawn in full.
  if (rects.reduce((sum, r) => sum + area(r), 0) > (fast.index ? 0.9 : 0.4) * w * h) return null;
  return rects.map((r) => [r[0], r[1], r[2] - r[0], r[3] - r[1]]);
}
// What the last frame did: how ('full', 'partial', 'scroll' or 'none'), and three.js's counts summed over
// its renders (draw calls, triangles, points, line segments: what the GPU was given, whatever the machine).
state.drawn = null;
function draw() {
  const w = view.clientWidth, h = view.clientHeight, dpr = renderer.getPixelRatio();
  updateCamera();
  renderer.info.reset();
  picked.triangles = picked.dots = 0;
  let how = 'full', pixels = w * h, drawnRects = [[0, 0, w, h]];  // pixels: how many the frame drew (CSS pixels), the shifted copy aside
  const sameScale = drawnView.scale === cam.scale && drawnView.w === w && drawnView.h === h && Number.isInteger(dpr);
  // The content's shift since the last frame, in CSS pixels (right, down).
  const sx = (drawnView.cx - cam.cx) / cam.scale, sy = (cam.cy - drawnView.cy) / cam.scale;
  const rx = Math.round(sx), ry = Math.round(sy);
  const whole = Math.abs(sx - rx) < 1e-3 && Math.abs(sy - ry) < 1e-3;
  let rects = null;
  if (!dirty && sameScale && whole && fast.partial) rects = boxRects(w, h);
  if (rects && rx === 0 && ry === 0) how = rects.length ? 'partial' : 'none';
  else if (rects && fast.scroll && Math.abs(rx) < w / 2 && Math.abs(ry) < h / 2) how = 'scroll';
  if (how === 'full' && !dirty && fast.scroll && zooming && drawnView.w === w && drawnView.h === h) how = 'zoom';
  zooming = false;
  if (previewing && how !== 'zoom') how = 'full';
  if (how === 'zoom') {
    const tw = w * dpr, th = h * dpr;
    renderer.setScissorTest(false);
    renderer.setViewport(0, 0, w, h);
    if (!previewing) {  // the canvas holds the view: it is the preview's source
      if (!zoom.texture || zoom.texture.image.width !== tw || zoom.texture.image.height !== th) {
        if (zoom.texture) zoom.texture.dispose();
        zoom.texture = new THREE.FramebufferTexture(tw, th);
        zoom.texture.minFilter = zoom.texture.magFilter = THREE.LinearFilter;
        zoom.material.uniforms.uFrame.value = zoom.texture;
      }
      renderer.copyFramebufferToTexture(zoom.texture);
      zoom.view = { ...drawnView };
      previewing = true;
    }
    const o = zoom.view, k = cam.scale / o.scale;
    zoom.map.value.set(k, k, (cam.cx - o.cx) / o.scale * dpr + (w / 2) * dpr * (1 - k),
                       (cam.cy - o.cy) / o.scale * dpr + (h / 2) * dpr * (1 - k));
    renderer.render(zoom.scene, camera);  // cleared to the background first: what the preview lacks
    clearTimeout(zoom.timer);
    zoom.timer = setTimeout(requestDraw, kZoomRest);
  } else if (how === 'full') {
    renderer.setScissorTest(false);
    renderer.setViewport(0, 0, w, h);
    const indexed = !reference && pick(camera.left, camera.bottom, camera.right, camera.top);
    renderer.render(indexed ? indexScene : scene, camera);
    previewing = false;
    clearTimeout(zoom.timer);
  } else {
    pixels = 0;
    if (how === 'scroll') {
      const tw = w * dpr, th = h * dpr;
      if (!blit.texture || blit.texture.image.width !== tw || blit.texture.image.height !== th) {
        if (blit.texture) blit.texture.dispose();
        blit.texture = new THREE.FramebufferTexture(tw, th);
        blit.texture.minFilter = blit.texture.magFilter = THREE.NearestFilter;
        blit.material.uniforms.uFrame.value = blit.texture;
      }
      renderer.setScissorTest(false);
      renderer.setViewport(0, 0, w, h);
      renderer.copyFramebufferToTexture(blit.texture);
      blit.shift.value.set(rx * dpr, -ry * dpr);
      renderer.autoClear = false;
      renderer.render(blit.scene, camera);
      renderer.autoClear = true;
      if (rx > 0) rects.push([0, 0, rx, h]); else if (rx < 0) rects.push([w + rx, 0, -rx, h]);
      if (ry > 0) rects.push([0, 0, w, ry]); else if (ry < 0) rects.push([0, h + ry, w, -ry]);
    }
    for (const [x, y, rw, rh] of rects) { renderRect(x, y, rw, rh, w, h); pixels += rw * rh; }
    drawnRects = rects;
    renderer.setScissorTest(false);
    renderer.setViewport(0, 0, w, h);
  }
  dirty = false;
  reference = false;
  boxes = [];
  Object.assign(drawnView, { cx: cam.cx, cy: cam.cy, scale: cam.scale, w, h });
  const r = renderer.info.render;
  state.drawn = { how, calls: r.calls, triangles: r.triangles, points: r.points, lines: r.lines, pixels, rects: drawnRects,
                  picked: picked.triangles, pickedDots: picked.dots };
}
// fast.overlay (?overlay=1): while a shore point is dragged, the moves go to the server and their changes
// into the buffers, but the mesh's frames are held: the point and its two shore edges are drawn on a 2D
// canvas over the WebGL one, so that at the release no mesh frame is being rasterized ahead of the final
// move's. The held rectangles are drawn in the frame that shows the final move, the overlay cleared in the
// same frame; when the pointer rests kRest ms the held frame is drawn. Off by default: with the grid
// (pick()) a move's frame is a few triangles, and on SwiftShader release to frame measured no better with
// the overlay than with the mesh following the drag (bench/RESULTS.md). Either way the final move's
// change is drawn as soon as it comes (applyChange), not at the next animation frame.
const kRest = 150;
const drag = { hold: false, lastMove: 0, id: null, to: null, shown: null, onFinal: null };
const overlay = document.createElement('canvas');
overlay.style.cssText = 'position:absolute;left:0;top:0;pointer-events:none';
renderer.domElement.after(overlay);
// Drawn on the CPU (willReadFrequently): a few lines, and the GPU (SwiftShader: the same CPUs) is left to the
// mesh's frames.
const overlay2d = overlay.getContext('2d', { willReadFrequently: true });
function holding() {
  return drag.hold && (press === null || performance.now() - drag.lastMove < kRest);
}
function clearOverlay() {
  const [x0, y0, x1, y1] = drag.shown;
  overlay2d.clearRect(x0, y0, x1 - x0, y1 - y0);
  drag.shown = null;
}
function drawOverlay() {  // when what it shows moved: an unchanged overlay costs the compositor nothing
  const v = drag.id === null ? null : state.verts.get(drag.id);
  if (!v) { if (drag.shown) clearOverlay(); return; }
  const dpr = renderer.getPixelRatio();
  const at = (u) => toScreen(u.x, u.y).map((c) => c * dpr);
  const ends = [v.prev, v.next].map((id) => (id === undefined ? null : state.verts.get(id))).filter(Boolean);
  const [px, py] = at(v), r = Math.max(uniforms.uPointSize.value * 2, 4) * dpr;
  const key = [px, py, r, ...ends.flatMap(at)].join(' ');
  if (drag.shown && drag.key === key) return;
  if (drag.shown) clearOverlay();
  drag.key = key;
  const b = [px - r - 2, py - r - 2, px + r + 2, py + r + 2];
  overlay2d.lineWidth = dpr;
  overlay2d.strokeStyle = 'rgb(10,61,145)';
  overlay2d.beginPath();
  for (const u of ends) {
    const [x, y] = at(u);
    overlay2d.moveTo(px, py); overlay2d.lineTo(x, y);
    b[0] = Math.min(b[0], x - 2); b[1] = Math.min(b[1], y - 2); b[2] = Math.max(b[2], x + 2); b[3] = Math.max(b[3], y + 2);
  }
  overlay2d.stroke();
  overlay2d.fillStyle = 'rgb(242,115,0)';
  overlay2d.beginPath();
  overlay2d.arc(px, py, r, 0, 2 * Math.PI);
  overlay2d.fill();
  drag.shown = b.map((c, i) => (i < 2 ? Math.floor(c) : Math.ceil(c)));
  ++state.overlayFrames;
}
state.overlayFrames = 0;
state.heldFrames = 0;  // animation frames in which an edit's rectangles waited for the end of a drag
// For tests: the overlay's painted pixels (none once a drag's frame is drawn).
state.overlayPainted = () => {
  const d = overlay2d.getImageData(0, 0, overlay.width, overlay.height).data;
  let n = 0;
  for (let i = 3; i < d.length; i += 4) if (d[i] !== 0) ++n;
  return n;
};
// Bench: draw each frame to the end (a pixel read back) so that frame times include the rasterizing.
state.syncFrames = false;
function renderFrame() {
  const viewMoved = cam.cx !== drawnView.cx || cam.cy !== drawnView.cy || cam.scale !== drawnView.scale ||
                    view.clientWidth !== drawnView.w || view.clientHeight !== drawnView.h;
  const held = holding() && !dirty && !viewMoved;  // only an edit's rectangles wait
  if (held && boxes.length) ++state.heldFrames;
  if (!held && (dirty || boxes.length || viewMoved)) {
    if (drag.shown) clearOverlay();  // the mesh's frame shows the point where the overlay had it
    const start = performance.now();
    draw();
    const rendered = performance.now();
    if (state.syncFrames) {
      const gl = renderer.getContext();
      gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, probe);
    }
    state.frameTiming = { start, renderMs: rendered - start, rasterMs: performance.now() - rendered };
    if (changeFrame && changeFrame.version === state.version && !changeFrame.drawn) {
      Object.assign(changeFrame, { drawn: state.drawn, start, end: performance.now(), ...state.frameTiming });
    }
    ++state.frames;
  }
}
function frame() {
  renderFrame();
  if (holding()) drawOverlay();
  const now = performance.now();
  for (const f of frameWaiters.splice(0)) f(now);
  requestAnimationFrame(frame);
}
const probe = new Uint8Array(4);
function nextFrame() { return new Promise((resolve) => frameWaiters.push(resolve)); }

// Screen (CSS pixels in the view) <-> mesh coordinates (absolute).
function toWorld(px, py) {
  return [state.origin[0] + cam.cx + (px - view.clientWidth / 2) * cam.scale,
          state.origin[1] + cam.cy - (py - view.clientHeight / 2) * cam.scale];
}
function toScreen(x, y) {
  return [(x - state.origin[0] - cam.cx) / cam.scale + view.clientWidth / 2,
          view.clientHeight / 2 - (y - state.origin[1] - cam.cy) / cam.scale];
}

// ---- the mesh from the server ----------------------------------------------------------------------------
async function load() {
  const buf = await (await fetch('mesh')).arrayBuffer();
  const magic = new TextDecoder().decode(new Uint8Array(buf, 0, 4));
  if (magic !== 'SMSH') throw new Error('GET /mesh: not a shoremesh mesh');
  const length = new DataView(buf).getUint32(4, true);
  const head = JSON.parse(new TextDecoder().decode(new Uint8Array(buf, 8, length)));
  const xy = new Float32Array(buf, 8 + length, head.slots * 6);
  const kinds = new Uint8Array(buf, 8 + length + head.slots * 24, head.slots * 3);
  const depthsAt = Math.ceil((8 + length + head.slots * 27) / 4) * 4;
  const depths = head.depths ? new Float32Array(buf, depthsAt, head.slots * 3) : null;
  Object.assign(state, { version: head.version, triangles: head.triangles, slots: head.slots, origin: head.origin,
                         side: head.side, units: head.units || '', hasDepths: !!head.depths });
  buffers = null;
  allocate(head.slots);
  {
    const lo = [Infinity, Infinity], hi = [-Infinity, -Infinity];
    for (let s = 0; s < head.slots; ++s) {
      if (kinds[s * 3] === 255) continue;
      for (let k = 0; k < 6; k += 2) {
        lo[0] = Math.min(lo[0], xy[s * 6 + k]); lo[1] = Math.min(lo[1], xy[s * 6 + k + 1]);
        hi[0] = Math.max(hi[0], xy[s * 6 + k]); hi[1] = Math.max(hi[1], xy[s * 6 + k + 1]);
      }
    }
    if (isFinite(lo[0])) setGrid(lo, hi); else setGrid([0, 0], [head.side, head.side]);
  }
  for (let s = 0; s < head.slots; ++s) {
    if (kinds[s * 3] === 255) continue;
    writeSlot(s, xy.subarray(s * 6, s * 6 + 6), kinds.subarray(s * 3, s * 3 + 3), -1e9)  // made before this page: not highlighted;
  }
  let lo = Infinity, hi = -Infinity;
  for (let s = 0; s < head.slots; ++s) if (kinds[s * 3] !== 255) { const v = buffers.size.array[s * 3]; lo = Math.min(lo, v); hi = Math.max(hi, v); }
  uniforms.uSizeRange.value.set(lo, hi);
  updateChunks();
  if (depths) {
    buffers.depth.array.set(depths);
    let dlo = Infinity, dhi = -Infinity;
    for (let i = 0; i < depths.length; ++i) if (kinds[i] !== 255) { dlo = Math.min(dlo, depths[i]); dhi = Math.max(dhi, depths[i]); }
    uniforms.uDepthRange.value.set(isFinite(dlo) ? dlo : 0, isFinite(dhi) ? dhi : 1);
  }
  $('colour-depth').disabled = !depths;
  if (!depths && uniforms.uColour.value === 3) { uniforms.uColour.value = 0; $('colour').value = '0'; }
  state.verts = new Map();
  for (const r of head.rings) {
    const n = r.ids.length, open = r.role === 'line';
    r.ids.forEach((id, i) => state.verts.set(id, { x: r.xy[2 * i], y: r.xy[2 * i + 1], ring: r.ring, role: r.role,
                                                  prev: open && i === 0 ? undefined : r.ids[(i + n - 1) % n],
                                                  next: open && i === n - 1 ? undefined : r.ids[(i + 1) % n] }));
  }
  head.loose.ids.forEach((id, i) => state.verts.set(id, { x: head.loose.xy[2 * i], y: head.loose.xy[2 * i + 1] }));
  rebuildRings();
  showCounts();
  requestDraw();
}

// One accepted edit's change, in version order (from the POST's answer or the event stream, whichever
// comes first). A gap means changes were missed: reload everything.
let flashBox = null;  // the last edit's triangles (highlighted)
// The last change: its version, when and how it came (the POST's answer or the event stream, whichever was
// first), and the first frame drawn after it (for tests and benches).
let changeFrame = null;
// A change ahead of the next version waits for the ones before it (a drag's final move is posted without
// waiting for the move in flight: its answer may come first); the event stream brings every change in
// order, so a gap that lasts a second means changes were missed: reload everything.
const ahead = new Map();
let gapTimer = null;
function applyChange(change, via = 'post') {
  if (change.version <= state.version) return false;
  if (change.version !== state.version + 1) {
    if (!ahead.has(change.version)) ++state.changesAhead;
    ahead.set(change.version, { change, via });
    if (!gapTimer) gapTimer = setTimeout(() => { gapTimer = null; if (ahead.size) { ahead.clear(); reload(); } }, 1000);
    return false;
  }
  applyInOrder(change, via);
  for (let next; (next = ahead.get(state.version + 1));) { ahead.delete(next.change.version); applyInOrder(next.change, next.via); }
  for (const v of ahead.keys()) if (v <= state.version) ahead.delete(v);
  if (!ahead.size && gapTimer) { clearTimeout(gapTimer); gapTimer = null; }
  return true;
}
function applyInOrder(change, via) {
  if (change.slots > capacity) allocate(change.slots);
  const written = [];
  // What to redraw: where the triangles went and came, where the last edit's highlight was, and any slot
  // whose depths changed.
  const box = emptyBox(), p = buffers.position.array;
  const slotBox = (s, b) => { for (let k = 0; k < 6; k += 2) growBox(b, p[s * 6 + k], p[s * 6 + k + 1]); };
  for (const s of change.cleared) { slotBox(s, box); clearSlot(s); written.push(s); }
  for (const a of change.added) {
    writeSlot(a[0], a.slice(1, 7), a.slice(7, 10), change.version);
    slotBox(a[0], box);
    written.push(a[0]);
  }
  markBox(flashBox);
  markBox(box);
  flashBox = box;
  for (const d of change.depths || []) {  // the added slots' depths, and slots whose nodes' depths changed
    buffers.depth.array.set([d[1], d[2], d[3]], d[0] * 3);
    written.push(d[0]);
    const b = emptyBox();
    slotBox(d[0], b);
    markBox(b);
  }
  upload([...new Set(written)]);
  updateChunks();
  let structural = false;
  for (const p of change.inputs) {
    const old = state.verts.get(p.id);
    if (p.gone) {
      if (old && old.ring !== undefined) {
        const a = state.verts.get(old.prev), b = state.verts.get(old.next);
        if (a && a.next === p.id) a.next = old.next;
        if (b && b.prev === p.id) b.prev = old.prev;
      }
      state.verts.delete(p.id);
      if (state.selected === p.id) state.selected = null;
      structural = true;
    } else {
      if (!old) structural = true;
      state.verts.set(p.id, { x: p.x, y: p.y, ring: p.ring, role: p.role, prev: p.prev, next: p.next });
      // Neighbours not seen yet (a new ring's) come later in this change; a line's ends have one.
      const a = p.prev === undefined ? null : state.verts.get(p.prev);
      const b = p.next === undefined ? null : state.verts.get(p.next);
      if (a && a.next !== p.id) { a.next = p.id; structural = true; }
      if (b && b.prev !== p.id) { b.prev = p.id; structural = true; }
    }
  }
  if (structural) { rebuildRings(); requestDraw(); } else refreshDots(change.inputs.map((p) => p.id));
  Object.assign(state, { version: change.version, triangles: change.triangles, slots: Math.max(state.slots, change.slots) });
  uniforms.uVersion.value = change.version;
  changeFrame = { version: change.version, via, applied: performance.now(), drawn: null };
  state.changeFrame = changeFrame;
  ++state.redraws;
  if (drag.to && change.inputs.some((p) => p.id === drag.id && p.x === drag.to[0] && p.y === drag.to[1])) {
    // The drag's final move: drawn now, not at the next animation frame (the rasterizing then overlaps the
    // wait for it; the compositor shows the canvas at its next frame either way).
    drag.hold = false;
    drag.to = null;
    renderFrame();
    if (drag.onFinal) drag.onFinal({ change });
  }
  $('changed').textContent = `${change.cleared.length} out, ${change.added.length} in`;
  showCounts(change.reply);
  scheduleStats();
  return true;
}
let reloading = null;
state.changesAhead = 0;  // changes that came before one they follow (waited for it)
state.reloads = 0;
function reload() {
  if (!reloading) ++state.reloads;
  if (!reloading) reloading = load().finally(() => { reloading = null; });
  return reloading;
}

// ---- edits -----------------------------------------------------------------------------------------------
const fmt = (ms) => (ms === undefined ? '' : `${ms.toFixed(ms < 10 ? 2 : 1)} ms`);
function setStatus(text, refused) {
  $('status').textContent = text;
  $('status').className = refused ? 'refused' : '';
}
// POSTs one edit line; applies its change; resolves to the reply (ok or refused). `opts.live`: a move
// while dragging (not a history entry, not `last`); `opts.since`: when the user asked for it (the mouse
// release of a drag), for the time to the frame.
// `opts.applied`: the edit was already sent and applied (the last move of a drag): {reply, roundTripMs}.
// Where the time went (`state.last.profile`, for bench/editor_latency.cjs), from the Resource Timing entry of
// the POST and the server's Server-Timing header: `server` the request on the server (`lock` of it waiting
// for the session, `edit` running the line, `json` writing the answer), `network` the rest until the
// answer's first byte, `download`, `parse` (JSON.parse), `apply` (the slots and buffers), `waitFrame`
// (until the next animation frame), `render` (three.js's calls) and `raster` (the GPU finishing the frame:
// measured only when state.syncFrames is set).
performance.setResourceTimingBufferSize(100000);
function postTiming() {
  const entries = performance.getEntriesByType('resource').filter((e) => e.initiatorType === 'fetch' && /\/edit$/.test(e.name));
  performance.clearResourceTimings();
  const e = entries[entries.length - 1];
  if (!e) return {};
  const server = {};
  for (const t of e.serverTiming || []) server[t.name] = t.duration;
  return { requestStart: e.requestStart, responseStart: e.responseStart, responseEnd: e.responseEnd, server,
           bytes: e.encodedBodySize };
}
async function send(line, opts = {}) {
  const t0 = performance.now();
  let reply, t1, profile = {};
  if (opts.applied) {  // the live move's POST and its profile
    reply = opts.applied.reply;
    t1 = t0 + opts.applied.roundTripMs;
    profile = { ...opts.applied.profile };
  } else {
    const posted = (async () => {
      ++posting;
      const res = await fetch('edit', { method: 'POST', body: line, headers: { 'Content-Type': 'text/plain' } })
        .finally(() => { --posting; });
      const text = await res.text();
      const tText = performance.now();
      const out = JSON.parse(text);
      const tParse = performance.now();
      if (!res.ok) return { error: out.error };
      const t1 = performance.now();
      for (const c of out.changes) applyChange(c);
      const tApply = performance.now();
      const rt = postTiming();
      const serverMs = rt.server ? rt.server.total : undefined;
      return {
        t1, reply: { ...out.replies[0], version: out.version },  // the session's version after it (drag order)
        profile: {
          fetchStart: t0, bytes: rt.bytes ?? text.length, server: serverMs, lock: rt.server?.lock, edit: rt.server?.edit,
          json: rt.server?.json,
          network: rt.responseStart !== undefined ? rt.responseStart - t0 - (serverMs ?? 0) : undefined,
          download: rt.responseEnd !== undefined ? rt.responseEnd - rt.responseStart : undefined,
          toText: tText - t0, parse: tParse - tText, apply: tApply - tParse, applied: tApply,
        },
      };
    })();
    // A drag's final move: its change (which carries the edit's reply) may come by the event stream before
    // the POST's answer; then the page answers from it, and the POST's profile fills in when it comes.
    const early = opts.final ? new Promise((resolve) => { drag.onFinal = resolve; }) : null;
    let r = early ? await Promise.race([posted, early]) : await posted;
    if (early) drag.onFinal = null;
    if (r.error !== undefined) { setStatus(`${line}: ${r.error}`, true); return { ok: false, error: r.error }; }
    if (r.change) {
      const c = r.change;
      r = { t1: performance.now(), reply: { ...c.reply, version: c.version }, profile: { fetchStart: t0, pending: true } };
      const filled = r.profile;
      posted.then((p) => Object.assign(filled, p.profile || {}, { pending: false, answerMs: (p.t1 ?? NaN) - t0 }));
    }
    ({ reply, t1, profile } = r);
  }
  if (opts.live) {
    state.liveProfile = profile;
    if (reply.ok) ++state.liveMoves;
    followCursor();
    $('live-count').textContent = state.liveMoves;
    $('ms-server').textContent = reply.ok ? fmt(reply.ms) : '';
    $('ms-round').textContent = fmt(t1 - t0);
    return reply;
  }
  drag.hold = false;  // an edit's answer is drawn in the next frame
  const t2 = await nextFrame();
  const since = opts.since ?? t0;
  // The change's own frame (it may have come by the event stream before the POST's answer, and for a drag
  // whose final move went while dragging, before the release: times from the release then negative).
  const cf = changeFrame;
  if (profile.fetchStart !== undefined) profile.since = profile.fetchStart - since;
  if (cf && cf.drawn && reply.ok) {
    Object.assign(profile, { via: cf.via, changeApplied: cf.applied - since, waitFrame: cf.start - cf.applied,
                             render: cf.renderMs, raster: cf.rasterMs, changeFrame: cf.end - since });
  }
  profile.drawn = cf && cf.drawn;
  state.last = { line, ok: reply.ok, serverMs: reply.ms, roundTripMs: t1 - t0, frameMs: t2 - since, reply, profile };
  if (reply.ok) {
    ++state.edits;
    $('edit-count').textContent = state.edits;
    setStatus(`${line} (${fmt(reply.ms)} on the server)`, false);
    $('ms-server').textContent = fmt(reply.ms);
  } else {
    setStatus(`refused: ${line}: ${reply.error}`, true);
    $('ms-server').textContent = '';
  }
  $('ms-round').textContent = fmt(t1 - t0);
  $('ms-frame').textContent = fmt(t2 - since);
  return reply;
}

// Undo and redo: each history entry knows its edit and its inverse. An undone add or remove makes a new id
// (ids are never reused): history entries name points (and rings) by the id they had first, and `alias`
// maps that first id to the current one (`firstId` the other way).
const resolve = (id) => state.alias.get(id) ?? id;
const orig = (id) => state.firstId.get(id) ?? id;
const resolveRing = (r) => state.ringAlias.get(r) ?? r;
const origRing = (r) => state.ringOrigin.get(r) ?? r;
const num = (v) => String(v);  // shortest exact decimal: the server reads the same double back
function lineOf(op) {
  switch (op.type) {
    case 'move': return `move ${resolve(op.id)} ${num(op.to[0])} ${num(op.to[1])}`;
    case 'add': return op.after === undefined ? `add ${num(op.at[0])} ${num(op.at[1])}`
                                              : `add ${num(op.at[0])} ${num(op.at[1])} after ${resolve(op.after)}`;
    case 'remove': return `remove ${resolve(op.id)}`;
    case 'add-ring': return `${op.open ? 'add-line' : 'add-ring'} ${op.xy.map(num).join(' ')}`;
    case 'remove-ring': return `remove-ring ${resolveRing(op.ring) + 1}`;
  }
}
// The inverse of an edit that was just applied (its reply known; new ids already linked to first ids).
function inverseOf(op, reply) {
  switch (op.type) {
    case 'move': return { type: 'move', id: op.id, to: op.from, from: op.to };
    case 'add': return { type: 'remove', id: orig(reply.id), at: op.at, after: op.after };
    case 'remove': return { type: 'add', at: op.at, after: op.after, replaces: op.id };
    case 'add-ring': {
      const at = new Map(reply.ids.map((id, i) => [orig(id), [op.xy[2 * i], op.xy[2 * i + 1]]]));
      return { type: 'remove-ring', ring: origRing(reply.ring - 1), at, open: op.open };
    }
    case 'remove-ring': {  // the ring again in the server's order (the reply's ids), so that a fresh run is the same
      const ids = reply.ids.map(orig);
      return { type: 'add-ring', xy: ids.flatMap((id) => op.at.get(id)), open: op.open, replaces: ids, replacesRing: op.ring };
    }
  }
}
function link(first, now, alias, origin) { alias.set(first, now); origin.set(now, first); }
async function perform(op, history = 'new', opts = {}) {
  const reply = await send(lineOf(op), opts);
  if (!reply.ok) return reply;
  if (op.replaces !== undefined) {  // the point (or ring) came back under a new id
    if (Array.isArray(op.replaces)) op.replaces.forEach((id, i) => link(id, reply.ids[i], state.alias, state.firstId));
    else link(op.replaces, reply.id, state.alias, state.firstId);
  }
  if (op.replacesRing !== undefined) link(op.replacesRing, reply.ring - 1, state.ringAlias, state.ringOrigin);
  const entry = { op, inverse: inverseOf(op, reply) };
  if (history === 'new') { state.undo.push(entry); state.redo = []; }
  else if (history === 'undo') state.redo.push({ op: entry.inverse, inverse: op });
  else state.undo.push(entry);
  return reply;
}
async function undo() {
  const e = state.undo.pop();
  if (!e) return;
  const r = await perform(e.inverse, 'undo');
  if (!r.ok) state.undo.push(e);
}
async function redo() {
  const e = state.redo.pop();
  if (!e) return;
  const r = await perform(e.op, 'redo');
  if (!r.ok) state.redo.push(e);
}
function removeSelected() {
  const id = state.selected;
  const v = id !== null && state.verts.get(id);
  if (!v) return setStatus('select a point first (click it)', true);
  if (v.ring !== undefined && v.prev === undefined)  // `add X Y after ID` cannot put it back (undo)
    return setStatus("a line's first point: remove the whole line (R), or move it", true);
  return perform({ type: 'remove', id: orig(id), at: [v.x, v.y], after: v.prev === undefined ? undefined : orig(v.prev) });
}
// A ring's (or line's) ids, in order from `id` (a line's from its first point).
function ringIds(id) {
  let start = id;
  while (state.verts.get(start).prev !== undefined && state.verts.get(start).role === 'line') start = state.verts.get(start).prev;
  const ids = [];
  let at = start;
  do { ids.push(at); at = state.verts.get(at).next; } while (at !== undefined && at !== start);
  return ids;
}
function removeRingOfSelected() {
  const v = state.selected !== null && state.verts.get(state.selected);
  if (!v || v.ring === undefined) return setStatus('select an island (click inside it) or a point of the ring or line first', true);
  const at = new Map(ringIds(state.selected).map((id) => [orig(id), [state.verts.get(id).x, state.verts.get(id).y]]));
  return perform({ type: 'remove-ring', ring: origRing(v.ring), at, open: v.role === 'line' });
}

// ---- the mouse and keys ----------------------------------------------------------------------------------
function nearestPoint(px, py, radius) {
  let best = null, bestD = radius * radius;
  for (const [id, v] of state.verts) {
    const [sx, sy] = toScreen(v.x, v.y);
    const d = (sx - px) ** 2 + (sy - py) ** 2;
    if (d < bestD) { bestD = d; best = id; }
  }
  return best;
}
function nearestEdge(px, py, radius) {  // a shore edge near the cursor: the id it starts at and the foot
  const [wx, wy] = toWorld(px, py);
  let best = null, bestD = (radius * cam.scale) ** 2;
  for (const [id, a] of state.verts) {
    if (a.ring === undefined || a.next === undefined) continue;
    const b = state.verts.get(a.next);
    const dx = b.x - a.x, dy = b.y - a.y, l2 = dx * dx + dy * dy;
    const t = l2 > 0 ? Math.min(0.9, Math.max(0.1, ((wx - a.x) * dx + (wy - a.y) * dy) / l2)) : 0.5;
    const fx = a.x + t * dx, fy = a.y + t * dy, d = (fx - wx) ** 2 + (fy - wy) ** 2;
    if (d < bestD) { bestD = d; best = { after: id, at: [fx, fy] }; }
  }
  return best;
}
// The island under a click (land inside an island ring): one of its points, or null. Crossing count over
// the islands' edges (a picking aid: the edit itself is decided by the server).
function islandAt(px, py) {
  const [wx, wy] = toWorld(px, py);
  const inside = new Map();  // ring -> [crossings odd, a point]
  for (const [id, a] of state.verts) {
    if (a.role !== 'island') continue;
    const b = state.verts.get(a.next);
    if (!inside.has(a.ring)) inside.set(a.ring, [false, id]);
    if ((a.y > wy) !== (b.y > wy) && wx < a.x + ((wy - a.y) * (b.x - a.x)) / (b.y - a.y)) inside.get(a.ring)[0] ^= true;
  }
  for (const [in_, id] of inside.values()) if (in_) return id;
  return null;
}
function select(id) {
  const old = state.selected;
  state.selected = id;
  const v = id === null ? null : state.verts.get(id);
  $('selected').textContent = !v ? 'none' : v.ring === undefined ? `point ${id}`
    : `point ${id} of ${v.role || 'ring'} ${v.ring + 1}`;
  refreshDots([old, id].filter((x) => x !== null));
}

// A drag moves the point on the server while the mouse moves, one move in flight at a time (the next
// goes when the previous one's answer is in, to where the cursor is then); on release the final move is
// the drag's edit (one undo entry, from where the point was). Each move is an edit like any other, so the
// end state is the fresh run's on the final input (Lemma 7.2). A refused final move puts the point back
// where it was before the drag: a refused edit changes nothing.
let press = null, drawing = null;  // drawing: an island or line being clicked in ({kind, xy})
function followCursor() {  // the server's answer to a live move put the dragged point where it was sent
  if (!press || press.hit === null || !press.to || !state.verts.has(press.hit)) return;
  const v = state.verts.get(press.hit);
  [v.x, v.y] = press.to;
  refreshDots([press.hit]);
}
function liveMove(p) {
  if (!state.liveDrag || p.inflight || p.released || !p.to) return;
  const to = p.to;
  if (p.sent && p.sent[0] === to[0] && p.sent[1] === to[1]) return;
  p.sent = to;
  const t0 = performance.now();
  p.inflight = send(`move ${p.hit} ${num(to[0])} ${num(to[1])}`, { live: true }).then((reply) => {
    if (reply.ok) { p.applied = to; p.appliedReply = { reply, roundTripMs: performance.now() - t0, profile: state.liveProfile }; }
    p.inflight = null;
    liveMove(p);
  });
}
view.addEventListener('pointerdown', (e) => {
  if (e.button !== 0 || !state.ready || state.dragging) return;
  const r = view.getBoundingClientRect(), px = e.clientX - r.left, py = e.clientY - r.top;
  const hit = drawing ? null : nearestPoint(px, py, 8);
  press = { px, py, hit, moved: false, cx: cam.cx, cy: cam.cy };
  if (hit !== null) state.dragging = true;
  view.setPointerCapture(e.pointerId);
});
view.addEventListener('pointermove', (e) => {
  if (!press) return;
  const r = view.getBoundingClientRect(), px = e.clientX - r.left, py = e.clientY - r.top;
  if (Math.hypot(px - press.px, py - press.py) > 3) press.moved = true;
  if (!press.moved) return;
  if (press.hit !== null) {  // the point follows the cursor, the mesh follows the point
    const v = state.verts.get(press.hit);
    if (!press.from) press.from = [v.x, v.y];
    press.to = toWorld(px, py);
    Object.assign(drag, { hold: fast.overlay, id: press.hit, lastMove: performance.now() });
    followCursor();
    liveMove(press);
  } else {
    // By whole device pixels, so that a frame shifts the last one's pixels (see draw()).
    const dpr = renderer.getPixelRatio();
    cam.cx = press.cx - (Math.round((px - press.px) * dpr) / dpr) * cam.scale;
    cam.cy = press.cy + (Math.round((py - press.py) * dpr) / dpr) * cam.scale;
  }
});
// The final move is posted at once, without waiting for the answer to a move still in flight (unless that
// move goes where the final one would: then its answer is the drag's). The server applies edits one at a
// time in the order it takes them: should it take the final move first (the two came on two connections),
// the one in flight ends with a later version and the final move is sent again, so the session ends
// where the mouse was released.
state.finalResent = 0;  // final moves sent again: the server had taken them before the move in flight
async function release(p, px, py) {
  const since = performance.now();
  p.released = true;
  const to = toWorld(px, py);
  const inflight = p.inflight, sentThere = p.sent && p.sent[0] === to[0] && p.sent[1] === to[1];
  if (inflight && sentThere) await inflight;
  const v = state.verts.get(p.hit);
  const op = { type: 'move', id: orig(p.hit), from: p.from, to };
  const same = p.applied && p.applied[0] === to[0] && p.applied[1] === to[1];
  if (same) { drag.hold = false; renderFrame(); }  // the final move's change is in: its frame now
  else drag.to = to;  // its change, from the POST's answer or the event stream, ends the hold (applyChange)
  const reply = await perform(op, 'new', { since, applied: same ? p.appliedReply : undefined, final: !same });
  if (inflight && !sentThere) {
    await inflight;
    if (reply.ok && p.appliedReply && p.appliedReply.reply.version > reply.version) {
      ++state.finalResent;
      await send(`move ${p.hit} ${num(to[0])} ${num(to[1])}`, { live: true });
    }
  }
  if (!reply.ok) {
    [v.x, v.y] = p.applied ?? p.from;  // the server says where it is
    refreshDots([p.hit]);
  }
  if (!reply.ok && p.applied) {  // the moves made while dragging go too
    await send(`move ${p.hit} ${num(p.from[0])} ${num(p.from[1])}`, { live: true });
    setStatus(`refused: ${lineOf(op)}: ${reply.error} (the point is back where the drag began)`, true);
  }
}
view.addEventListener('pointerup', async (e) => {
  if (!press) return;
  const p = press;
  press = null;
  const r = view.getBoundingClientRect(), px = e.clientX - r.left, py = e.clientY - r.top;
  try {
    if (drawing && !p.moved) {
      drawing.xy.push(...toWorld(px, py));
      setStatus(`${drawing.kind}: ${drawing.xy.length / 2} point(s); Enter ends it, Escape drops it`, false);
    } else if (p.hit !== null && p.moved) {
      await release(p, px, py);
    } else if (p.hit !== null) {
      select(p.hit);
    } else if (!p.moved) {
      const edge = nearestEdge(px, py, 6);
      if (edge) await perform({ type: 'add', at: edge.at, after: orig(edge.after) });
      else select(islandAt(px, py));
    }
  } finally {
    state.dragging = false;
    Object.assign(drag, { hold: false, to: null });
  }
});
view.addEventListener('wheel', (e) => {
  e.preventDefault();
  const r = view.getBoundingClientRect(), px = e.clientX - r.left, py = e.clientY - r.top;
  const [wx, wy] = toWorld(px, py);
  cam.scale *= Math.exp(e.deltaY * 0.0015);
  const [nx, ny] = toWorld(px, py);
  cam.cx += wx - nx; cam.cy += wy - ny;
  zooming = true;
}, { passive: false });
function startDrawing(kind) {
  drawing = { kind, xy: [] };
  setStatus(kind === 'island' ? 'island: click its corners, Enter closes it, Escape drops it'
                              : 'line (a breakwater): click its points, Enter ends it, Escape drops it', false);
}
async function finishDrawing() {
  const { kind, xy } = drawing;
  drawing = null;
  if (kind === 'island' && xy.length < 6) return setStatus('an island needs three corners', true);
  if (kind === 'line' && xy.length < 4) return setStatus('a line needs two points', true);
  await perform({ type: 'add-ring', xy, open: kind === 'line' });
}
window.addEventListener('keydown', (e) => {
  if (e.target.tagName === 'INPUT') return;
  const k = e.key.toLowerCase();
  if ((e.ctrlKey || e.metaKey) && k === 'z') { e.preventDefault(); e.shiftKey ? redo() : undo(); }
  else if ((e.ctrlKey || e.metaKey) && k === 'y') { e.preventDefault(); redo(); }
  else if (k === 'delete' || k === 'backspace') removeSelected();
  else if (k === 'i') startDrawing('island');
  else if (k === 'l') startDrawing('line');
  else if (k === 'r') removeRingOfSelected();
  else if (k === 'enter' && drawing) finishDrawing();
  else if (k === 'escape') { drawing = null; setStatus('', false); }
  else if (k === 'f') { fit(); requestDraw(); }
});
$('remove').onclick = () => removeSelected();
$('undo').onclick = () => undo();
$('redo').onclick = () => redo();
$('island').onclick = () => startDrawing('island');
$('line').onclick = () => startDrawing('line');
$('remove-ring').onclick = () => removeRingOfSelected();
$('live').onchange = (e) => { state.liveDrag = e.target.checked; };
$('colour').onchange = (e) => { uniforms.uColour.value = Number(e.target.value); showLegend(); requestDraw(); };
$('export').onclick = async () => {
  const name = $('export-name').value.trim();
  const res = await fetch('edit', { method: 'POST', body: `export ${name}` });
  const out = await res.json();
  const reply = out.replies ? out.replies[0] : { ok: false, error: out.error };
  $('export-status').textContent = reply.ok ? `wrote ${reply.path} (${fmt(reply.ms)})` : `refused: ${reply.error}`;
};

// ---- the side panel --------------------------------------------------------------------------------------
function showCounts(reply) {
  $('tri-count').textContent = state.triangles.toLocaleString('en');
  if (reply) {
    $('input-count').textContent = reply.input_points?.toLocaleString('en') ?? '';
    $('split-count').textContent = reply.shore_splits?.toLocaleString('en') ?? '';
    $('steiner-count').textContent = reply.steiner_points?.toLocaleString('en') ?? '';
  }
}
// The summary (GET /stats) measures the whole mesh on the server (seconds at a million triangles on a loaded
// machine; on a session of its own, so edits go on meanwhile, but it takes CPU from them): asked for only
// once the edits have paused for a second and no drag or edit is under way.
let statsTimer = null, posting = 0;
function scheduleStats() {
  clearTimeout(statsTimer);
  statsTimer = setTimeout(() => (state.dragging || posting > 0 ? scheduleStats() : loadStats()), 1000);
}
async function loadStats() {
  const s = await (await fetch('stats')).json();
  showCounts(s);
  $('angles').textContent = `${s.min_angle.toFixed(2)}°–${s.max_angle.toFixed(2)}°`;
  $('shoreline').textContent = s.shore_segments === undefined ? 'no rings'
    : s.shore_conforming ? `conforming (${s.shore_segments})` : `${s.shore_covered} of ${s.shore_segments} segments`;
  if (uniforms.uBound.value !== s.min_angle_bound) requestDraw();  // the colours change everywhere
  uniforms.uBound.value = s.min_angle_bound;
  state.stats = s;
  showLegend();
}
function showLegend() {
  const mode = uniforms.uColour.value;
  const ramp = 'linear-gradient(to right, rgb(237,219,140), rgb(115,191,217), rgb(41,97,184))';
  const depthRamp = 'linear-gradient(to right, rgb(204,237,224), rgb(77,158,204), rgb(13,33,97))';
  $('legend').style.background = mode === 0 ? `linear-gradient(to right, rgb(217,51,38) 12%, rgb(237,219,140) 12%, rgb(115,191,217), rgb(41,97,184))`
    : mode === 1 ? ramp : mode === 3 ? depthRamp : 'rgb(158,204,230)';
  const [lo, hi] = uniforms.uSizeRange.value.toArray().map((v) => 2 ** v);
  const [dlo, dhi] = uniforms.uDepthRange.value.toArray();
  $('legend-text').textContent = mode === 0 ? `red: min angle below the bound ${uniforms.uBound.value.toFixed(2)}°; then up to 60°`
    : mode === 1 ? `longest edge ${lo.toPrecision(3)} to ${hi.toPrecision(3)} ${state.units} (log scale)`
    : mode === 3 ? `depth ${dlo.toPrecision(3)} to ${dhi.toPrecision(3)} m (positive down, square-root scale; at the nodes as exports give them)` : '';
}

// For tests and scripts: a point's place on the screen, and a view centred on it.
state.screenOf = (id) => { const v = state.verts.get(id); return toScreen(v.x, v.y); };
state.zoomTo = (id, unitsPerPixel) => {  // id null: the view's centre, unitsPerPixel times the scale
  if (id === null) cam.scale *= unitsPerPixel;
  else {
    const v = state.verts.get(id);
    cam.cx = v.x - state.origin[0]; cam.cy = v.y - state.origin[1]; cam.scale = unitsPerPixel;
  }
  requestDraw();
  return nextFrame();
};
state.nextFrame = nextFrame;
state.pan = (dx, dy) => { cam.cx += dx * cam.scale; cam.cy -= dy * cam.scale; return nextFrame(); };  // CSS pixels
state.fit = () => { fit(); requestDraw(); return nextFrame(); };
// A wheel step about the view's centre (factor > 1: out), drawn as the wheel draws it; and the time until
// the full frame after the wheel rested.
state.zoom = (factor) => { cam.scale *= factor; zooming = true; return nextFrame(); };
state.zoomRest = kZoomRest;
// Profiling (bench/): one frame drawn and read back (a pixel: the draw must have run), in ms; and layers
// switched off.
// `how`: 'chunks' (every chunk in view), 'grid' (what the grid picks in the view), 'clear' (nothing drawn);
// `rect`: [x, y, w, h] CSS pixels, a scissored rectangle through the camera of renderRect.
state.profileFrame = ({ how = 'chunks', rect = null } = {}) => {
  updateCamera();
  renderer.info.reset();
  picked.triangles = picked.dots = 0;
  const w = view.clientWidth, h = view.clientHeight;
  const t = performance.now();
  if (rect) {
    const [x, y, rw, rh] = rect;
    renderer.setViewport(x, h - y - rh, rw, rh);
    renderer.setScissor(x, h - y - rh, rw, rh);
    renderer.setScissorTest(true);
  }
  const cam2 = rect ? subCamera : camera;
  if (rect) {
    const [x, y, rw, rh] = rect;
    subCamera.left = cam.cx + (x - w / 2) * cam.scale; subCamera.right = cam.cx + (x + rw - w / 2) * cam.scale;
    subCamera.top = cam.cy - (y - h / 2) * cam.scale; subCamera.bottom = cam.cy - (y + rh - h / 2) * cam.scale;
    subCamera.updateProjectionMatrix();
  }
  if (how === 'clear') renderer.clear();
  else if (how === 'grid' && pick(cam2.left, cam2.bottom, cam2.right, cam2.top)) renderer.render(indexScene, cam2);
  else renderer.render(rect ? fineScene : scene, cam2);
  renderer.setScissorTest(false);
  renderer.setViewport(0, 0, w, h);
  const gl = renderer.getContext();
  gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, probe);
  const ms = performance.now() - t;
  state.drawn = { ...renderer.info.render, picked: picked.triangles, pickedDots: picked.dots };
  requestDraw();  // what the view shows again
  return ms;
};
state.layers = ({ dots: d = true, corners: c = true, triangles: t = true }) => {
  for (const k of [...chunks, ...fineChunks]) { k.mesh.visible = t && isFinite(k.lo[0]); k.corners.visible = c && k.mesh.visible; }
  layerMask = { d, c, t };
  requestDraw();
};
// What the page draws, for tests: each triangle's corners (float32, relative to the origin) as sorted
// text, the triangles sorted; and each drawn node's depth (by its float32 place).
state.drawnTriangles = () => {
  const p = buffers.position.array, out = [];
  for (let s = 0; s < state.slots; ++s) {
    if (buffers.kind.array[s * 3] === 255) continue;
    out.push([0, 1, 2].map((k) => `${p[s * 6 + 2 * k]} ${p[s * 6 + 2 * k + 1]}`).sort().join('|'));
  }
  return out.sort();
};
// The screen boxes (CSS pixels: x0, y0, x1, y1, clipped to the view) of the triangles the last edit wrote.
state.lastEditBoxes = () => {
  const p = buffers.position.array, out = [], w = view.clientWidth, h = view.clientHeight;
  for (let s = 0; s < state.slots; ++s) {
    if (buffers.kind.array[s * 3] === 255 || buffers.changed.array[s * 3] !== state.version) continue;
    const xs = [0, 2, 4].map((k) => toScreen(p[s * 6 + k] + state.origin[0], p[s * 6 + k + 1] + state.origin[1]));
    const b = [Math.max(0, Math.min(...xs.map((q) => q[0]))), Math.max(0, Math.min(...xs.map((q) => q[1]))),
               Math.min(w, Math.max(...xs.map((q) => q[0]))), Math.min(h, Math.max(...xs.map((q) => q[1])))];
    if (b[0] < b[2] && b[1] < b[3]) out.push(b);
  }
  return out;
};
state.drawnDepths = () => {
  const p = buffers.position.array, d = buffers.depth.array, at = new Map();
  for (let c = 0; c < state.slots * 3; ++c) if (buffers.kind.array[c] !== 255) at.set(`${p[2 * c]} ${p[2 * c + 1]}`, d[c]);
  return [...at.values()].sort((a, b) => a - b);
};
state.undoLast = undo;
state.setColour = (mode) => { uniforms.uColour.value = mode; $('colour').value = String(mode); showLegend(); requestDraw(); return nextFrame(); };
// For tests: the next frame redraws everything (to compare with what the partial frames left).
// The reference draws every chunk in view, as a full frame did before the grid (pick()).
state.redrawAll = () => { requestDraw(); reference = true; return nextFrame(); };
state.redraw = () => { requestDraw(); return nextFrame(); };  // a full frame as the page draws one
state.redoLast = redo;

window.addEventListener('resize', resize);
resize();
requestAnimationFrame(frame);
load().then(() => {
  fit();
  const events = new EventSource('events');
  events.addEventListener('change', (e) => applyChange(JSON.parse(e.data), 'events'));
  events.addEventListener('reload', () => reload());
  state.ready = true;
  return loadStats();
}).catch((err) => setStatus(`cannot load the mesh: ${err.message}`, true));
