// @ts-check
// The parameter table of the core (Session.describe(), C++
// crestline/parameters.h) as the page uses it: the panel's controls and the
// widget's attributes are made from it, so no default or range is written
// down in JavaScript.

/**
 * @typedef {{key: string, flag: string, group: string, kind: 'integer' | 'number' | 'boolean' | 'choice',
 *            automatic: boolean, default: number | boolean | string, min: number | null, max: number | null,
 *            choices: string[], unit: string, help: string, stage: string | null}} Parameter
 *   min/max: null for booleans and choices; max Infinity when unbounded
 */

/** The parameters that change the lines (those a change re-runs a stage for). @param {Parameter[]} table */
export const pipelineParameters = (table) => table.filter((p) => p.group === 'pipeline' && p.stage !== null);

/** The attribute of <crestline-viewer> for a parameter: its CLI flag without the dashes. @param {Parameter} p */
export const attributeName = (p) => p.flag.replace(/^--/, '');

/** Older attribute names the element still reads (README), → the table's flag names. */
export const ATTRIBUTE_ALIASES = { smoothing: 'smoothing-steps', fairing: 'fairing-bound' };

/**
 * A parameter's value from text (an attribute), or undefined when the text
 * is absent or not a valid value (the core's default then applies).
 * @param {Parameter} p
 * @param {string | null} text
 * @returns {number | boolean | string | undefined}
 */
export function parseParameter(p, text) {
  if (text === null) return undefined;
  const t = text.trim().toLowerCase();
  if (p.automatic && t === 'auto') return 'auto';
  if (p.kind === 'boolean') return t === '' || t === 'true' ? true : t === 'false' ? false : undefined;
  if (p.kind === 'choice') return p.choices.includes(t) ? t : undefined;
  if (t === '') return undefined;
  const value = Number(t);
  if (!Number.isFinite(value) || (p.kind === 'integer' && !Number.isInteger(value))) return undefined;
  if (value < /** @type {number} */ (p.min) || value > (p.max ?? Infinity)) return undefined;
  return value;
}

/** "--smoothing-steps" → "smoothing steps". @param {Parameter} p */
export const label = (p) => attributeName(p).replace(/-/g, ' ');

/** The help text with its unit, for a tooltip. @param {Parameter} p */
export const describeParameter = (p) => (p.unit ? `${p.help} (${p.unit})` : p.help);
