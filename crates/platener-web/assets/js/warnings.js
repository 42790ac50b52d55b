// A conversion's warnings, grouped where they came from: the model's preparation (the steps
// every method shares), the method whose plan is shown, then each other method. A clean plan
// says so in words, even when methods the page does not show left notes.

import { count, jargonIn, methodName } from './wording.js';

const $ = (id) => document.getElementById(id);

/** One warning as a sentence naming its step (and part). */
function sentence(w) {
  return typeof w === 'string' ? w : `${w.step}${w.part ? `, part ${w.part}` : ''}: ${w.message}`;
}

/**
 * The warnings of conversion `c` in groups `{method, title, shown, lines}`: the shared steps'
 * (method null) and the shown method's first (`shown`: they concern the plan on screen; with
 * no plan, every group does), then the other methods', each line once.
 */
export function warningGroups(c, shownMethod = c.best) {
  const seen = new Set();
  const lines = (list) => (list || []).map(sentence).filter((l) => !seen.has(l) && seen.add(l));
  const shared = (c.steps || []).flatMap((s) => lines(s.warnings));
  const groups = [{ method: null, title: 'Preparing the model', shown: true, lines: shared }];
  for (const m of c.methods || []) {
    const shown = !shownMethod || m.method === shownMethod;
    const title = `${methodName(m.method)}${shownMethod ? (shown ? ', the plan shown' : ', not shown') : ''}`;
    groups.push({ method: m.method, title, shown, lines: lines(m.warnings) });
  }
  const order = (g) => (g.shown ? 0 : 1);
  return groups.filter((g) => g.lines.length).sort((a, b) => order(a) - order(b));
}

/** One warning; one that uses jargon gets a folded "why?" that says what the words mean. */
function warningItem(line) {
  const li = Object.assign(document.createElement('li'), { textContent: line });
  const words = jargonIn(line);
  if (!words.length) return li;
  const why = Object.assign(document.createElement('details'), { className: 'why' });
  why.dataset.testid = 'why';
  const dl = document.createElement('dl');
  for (const [word, meaning] of words) {
    dl.append(Object.assign(document.createElement('dt'), { textContent: word }));
    dl.append(Object.assign(document.createElement('dd'), { textContent: meaning }));
  }
  why.append(Object.assign(document.createElement('summary'), { textContent: 'why?' }), dl);
  li.append(' ', why);
  return li;
}

/** The summary line over the groups, in words. */
export function warningsTitle(groups) {
  const shown = groups.filter((g) => g.shown).reduce((n, g) => n + g.lines.length, 0);
  const other = groups.filter((g) => !g.shown).reduce((n, g) => n + g.lines.length, 0);
  const notes = other ? `${count(other, 'note')} from the methods not shown` : '';
  if (!shown) return `No warnings about this plan (${notes})`;
  return `${count(shown, 'warning')} about this plan${notes ? `, and ${notes}` : ''}`;
}

/** Fills the warnings box (hidden when there is nothing to say); `shownMethod`: the method
 * whose plan is on screen (the best unless the maker chose another). */
export function showWarnings(c, shownMethod = c.best) {
  const groups = warningGroups(c, shownMethod);
  $('warnings').replaceChildren(...groups.map((g) => {
    const li = document.createElement('li');
    li.className = g.shown ? 'group' : 'group other-method';
    if (g.method) li.dataset.method = g.method;
    const head = document.createElement('strong');
    head.textContent = `${g.title}: ${count(g.lines.length, g.shown ? 'warning' : 'note')}`;
    const ul = document.createElement('ul');
    ul.append(...g.lines.map(warningItem));
    li.append(head, ul);
    return li;
  }));
  $('warnings-title').textContent = warningsTitle(groups);
  $('warnings-box').hidden = groups.length === 0;
}
