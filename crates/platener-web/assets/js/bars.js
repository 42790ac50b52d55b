// One progress bar per method, for makers: the step the method is at in words (the `label` of
// the server's step events, from the library's one table of them, never a copy here) and how
// far it is (steps done of that method's steps, `index` and `of` of the same events). The
// developer's step log with times stays in progress.js, behind "Details".

const $ = (id) => document.getElementById(id);

let onShow = () => {};

/** `show(method)` runs when a bar's "Show" button is pressed (a landed method's plan). */
export function initBars(show) {
  onShow = show;
}

/** The method select's option of `method`, if it has one. */
function option(method) {
  return document.querySelector(`#method option[value="${CSS.escape(method)}"]`);
}

/** The method's name as the method select words it ("Plates"), else its API name. */
function title(method) {
  const o = option(method);
  return o ? o.textContent.trim() : method;
}

/** Where `method`'s bar goes: the select's order (methods run side by side, so their first
 * events come in any order), unknown methods last. */
function rank(method) {
  const o = option(method);
  return o ? o.index : Number.MAX_SAFE_INTEGER;
}

/** The bar of `method`, made on its first event. */
function bar(method) {
  const list = $('progress-bars');
  let li = list.querySelector(`li[data-method="${CSS.escape(method)}"]`);
  if (li) return li;
  li = document.createElement('li');
  li.dataset.testid = 'method-bar';
  li.dataset.method = method;
  li.dataset.state = 'running';
  const name = Object.assign(document.createElement('span'), { className: 'bar-title', textContent: title(method) });
  const meter = Object.assign(document.createElement('progress'), { max: 1, value: 0 });
  meter.setAttribute('aria-label', `${title(method)}: progress`);
  const step = Object.assign(document.createElement('span'), { className: 'bar-step' });
  step.dataset.testid = 'method-step';
  const show = Object.assign(document.createElement('button'), { type: 'button', textContent: 'Show', hidden: true });
  show.dataset.testid = 'method-show';
  show.addEventListener('click', () => onShow(method));
  li.append(name, meter, step, show);
  const after = [...list.children].find((other) => rank(other.dataset.method) > rank(method));
  list.insertBefore(li, after || null);
  return li;
}

export function clearBars() {
  $('progress-bars').replaceChildren();
}

/** One `step` event of a method: `{method, step, state, label, index, of}`. Shared steps
 * (no method) have no bar: the status line says them (`stepPhrase`). */
export function barStep(d) {
  if (!d.method) return;
  const li = bar(d.method);
  if (li.dataset.state !== 'running') return;
  const meter = li.querySelector('progress');
  if (d.of > 0 && d.index != null) {
    meter.max = d.of;
    const done = d.state === 'finished' ? d.index + 1 : d.index;
    meter.value = Math.max(meter.value, done);
  }
  li.dataset.step = d.step;
  li.querySelector('.bar-step').textContent = d.state === 'started' ? `${stepPhrase(d)}…` : stepPhrase(d);
}

/** The step in words: its label, else (an older server) its name. */
export function stepPhrase(d) {
  const words = d.label || d.step || '';
  return words.charAt(0).toUpperCase() + words.slice(1);
}

/** One `method` event (or a method line of a finished conversion): how the method ended. */
export function barMethod(m) {
  const li = bar(m.method);
  li.dataset.state = m.status;
  const meter = li.querySelector('progress');
  meter.value = meter.max;
  const error = m.error ? (m.error.message || String(m.error)) : '';
  let text;
  if (m.status === 'done') {
    const parts = m.parts != null ? `${m.parts} part${m.parts === 1 ? '' : 's'}` : 'plan made';
    text = `${parts}${m.glue ? `, ${m.glue}` : ''}${m.score != null ? `, score ${Number(m.score).toFixed(2)}` : ''}`;
  } else if (m.status === 'skipped') {
    // The reason is long and for the curious: a tooltip.
    text = 'not needed for this model';
    li.title = error;
  } else {
    text = `${m.status}${error ? `: ${error}` : ''}`;
  }
  li.querySelector('.bar-step').textContent = text;
  li.querySelector('button').hidden = m.status !== 'done';
}

/** The conversion ended (`status`) while these bars still ran: they stopped there. */
export function endBars(status) {
  for (const li of $('progress-bars').querySelectorAll('li[data-state="running"]')) {
    li.dataset.state = status === 'cancelled' ? 'cancelled' : 'stopped';
    li.querySelector('.bar-step').textContent = status === 'cancelled' ? 'cancelled' : 'stopped';
  }
}

/** Marks the bar of the method whose plan is shown (none: null). */
export function markShown(method) {
  for (const li of $('progress-bars').querySelectorAll('li')) {
    li.classList.toggle('shown', li.dataset.method === method);
    li.querySelector('button').disabled = li.dataset.method === method;
  }
}
