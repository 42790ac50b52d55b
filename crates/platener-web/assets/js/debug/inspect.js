// The snapshot panel (timing, warnings, the step's JSON with per-step toggles of what it
// shows) and the plate panel (a clicked plate's id, its connections and their joint kinds).

import { el } from './dom.js';

/** Keys hidden per step name: the toggles remember them while the page lives. */
const hidden = new Map();

function hiddenOf(step) {
  if (!hidden.has(step)) hidden.set(step, new Set());
  return hidden.get(step);
}

/** `obj` without the keys in `off`. */
function without(obj, off) {
  if (!obj || typeof obj !== 'object' || Array.isArray(obj)) return obj;
  return Object.fromEntries(Object.entries(obj).filter(([k]) => !off.has(k)));
}

/** The keys a step's JSON can toggle: its summary's and its snapshot's. */
function toggleKeys(data) {
  const keys = new Set();
  for (const part of [data.summary, data.snapshot]) {
    if (part && typeof part === 'object' && !Array.isArray(part)) Object.keys(part).forEach((k) => keys.add(k));
  }
  return [...keys].sort();
}

/**
 * Fills `panel` (timing, warnings, toggles, JSON) with one step's snapshot `data`; `prefix`
 * names its data-testids (`debug` for the output, `debug-input` for the input).
 */
export function showSnapshot(panel, data, prefix = 'debug') {
  const off = hiddenOf(data.step);
  const pre = el('pre', { 'data-testid': `${prefix}-json`, tabindex: 0, 'aria-label': `snapshot of ${data.step}` });
  const draw = () => {
    const shown = { step: data.step, input: data.input, summary: without(data.summary, off), snapshot: without(data.snapshot, off) };
    pre.textContent = JSON.stringify(shown, null, 2);
  };
  const toggles = el('fieldset', { 'data-testid': `${prefix}-toggles`, class: 'debug-toggles' }, el('legend', {}, `What the ${data.step} snapshot shows`));
  for (const key of toggleKeys(data)) {
    const box = el('input', { type: 'checkbox', 'data-testid': `${prefix}-toggle-${key}`, checked: !off.has(key) });
    box.addEventListener('change', () => {
      if (box.checked) off.delete(key);
      else off.add(key);
      draw();
    });
    toggles.append(el('label', {}, box, key));
  }
  const warnings = el('ul', { 'data-testid': `${prefix}-warnings`, class: 'debug-warnings' });
  for (const w of data.warnings || []) warnings.append(el('li', {}, `${w.kind || 'warning'}: ${w.message}`));
  if (!warnings.children.length) warnings.append(el('li', { class: 'debug-none' }, 'no warnings'));
  const timing = el('p', { 'data-testid': `${prefix}-timing` }, `${data.step}: ${data.millis.toFixed(2)} ms`,
    data.input ? ` (input: the ${data.input} step's output)` : ' (input: the model file)');
  draw();
  panel.replaceChildren(timing, warnings, toggles, pre);
}

/** The lines the plate panel prints for plate `n` (1-based) from the plates and joints summaries. */
export function plateLines(n, plates, joints) {
  const plate = plates && plates.plates ? plates.plates.find((p) => p.id === n) : null;
  if (!plate) return [`Plate ${n}: not in the plates snapshot`];
  const lines = [`Plate ${n}: ${plate.kind}, ${plate.thickness} mm, ${Math.round(plate.area)} mm², from shapes ${plate.shapes.join(', ')}`];
  const mine = joints && joints.connections ? joints.connections.filter((c) => c.plates.includes(n)) : [];
  lines.push(joints ? `${mine.length} connection${mine.length === 1 ? '' : 's'}` : 'no joints step in this run');
  for (const c of mine) {
    const other = c.plates[0] === n ? c.plates[1] : c.plates[0];
    lines.push(`with plate ${other}: ${c.kind} joint, ${c.style} style, ${Math.round(c.angle_deg)}°, label ${c.label}`);
  }
  return lines;
}

/** The lines the plate panel prints for part `n` of the final scene from the parts summary. */
export function partLines(n, parts) {
  const part = parts && parts.parts ? parts.parts.find((p) => p.id === n) : null;
  if (!part) return [`Part ${n}: not in the parts snapshot`];
  const mine = parts.joints.filter((j) => j.parts.includes(n));
  const lines = [`Part ${n}: ${part.kind}, ${part.thickness} mm, ${Math.round(part.area)} mm²`, `${mine.length} joint${mine.length === 1 ? '' : 's'}`];
  for (const j of mine) {
    const other = j.parts[0] === n ? j.parts[1] : j.parts[0];
    lines.push(`with part ${other}: ${j.kind} joint, ${Math.round(j.angle_deg)}°, label ${j.label}`);
  }
  return lines;
}

/** Prints `lines` into the plate panel. */
export function showLines(panel, lines) {
  panel.replaceChildren(el('h3', {}, lines[0]), el('ul', {}, lines.slice(1).map((l) => el('li', {}, l))));
}
