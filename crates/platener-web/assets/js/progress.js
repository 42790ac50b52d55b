// Progress, errors and warnings of a conversion, in words: one list item per pipeline step
// (from the event stream, then from the finished conversion), and an alert for what went wrong.

const $ = (id) => document.getElementById(id);

/** Milliseconds as people read them. */
export function duration(ms) {
  if (ms == null || Number.isNaN(Number(ms))) return '';
  if (ms < 1) return '<1 ms';
  if (ms < 1000) return `${Math.round(ms)} ms`;
  return `${(ms / 1000).toFixed(1)} s`;
}

/** The list item of `key`, made if new: before the item of `beforeKey` when that is there
 * (a method's steps replayed after its result line still read above it), else at the end. */
function item(key, beforeKey) {
  const list = $('progress');
  const find = (k) => list.querySelector(`li[data-key="${CSS.escape(k)}"]`);
  let li = find(key);
  if (!li) {
    li = document.createElement('li');
    li.dataset.key = key;
    const next = beforeKey && find(beforeKey);
    if (next) next.before(li);
    else list.append(li);
  }
  return li;
}

export function clearProgress() {
  $('progress').replaceChildren();
  showError(null);
  status('');
}

export function status(text) {
  $('status-line').textContent = text;
}

/** One `step` event: `{method, step, state, ms, warnings}`. */
export function stepEvent(d) {
  const li = item(`${d.method || ''}/${d.step}`, d.method && `method/${d.method}`);
  li.dataset.step = d.step;
  if (d.method) li.dataset.method = d.method;
  li.dataset.state = d.state;
  const who = d.method ? `${d.method} · ` : '';
  const extra = d.state === 'finished' ? ` ${duration(d.ms)}${d.warnings ? `, ${d.warnings} warning${d.warnings > 1 ? 's' : ''}` : ''}` : ' …';
  li.textContent = `${who}${d.step}${extra}`;
  li.className = d.state;
}

/** One `method` event: `{method, status, score, error}`. */
export function methodEvent(d) {
  const li = item(`method/${d.method}`);
  li.dataset.step = `method:${d.method}`;
  li.dataset.state = d.status;
  // `skipped`: the method had nothing to add (the classifier on exact faces); not a failure.
  li.className = d.status === 'done' ? 'method done' : d.status === 'skipped' ? 'method skipped' : 'method failed';
  li.textContent = d.status === 'done'
    ? `${d.method}: plan made, score ${Number(d.score).toFixed(2)}`
    : `${d.method}: ${d.status}${d.error ? ` (${d.error.message || d.error})` : ''}`;
}

/** The shared steps and each method's result of a finished conversion (for one opened after
 * it ran); the methods' own steps are not in the conversion JSON: they come from the event
 * stream's replay (`stepEvent`). */
export function finishedSteps(c) {
  for (const s of c.steps || []) {
    stepEvent({ step: s.name, state: 'finished', ms: s.ms, warnings: (s.warnings || []).length });
  }
  for (const m of c.methods || []) methodEvent(m);
}

/** Shows `message` (and `details`, a list of sentences) in the alert; null hides it. */
export function showError(message, details = []) {
  const box = $('error');
  box.replaceChildren();
  if (!message) {
    box.hidden = true;
    return;
  }
  const p = document.createElement('p');
  p.textContent = message;
  box.append(p);
  if (details.length) {
    const ul = document.createElement('ul');
    for (const d of details) {
      const li = document.createElement('li');
      li.textContent = d;
      ul.append(li);
    }
    box.append(ul);
  }
  box.hidden = false;
}

/** What went wrong with a conversion, in words; null when it has a plan and no error. */
export function errorOf(c) {
  if (c.error) return c.error.message || String(c.error);
  if (c.status === 'failed' || (c.status === 'done' && !c.best)) {
    const reasons = (c.methods || []).filter((m) => m.error).map((m) => `${m.method}: ${m.error}`);
    return `No method could convert this model${reasons.length ? `: ${reasons.join('; ')}` : '.'}`;
  }
  if (c.status === 'cancelled') return 'The conversion was cancelled.';
  return null;
}
