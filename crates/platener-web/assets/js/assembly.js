// The assembly player's order: a buildable sequence of parts from plan.json's joints.

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
