// The 3D viewer: one GLB scene at a time (the API's scenes follow plan-format.md's conventions:
// millimetres under a root that scales to metres and turns Z-up into Y-up), orbit controls, a
// millimetre grid and axes under the model, hover picking of numbered nodes (`part-N` in the
// final view, `plate-N` in the plates and bent views), an exploded view and an assembly player.
// It renders on demand (on a change, not 60 times a second), so an idle page costs nothing.

import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';
import { getBuffer } from './api.js';

/** Names of pickable nodes and the number they carry. */
const NODE = /^(part|plate)-(\d+)$/;
const HIGHLIGHT = new THREE.Color(0xff7a00);
const MM = 0.001;
/** The grid lies this far below the model (a share of its size, at least 0.2 mm), so the
 * bottom plate's underside never fights with it for the same pixels. */
const GRID_DROP = 0.004;
/** A part the player adds slides in along its assembly direction over this long, ms… */
const MOVE_MS = 600;
/** …from this share of the model's size away. */
const MOVE_REACH = 0.35;

/** The numbered node an object belongs to, with its kind and number; null if none. */
function numbered(object) {
  for (let o = object; o; o = o.parent) {
    const m = NODE.exec(o.name || '');
    if (m) return { node: o, kind: m[1], number: Number(m[2]) };
  }
  return null;
}

/** Grid cell (1, 10 or 100 mm) that keeps a grid of `extentMm` to ~60 lines or fewer. */
export function gridCellMm(extentMm) {
  if (extentMm <= 40) return 1;
  if (extentMm <= 400) return 10;
  return 100;
}

function disposeTree(root) {
  root.traverse((o) => {
    if (o.geometry) o.geometry.dispose();
    const mats = Array.isArray(o.material) ? o.material : o.material ? [o.material] : [];
    mats.forEach((m) => m.dispose());
  });
}

/**
 * createViewer(canvas, { onHover(number|null, kind) }) → the viewer API of the page's contract:
 * load, setRender, highlight, explode, showUpTo, setOrder, setDirections, frame, clear, dispose,
 * and `stats`
 * (frames rendered, lastFrameMs: how long the last frame took).
 */
