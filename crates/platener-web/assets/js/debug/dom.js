// A small element builder for the debug view: no innerHTML anywhere, so names and messages
// from models and the server are always text, never markup.

/** el('div', { class: 'x', 'data-testid': 'y', onclick: f }, child, 'text', …). */
export function el(tag, attrs = {}, ...children) {
  const node = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs)) {
    if (v === null || v === undefined || v === false) continue;
    if (k.startsWith('on') && typeof v === 'function') node.addEventListener(k.slice(2), v);
    else if (k === 'text') node.textContent = String(v);
    else node.setAttribute(k, v === true ? '' : String(v));
  }
  for (const c of children.flat()) {
    if (c === null || c === undefined || c === false) continue;
    node.append(c instanceof Node ? c : document.createTextNode(String(c)));
  }
  return node;
}

/** A labelled control: <label>text control</label>. */
export function field(text, control) {
  return el('label', { class: 'debug-field' }, el('span', {}, text), control);
}

/** A <select> of [value, text] pairs. */
export function select(testid, options, value) {
  const s = el('select', { 'data-testid': testid });
  for (const [v, t] of options) s.append(el('option', { value: v, selected: v === value }, t));
  return s;
}
