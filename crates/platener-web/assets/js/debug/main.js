// The debug view (#/debug, issue 18): any pipeline step's input and output as 3D scene and
// JSON, with its time and warnings. Conversions run in the service's workers like every other
// (submitted with debug=true); this page only shows the snapshots they stored.
//
// Two modes, as in the thesis: "isolated step" (a test model and one step: its input, the
// previous step's output, beside its output) and "converting" (the whole pipeline of one
// method, any step chosen from the list). Options that re-run the conversion: weld distance,
// inherent plates only, joint type, features. The render mode only changes the viewers.
// Clicking a plate (plates view) or part (final view) prints its id, connections and their
// joint kinds; the plate list does the same from the keyboard.
//
// Stable selectors (data-testid): debug-mode, debug-model, debug-upload, debug-method,
// debug-step, debug-weld, debug-weld-auto, debug-weld-value, debug-inherent, debug-joint,
// debug-features, debug-render, debug-run, debug-status, debug-error, debug-progress,
// debug-steps (converting mode: one button per step, data-step), debug-viewer-input,
// debug-viewer-output (canvases), debug-input-caption, debug-output-caption, and per
// snapshot panel (prefix debug- for the output, debug-input- for the input): -timing,
// -warnings, -toggles, -toggle-{key}, -json; debug-plate-select, debug-plate-info.
// The root carries data-status = idle | running | ready | failed; window.platenerDebug.state
// (read-only) has id, status, mode, method, step, scenes {input, output}.

import { createViewer } from '../viewer.js';
import { el, field, select } from './dom.js';
import { choicesOf } from '../settings-form.js';
import { debugIndex, finished, stepJson, submit, testModel, testSet } from './jobs.js';
import { partLines, plateLines, showLines, showSnapshot } from './inspect.js';

const st = {
  mode: 'isolated', method: 'plate', step: 'plates', id: null, status: 'idle',
  index: null, steps: {}, models: [], hovered: null, scenes: { input: null, output: null }, run: 0,
};
Object.defineProperty(window, 'platenerDebug', {
  value: Object.freeze({ get state() { return JSON.parse(JSON.stringify({ ...st, index: null, models: undefined, steps: undefined })); } }),
});

/** Builds the view in `root`. `api` (the page's api.js) is imported directly by the modules. */
export async function mount(root) {
  document.head.append(el('link', { rel: 'stylesheet', href: '/assets/js/debug/debug.css' }));
  const ui = build();
  root.replaceChildren(ui.page);
  ui.root = root;
  const viewers = {
    input: createViewer(ui.canvasInput),
    output: createViewer(ui.canvasOutput, { onHover: (n, kind) => { st.hovered = n === null ? null : { n, kind }; } }),
  };
  wire(ui, viewers);
  try {
    const set = await testSet();
    st.models = set.models;
    st.steps = set.methods;
    ui.model.replaceChildren(...set.models.map((m) => el('option', { value: m.name }, `${m.name}: ${m.label}`)));
    fillSteps(ui, st.steps[st.method] || []);
    setStatus(ui, 'idle', 'Choose a model and a step, then Convert.');
  } catch (e) {
    fail(ui, e);
  }
}

