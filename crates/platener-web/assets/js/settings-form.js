// The settings form, built from GET /api/settings (the library's one definition of each
// setting): groups in order, folded ones in <details>, each setting's control by its kind,
// its help as a tooltip and a line under it. Reads and writes the API's JSON (keys as in a
// conversion's `settings`), and reports changes after a short pause so several clicks make
// one conversion.
//
// Controls carry data-setting="name" (and id = data-testid = the setting's name, except the
// thickness boxes: name="thickness", and thickness-custom). Sheet: a select of presets plus
// "Custom" with sheet-width / sheet-height. Scale: with the model's size and a "longest side"
// field (scale-target) that sets it.

const $ = (id) => document.getElementById(id);

/** How long the form waits after a change for another before it reports them (ms). */
export const SETTLE_MS = 450;

let schema = null;

/**
 * The choices of setting `name` as [value, label] pairs, from the schema the form was built
 * from (empty before it is): other parts of the page (the debug view, the methods' names) list
 * values from here instead of by hand.
 */
export function choicesOf(name) {
  const def = schema && schema.settings.find((d) => d.name === name);
  return def && def.kind.choices ? def.kind.choices.map((c) => [c.value, c.label]) : [];
}

/** Fetches nothing: builds the form in `form` from the schema `s` (GET /api/settings). */
export function buildForm(form, s) {
  schema = s;
  form.replaceChildren();
  for (const group of s.groups) {
    const defs = s.settings.filter((d) => d.group === group.id);
    if (!defs.length) continue;
    const box = group.folded ? document.createElement('details') : document.createElement('fieldset');
    box.className = 'group';
    box.dataset.group = group.id;
    box.dataset.testid = `group-${group.id}`;
    const title = document.createElement(group.folded ? 'summary' : 'legend');
    title.textContent = group.label;
    box.append(title, ...defs.map(control));
    form.append(box);
  }
}

/** One setting's row: label, control, help. */
function control(def) {
  const row = document.createElement('div');
  row.className = `setting kind-${def.kind.type}`;
  row.dataset.setting = def.name;
  row.title = def.doc;
  const make = { choice: choiceControl, number: numberControl, numbers: numbersControl, sheet: sheetControl, text: textControl };
  row.append(...make[def.kind.type](def));
  const help = document.createElement('p');
  help.className = 'help';
  help.textContent = def.help;
  row.append(help);
  return row;
}

function labelFor(def, input) {
  const label = document.createElement('label');
  label.htmlFor = input.id;
  label.textContent = def.label;
  return label;
}

/** The select of setting `def` with `options` (choices or presets), its default selected. */
function selectOf(def, options) {
  const select = document.createElement('select');
  select.id = def.name;
  select.name = def.name;
  select.dataset.testid = def.name;
  select.dataset.setting = def.name;
  for (const c of options) {
    const option = new Option(c.label, c.value, false, c.value === def.default);
    option.title = c.help;
    select.append(option);
  }
  return select;
}

function choiceControl(def) {
  const select = selectOf(def, def.kind.choices);
  return [labelFor(def, select), select];
}

function numberInput(def, id) {
  const input = document.createElement('input');
  input.type = 'number';
  input.id = id;
  input.dataset.testid = id;
  input.min = String(def.kind.min);
  input.max = String(def.kind.max);
  input.step = 'any';
  input.inputMode = 'decimal';
  return input;
}

function numberControl(def) {
  const input = numberInput(def, def.name);
  input.name = def.name;
  input.dataset.setting = def.name;
  input.placeholder = def.kind.auto ? 'auto' : '';
  if (def.default != null) input.value = String(def.default);
  if (def.kind.auto) input.title = `Empty: ${def.kind.auto}`;
  const unit = Object.assign(document.createElement('span'), { className: 'unit', textContent: def.kind.unit });
  const parts = [labelFor(def, input), input, unit];
  if (def.name === 'scale') parts.push(scaleHelper());
  if (def.name === 'kerf') parts.push(kerfStripLink());
  return parts;
}

/** The model's size and a target for its longest side (sets the scale). */
function scaleHelper() {
  const box = document.createElement('div');
  box.className = 'scale-helper';
  const size = Object.assign(document.createElement('p'), { id: 'model-size', className: 'note' });
  size.dataset.testid = 'model-size';
  const target = document.createElement('input');
  Object.assign(target, { type: 'number', id: 'scale-target', min: '1', step: 'any', placeholder: 'mm' });
  target.dataset.testid = 'scale-target';
  const label = Object.assign(document.createElement('label'), { htmlFor: 'scale-target', textContent: 'Longest side' });
  target.addEventListener('change', () => {
    const want = Number(target.value);
    if (!(want > 0) || !modelLongest) return;
    $('scale').value = String(round(want / modelLongest));
    $('scale').dispatchEvent(new Event('change', { bubbles: true }));
  });
  box.append(size, label, target);
  return box;
}