export function createViewer(canvas, { onHover = () => {}, stats = { frames: 0, lastFrameMs: 0 } } = {}) {
  const renderer = new THREE.WebGLRenderer({ canvas, antialias: true, preserveDrawingBuffer: true });
  renderer.setPixelRatio(Math.min(window.devicePixelRatio || 1, 2));
  const scene = new THREE.Scene();
  scene.background = new THREE.Color(0xf4f5f7);
  scene.add(new THREE.HemisphereLight(0xffffff, 0x8a8f99, 2.2));
  const sun = new THREE.DirectionalLight(0xffffff, 1.6);
  sun.position.set(1, 2, 1.5);
  scene.add(sun);
  const camera = new THREE.PerspectiveCamera(40, 1, 0.0005, 100);
  camera.position.set(0.3, 0.25, 0.3);
  const controls = new OrbitControls(camera, canvas);
  controls.enableDamping = false;
  const helpers = new THREE.Group();
  scene.add(helpers);

  const state = {
    model: null,
    nodes: new Map(), // number → { node, kind, home: Vector3, dir: Vector3 }
    order: [],
    directions: new Map(), // number → [x, y, z]: the way the part moves in, model axes
    motion: null, // { from: Map, to: Map, start } while parts slide in
    shown: Infinity,
    exploded: 0,
    highlighted: null,
    render: 'solid',
    size: 0.1,
    pending: false,
    disposed: false,
    generation: 0, // bumped by every load and clear: a load that finishes late is dropped
  };

  function requestRender() {
    if (state.pending || state.disposed) return;
    state.pending = true;
    requestAnimationFrame(() => {
      state.pending = false;
      const t0 = performance.now();
      renderer.render(scene, camera);
      stats.lastFrameMs = performance.now() - t0;
      stats.frames += 1;
    });
  }
  controls.addEventListener('change', requestRender);

  function resize() {
    const w = canvas.clientWidth || 1;
    const h = canvas.clientHeight || 1;
    renderer.setSize(w, h, false);
    camera.aspect = w / h;
    camera.updateProjectionMatrix();
    requestRender();
  }
  const observer = new ResizeObserver(resize);
  observer.observe(canvas);

  /** Rebuilds the grid and axes under the model's bounding box. */
  function placeHelpers(box) {
    disposeTree(helpers);
    helpers.clear();
    const size = box.getSize(new THREE.Vector3());
    const extentMm = Math.max(size.x, size.z, 0.01) / MM;
    const cell = gridCellMm(extentMm);
    const cells = Math.max(2, Math.ceil((extentMm * 1.4) / cell / 2) * 2);
    const grid = new THREE.GridHelper(cells * cell * MM, cells, 0x9aa3af, 0xd5d9df);
    const centre = box.getCenter(new THREE.Vector3());
    const floor = box.min.y - Math.max(size.length() * GRID_DROP, 0.2 * MM);
    grid.position.set(centre.x, floor, centre.z);
    // The axes start at the grid's corner, beside the model rather than hidden inside it.
    const half = (cells * cell * MM) / 2;
    const axes = new THREE.AxesHelper(Math.max(size.x, size.y, size.z) * 0.5);
    axes.position.set(centre.x - half, floor, centre.z + half);
    helpers.add(grid, axes);
    helpers.userData.cellMm = cell;
    stats.gridBelowModelMm = Math.round(((box.min.y - floor) / MM) * 1000) / 1000;
  }

  /** Numbered nodes get their own materials (so one can light up) and explode directions. */
  function indexNodes(root, centre) {
    state.nodes.clear();
    root.traverse((o) => {
      if (o.isMesh) o.material = o.material.clone();
      const m = NODE.exec(o.name || '');
      if (!m || state.nodes.has(Number(m[2]))) return;
      const c = new THREE.Box3().setFromObject(o).getCenter(new THREE.Vector3());
      const dir = c.sub(centre);
      if (dir.lengthSq() < 1e-12) dir.set(0, 1, 0);
      state.nodes.set(Number(m[2]), { node: o, kind: m[1], home: o.position.clone(), dir: dir.normalize() });
    });
    state.order = [...state.nodes.keys()].sort((a, b) => a - b);
  }

  /** What the tests read from window.platener.state: each numbered node's centre in
   * millimetres where the scene graph has it now (as exploded), the explode amount, and the
   * numbers shown, in assembly order. */
  function report() {
    const centres = {};
    for (const [n, { node }] of state.nodes) {
      const c = new THREE.Box3().setFromObject(node).getCenter(new THREE.Vector3());
      centres[n] = c.toArray().map((v) => Math.round((v / MM) * 1000) / 1000);
    }
    stats.partCentres = centres;
    stats.exploded = state.exploded;
    stats.shownParts = state.order.filter((n) => state.nodes.get(n).node.visible);
    stats.offscreenParts = offscreen();
  }

  /** The numbered nodes not wholly in the camera's view (a corner of their box outside it). */
  function offscreen() {
    camera.updateMatrixWorld();
    const out = [];
    for (const [n, { node }] of state.nodes) {
      const b = new THREE.Box3().setFromObject(node);
      if (b.isEmpty()) continue;
      const corners = [0, 1, 2, 3, 4, 5, 6, 7].map((i) => new THREE.Vector3(
        i & 1 ? b.max.x : b.min.x, i & 2 ? b.max.y : b.min.y, i & 4 ? b.max.z : b.min.z).project(camera));
      if (corners.some((c) => Math.abs(c.x) > 1 || Math.abs(c.y) > 1)) out.push(n);
    }
    return out;
  }

  /** Loads a GLB; `keepCamera` keeps the camera where it is (a re-cut of the same model).
   * Resolves to null when a later load or clear superseded it (nothing of it is shown). */
  async function load(url, { keepCamera = false } = {}) {
    const generation = ++state.generation;
    const buffer = await getBuffer(url);
    const gltf = await new Promise((resolve, reject) => {
      new GLTFLoader().parse(buffer, '', resolve, (e) => reject(new Error(`The 3D scene cannot be read: ${e.message || e}`)));
    });
    // A newer load or a clear came while this one was on its way: its scene is stale.
    if (generation !== state.generation) {
      disposeTree(gltf.scene);
      stats.scenesDropped = (stats.scenesDropped || 0) + 1;
      return null;
    }
    if (state.model) {
      scene.remove(state.model);
      disposeTree(state.model);
    }
    state.model = gltf.scene;
    dropMotion();
    state.directions = new Map();
    // Sample points (the primitives view) load one pixel wide: too small to see a primitive's
    // inliers by.
    state.model.traverse((o) => {
      if (o.isPoints) o.material.size = 3;
    });
    scene.add(state.model);
    state.model.updateMatrixWorld(true);
    const box = new THREE.Box3().setFromObject(state.model);
    if (box.isEmpty()) box.set(new THREE.Vector3(-0.05, 0, -0.05), new THREE.Vector3(0.05, 0.1, 0.05));
    state.size = box.getSize(new THREE.Vector3()).length();
    indexNodes(state.model, box.getCenter(new THREE.Vector3()));
    placeHelpers(box);
    state.highlighted = null;
    state.exploded = 0;
    state.shown = Infinity;
    setRender(state.render);
    if (keepCamera && state.framed) requestRender();
    else frame();
    state.framed = true;
    report();
    return { parts: state.nodes.size, triangles: triangleCount(state.model) };
  }

  /** Triangles drawn (lines and points not counted): the page compares them with the model's. */
  function triangleCount(root) {
    let n = 0;
    root.traverse((o) => {
      if (!o.isMesh || o.isLine || o.isPoints) return;
      const g = o.geometry;
      n += (g.index ? g.index.count : g.attributes.position.count) / 3;
    });
    return n;
  }

  function materials(o) {
    return Array.isArray(o.material) ? o.material : o.material ? [o.material] : [];
  }

  /** The highlighted part glows, and a translucent copy of it is drawn over everything (no
   * depth test): a part hidden behind others still shows where it is. */
  const overlayMaterial = new THREE.MeshBasicMaterial({
    color: HIGHLIGHT, transparent: true, opacity: 0.35, depthTest: false, depthWrite: false,
  });

  function highlight(number) {
    const paint = (n, on) => {
      const entry = state.nodes.get(n);
      if (!entry) return;
      const meshes = [];
      entry.node.traverse((o) => {
        if (o.userData.overlay) return;
        for (const m of materials(o)) if (m.emissive) m.emissive.copy(on ? HIGHLIGHT : new THREE.Color(0));
        if (o.isMesh && !o.isPoints && !o.userData.vertexCloud) meshes.push(o);
      });
      for (const o of meshes) {
        for (const child of o.children.filter((c) => c.userData.overlay)) o.remove(child);
        if (!on) continue;
        const ghost = new THREE.Mesh(o.geometry, overlayMaterial);
        ghost.userData.overlay = true;
        ghost.renderOrder = 10;
        ghost.raycast = () => {};
        o.add(ghost);
      }
    };
    if (state.highlighted !== null) paint(state.highlighted, false);
    state.highlighted = state.nodes.has(number) ? number : null;
    if (state.highlighted !== null) paint(state.highlighted, true);
    requestRender();
  }

  /** 'solid' | 'wireframe' | 'hidden' | 'vertices'. */
  function setRender(mode) {
    state.render = mode;
    if (!state.model) return;
    state.model.visible = mode !== 'hidden';
    state.model.traverse((o) => {
      if (o.userData.vertexCloud) {
        o.visible = mode === 'vertices';
        return;
      }
      if (!o.isMesh || o.userData.overlay) return;
      for (const m of materials(o)) m.wireframe = mode === 'wireframe';
      o.material.visible = mode !== 'vertices';
      if (mode === 'vertices' && !o.userData.points) {
        const points = new THREE.Points(o.geometry, new THREE.PointsMaterial({ color: 0x1f2937, size: 3, sizeAttenuation: false }));
        points.userData.vertexCloud = true;
        o.userData.points = points;
        o.add(points);
      }
    });
    requestRender();
  }

  /** Where a numbered node rests: its place, moved out by the exploded view. */
  function restPosition({ node, home, dir }) {
    const parent = node.parent;
    const world = parent.localToWorld(home.clone()).addScaledVector(dir, state.exploded * state.size * 0.3);
    return parent.worldToLocal(world);
  }

  /** Moves every numbered node out from the centre by t (0..1) of the model's size. */
  function explode(t) {
    endMotion();
    state.exploded = Math.max(0, Math.min(1, Number(t) || 0));
    for (const entry of state.nodes.values()) entry.node.position.copy(restPosition(entry));
    // The exploded parts stay in the picture and above the grid.
    const box = new THREE.Box3().setFromObject(state.model);
    placeHelpers(box);
    fit(box, camera.position.clone().sub(controls.target));
    report();
  }

  /** The assembly order for showUpTo (numbers); unknown numbers are ignored. */
  function setOrder(numbers) {
    const known = numbers.filter((n) => state.nodes.has(n));
    const rest = [...state.nodes.keys()].filter((n) => !known.includes(n)).sort((a, b) => a - b);
    state.order = known.concat(rest);
    report();
  }

  /** The way each part moves into place (plan.json's assembly steps, model axes); parts not
   * named appear where they are. */
  function setDirections(byNumber) {
    state.directions = new Map(Object.entries(byNumber || {}).map(([n, d]) => [Number(n), d]));
  }

  /** Shows the first k parts of the assembly order (Infinity: all). With `animate`, the parts
   * this adds slide into place along their directions (not with reduced motion asked for). */
  function showUpTo(k, { animate = false } = {}) {
    endMotion();
    const before = state.order.filter((n, i) => i < state.shown);
    state.shown = k;
    state.order.forEach((n, i) => {
      state.nodes.get(n).node.visible = i < k;
    });
    const added = state.order.filter((n, i) => i < k && !before.includes(n) && state.directions.has(n));
    const calm = window.matchMedia && window.matchMedia('(prefers-reduced-motion: reduce)').matches;
    if (animate && !calm && added.length && added.length <= 24) startMotion(added);
    report();
    requestRender();
  }

  /** Starts `numbers` sliding in: each from MOVE_REACH of the model's size back along its
   * direction (the way it came from) to where it rests. */
  function startMotion(numbers) {
    const from = new Map();
    const to = new Map();
    for (const n of numbers) {
      const entry = state.nodes.get(n);
      const parent = entry.node.parent;
      const rest = restPosition(entry);
      const way = new THREE.Vector3(...state.directions.get(n));
      if (way.lengthSq() < 0.25) continue;
      // The direction is in the model's axes, the parent's frame: its length in the world
      // says how far one millimetre is.
      const worldRest = parent.localToWorld(rest.clone());
      const worldWay = parent.localToWorld(rest.clone().add(way.normalize())).sub(worldRest).normalize();
      const start = parent.worldToLocal(worldRest.clone().addScaledVector(worldWay, -state.size * MOVE_REACH));
      from.set(n, start);
      to.set(n, rest);
      entry.node.position.copy(start);
    }
    if (!from.size) return;
    state.motion = { from, to, start: performance.now() };
    stats.motion = Object.fromEntries([...from.keys()].map((n) => [n, {
      direction: state.directions.get(n),
      from: from.get(n).toArray(),
      to: to.get(n).toArray(),
    }]));
    stats.moving = [...from.keys()];
    requestAnimationFrame(stepMotion);
  }

  function stepMotion(now) {
    const m = state.motion;
    if (!m || state.disposed) return;
    const t = Math.min(1, Math.max(0, (now - m.start) / MOVE_MS));
    const eased = 1 - (1 - t) ** 3;
    for (const [n, from] of m.from) state.nodes.get(n).node.position.lerpVectors(from, m.to.get(n), eased);
    requestRender();
    if (t < 1) requestAnimationFrame(stepMotion);
    else endMotion();
  }

  /** Forgets a motion under way (its scene is gone). */
  function dropMotion() {
    state.motion = null;
    stats.moving = [];
  }

  /** Puts the moving parts where they rest (a new step, an explode, a new scene). */
  function endMotion() {
    const m = state.motion;
    if (!m) return;
    state.motion = null;
    for (const [n, to] of m.to) {
      const entry = state.nodes.get(n);
      if (entry) entry.node.position.copy(to);
    }
    stats.moving = [];
    report();
    requestRender();
  }

  function frame() {
    if (!state.model) return;
    fit(new THREE.Box3().setFromObject(state.model), new THREE.Vector3(1, 0.8, 1.2));
  }

  /** Points the camera at `box` from direction `from` (kept: the user's orbit), just far
   * enough that the box's bounding sphere fills the view. */
  function fit(box, from) {
    if (box.isEmpty()) return;
    const centre = box.getCenter(new THREE.Vector3());
    const radius = Math.max(box.getSize(new THREE.Vector3()).length() / 2, 0.005);
    // The narrower of the two half-angles, so a tall canvas (a phone) keeps the sides too.
    const vHalf = THREE.MathUtils.degToRad(camera.fov / 2);
    const half = Math.min(vHalf, Math.atan(Math.tan(vHalf) * camera.aspect));
    const distance = radius / Math.sin(half) * 1.05;
    const dir = from.lengthSq() > 0 ? from.clone().normalize() : new THREE.Vector3(1, 0.8, 1.2).normalize();
    camera.near = distance / 100;
    camera.far = distance * 100;
    camera.position.copy(centre).addScaledVector(dir, distance);
    camera.updateProjectionMatrix();
    controls.target.copy(centre);
    controls.update();
    requestRender();
  }

  // Hover picking: the nearest numbered node under the pointer.
  const ray = new THREE.Raycaster();
  const pointer = new THREE.Vector2();
  let hovered = null;
  function setHovered(hit) {
    const n = hit ? hit.number : null;
    if (n === hovered) return;
    hovered = n;
    highlight(n);
    onHover(n, hit ? hit.kind : null);
  }
  function pick(event) {
    if (!state.model || state.nodes.size === 0 || event.buttons) return;
    const r = canvas.getBoundingClientRect();
    pointer.set(((event.clientX - r.left) / r.width) * 2 - 1, -((event.clientY - r.top) / r.height) * 2 + 1);
    ray.setFromCamera(pointer, camera);
    const hits = ray.intersectObject(state.model, true).filter((h) => h.object.isMesh && h.object.visible);
    setHovered(hits.length ? numbered(hits[0].object) : null);
  }
  canvas.addEventListener('pointermove', pick);
  canvas.addEventListener('pointerleave', () => setHovered(null));

  // Keyboard: arrows turn, + and - zoom, f or Home frames the model, n and p step through parts.
  canvas.addEventListener('keydown', (e) => {
    const offset = camera.position.clone().sub(controls.target);
    const s = new THREE.Spherical().setFromVector3(offset);
    const step = Math.PI / 24;
    const keys = {
      ArrowLeft: () => (s.theta -= step),
      ArrowRight: () => (s.theta += step),
      ArrowUp: () => (s.phi = Math.max(0.05, s.phi - step)),
      ArrowDown: () => (s.phi = Math.min(Math.PI - 0.05, s.phi + step)),
      '+': () => (s.radius *= 0.85),
      '=': () => (s.radius *= 0.85),
      '-': () => (s.radius /= 0.85),
    };
    if (e.key === 'n' || e.key === 'p') {
      // Step through the parts from the keyboard, as hovering does with the pointer.
      const numbers = state.order.filter((n) => state.nodes.get(n).node.visible);
      if (!numbers.length) return;
      const i = numbers.indexOf(hovered);
      const next = numbers[(i + (e.key === 'n' ? 1 : numbers.length - 1 + (i < 0 ? 1 : 0))) % numbers.length];
      setHovered({ number: next, kind: state.nodes.get(next).kind });
    } else if (e.key === 'f' || e.key === 'Home') {
      frame();
    } else if (keys[e.key]) {
      keys[e.key]();
      camera.position.copy(controls.target).add(new THREE.Vector3().setFromSpherical(s));
      controls.update();
    } else {
      return;
    }
    e.preventDefault();
  });

  /** Removes the model (the grid and axes stay). */
  function clear() {
    state.generation += 1;
    if (state.model) {
      scene.remove(state.model);
      disposeTree(state.model);
    }
    state.model = null;
    dropMotion();
    state.nodes.clear();
    state.order = [];
    state.highlighted = null;
    report();
    requestRender();
  }

  function dispose() {
    state.disposed = true;
    overlayMaterial.dispose();
    observer.disconnect();
    controls.dispose();
    if (state.model) disposeTree(state.model);
    disposeTree(helpers);
    renderer.dispose();
  }

  resize();
  return {
    load, setRender, highlight, explode, showUpTo, setOrder, setDirections, frame, clear, dispose, stats,
    get parts() { return [...state.nodes.keys()]; },
    get gridCellMm() { return helpers.userData.cellMm || null; },
  };
}
