// The gallery: published conversions as cards (a picture of the assembled object, drawn by the
// server; on hover or keyboard focus the name, a View button that opens it in the conversion
// area, and a Download link), paged as the API pages it (newest first).

import { gallery as fetchGallery } from './api.js';

function card(item) {
  const li = document.createElement('li');
  li.className = 'card';
  li.dataset.testid = 'gallery-item';
  li.dataset.id = item.id;
  const figure = document.createElement('div');
  figure.className = 'thumb';
  if (item.thumbnail) {
    const img = document.createElement('img');
    img.src = item.thumbnail;
    img.alt = `${item.name}, assembled`;
    img.loading = 'lazy';
    img.decoding = 'async';
    figure.append(img);
  } else {
    figure.textContent = item.status === 'failed' ? 'No plan' : 'Converting…';
  }
  const info = document.createElement('div');
  info.className = 'card-info';
  const name = document.createElement('h3');
  name.textContent = item.name;
  const facts = document.createElement('p');
  facts.className = 'note';
  facts.textContent = item.parts != null ? `${item.parts} parts · ${item.best} · score ${Number(item.score).toFixed(2)}` : item.status;
  const view = document.createElement('a');
  view.className = 'button primary';
  view.href = `#/c/${encodeURIComponent(item.id)}`;
  view.textContent = 'View';
  view.dataset.testid = 'gallery-view';
  view.setAttribute('aria-label', `View ${item.name}`);
  info.append(name, facts, view);
  if (item.best) {
    const dl = document.createElement('a');
    dl.className = 'button';
    dl.href = `${item.links.self}/plan.zip`;
    dl.setAttribute('download', '');
    dl.textContent = 'Download';
    dl.dataset.testid = 'gallery-download';
    dl.setAttribute('aria-label', `Download the plan of ${item.name}`);
    info.append(dl);
  }
  li.append(figure, info);
  return li;
}

/** Binds the gallery list and its pager; `load(page)` shows that page. */
export function createGallery(list, { prev, next, label, onError }) {
  let page = 1;
  async function load(p) {
    try {
      const data = await fetchGallery(p);
      page = data.page;
      list.replaceChildren(...data.items.map(card));
      if (!data.items.length) {
        const li = document.createElement('li');
        li.className = 'empty';
        li.textContent = 'Nothing published yet: convert a model and publish it.';
        list.append(li);
      }
      prev.disabled = page <= 1;
      next.disabled = !data.next;
      label.textContent = `Page ${page}`;
    } catch (e) {
      onError(e);
    }
  }
  prev.addEventListener('click', () => load(Math.max(1, page - 1)));
  next.addEventListener('click', () => load(page + 1));
  return { load, reload: () => load(page) };
}
