// Plain words for what the page counts and estimates: singular and plural, the assembly
// player's count, the laser-time note of a plan, the methods' names.

import { choicesOf } from './settings-form.js';

/** "1 part", "2 parts": `noun` is the singular, `plural` its plural when not noun + s. */
export function count(n, noun, plural = `${noun}s`) {
  return `${n} ${n === 1 ? noun : plural}`;
}

/** The assembly player's line: k of the plan's parts shown, `last` the one just joined. */
export function partsShown(k, total, last) {
  if (k >= total) return total === 1 ? 'The only part' : `All ${total} parts`;
  return `${k} of ${count(total, 'part')}${last ? `: part ${last} joined` : ''}`;
}

/** A method's name for people ("Stacked layers") as the settings name it, the API's word
 * when the settings do not (not loaded, or a new method). */
export function methodName(method) {
  const found = choicesOf('method').find(([value]) => value === method);
  return found ? found[1] : method;
}

/** Materials as a maker calls them. */
const MATERIAL_NAMES = { wood: 'plywood or MDF', acrylic: 'acrylic', cardboard: 'cardboard', paper: 'paper' };

/** "3 mm", "3 and 6 mm", "1.5, 3 and 6 mm". */
function thicknesses(list) {
  const ts = [...new Set((list || []).map(Number))].sort((a, b) => a - b).map(String);
  if (ts.length <= 1) return `${ts[0] || '?'} mm`;
  return `${ts.slice(0, -1).join(', ')} and ${ts.at(-1)} mm`;
}

/** A duration as a maker reads it: seconds under a minute, minutes under two hours, hours. */
export function duration(seconds) {
  if (seconds < 60) return `${Math.round(seconds)} s`;
  if (seconds < 7200) return `${Math.round(seconds / 60)} min`;
  return `${(seconds / 3600).toFixed(1)} h`;
}

/** The note under the laser time, from report.json: the plan's material and thicknesses and
 * the speeds the estimate assumed (the first sheet's, from the `laser` setting), so a maker can
 * compare them with their laser's. Kept to two lines: the handwork and the print profile are
 * in the times' tooltips (`timesTitles`). */
export function laserNote(report) {
  const r = report || {};
  const s = r.settings || {};
  const f = r.fabrication;
  const speeds = ((r.sheets || [])[0] || {}).laser_speeds;
  if (!f || !speeds) return '';
  const what = `${thicknesses(s.thicknesses)} ${MATERIAL_NAMES[s.material] || s.material || 'sheet'}`;
  return `Laser time for ${what}: a ${f.laser} laser cutting at ${speeds.cut} mm/s, engraving at ${speeds.engrave} mm/s, moving at ${speeds.travel} mm/s, ${speeds.pierce} s a cut started.`;
}

/** The tooltips of the laser and print times: what else the making takes, and what printer. */
export function timesTitles(report) {
  const f = (report || {}).fabrication;
  if (!f) return { laser: '', print: '' };
  return {
    laser: `Then ${duration(f.sheet_seconds)} to load the sheets and ${duration(f.assembly_seconds)} to take the parts out and assemble them.`,
    print: f.print_profile ? `The model printed as it lies: ${f.print_profile}.` : '',
  };
}

/**
 * Words of the warnings a maker may not know, each with what it means and why it matters. A
 * warning that uses one gets a "why?" that explains it (js/warnings.js).
 */
export const GLOSSARY = [
  ['inherent plate', 'A plate the model already has: two of its faces a sheet’s thickness apart, cut as one part.'],
  ['extruded', 'A single face of the model made into a plate by growing it inwards by a sheet’s thickness; a solid block becomes a hollow shell this way.'],
  ['kerf', 'The width of material the laser burns away. Outlines are offset by half of it so parts come out at their true size and joints fit.'],
  ['weld', 'Merging the model’s vertices that lie closer than a small distance, so faces meant to be one flat face are one; it removes bevels but can close thin gaps.'],
  ['coplanar', 'Faces in one plane; each group of them may become a plate.'],
  ['jimjoint', 'Fingers that widen towards their tip and snap behind the other part: they hold in card and paper, which give way.'],
  ['halved', 'Two plates crossing, each slotted half way so they slide into each other.'],
  ['shaft', 'A strip cut from a sheet that goes through slots in stacked layers and holds them in line.'],
  ['peg', 'A short shaft through two or more layers where a full shaft has no room. Where even a peg would not fit, a small square is added to both layers to hold one: glue is not needed.'],
  ['other family', 'The interlocked method stands two families of slices at right angles: A across the model’s longer side, B across the other. B slices stand first; each A slice is lowered onto them, crossing each in a slot.'],
  ['island', 'A separate piece of one layer or plate; one too small or thin to cut is left out.'],
  ['neck', 'A narrow part of an outline that would break when cut; it is widened or the part is split.'],
  ['living hinge', 'Rows of slits that let a wood sheet bend; the part is cut flat and bent by hand.'],
  ['standoff', 'A post standing on a plate, taller than a sheet (to hold a board or a lid): cut as discs stacked on a peg, or on a screw through its own hole, which is cut through the plate too.'],
  ['boss', 'A post or knob standing on a plate, taller than a sheet. One too small to cut as discs is left out; its screw hole, if it has one, is cut through the plate so a bought spacer and a screw can stand in for it.'],
  ['glue', 'These parts touch but no joint holds them: glue them, or change the thickness or method so joints fit.'],
  ['score', 'A line engraved, not cut through: a fold line in paper, or a feature drawn on a face.'],
];

/** The glossary entries whose words `line` uses. */
export function jargonIn(line) {
  const lower = line.toLowerCase();
  return GLOSSARY.filter(([word]) => lower.includes(word));
}
