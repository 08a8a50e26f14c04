// Open by link: index.html#src=URL&threshold=2&smoothing-steps=5&up-axis=z,
// the names of <crestline-viewer>'s attributes (embed.html takes the same):
// a parameter by its CLI flag, read with the core's table. The mesh is
// fetched by the worker like the widget's src (same origin, or a server that
// allows cross-origin requests) and read like a dropped file.
import { ATTRIBUTE_ALIASES, attributeName, parseParameter, pipelineParameters } from '../client/parameters.js';
import { autoKey } from './gui.js';

/**
 * The link's mesh and settings, or null without `src`.
 * @param {string} hash location.hash
 * @param {import('../client/parameters.js').Parameter[]} table
 * @param {string} base the page's URL: a relative src is resolved against it
 * @returns {{url: string, name: string, settings: Record<string, unknown>} | null}
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
    return { url: '', name: src, settings: {} };
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
  return { url: url.href, name, settings };
}