/** The controls, the two viewers and the panels. */
function build() {
  const ui = {};
  ui.mode = select('debug-mode', [['isolated', 'isolated step'], ['converting', 'converting']], st.mode);
  ui.model = el('select', { 'data-testid': 'debug-model' });
  ui.upload = el('input', { type: 'file', accept: '.stl,.obj,.3mf', 'data-testid': 'debug-upload' });
  ui.method = select('debug-method', choicesOf('method').filter(([v]) => v !== 'all'), st.method);
  ui.step = el('select', { 'data-testid': 'debug-step' });
  ui.weld = el('input', { type: 'range', min: 0, max: 2, step: 0.01, value: 0.1, disabled: true, 'data-testid': 'debug-weld' });
  ui.weldAuto = el('input', { type: 'checkbox', checked: true, 'data-testid': 'debug-weld-auto' });
  ui.weldValue = el('output', { 'data-testid': 'debug-weld-value' }, 'auto');
  ui.inherent = el('input', { type: 'checkbox', 'data-testid': 'debug-inherent' });
  ui.joint = select('debug-joint', choicesOf('joint'), 'auto');
  ui.features = select('debug-features', choicesOf('features'), 'engrave');
  ui.render = select('debug-render', [['solid', 'solid'], ['wireframe', 'wireframe'], ['vertices', 'vertices'], ['hidden', 'hidden']], 'solid');
  ui.run = el('button', { type: 'button', 'data-testid': 'debug-run' }, 'Convert');
  ui.status = el('p', { role: 'status', 'data-testid': 'debug-status' });
  ui.error = el('p', { role: 'alert', class: 'debug-error', 'data-testid': 'debug-error', hidden: true });
  ui.progress = el('ol', { class: 'debug-progress', 'data-testid': 'debug-progress' });
  ui.stepList = el('ol', { class: 'debug-steps', 'data-testid': 'debug-steps', hidden: true });
  ui.canvasInput = el('canvas', { 'data-testid': 'debug-viewer-input', tabindex: 0, 'aria-label': 'input of the step, 3D' });
  ui.canvasOutput = el('canvas', { 'data-testid': 'debug-viewer-output', tabindex: 0, 'aria-label': 'output of the step, 3D; click a plate for its connections' });
  ui.captionInput = el('figcaption', { 'data-testid': 'debug-input-caption' }, 'input');
  ui.captionOutput = el('figcaption', { 'data-testid': 'debug-output-caption' }, 'output');
  ui.inputFigure = el('figure', { class: 'debug-figure' }, ui.captionInput, ui.canvasInput);
  ui.inputPanel = el('section', { class: 'debug-panel', 'aria-label': 'input snapshot' });
  ui.outputPanel = el('section', { class: 'debug-panel', 'aria-label': 'output snapshot' });
  ui.plateSelect = el('select', { 'data-testid': 'debug-plate-select' }, el('option', { value: '' }, '(none)'));
  ui.plateInfo = el('aside', { class: 'debug-plate-info', 'data-testid': 'debug-plate-info', 'aria-live': 'polite' }, 'Click a plate or part in the output view.');
  const options = el('fieldset', { class: 'debug-options' }, el('legend', {}, 'Options (re-run the conversion)'),
    field('weld distance, mm', el('span', {}, ui.weld, ui.weldValue)), field('automatic weld', ui.weldAuto),
    field('inherent plates only', ui.inherent), field('joint type', ui.joint), field('features', ui.features));
  const controls = el('div', { class: 'debug-controls' },
    field('mode', ui.mode), field('test model', ui.model), field('or a file', ui.upload), field('method', ui.method),
    field('step', ui.step), options, field('model rendering', ui.render), ui.run);
  const views = el('div', { class: 'debug-views' }, ui.inputFigure,
    el('figure', { class: 'debug-figure' }, ui.captionOutput, ui.canvasOutput));
  const side = el('div', { class: 'debug-side' }, field('plate or part', ui.plateSelect), ui.plateInfo);
  const panels = el('div', { class: 'debug-panels' }, ui.inputPanel, ui.outputPanel);
  ui.page = el('div', { class: 'debug-page' }, el('h1', {}, 'Debug view'), controls, ui.status, ui.error,
    ui.progress, ui.stepList, el('div', { class: 'debug-main' }, views, side), panels);
  return ui;
}

/** Event handlers: options re-run, mode/step/method re-show, render re-draws. */
function wire(ui, viewers) {
  const rerun = () => { if (st.id) convert(ui, viewers); };
  ui.run.addEventListener('click', () => convert(ui, viewers));
  ui.weldAuto.addEventListener('change', () => { ui.weld.disabled = ui.weldAuto.checked; showWeld(ui); rerun(); });
  ui.weld.addEventListener('input', () => showWeld(ui));
  ui.weld.addEventListener('change', rerun);
  for (const c of [ui.inherent, ui.joint, ui.features]) c.addEventListener('change', rerun);
  ui.method.addEventListener('change', () => {
    st.method = ui.method.value;
    fillSteps(ui, st.steps[st.method] || []);
    rerun();
  });
  ui.mode.addEventListener('change', () => { st.mode = ui.mode.value; redraw(ui, viewers); });
  ui.step.addEventListener('change', () => { st.step = ui.step.value; redraw(ui, viewers); });
  ui.render.addEventListener('change', () => Object.values(viewers).forEach((v) => v.setRender(ui.render.value)));
  ui.canvasOutput.addEventListener('click', () => { if (st.hovered) describe(ui, st.hovered.kind, st.hovered.n); });
  ui.plateSelect.addEventListener('change', () => {
    const [kind, n] = ui.plateSelect.value.split('-');
    if (n) describe(ui, kind, Number(n));
  });
}

function showWeld(ui) {
  ui.weldValue.textContent = ui.weldAuto.checked ? 'auto' : `${Number(ui.weld.value).toFixed(2)} mm`;
}

/** The step select's options; keeps the chosen step when the method has it. */
function fillSteps(ui, steps) {
  if (!steps.includes(st.step)) st.step = steps.includes('plates') ? 'plates' : steps[steps.length - 1];
  ui.step.replaceChildren(...steps.map((s) => el('option', { value: s, selected: s === st.step }, s)));
}

function setStatus(ui, status, text) {
  st.status = status;
  ui.root.dataset.status = status;
  ui.status.textContent = text;
  ui.run.disabled = status === 'running';
}

function fail(ui, e) {
  ui.error.hidden = false;
  ui.error.textContent = e.message || String(e);
  setStatus(ui, 'failed', 'Failed: see the message.');
}

/** The file to convert: the uploaded one, else the chosen test model. */
async function chosenFile(ui) {
  if (ui.upload.files && ui.upload.files.length) return ui.upload.files[0];
  const model = st.models.find((m) => m.name === ui.model.value) || st.models[0];
  return testModel(model);
}

