// The interactive kerf test strip of the download dialog, drawn from /api/test-strip.json at true
// proportions (one SVG user unit = 1 mm): the strip's outline, the spike, and one button per
// hole. Choosing a hole calls onPick(kerf).

const SVG_NS = 'http://www.w3.org/2000/svg';

function el(name, attrs = {}, text) {
  const e = document.createElementNS(SVG_NS, name);
  for (const [k, v] of Object.entries(attrs)) e.setAttribute(k, String(v));
  if (text !== undefined) e.textContent = text;
  return e;
}

const pathOf = (ring) => ring.map(([x, y], i) => `${i ? 'L' : 'M'}${x} ${y}`).join(' ') + ' Z';

/** Round to the 0.001 mm the API's kerfs are written with. */
export const sameKerf = (a, b) => Math.abs(Number(a) - Number(b)) < 0.0005;

/** Draws `strip` (the JSON) into `svg`; the hole of `kerf` is marked as chosen. */
export function drawStrip(svg, strip, kerf, onPick) {
  svg.replaceChildren();
  svg.setAttribute('viewBox', `0 0 ${strip.width} ${strip.height}`);
  svg.setAttribute('preserveAspectRatio', 'xMinYMin meet');
  svg.dataset.widthMm = String(strip.width);
  svg.dataset.heightMm = String(strip.height);
  svg.append(el('rect', { x: 0, y: 0, width: strip.width, height: strip.height, class: 'strip-sheet' }));
  if (strip.strip) svg.append(el('path', { d: pathOf(strip.strip), class: 'strip-outline' }));
  if (strip.spike) svg.append(el('path', { d: pathOf(strip.spike), class: 'strip-spike' }));
  // The engraving (hole numbers and the kerf table), as the laser draws it.
  const lines = (strip.engrave || []).map((l) => l.map(([x, y], i) => `${i ? 'L' : 'M'}${x} ${y}`).join(' '));
  if (lines.length) svg.append(el('path', { d: lines.join(' '), class: 'strip-engrave' }));
  // The slot row measures the sheet's thickness; drawn, not picked here.
  for (const slot of strip.slots || []) svg.append(el('path', { d: pathOf(slot.ring), class: 'strip-slot' }));
  for (const hole of strip.holes) {
    const xs = (hole.ring || []).map((p) => p[0]);
    const ys = (hole.ring || []).map((p) => p[1]);
    if (!xs.length) continue;
    const [x0, x1, y0, y1] = [Math.min(...xs), Math.max(...xs), Math.min(...ys), Math.max(...ys)];
    const chosen = sameKerf(hole.kerf, kerf);
    const g = el('g', {
      class: chosen ? 'strip-hole chosen' : 'strip-hole',
      tabindex: 0,
      role: 'button',
      'data-testid': 'strip-hole',
      'data-kerf': hole.kerf.toFixed(3),
      'data-number': hole.number,
      'aria-pressed': chosen ? 'true' : 'false',
      'aria-label': `Hole ${hole.number}: kerf ${hole.kerf.toFixed(3)} mm`,
    });
    // A generous invisible target around the hole: holes are only a few mm wide.
    g.append(el('rect', { x: x0 - 1.5, y: y0 - 1.5, width: x1 - x0 + 3, height: y1 - y0 + 8, class: 'strip-target' }));
    g.append(el('path', { d: pathOf(hole.ring), class: 'strip-hole-cut' }));
    if (!lines.length) g.append(el('text', { x: (x0 + x1) / 2, y: y1 + 5, class: 'strip-number', 'text-anchor': 'middle' }, String(hole.number)));
    g.append(el('title', {}, `Hole ${hole.number}: kerf ${hole.kerf.toFixed(3)} mm`));
    const pick = () => onPick(hole.kerf);
    g.addEventListener('click', pick);
    g.addEventListener('keydown', (e) => {
      if (e.key === 'Enter' || e.key === ' ') {
        e.preventDefault();
        pick();
      }
    });
    svg.append(g);
  }
}
