// The page's entry point: hash routes (#/ landing, #/c/{id} a conversion, #/debug the debug
// view), the drop zone over the whole page, the upload button, settings that re-cut, the
// download dialog, publishing and the gallery. Exposes window.platener.state (read-only).

import * as api from './api.js';
import { createConversionArea, uploadModel, recutModel } from './conversion.js';
import { createGallery } from './gallery.js';
import { drawStrip } from './strip.js';
import { bindPublishing } from './publish.js';
import { showError, status } from './progress.js';
import { buildForm, onSettled } from './settings-form.js';

const $ = (id) => document.getElementById(id);

const state = {
  id: null, status: null, view: 'final', loadedView: null, hovered: null,
  frames: 0, lastFrameMs: 0, scenesDropped: 0, assembly: [], kerf: null, route: '#/',
};
Object.defineProperty(window, 'platener', {
  value: Object.freeze({ get state() { return JSON.parse(JSON.stringify(state)); } }),
});

// The form comes from the server's definition of the settings; the app starts once it is
// built, so nothing reads a form that is not there yet.
try {
  buildForm($('settings'), await api.getJson('/api/settings'));
} catch (e) {
  $('settings').textContent = `The settings could not be loaded (${e.message}); conversions use the defaults.`;
}

const area = createConversionArea({ state });
const gallery = createGallery($('gallery'), {
  prev: $('gallery-prev'), next: $('gallery-next'), label: $('gallery-page'),
  onError: (e) => showError(`The gallery could not be loaded: ${e.message}`),
});

/** Starts a conversion of `file` (dropped or chosen). */
async function start(file) {
  if (!file) return;
  status(`Uploading ${file.name}…`);
  showError(null);
  try {
    const c = await uploadModel(file);
    location.hash = `#/c/${encodeURIComponent(c.id)}`;
  } catch (e) {
    status('');
    showError(e.message);
  }
}

// Upload button and file chooser.
$('upload').addEventListener('click', () => $('file-input').click());
$('file-input').addEventListener('change', (e) => {
  start(e.target.files[0]);
  e.target.value = '';
});

// The drop zone: the whole page; the overlay shows while a file is dragged over it.
let dragDepth = 0;
const hasFiles = (e) => e.dataTransfer && [...(e.dataTransfer.types || [])].includes('Files');
document.addEventListener('dragenter', (e) => {
  if (!hasFiles(e)) return;
  e.preventDefault();
  dragDepth += 1;
  $('drop-zone').hidden = false;
});
document.addEventListener('dragover', (e) => {
  if (!hasFiles(e)) return;
  e.preventDefault();
  e.dataTransfer.dropEffect = 'copy';
});
document.addEventListener('dragleave', () => {
  dragDepth = Math.max(0, dragDepth - 1);
  if (dragDepth === 0) $('drop-zone').hidden = true;
});
document.addEventListener('drop', (e) => {
  e.preventDefault();
  dragDepth = 0;
  $('drop-zone').hidden = true;
  const file = e.dataTransfer && e.dataTransfer.files && e.dataTransfer.files[0];
  if (file) start(file);
});

/** Re-cuts the open conversion with `changes` and shows the new one in the same view. */
async function recut(changes) {
  const c = area.conversion;
  if (!c) return;
  status('Cutting again with the new settings…');
  try {
    const next = await recutModel(c.id, changes);
    await area.open(next.id, { recut: true });
    location.hash = `#/c/${encodeURIComponent(next.id)}`;
  } catch (e) {
    showError(e.message);
  }
}

// Settings: once the form has been still for a moment, the changes re-cut the open
// conversion (a material change also resets the kerf to the new material's own).
// Choosing a method this conversion already ran shows its stored plan instead of converting
// again.
onSettled($('settings'), (settings, changed) => {
  if (changed.includes('method') && area.chooseMethod(settings.method)) {
    changed = changed.filter((name) => name !== 'method');
    if (!changed.length) return;
  }
  const changes = Object.fromEntries(changed.map((name) => {
    const key = name === 'thickness' ? 'thicknesses' : name;
    return [key, settings[key]];
  }));
  if (changed.includes('material') && !changed.includes('kerf')) changes.kerf = null;
  recut(changes);
});
$('settings').addEventListener('submit', (e) => e.preventDefault());

// Publishing the user's own conversion (it asks first) and unpublishing it.
bindPublishing({
  conversion: () => area.conversion,
  onChange: () => gallery.load(1),
  onError: (message) => showError(message),
});

/** Fills the download dialog for the open conversion: ZIP, kerf, the interactive strip. */
async function fillDownload() {
  const c = area.conversion;
  const plan = area.plan;
  if (!c || !area.planLink) return;
  $('download-zip').href = area.planLink;
  const thickness = (plan && plan.parts[0] && plan.parts[0].thickness) || c.settings.thicknesses[0] || 3;
  const material = (plan && plan.settings.material) || c.settings.material;
  state.kerf = plan && plan.settings ? plan.settings.kerf : c.settings.kerf;
  $('kerf').textContent = state.kerf == null ? 'the material’s default' : `${Number(state.kerf).toFixed(3)} mm`;
  // The strip's table stars the kerf this plan was cut with.
  $('test-strip-svg').href = api.stripSvgUrl(thickness, material, state.kerf);
  try {
    const strip = await api.stripJson(thickness, material, state.kerf);
    drawStrip($('test-strip'), strip, state.kerf, (kerf) => {
      $('kerf').textContent = `${kerf.toFixed(3)} mm: cutting again…`;
      recut({ kerf });
    });
  } catch (e) {
    showError(`The test strip could not be drawn: ${e.message}`);
  }
}
$('download').addEventListener('click', () => {
  fillDownload();
  $('download-dialog').showModal();
});
area.on((kind) => {
  if (kind === 'finished' && $('download-dialog').open) fillDownload();
});

$('nav-gallery').addEventListener('click', (e) => {
  e.preventDefault();
  document.querySelector('.gallery-section').scrollIntoView({ behavior: 'smooth' });
  $('gallery-title').focus({ preventScroll: true });
});

let debugMounted = null;
/** The debug view lives in js/debug/ and is loaded only when asked for. */
async function showDebug() {
  $('landing').hidden = true;
  const root = $('debug-root');
  root.hidden = false;
  if (debugMounted) return;
  debugMounted = true;
  try {
    const mod = await import('./debug/main.js');
    mod.mount(root, api);
  } catch (e) {
    root.textContent = `The debug view could not be loaded: ${e.message}`;
  }
}

function route() {
  const hash = location.hash || '#/';
  state.route = hash;
  if (hash.startsWith('#/debug')) return showDebug();
  $('debug-root').hidden = true;
  $('landing').hidden = false;
  const m = /^#\/c\/([^/?#]+)/.exec(hash);
  if (m) {
    const id = decodeURIComponent(m[1]);
    if (id !== state.id) {
      area.open(id);
      window.scrollTo({ top: 0 });
    }
  } else if (hash === '#/' || hash === '#') {
    area.reset();
  }
}
window.addEventListener('hashchange', route);
route();
gallery.load(1);
