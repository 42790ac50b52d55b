// Plain words for what the page counts and estimates: singular and plural, the assembly
// player's count, the laser-time note of a plan, the methods' names.

/** "1 part", "2 parts": `noun` is the singular, `plural` its plural when not noun + s. */
export function count(n, noun, plural = `${noun}s`) {
  return `${n} ${n === 1 ? noun : plural}`;
}

/** The assembly player's line: k of the plan's parts shown, `last` the one just joined. */
export function partsShown(k, total, last) {
  if (k >= total) return total === 1 ? 'The only part' : `All ${total} parts`;
  return `${k} of ${count(total, 'part')}${last ? `: part ${last} joined` : ''}`;
}

/** The methods as the page's method select names them. */
const METHOD_NAMES = { plate: 'Plates', stacked: 'Stacked layers', classifier: 'Primitives' };

/** A method's name for people ("Stacked layers"), the API's word when it is a new one. */
export function methodName(method) {
  return METHOD_NAMES[method] || method;
}

/** Materials as a maker calls them. */
const MATERIAL_NAMES = { wood: 'plywood or MDF', acrylic: 'acrylic', cardboard: 'cardboard', paper: 'paper' };

/** "3 mm", "3 and 6 mm", "1.5, 3 and 6 mm". */
function thicknesses(list) {
  const ts = [...new Set((list || []).map(Number))].sort((a, b) => a - b).map(String);
  if (ts.length <= 1) return `${ts[0] || '?'} mm`;
  return `${ts.slice(0, -1).join(', ')} and ${ts.at(-1)} mm`;
}

/** The note under the laser time, for the plan's own material and thicknesses (report.json's
 * `settings`): the speeds the estimate assumed, so a maker can compare them with their laser's. */
export function laserNote(settings) {
  const s = settings || {};
  if (!s.cut_speed) return '';
  const what = `${thicknesses(s.thicknesses)} ${MATERIAL_NAMES[s.material] || s.material || 'sheet'}`;
  return `Laser time for ${what}: cutting at ${s.cut_speed} mm/s and engraving at ${s.engrave_speed} mm/s, without travel moves.`;
}
