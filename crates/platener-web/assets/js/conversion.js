// The conversion area: upload, settings (a change re-cuts and keeps the view), progress, the seven
// 3D views, the sheets with their numbers, hover linking between 3D and sheet, the final view's
// exploded slider and assembly player, publishing. Results show as they come (live.js): the
// model view as soon as the model is read, each method's plan when it lands, any stored plan on
// request without converting again; a running conversion can be cancelled.

import * as api from './api.js';
import { createViewer } from './viewer.js';
import { createSheets } from './sheets.js';
import { assemblyOrder } from './assembly.js';
import * as progress from './progress.js';
import { adviceFor, readSettings, showModelSize, writeSettings } from './settings-form.js';
import { follow } from './live.js';
import { initBars, barMethod, clearBars, endBars, markShown } from './bars.js';
import { showPublishing } from './publish.js';
import { showWarnings } from './warnings.js';
import { showSteps } from './steps.js';
import { duration, laserNote, partsShown, timesTitles } from './wording.js';

const $ = (id) => document.getElementById(id);
export const VIEWS = ['model', 'wireframe', 'coplanar', 'primitives', 'plates', 'bent', 'final'];
const FINISHED = new Set(['done', 'failed', 'cancelled']);

export function createConversionArea({ state, onGalleryChange }) {
  let viewer = null;
  let current = null; // the conversion JSON
  let plan = null;
  // The shown plan's instruction steps (report.json) and their page's link.
  let steps = { list: [], href: null };
  let stopEvents = () => {};
  let playTimer = null;
  let keepCamera = false; // the next scene is a re-cut of the one shown: keep the camera
  let wanted = state.view || 'final'; // the view asked for by its button, shown with each plan
  let sceneShown = false; // the viewer holds a scene (a re-cut keeps the old one until its own)
  let displaying = Promise.resolve(); // plans are shown one after the other: the last asked wins
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

  /** The scene of `view` for the method shown; the model view, one for all methods, is there
   * as soon as the model is read. */
  function sceneUrl(view) {
    const links = current && current.links;
    if (!links) return null;
    const own = state.method && links.methods && links.methods[state.method];
    if (own && own.scenes && own.scenes[view]) return own.scenes[view];
    return view === 'model' && links.scenes ? links.scenes.model || null : null;
  }

  /** The ZIP of the method shown, once it landed. */
  function planLink() {
    const own = current && state.method && current.links.methods && current.links.methods[state.method];
    return own ? own.plan_zip || null : null;
  }

  function setViewButtons() {
    for (const b of document.querySelectorAll('[data-view]')) {
      b.setAttribute('aria-pressed', String(b.dataset.view === state.view));
      b.disabled = !sceneUrl(b.dataset.view);
    }
    $('final-tools').hidden = state.view !== 'final' || !state.loadedView;
  }

  /** Cancel while queued or running (own conversions: the page has their delete token), and
   * Download once the plan shown has its ZIP. */
  function syncControls() {
    const active = !!current && (state.status === 'queued' || state.status === 'running');
    $('cancel').hidden = !(active && api.tokens.get(current.id));
    $('download').disabled = !planLink();
  }

  async function showView(view) {
    state.view = view;
    setViewButtons();
    const url = sceneUrl(view);
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
      sceneShown = true;
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

  /** Exploded view and assembly player for the final view, in plan.json's `assembly` order
   * (older plans: from their joints and method, see assembly.js). */
  function setupFinal() {
    $('explode').value = '0';
    const parts = plan ? plan.parts.map((p) => p.id) : viewer.parts;
    state.assembly = plan
      ? assemblyOrder(parts, plan.joints, plan.method, plan.assembly)
      : assemblyOrder(parts, [], null);
    viewer.setOrder(state.assembly);
    viewer.setDirections(partDirections(plan && plan.assembly));
    const player = $('player');
    player.max = String(state.assembly.length);
    player.value = String(state.assembly.length);
    showParts(state.assembly.length);
    // A step shows the parts before it, then its own sliding in.
    showSteps($('assembly-steps'), steps.list, $('steps-link'), steps.href, (k, own) => {
      stopPlaying();
      showParts(k - own);
      showParts(k, true);
    });
  }

  /** Each part's way into place, from plan.json's assembly steps (model axes). */
  function partDirections(steps) {
    const out = {};
    for (const step of steps || []) for (const id of step.parts || []) out[id] = step.direction;
    return out;
  }

  /** Shows the first k parts; `animate`: the parts this adds slide in along their ways. */
  function showParts(k, animate = false) {
    viewer.showUpTo(k, { animate });
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
    showParts(k >= state.assembly.length ? 1 : k + 1, true);
  });
  $('player-play').addEventListener('click', () => {
    if (playTimer) return stopPlaying();
    showParts(1);
    $('player-play').textContent = 'Stop';
    playTimer = setInterval(() => {
      const k = Number($('player').value);
      if (k >= state.assembly.length) return stopPlaying();
      showParts(k + 1, true);
    }, 900);
  });
  for (const b of document.querySelectorAll('[data-view]')) {
    b.addEventListener('click', () => {
      wanted = b.dataset.view;
      showView(b.dataset.view);
    });
  }
  $('cancel').addEventListener('click', cancelShown);
  initBars((method) => {
    if (chooseMethod(method)) $('method').value = method;
  });
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
    get planLink() { return planLink(); },
    get viewer() { return viewer; },
    on(f) { listeners.add(f); },
    writeSettings,
    chooseMethod,
    open: openConversion,
    reset,
  };

  /** Back to no conversion; `keepScene` (a re-cut): the old scene stays drawn until the new
   * conversion's own is loaded, so the view does not go blank meanwhile. */
  function reset({ keepScene = false } = {}) {
    stopEvents();
    stopPlaying();
    current = null;
    plan = null;
    state.id = null;
    state.status = null;
    state.loadedView = null;
    state.hovered = null;
    state.method = null;
    state.picked = null;
    if (viewer && !keepScene) {
      viewer.clear();
      sceneShown = false;
    }
    $('viewer-note').hidden = sceneShown;
    $('part-label').textContent = '';
    $('simplified').hidden = true;
    progress.clearProgress();
    clearBars();
    progress.status('No model yet.');
    sheets.clear();
    showStats(null, null, null);
    setViewButtons();
    syncControls();
    showPublishing(null);
    $('share').hidden = true;
    $('warnings-box').hidden = true;
  }

  /** Opens conversion `id`; `recut`: it re-cuts the one shown, so the camera and the scene stay
   * and the one shown, if still running, is cancelled (it is superseded). */
  async function openConversion(id, { recut = false } = {}) {
    if (recut) supersede();
    reset({ keepScene: recut });
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
    if (state.id !== id) return;
    writeSettings(current.settings);
    showModelSize(current.model && current.model.bbox_mm, current.settings && current.settings.scale);
    state.status = current.status;
    syncControls();
    if (FINISHED.has(current.status)) return finished(current);
    progress.status(`Converting ${current.model.name}…`);
    landed(current, null);
    const first = planOf(current, null);
    if (first) display(first);
    stopEvents = follow(current, { state, still: () => state.id === id, landed, ended: finished });
  }

  /** A re-cut replaces the conversion shown: if that one is still queued or running and is the
   * user's own (its delete token is kept), it is cancelled, so superseded work frees its
   * worker. It may have ended meanwhile (409): then there is nothing to stop. */
  function supersede() {
    const old = current;
    const token = old && api.tokens.get(old.id);
    if (token && (state.status === 'queued' || state.status === 'running')) api.cancel(old.id, token).catch(() => {});
  }

  /** The Cancel button: the conversion ends at once as cancelled, keeping the plans made. */
  async function cancelShown() {
    const c = current;
    const token = c && api.tokens.get(c.id);
    if (!token) return;
    $('cancel').disabled = true;
    try {
      const answer = await api.cancel(c.id, token);
      if (state.id === c.id) {
        stopEvents();
        await finished(answer);
      }
    } catch (e) {
      progress.showError(`Cancelling failed: ${e.message}`);
    } finally {
      $('cancel').disabled = false;
    }
  }

  /** The conversion fetched again after something landed: the model scene (`method` null),
   * drawn at once unless a re-cut still shows the old scene; or a method, whose plan is shown
   * when it is the first to land or the one chosen. A method that failed changes nothing
   * shown, so the model view stays. */
  function landed(c, method) {
    current = c;
    setViewButtons();
    syncControls();
    if (!method) {
      if (!sceneShown && !state.method && sceneUrl('model')) showView('model');
      return;
    }
    const line = (c.methods || []).find((m) => m.method === method);
    if (line && line.status === 'done' && (!state.method || state.picked === method)) display(method);
  }

  /** The method select (or a bar's Show button) chose `value`: shows that method's stored
   * plan, or for `all` the best (while running, the first made), without converting again.
   * A chosen method still running shows when it lands. False when this conversion cannot
   * show it (it did not run that method, or the method made no plan): the caller re-cuts. */
  function chooseMethod(value) {
    const c = current;
    const ran = c && (c.settings.method === 'all' || c.settings.method === value);
    if (!ran) return false;
    if (value === 'all') {
      state.picked = null;
      const m = planOf(c, null);
      if (m && m !== state.method) display(m);
      return true;
    }
    const line = (c.methods || []).find((m) => m.method === value);
    if (line ? line.status !== 'done' : FINISHED.has(c.status)) return false;
    state.picked = value;
    if (line) display(value);
    else progress.status(`The ${value} plan shows here as soon as it is made…`);
    return true;
  }

  /** The method whose plan to show: `picked` if it made one, else the best, else the one shown,
   * else the first that made a plan (a cancelled conversion keeps what landed); null: none. */
  function planOf(c, picked) {
    const made = (m) => !!m && (c.methods || []).some((x) => x.method === m && x.status === 'done') && !!c.links.methods[m];
    const first = (c.methods || []).find((x) => made(x.method));
    return [picked, c.best, state.method].find(made) || (first ? first.method : null);
  }

  /** Shows `method`'s stored plan: its stats, sheets and the wanted view's scene (the final
   * view when the method has not that one). Plans show one after the other. */
  function display(method) {
    const id = state.id;
    state.method = method;
    markShown(method);
    syncControls();
    displaying = displaying.then(async () => {
      if (state.id !== id || state.method !== method) return;
      plan = null;
      const view = sceneUrl(wanted) ? wanted : 'final';
      await Promise.all([loadPlanAndSheets(current, method), showView(view)]);
      showWarnings(current, method);
    });
    return displaying;
  }

  async function finished(c) {
    current = c;
    state.status = c.status;
    syncControls();
    if (!document.querySelector('#progress li')) {
      progress.finishedSteps(c);
      replayMethodSteps(c.id);
    } else {
      for (const m of c.methods || []) progress.methodEvent(m);
    }
    for (const m of c.methods || []) barMethod(m);
    endBars(c.status);
    const err = progress.errorOf(c);
    progress.showError(err);
    showWarnings(c, state.method || c.best);
    progress.status(endText(c));
    setViewButtons();
    if (!c.best) {
      const advice = adviceFor(c);
      if (advice) {
        $('error').prepend(advice);
        $('error').hidden = false;
      }
    }
    if (c.best) {
      showPublishing(c);
      $('share').hidden = false;
      $('share').href = `#/c/${encodeURIComponent(c.id)}`;
    }
    // A plan already shown (it landed while the conversion ran) is not loaded again.
    const method = planOf(c, state.picked);
    if (method && method !== state.method) await display(method);
    else if (method) await displaying;
    else if (state.loadedView !== 'model' && sceneUrl('model')) await showView('model');
    markShown(state.method);
    emit('finished', c);
  }

  /** The status line of an ended conversion. */
  function endText(c) {
    const name = c.model.name;
    if (c.best) return `${name}: plan made by the ${c.best} method.`;
    if (c.status === 'cancelled') return `${name}: cancelled${state.method ? '; the plans made before are kept' : ''}.`;
    return `${name}: no plan.`;
  }

  /** A conversion opened after it ran: each method's steps with their times, from the event
   * stream, which replays every event of a finished conversion and then closes. */
  function replayMethodSteps(id) {
    stopEvents = api.events(id, (kind, data) => {
      if (state.id === id && kind === 'step' && data.method && data.state === 'finished') progress.stepEvent(data);
    });
  }

  async function loadPlanAndSheets(c, method) {
    const links = c.links.methods[method] || {};
    try {
      const [p, report] = await Promise.all([api.getJson(links.plan_json), api.getJson(links.report_json), sheets.show(links.sheets || [])]);
      if (state.id !== c.id || state.method !== method) return;
      plan = p;
      steps = { list: (report && report.assembly_steps) || [], href: links.assembly_html || null };
      showStats(c, report, method);
      if (state.loadedView === 'final') setupFinal();
    } catch (e) {
      progress.showError(`The sheets could not be shown: ${e.message}`);
    }
  }

  /** Score, counts, cut length, laser and print time and the speed-up (report.json's
   * estimates at their stated speeds) of `method`'s plan. */
  function showStats(c, report, method) {
    const m = c && (c.methods || []).find((x) => x.method === method);
    const set = (k, v) => (document.querySelector(`#stats [data-stat="${k}"]`).textContent = v);
    set('score', m && m.score != null ? Number(m.score).toFixed(2) : '–');
    set('parts', m ? String(m.parts) : '–');
    set('sheets', m ? String(m.sheets) : '–');
    const r = report || {};
    set('cut', r.cut_length != null ? `${(r.cut_length / 1000).toFixed(2)} m` : '–');
    const f = r.fabrication;
    set('minutes', r.estimated_cutting_seconds != null ? `≈ ${duration(r.estimated_cutting_seconds)}` : '–');
    set('print', f && f.print_seconds != null ? `≈ ${duration(f.print_seconds)}` : '–');
    set('speedup', f && f.speed_up != null ? `${Math.round(f.speed_up)}× faster` : '–');
    $('speed-note').textContent = laserNote(r);
    const titles = timesTitles(r);
    document.querySelector('#stats [data-stat="minutes"]').title = titles.laser;
    document.querySelector('#stats [data-stat="print"]').title = titles.print;
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
