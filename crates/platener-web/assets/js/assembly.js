// The assembly player's order: plan.json's `assembly`, the order the library plans from the
// parts' geometry (docs/cutting-plans.md); for plans made before it, a sequence from the joints.

/**
 * The order of part ids to show: plan.json's `steps` (its `assembly`) when there are any, each
 * part once, parts it does not name appended by id; else, for an older plan, from its joints:
 * start with the part that has the most joints (ties: the lowest id); then, again and again,
 * the lowest id joined to a part already placed. A part joined to nothing placed (a separate
 * piece of the model) starts a new group, so every part appears exactly once.
 */
export function assemblyOrder(partIds, joints, method, steps) {
  if (steps && steps.length) return stepsOrder(partIds, steps);
  if (method === 'interlocked') return interlockedOrder(partIds, joints);
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

/**
 * The interlocked method's order: every B slice stood up first, then every A slice lowered onto
 * them (each halved joint names its A slice first); parts in no joint last.
 */
function interlockedOrder(partIds, joints) {
  const a = new Set((joints || []).map((j) => (j.parts || [])[0]));
  const b = new Set((joints || []).map((j) => (j.parts || [])[1]));
  const rank = (id) => (b.has(id) && !a.has(id) ? 0 : a.has(id) ? 1 : 2);
  return [...partIds].sort((x, y) => rank(x) - rank(y) || x - y);
}

/** The parts of plan.json's assembly steps in order, each once; parts no step names last. */
function stepsOrder(partIds, steps) {
  const known = new Set(partIds);
  const order = [];
  for (const step of steps) {
    for (const id of step.parts || []) {
      if (known.has(id) && !order.includes(id)) order.push(id);
    }
  }
  const rest = partIds.filter((id) => !order.includes(id)).sort((a, b) => a - b);
  return order.concat(rest);
}
