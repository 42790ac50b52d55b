// Stub of the debug view (#/debug). The debug helper owns js/debug/** and replaces this file;
// app.js calls mount(rootElement, api) the first time the route is opened.

export function mount(root) {
  const h = document.createElement('h1');
  h.textContent = 'Debug view';
  const p = document.createElement('p');
  p.textContent = 'The debug view is not built yet.';
  root.replaceChildren(h, p);
}
