// The SVG sheets, inlined (not <img>) so parts can be hovered: each sheet is fetched, parsed
// with DOMParser as SVG, stripped of anything active (scripts, foreignObject, event handler
// attributes, links), and imported. Each part's group `<g id="part-N">` becomes
// data-testid="sheet-part" data-part="N".

import { getText } from './api.js';

const SVG_NS = 'http://www.w3.org/2000/svg';
const DROP = new Set(['script', 'foreignobject', 'iframe', 'object', 'embed', 'a', 'use', 'image', 'animate', 'set', 'style', 'animatemotion', 'animatetransform', 'handler', 'listener']);

/** Removes everything that could run or load something; returns the cleaned <svg>. */
export function sanitizeSvg(root) {
  const walk = (el) => {
    for (const child of [...el.children]) {
      if (DROP.has(child.localName.toLowerCase()) || child.namespaceURI !== SVG_NS) {
        child.remove();
        continue;
      }
      walk(child);
    }
    for (const attr of [...el.attributes]) {
      const name = attr.name.toLowerCase();
      const value = attr.value.replace(/\s+/g, '').toLowerCase();
      if (name.startsWith('on') || name === 'style' || name.endsWith('href') || value.startsWith('javascript:') || value.includes('url(')) {
        el.removeAttribute(attr.name);
      }
    }
  };
  walk(root);
  return root;
}

/** Parses SVG text into a clean element for this document; throws on anything else. */
export function parseSvg(text) {
  const doc = new DOMParser().parseFromString(text, 'image/svg+xml');
  const root = doc.documentElement;
  if (!root || root.localName !== 'svg' || root.namespaceURI !== SVG_NS || doc.querySelector('parsererror')) {
    throw new Error('A sheet is not a valid SVG file.');
  }
  return document.importNode(sanitizeSvg(root), true);
}

/**
 * The sheets panel: `show(urls)` replaces its content, `highlight(n, { reveal })` marks part n
 * on every sheet (and scrolls to it), `sheetOf(n)` and `count` say where it is and how many
 * sheets there are, `zoom(factor | 'fit')`; `onHover(n|null)` is called as parts are hovered or
 * focused.
 */
export function createSheets(container, { onHover = () => {} } = {}) {
  let zoom = 1;
  let current = null;

  function applyZoom() {
    for (const svg of container.querySelectorAll('svg')) {
      svg.style.width = `${Math.round(zoom * 100)}%`;
      // At "fit" a tall sheet stays within the panel; zoomed in, it may grow.
      svg.style.maxHeight = zoom > 1 ? 'none' : '';
    }
  }

  function decorate(svg, sheetNumber) {
    svg.removeAttribute('width');
    svg.removeAttribute('height');
    svg.setAttribute('role', 'img');
    svg.setAttribute('aria-label', `Sheet ${sheetNumber}`);
    svg.classList.add('sheet');
    for (const g of svg.querySelectorAll('g[id^="part-"]')) {
      const n = Number(g.id.slice(5));
      if (!Number.isInteger(n)) continue;
      g.dataset.testid = 'sheet-part';
      g.dataset.part = String(n);
      g.setAttribute('tabindex', '0');
      g.setAttribute('aria-label', `Part ${n}`);
      g.setAttribute('role', 'button');
    }
  }

  async function show(urls) {
    const texts = await Promise.all(urls.map((u) => getText(u)));
    container.replaceChildren();
    texts.forEach((text, i) => {
      const figure = document.createElement('figure');
      const svg = parseSvg(text);
      const size = (svg.getAttribute('viewBox') || '').split(/[\s,]+/).slice(2).map(Number);
      decorate(svg, i + 1);
      const caption = document.createElement('figcaption');
      caption.textContent = size.length === 2 ? `Sheet ${i + 1} (${size[0]} × ${size[1]} mm), cropped to its parts` : `Sheet ${i + 1}`;
      figure.append(svg, caption);
      container.append(figure);
      cropToParts(svg);
    });
    applyZoom();
    current = null;
  }

  /** Shows the parts' area of a sheet (plus 5 mm), not the whole mostly empty sheet. */
  function cropToParts(svg) {
    try {
      const b = svg.getBBox();
      if (b.width > 0 && b.height > 0) svg.setAttribute('viewBox', `${b.x - 5} ${b.y - 5} ${b.width + 10} ${b.height + 10}`);
    } catch (_) {
      // Not rendered (a hidden panel): keep the whole sheet.
    }
  }

  /** Marks part n on every sheet; with `reveal`, scrolls the sheet list (only it, never the
   * page: the pointer stays where it is) so the part is in view. */
  function highlight(n, { reveal = false } = {}) {
    current = n;
    for (const g of container.querySelectorAll('[data-part].hot')) g.classList.remove('hot');
    if (n === null || n === undefined) return;
    const parts = [...container.querySelectorAll(`[data-part="${Number(n)}"]`)];
    for (const g of parts) g.classList.add('hot');
    if (reveal && parts.length) scrollTo(parts[0]);
  }

  /** Scrolls the container by as much as brings `el` into its view, centred when it moves. */
  function scrollTo(el) {
    const box = container.getBoundingClientRect();
    const r = el.getBoundingClientRect();
    const inside = r.top >= box.top && r.bottom <= box.bottom && r.left >= box.left && r.right <= box.right;
    if (inside) return;
    container.scrollTop += r.top - box.top - (box.height - r.height) / 2;
    container.scrollLeft += r.left - box.left - (box.width - r.width) / 2;
  }

  /** The number (from 1) of the sheet part n is cut from; null if it is on none shown. */
  function sheetOf(n) {
    const g = container.querySelector(`[data-part="${Number(n)}"]`);
    const figure = g && g.closest('figure');
    return figure ? [...container.children].indexOf(figure) + 1 : null;
  }

  const partOf = (target) => (target instanceof Element ? target.closest('[data-part]') : null);
  const enter = (e) => {
    const g = partOf(e.target);
    const n = g ? Number(g.dataset.part) : null;
    if (n !== current) {
      highlight(n);
      onHover(n);
    }
  };
  container.addEventListener('pointerover', enter);
  container.addEventListener('focusin', enter);
  container.addEventListener('pointerleave', () => {
    highlight(null);
    onHover(null);
  });
  container.addEventListener('focusout', (e) => {
    if (!container.contains(e.relatedTarget)) {
      highlight(null);
      onHover(null);
    }
  });

  return {
    show,
    highlight,
    sheetOf,
    get count() { return container.querySelectorAll('figure').length; },
    clear() {
      container.replaceChildren();
      current = null;
    },
    zoom(f) {
      zoom = f === 'fit' ? 1 : Math.min(8, Math.max(0.25, zoom * f));
      applyZoom();
      return zoom;
    },
  };
}
