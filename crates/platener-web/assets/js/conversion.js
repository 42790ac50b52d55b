// The conversion area: upload, settings (a change re-cuts and keeps the view), progress, the seven
// 3D views, the sheets with their numbers, hover linking between 3D and sheet, the final view's
// exploded slider and assembly player, publishing.

import * as api from './api.js';
import { createViewer } from './viewer.js';
import { createSheets } from './sheets.js';
import { assemblyOrder } from './assembly.js';
import * as progress from './progress.js';
import { showPublishing } from './publish.js';
import { showWarnings } from './warnings.js';
import { laserNote, partsShown } from './wording.js';

const $ = (id) => document.getElementById(id);
export const VIEWS = ['model', 'wireframe', 'coplanar', 'primitives', 'plates', 'bent', 'final'];
const FINISHED = new Set(['done', 'failed', 'cancelled']);

/** The settings form as the API takes them. */
export function readSettings() {
  const thicknesses = [...document.querySelectorAll('input[name="thickness"]:checked')].map((i) => Number(i.value));
  const custom = Number($('thickness-custom').value);
  if (custom > 0 && !thicknesses.includes(custom)) thicknesses.push(custom);
  return { thicknesses: thicknesses.length ? thicknesses : [3], material: $('material').value, method: $('method').value };
}

function writeSettings(s) {
  if (!s) return;
  const ts = (s.thicknesses || []).map(Number);
  const common = [];
  for (const box of document.querySelectorAll('input[name="thickness"]')) {
    box.checked = ts.includes(Number(box.value));
    if (box.checked) common.push(Number(box.value));
  }
  const other = ts.find((t) => !common.includes(t));
  $('thickness-custom').value = other === undefined ? '' : String(other);
  if (s.material) $('material').value = s.material;
  if (s.method) $('method').value = s.method;
}