/** Submits the model with the options, follows its steps, then shows the chosen step. */
async function convert(ui, viewers) {
  const run = ++st.run;
  ui.error.hidden = true;
  ui.progress.replaceChildren();
  ui.plateInfo.replaceChildren('Click a plate or part in the output view.');
  setStatus(ui, 'running', 'Converting in a worker…');
  try {
    const file = await chosenFile(ui);
    const c = await submit(file, {
      method: st.method, thickness: 3, joint: ui.joint.value, features: ui.features.value,
      inherent: ui.inherent.checked, weld: ui.weldAuto.checked ? null : Number(ui.weld.value),
    });
    st.id = c.id;
    const end = await finished(c.id, (d) => {
      // A run superseded by a newer one (an option changed meanwhile) no longer draws.
      if (d.state === 'finished' && run === st.run) ui.progress.append(el('li', { 'data-step': d.step }, `${d.step} ${Number(d.ms).toFixed(1)} ms`));
    });
    if (run !== st.run) return;
    const index = await debugIndex(c.id);
    st.index = index.methods.find((m) => m.method === st.method) || index.methods[0];
    fillSteps(ui, st.index.steps.map((s) => s.step));
    await show(ui, viewers);
    setStatus(ui, end === 'done' ? 'ready' : 'failed', `${file.name}: conversion ${end} (${st.index.steps.length} steps stored)`);
  } catch (e) {
    if (run === st.run) fail(ui, e);
  }
}

/** show() for event handlers: a scene or snapshot that fails to load becomes the error line. */
function redraw(ui, viewers) {
  show(ui, viewers).catch((e) => fail(ui, e));
}

/** Shows the chosen step: isolated (input beside output) or converting (the step list). */
async function show(ui, viewers) {
  ui.inputFigure.hidden = st.mode !== 'isolated';
  ui.inputPanel.hidden = st.mode !== 'isolated';
  ui.stepList.hidden = st.mode !== 'converting';
  if (!st.index) return;
  const steps = st.index.steps;
  const step = steps.find((s) => s.step === st.step) || steps[steps.length - 1];
  st.step = step.step;
  ui.step.value = step.step;
  if (st.mode === 'converting') drawStepList(ui, viewers, steps);
  await showSide(ui, viewers.output, 'output', step, 'debug');
  const input = steps.find((s) => s.step === step.input);
  if (st.mode === 'isolated') {
    if (input) await showSide(ui, viewers.input, 'input', input, 'debug-input');
    else ui.inputPanel.replaceChildren(el('p', {}, 'The read step has no input snapshot: its input is the model file.'));
  }
  fillPlates(ui, viewers.output);
}

/** One side (input or output): its scene in its viewer and its snapshot panel. */
async function showSide(ui, viewer, side, step, prefix) {
  const caption = side === 'input' ? ui.captionInput : ui.captionOutput;
  const exact = step.view_exact ? '' : ` (the ${step.view} view: this step draws nothing of its own)`;
  caption.textContent = `${side}: ${step.step}${step.scene ? exact : ' (no scene)'}`;
  if (!step.scene) {
    // Nothing to draw (the step failed before its view's snapshot): hide the old scene.
    viewer.setRender('hidden');
    st.scenes[side] = null;
  } else if (st.scenes[side] !== step.scene) {
    await viewer.load(step.scene);
    viewer.setRender(ui.render.value);
    st.scenes[side] = step.scene;
  }
  const data = await stepJson(step.json);
  showSnapshot(side === 'input' ? ui.inputPanel : ui.outputPanel, data, prefix);
}

function drawStepList(ui, viewers, steps) {
  ui.stepList.replaceChildren(...steps.map((s) => el('li', {}, el('button', {
    type: 'button', 'data-step': s.step, 'aria-pressed': String(s.step === st.step),
    onclick: () => { st.step = s.step; redraw(ui, viewers); },
  }, `${s.step} · ${Number(s.ms).toFixed(1)} ms · ${s.warnings} warning${s.warnings === 1 ? '' : 's'}`))));
}

/** The plate list: the numbered nodes of the output scene (plates or parts). */
function fillPlates(ui, viewer) {
  const kind = /final/.test(st.scenes.output || '') ? 'part' : 'plate';
  const options = [el('option', { value: '' }, '(none)')];
  for (const n of viewer.parts) options.push(el('option', { value: `${kind}-${n}` }, `${kind} ${n}`));
  ui.plateSelect.replaceChildren(...options);
}

/** Prints plate or part `n`'s id, connections and joint kinds in the side panel. */
async function describe(ui, kind, n) {
  const url = (name) => { const s = st.index && st.index.steps.find((x) => x.step === name); return s ? s.json : null; };
  try {
    if (kind === 'plate') {
      const plates = url('plates') ? (await stepJson(url('plates'))).summary : null;
      const joints = url('joints') ? (await stepJson(url('joints'))).summary : null;
      showLines(ui.plateInfo, plateLines(n, plates, joints));
    } else {
      const made = url('parts') || url('stacked') || url('interlocked');
      showLines(ui.plateInfo, partLines(n, made ? (await stepJson(made)).summary : null));
    }
    ui.plateInfo.dataset.selected = `${kind}-${n}`;
  } catch (e) {
    fail(ui, e);
  }
}