function kerfStripLink() {
  const a = Object.assign(document.createElement('a'), { id: 'kerf-strip', className: 'note', textContent: 'test strip' });
  a.dataset.testid = 'kerf-strip';
  a.download = 'test-strip.svg';
  a.title = 'Cut this strip from your sheet, push its spike into the holes: the snug one names your kerf.';
  return a;
}

function numbersControl(def) {
  const set = document.createElement('fieldset');
  set.id = def.name;
  set.dataset.testid = def.name;
  set.dataset.setting = def.name;
  const legend = Object.assign(document.createElement('legend'), { textContent: `${def.label} (${def.kind.unit})` });
  const chips = Object.assign(document.createElement('div'), { className: 'chips' });
  for (const t of def.kind.common) {
    const box = Object.assign(document.createElement('input'), { type: 'checkbox', name: def.name, value: String(t) });
    box.checked = def.default.includes(t);
    const label = document.createElement('label');
    label.append(box, ` ${t}`);
    chips.append(label);
  }
  // Text, not a number box: a sheet that measures other than it is sold as is given as
  // nominal@measured (3@2.85), which the API takes as it is.
  const custom = Object.assign(document.createElement('input'), {
    type: 'text', id: `${def.name}-custom`, inputMode: 'decimal', placeholder: `${def.kind.unit} or 3@2.85`,
    pattern: '\\s*[0-9]*\\.?[0-9]+(\\s*@\\s*[0-9]*\\.?[0-9]+)?\\s*',
  });
  custom.dataset.testid = custom.id;
  const label = Object.assign(document.createElement('label'), { className: 'custom' });
  label.append('Custom ', custom);
  set.append(legend, chips, label);
  return [set];
}

/** Free text in a format of its own (the stock list); the empty field is the API's `none`. */
function textControl(def) {
  const input = Object.assign(document.createElement('input'), {
    type: 'text', id: def.name, name: def.name, placeholder: def.kind.example, value: def.default === 'none' ? '' : def.default,
  });
  input.dataset.testid = def.name;
  input.dataset.setting = def.name;
  input.title = def.kind.format;
  return [labelFor(def, input), input];
}

function sheetControl(def) {
  const select = selectOf(def, def.kind.presets);
  select.append(new Option('Custom…', 'custom'));
  const custom = document.createElement('div');
  custom.className = 'sheet-custom';
  custom.hidden = true;
  for (const side of ['width', 'height']) {
    const input = numberInput({ kind: { min: 10, max: def.kind.max } }, `sheet-${side}`);
    input.placeholder = side;
    input.setAttribute('aria-label', `Sheet ${side} (mm)`);
    custom.append(input);
  }
  select.addEventListener('change', () => { custom.hidden = select.value !== 'custom'; });
  return [labelFor(def, select), select, custom];
}

function round(x) {
  return Number(x.toPrecision(4));
}

/** The form's values as the API takes them (JSON keys; `null` for auto). */
export function readSettings() {
  const out = {};
  for (const def of schema ? schema.settings : []) out[def.key] = readOne(def);
  return out;
}

function readOne(def) {
  switch (def.kind.type) {
    case 'numbers': {
      const ts = [...document.querySelectorAll(`input[name="${def.name}"]:checked`)].map((i) => Number(i.value));
      const text = $(`${def.name}-custom`).value.trim();
      if (text.includes('@')) {
        // A measured sheet replaces its nominal box: 3@2.85 is the 3 mm sheet.
        const nominal = Number(text.split('@')[0]);
        return [...ts.filter((t) => t !== nominal), text.replace(/\s+/g, '')];
      }
      const custom = Number(text);
      if (custom > 0 && !ts.includes(custom)) ts.push(custom);
      return ts.length ? ts : def.default;
    }
    case 'number': {
      const v = $(def.name).value.trim();
      return v === '' ? (def.kind.auto ? null : def.default) : Number(v);
    }
    case 'sheet': {
      const v = $(def.name).value;
      if (v !== 'custom') return v;
      const w = Number($('sheet-width').value);
      const h = Number($('sheet-height').value);
      return w > 0 && h > 0 ? `${w}x${h}` : def.default;
    }
    case 'text':
      return $(def.name).value.trim() || 'none';
    default:
      return $(def.name).value;
  }
}

/** Shows `settings` (a conversion's) in the form. */
export function writeSettings(settings) {
  if (!settings || !schema) return;
  for (const def of schema.settings) {
    if (!(def.key in settings)) continue;
    writeOne(def, settings[def.key]);
  }
  updateStripLink(settings);
}

