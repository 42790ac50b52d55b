// Plan arithmetic the page shows: the assembly order (a buildable sequence from plan.json's
// joints), cut length and an estimated laser time.

/**
 * A buildable order of part ids: start with the part that has the most joints (ties: the
 * lowest id); then, again and again, the lowest id joined to a part already placed. A part
 * joined to nothing placed (a separate piece of the model) starts a new group, so every part
 * appears exactly once.
 */
export function assemblyOrder(partIds, joints) {
  const neighbours = new Map(partIds.map((id) => [id, new Set()]));
  for (const j of joints || []) {
    const [a, b] = j.parts || [];
    if (neighbours.has(a) && neighbours.has(b) && a !== b) {
      neighbours.get(a).add(b);
      neighbours.get(b).add(a);
    }
  }
  const left = new Set(partIds);
  const order = [];
  const frontier = new Set();
  while (left.size) {
    let next;
    const ready = [...frontier].filter((id) => left.has(id));
    if (ready.length) {
      next = Math.min(...ready);
    } else {
      next = [...left].sort((a, b) => neighbours.get(b).size - neighbours.get(a).size || a - b)[0];
    }
    order.push(next);
    left.delete(next);
    frontier.delete(next);
    for (const n of neighbours.get(next)) if (left.has(n)) frontier.add(n);
  }
  return order;
}

function ringLength(ring, closed) {
  let sum = 0;
  for (let i = 1; i < ring.length; i++) sum += Math.hypot(ring[i][0] - ring[i - 1][0], ring[i][1] - ring[i - 1][1]);
  if (closed && ring.length > 2) {
    const a = ring[ring.length - 1];
    sum += Math.hypot(ring[0][0] - a[0], ring[0][1] - a[1]);
  }
  return sum;
}

/** Total cut length of a plan, mm: every outline, hole and `cut` mark (not engraving). */
export function cutLengthMm(plan) {
  let sum = 0;
  for (const p of plan.parts || []) {
    sum += ringLength(p.outline || [], true);
    for (const h of p.holes || []) sum += ringLength(h, true);
    for (const m of p.marks || []) if (m.kind === 'cut') sum += ringLength(m.path || [], false);
  }
  return sum;
}

/**
 * Cutting speed assumed for the laser-time estimate, mm/s: a 40 W CO2 laser (the common hobby
 * and maker-space machine) cutting 3 mm of the material in one pass, scaled by 3 / thickness.
 * Travel moves and engraving are left out, so the estimate is a lower bound.
 */
export const SPEED_3MM = { wood: 12, acrylic: 8, cardboard: 40, paper: 80 };

/** Estimated laser minutes of a plan at SPEED_3MM (thickness: that of each part). */
export function laserMinutes(plan, material) {
  const base = SPEED_3MM[material] || SPEED_3MM.wood;
  let seconds = 0;
  for (const p of plan.parts || []) {
    const one = { parts: [p] };
    const speed = base * 3 / Math.max(p.thickness || 3, 0.1);
    seconds += cutLengthMm(one) / speed;
  }
  return seconds / 60;
}