export function createConversionArea({ state, onGalleryChange }) {
  let viewer = null;
  let current = null; // the conversion JSON
  let plan = null;
  let stopEvents = () => {};
  let playTimer = null;
  let keepCamera = false; // the next scene is a re-cut of the one shown: keep the camera
  const listeners = new Set();
  const sheets = createSheets($('sheets'), { onHover: (n) => hover(n, 'part', 'sheet') });

  try {
    viewer = createViewer($('viewer'), { onHover: (n, kind) => hover(n, kind, 'viewer'), stats: state });
  } catch (e) {
    $('viewer-note').textContent = 'This browser cannot show 3D (WebGL is off); the sheets and downloads still work.';
  }

  /** Hover from either side: label (with its sheet when there are several), and the same
   * part on the other side (the sheet list scrolled to it). */
  function hover(n, kind, from) {
    state.hovered = n;
    const sheet = kind === 'part' && sheets.count > 1 ? sheets.sheetOf(n) : null;
    $('part-label').textContent = n == null ? '' : `${kind === 'plate' ? 'Plate' : 'Part'} ${n}${sheet ? `, sheet ${sheet}` : ''}`;
    if (from === 'viewer') sheets.highlight(kind === 'part' ? n : null, { reveal: true });
    if (from === 'sheet' && viewer && state.view === 'final') viewer.highlight(n);
  }

  function setViewButtons() {
    for (const b of document.querySelectorAll('[data-view]')) {
      b.setAttribute('aria-pressed', String(b.dataset.view === state.view));
      b.disabled = !(current && current.links && current.links.scenes && current.links.scenes[b.dataset.view]);
    }
    $('final-tools').hidden = state.view !== 'final' || !state.loadedView;
  }

  async function showView(view) {
    state.view = view;
    setViewButtons();
    const url = current && current.links.scenes && current.links.scenes[view];
    if (!viewer || !url) return;
    state.loadedView = null;
    hover(null, null, 'viewer');
    const id = state.id;
    try {
      const loaded = await viewer.load(url, { keepCamera });
      keepCamera = false;
      // Superseded (another view, or another conversion opened meanwhile): not ours to mark.
      if (!loaded || state.view !== view || state.id !== id) return;
      state.loadedView = view;
      $('viewer-note').hidden = true;
      noteSimplified(view, loaded.triangles);
      if (view === 'final') setupFinal();
      setViewButtons();
      emit('view', view);
    } catch (e) {
      progress.showError(`The ${view} view could not be shown: ${e.message}`);
    }
  }

  /** The server draws very large models simplified (a CPU renderer could not turn them):
   * say so under the model view, with the counts, so nobody takes it for the model's detail. */
  function noteSimplified(view, drawn) {
    const read = current && current.model && current.model.triangles;
    const simplified = view === 'model' && read > 0 && drawn < read;
    const n = (x) => Math.round(x).toLocaleString('en');
    $('simplified').textContent = simplified
      ? `Simplified for viewing: ${n(drawn)} of the model's ${n(read)} triangles are drawn. The plan is made from all of them.`
      : '';
    $('simplified').hidden = !simplified;
  }

  /** Exploded view and assembly player for the final view, from plan.json's joints. */
  function setupFinal() {
    $('explode').value = '0';
    const parts = plan ? plan.parts.map((p) => p.id) : viewer.parts;
    state.assembly = assemblyOrder(parts, plan ? plan.joints : []);
    viewer.setOrder(state.assembly);
    const player = $('player');
    player.max = String(state.assembly.length);
    player.value = String(state.assembly.length);
    showParts(state.assembly.length);
  }

  function showParts(k) {
    viewer.showUpTo(k);
    $('player').value = String(k);
    const total = state.assembly.length;
    const last = state.assembly[k - 1];
    $('player-out').textContent = partsShown(k, total, last);
  }

  function stopPlaying() {
    clearInterval(playTimer);
    playTimer = null;
    $('player-play').textContent = 'Play assembly';
  }

  $('explode').addEventListener('input', (e) => viewer && viewer.explode(Number(e.target.value) / 100));
  $('player').addEventListener('input', (e) => {
    stopPlaying();
    showParts(Number(e.target.value));
  });
  $('player-step').addEventListener('click', () => {
    stopPlaying();
    const k = Number($('player').value);
    showParts(k >= state.assembly.length ? 1 : k + 1);
  });
  $('player-play').addEventListener('click', () => {
    if (playTimer) return stopPlaying();
    showParts(1);
    $('player-play').textContent = 'Stop';
    playTimer = setInterval(() => {
      const k = Number($('player').value);
      if (k >= state.assembly.length) return stopPlaying();
      showParts(k + 1);
    }, 700);
  });
  for (const b of document.querySelectorAll('[data-view]')) b.addEventListener('click', () => showView(b.dataset.view));
  $('zoom-in').addEventListener('click', () => sheets.zoom(1.5));
  $('zoom-out').addEventListener('click', () => sheets.zoom(1 / 1.5));
  $('zoom-fit').addEventListener('click', () => sheets.zoom('fit'));
  $('sheets').addEventListener('keydown', (e) => {
    const factor = { '+': 1.5, '=': 1.5, '-': 1 / 1.5, 0: 'fit' }[e.key];
    if (factor === undefined) return;
    e.preventDefault();
    sheets.zoom(factor);
  });

  function emit(kind, data) {
    for (const f of listeners) f(kind, data);
  }

  return {
    get conversion() { return current; },
    get plan() { return plan; },
    get viewer() { return viewer; },
    on(f) { listeners.add(f); },
    writeSettings,
    open: openConversion,
    reset,
  };

  function reset() {
    stopEvents();
    stopPlaying();
    current = null;
    plan = null;
    state.id = null;
    state.status = null;
    state.loadedView = null;
    state.hovered = null;
    if (viewer) viewer.clear();
    $('viewer-note').hidden = false;
    $('part-label').textContent = '';
    $('simplified').hidden = true;
    progress.clearProgress();
    progress.status('No model yet.');
    sheets.clear();
    showStats(null, null);
    setViewButtons();
    $('download').disabled = true;
    showPublishing(null);
    $('share').hidden = true;
    $('warnings-box').hidden = true;
  }

  /** Opens conversion `id`; `recut`: it re-cuts the one shown, so the camera stays. */
  async function openConversion(id, { recut = false } = {}) {
    reset();
    keepCamera = recut;
    state.id = id;
    progress.status('Loading…');
    try {
      current = await api.conversion(id);
    } catch (e) {
      progress.status('');
      progress.showError(e.message);
      return;
    }
    writeSettings(current.settings);
    state.status = current.status;
    if (FINISHED.has(current.status)) return finished(current);
    progress.status(`Converting ${current.model.name}…`);
    stopEvents = api.events(id, (kind, data) => onEvent(id, kind, data));
  }

  function onEvent(id, kind, data) {
    if (state.id !== id) return;
    if (kind === 'step') progress.stepEvent(data);
    else if (kind === 'method') progress.methodEvent(data);
    else if (FINISHED.has(kind) || kind === 'lost') reload(id);
  }

  /** After the last event (or a lost stream): the conversion as it is now. A stream lost
   * while the job still runs (a restarting server) is followed again a moment later. */
  async function reload(id) {
    try {
      const c = await api.conversion(id);
      if (state.id !== id) return;
      if (FINISHED.has(c.status)) return await finished(c);
      setTimeout(() => {
        if (state.id === id) stopEvents = api.events(id, (kind, data) => onEvent(id, kind, data));
      }, 2000);
    } catch (e) {
      progress.showError(e.message);
    }
  }

  async function finished(c) {
    current = c;
    state.status = c.status;
    if (!document.querySelector('#progress li')) {
      progress.finishedSteps(c);
      replayMethodSteps(c.id);
    } else {
      for (const m of c.methods || []) progress.methodEvent(m);
    }
    const err = progress.errorOf(c);
    progress.showError(err);
    showWarnings(c);
    progress.status(c.best ? `${c.model.name}: plan made by the ${c.best} method.` : `${c.model.name}: no plan.`);
    setViewButtons();
    if (!c.best) return emit('finished', c);
    $('download').disabled = false;
    showPublishing(c);
    $('share').hidden = false;
    $('share').href = `#/c/${encodeURIComponent(c.id)}`;
    await Promise.all([loadPlanAndSheets(c), showView(state.view || 'final')]);
    emit('finished', c);
  }

  /** A conversion opened after it ran: each method's steps with their times, from the event
   * stream, which replays every event of a finished conversion and then closes. */
  function replayMethodSteps(id) {
    stopEvents = api.events(id, (kind, data) => {
      if (state.id === id && kind === 'step' && data.method && data.state === 'finished') progress.stepEvent(data);
    });
  }

  async function loadPlanAndSheets(c) {
    const links = c.links.methods[c.best] || {};
    try {
      const [p, report] = await Promise.all([api.getJson(links.plan_json), api.getJson(links.report_json), sheets.show(links.sheets || [])]);
      plan = p;
      showStats(c, report);
      if (state.loadedView === 'final') setupFinal();
    } catch (e) {
      progress.showError(`The sheets could not be shown: ${e.message}`);
    }
  }

  /** Score, counts, cut length and laser time (report.json's estimate at its stated speeds). */
  function showStats(c, report) {
    const m = c && (c.methods || []).find((x) => x.method === c.best);
    const set = (k, v) => (document.querySelector(`#stats [data-stat="${k}"]`).textContent = v);
    set('score', m && m.score != null ? Number(m.score).toFixed(2) : '–');
    set('parts', m ? String(m.parts) : '–');
    set('sheets', m ? String(m.sheets) : '–');
    const r = report || {};
    set('cut', r.cut_length != null ? `${(r.cut_length / 1000).toFixed(2)} m` : '–');
    set('minutes', r.estimated_cutting_seconds != null ? `≈ ${(r.estimated_cutting_seconds / 60).toFixed(1)} min` : '–');
    $('speed-note').textContent = laserNote(r.settings);
  }
}

/** Uploads a file and returns the new conversion (its delete token kept in localStorage). */
export async function uploadModel(file) {
  const c = await api.upload(file, readSettings());
  if (c.delete_token) api.tokens.set(c.id, c.delete_token);
  return c;
}

/** Re-cuts conversion `id` with `changes`; the new conversion's token is kept too. */
export async function recutModel(id, changes) {
  const c = await api.recut(id, changes);
  if (c.delete_token) api.tokens.set(c.id, c.delete_token);
  return c;
}