function writeOne(def, value) {
  switch (def.kind.type) {
    case 'numbers': {
      // Numbers, and "3@2.85" for a measured sheet, which goes in the custom box.
      const ts = (value || []).map((v) => (typeof v === 'string' && v.includes('@') ? v : Number(v)));
      const ticked = [];
      for (const box of document.querySelectorAll(`input[name="${def.name}"]`)) {
        box.checked = ts.includes(Number(box.value));
        if (box.checked) ticked.push(Number(box.value));
      }
      const other = ts.find((t) => !ticked.includes(t));
      $(`${def.name}-custom`).value = other === undefined ? '' : String(other);
      break;
    }
    case 'number':
      $(def.name).value = value == null ? '' : String(value);
      break;
    case 'sheet': {
      const select = $(def.name);
      const preset = [...select.options].some((o) => o.value === value);
      select.value = preset ? value : 'custom';
      select.nextElementSibling.hidden = preset;
      if (!preset && typeof value === 'string') {
        const [w, h] = value.split('x');
        $('sheet-width').value = w;
        $('sheet-height').value = h;
      }
      break;
    }
    case 'text':
      $(def.name).value = value == null || value === 'none' ? '' : String(value);
      break;
    default:
      $(def.name).value = value;
  }
}

function updateStripLink(settings) {
  const a = $('kerf-strip');
  if (!a) return;
  const t = (settings.thicknesses || [3])[0];
  a.href = `/api/test-strip.svg?${new URLSearchParams({ thickness: String(t), material: settings.material || 'wood' })}`;
}

let modelLongest = 0;

/** Shows the model's size (mm, as converted with `scale`) and remembers its longest side at scale 1. */
export function showModelSize(bboxMm, scale) {
  const box = $('model-size');
  if (!box) return;
  if (!bboxMm) {
    box.textContent = '';
    modelLongest = 0;
    return;
  }
  const longest = Math.max(...bboxMm);
  modelLongest = longest / (scale || 1);
  box.textContent = `The model is ${bboxMm.map((v) => formatMm(v)).join(' × ')} mm.`;
  $('scale-target').value = String(round(longest));
}

function formatMm(v) {
  return v >= 10 ? v.toFixed(0) : v >= 1 ? v.toFixed(1) : String(round(v));
}

/**
 * Advice for a model whose size looks wrong (a failed conversion): its size in words and the
 * scale that probably fixes it, or null. `bboxMm` is the size as converted, `scale` the
 * scale it was converted with, `thinnest` the thinnest sheet.
 */
export function sizeAdvice(bboxMm, scale, thinnest) {
  if (!bboxMm) return null;
  const longest = Math.max(...bboxMm);
  const size = `The model is ${bboxMm.map((v) => formatMm(v)).join(' × ')} mm`;
  const guesses = [
    { factor: 1000, unit: 'metres' },
    { factor: 25.4, unit: 'inches' },
    { factor: 10, unit: 'centimetres' },
  ];
  if (longest < 20 * (thinnest || 3)) {
    const guess = guesses.find((g) => longest * g.factor >= 40 && longest * g.factor <= 2000);
    const factor = guess ? guess.factor : round(100 / longest);
    const why = guess ? `It looks like ${guess.unit}` : 'It is small for your sheets';
    return { text: `${size} across. ${why}: scale ×${factor}.`, scale: round((scale || 1) * factor) };
  }
  if (longest > 3000) {
    const factor = longest > 300000 ? 0.001 : 0.1;
    return { text: `${size} across. It is larger than any sheet: scale ×${factor}.`, scale: round((scale || 1) * factor) };
  }
  return null;
}

/**
 * For a conversion no method converted: its size in words and a button that applies the
 * scale that probably fixes it (data-testid apply-scale), or null when its size looks right.
 */
export function adviceFor(c) {
  const s = c.settings || {};
  const advice = sizeAdvice(c.model && c.model.bbox_mm, s.scale, Math.min(...(s.thicknesses || [3])));
  if (!advice) return null;
  const p = Object.assign(document.createElement('p'), { className: 'advice', textContent: `${advice.text} ` });
  const button = Object.assign(document.createElement('button'), { type: 'button', textContent: `Scale ×${round(advice.scale / (s.scale || 1))}` });
  button.dataset.testid = 'apply-scale';
  button.addEventListener('click', () => {
    $('scale').value = String(advice.scale);
    $('scale').dispatchEvent(new Event('change', { bubbles: true }));
  });
  p.append(button);
  return p;
}

/**
 * Calls `onChange(settings, changedKeys)` once the form has been still for SETTLE_MS after a
 * change, with every change made meanwhile.
 */
export function onSettled(form, onChange) {
  let timer = null;
  const changed = new Set();
  form.addEventListener('change', (e) => {
    const row = e.target.closest('[data-setting]');
    if (!row || e.target.id === 'scale-target') return;
    const customSheet = e.target.closest('.sheet-custom') || (e.target.id === 'sheet' && e.target.value === 'custom');
    if (customSheet && !sheetComplete()) return;
    changed.add(row.dataset.setting);
    clearTimeout(timer);
    timer = setTimeout(() => {
      const keys = [...changed];
      changed.clear();
      const settings = readSettings();
      updateStripLink(settings);
      onChange(settings, keys);
    }, SETTLE_MS);
  });
}

function sheetComplete() {
  return Number($('sheet-width').value) > 0 && Number($('sheet-height').value) > 0;
}
