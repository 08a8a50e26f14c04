// Open by link: index.html#src=URL&threshold=2&smoothing-steps=5&up-axis=z,
// the names of <crestline-viewer>'s attributes (embed.html takes the same):
// a parameter by its CLI flag, read with the core's table. The mesh is
// fetched by the worker like the widget's src (same origin, or a server that
// allows cross-origin requests) and read like a dropped file. While the page
// shows a linked mesh, the address bar holds the link to what it shows.
import { ATTRIBUTE_ALIASES, attributeName, parseParameter, pipelineParameters } from '../client/parameters.js';
import { autoKey } from './gui.js';

/**
 * The link's mesh and settings, or null without `src`.
 * @param {string} hash location.hash
 * @param {import('../client/parameters.js').Parameter[]} table
 * @param {string} base the page's URL: a relative src is resolved against it
 * @returns {{url: string, name: string, src: string, settings: Record<string, unknown>} | null}
 */
export function parseLink(hash, table, base) {
  const fragment = new URLSearchParams(hash.replace(/^#/, ''));
  for (const [alias, flag] of Object.entries(ATTRIBUTE_ALIASES)) if (fragment.has(alias) && !fragment.has(flag)) fragment.set(flag, fragment.get(alias));
  const src = fragment.get('src');
  if (!src) return null;
  let url;
  try {
    url = new URL(src, base);
  } catch {
    return { url: '', name: src, src, settings: {} };
  }
  const name = decodeURIComponent(url.pathname.split('/').pop() || url.hostname || 'model');
  const settings = {};
  for (const p of pipelineParameters(table)) {
    const value = parseParameter(p, fragment.get(attributeName(p)));
    if (value === undefined) continue;
    if (p.automatic) settings[autoKey(p)] = value === 'auto';
    if (value !== 'auto') settings[p.key] = value;
  }
  const up = fragment.get('up-axis')?.toLowerCase();
  if (up === 'y' || up === 'z') settings.upAxis = up;
  return { url: url.href, name, src, settings };
}

/**
 * The fragment that opens `src` as the page shows it: the parameters that
 * differ from the table's defaults, by their flags, and the up axis.
 * @param {string} src the link's src as given
 * @param {Record<string, any>} params the panel's values
 * @param {import('../client/parameters.js').Parameter[]} table
 */
export function linkFragment(src, params, table) {
  const fragment = new URLSearchParams({ src });
  for (const p of pipelineParameters(table)) {
    const value = p.automatic && params[autoKey(p)] ? 'auto' : params[p.key];
    if (String(value) !== String(p.default)) fragment.set(attributeName(p), String(value));
  }
  if (params.upAxis && params.upAxis !== 'y') fragment.set('up-axis', params.upAxis);
  return `#${fragment}`;
}
