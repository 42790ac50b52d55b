// Conversions of the debug view: submitted with `debug=true` and the chosen options, run by
// the service's workers like any other conversion; the worker stores every step's snapshot,
// which the debug endpoints serve (GET …/debug, …/debug/{method}/{step}.json).

import { request, getJson, events } from '../api.js';

/** The test set (`models`: the library's labelled samples and the shipped examples) and `methods`: each method's steps. */
export async function testSet() {
  return getJson("/api/debug/models");
}

/** The bytes of a test-set model, as a File ready to upload. */
export async function testModel(model) {
  const bytes = await (await request(model.url)).arrayBuffer();
  return new File([bytes], `${model.name}.stl`, { type: 'model/stl' });
}

/**
 * Submits `file` for conversion with debug snapshots. `options`: method, weld (mm or null
 * for automatic), inherent (bool), joint, features, thickness.
 */
export async function submit(file, options) {
  const form = new FormData();
  form.append('debug', 'true');
  form.append('method', options.method);
  form.append('thickness', String(options.thickness));
  form.append('joint', options.joint);
  form.append('features', options.features);
  form.append('plates', options.inherent ? 'inherent' : 'all');
  if (options.weld !== null) form.append('weld', String(options.weld));
  form.append('model', file, file.name);
  return (await request('/api/conversions', { method: 'POST', body: form })).json();
}

/** Waits for the conversion's last event (or a lost stream); `onStep(data)` sees each step as
 * it runs. Results landing while it runs (`model`, `method`) and a `retry` are not the end. */
export function finished(id, onStep) {
  return new Promise((resolve) => {
    events(id, (kind, data) => {
      if (kind === 'step') onStep(data);
      else if (!['method', 'model', 'retry'].includes(kind)) resolve(kind);
    });
  });
}

/** The debug index: per method, its steps with time, warnings and links. */
export function debugIndex(id) {
  return getJson(`/api/conversions/${encodeURIComponent(id)}/debug`);
}

const snapshots = new Map();
/** One step's snapshot JSON (cached: a stored snapshot never changes). */
export function stepJson(url) {
  if (!snapshots.has(url)) snapshots.set(url, getJson(url).catch((e) => { snapshots.delete(url); throw e; }));
  return snapshots.get(url);
}
