// The page's text, all drawn from the one page state (page-state.js): the
// header, the label over a previous mesh, progress, the one-sentence error,
// notes, stats.
import { countsOf, headerOf, phaseOf, viewLabelOf } from './page-state.js';
import { colormapGradient } from '../three/colormap.js';

const $ = (id) => document.getElementById(id);

/** Draws every view of `state` except the 3D picture (main.js). @param {import('./page-state.js').PageState} state */
export function render(state) {
  const phase = phaseOf(state);
  document.body.dataset.state = phase;
  const header = headerOf(state);
  $('file').firstChild.textContent = header ? `${header} — drop another mesh or ` : 'Drop a mesh anywhere (glTF/GLB with its .bin, OBJ, PLY, STL, OFF) or ';
  const label = viewLabelOf(state);
  $('view-label').hidden = !label;
  $('view-label').textContent = label;
  document.body.classList.toggle('previous', Boolean(label));
  const progress = phase === 'loading' || phase === 'computing' ? (state.progress ?? { stage: 'waiting', fraction: 0 }) : null;
  $('progress').hidden = !progress;
  if (progress) {
    $('progress-bar').value = progress.fraction;
    $('progress-text').textContent = progress.stage;
  }
  $('error').hidden = !state.error;
  $('error').textContent = state.error ?? '';
  $('notes').textContent = state.notes.join(' ');
  const { shown } = state;
  if (shown?.result) showStats(shown.result, shown);
  else $('stats').textContent = shown ? countsOf(shown) : '';
}

const fmt = (x, digits = 3) => (Number.isFinite(x) ? Number(x.toPrecision(digits)).toString() : '–');

/** Pipeline statistics; `mesh` adds the time to read the file and to repair the mesh. */
function showStats({ stats, ran, milliseconds }, mesh = {}) {
  const times = ran.map((stage) => `${stage} ${(1000 * (stats.seconds[stage] ?? 0)).toFixed(1)} ms`).join(', ');
  $('stats').textContent = [
    mesh.name,
    `${stats.vertices.toLocaleString()} vertices, ${stats.triangles.toLocaleString()} triangles`,
    `ridges  ${stats.ridges} (length ${fmt(stats.ridgeLength)})`,
    `valleys ${stats.valleys} (length ${fmt(stats.valleyLength)})`,
    `creases ${stats.creases ?? 0} (length ${fmt(stats.creaseLength)}, angle ${fmt(stats.creaseAngle)}°)`,
    `threshold ${fmt(stats.threshold)}, singular triangles ${stats.singularMax} max / ${stats.singularMin} min`,
    `ran: ${times} — ${milliseconds.toFixed(1)} ms in total`,
    mesh.loadMs === undefined ? '' : `read and repair ${mesh.loadMs.toFixed(0)} ms`,
  ]
    .filter(Boolean)
    .join('\n');
}

/** The legend: each line kind in its colour, struck through when hidden. */
export function showLegend({ ridgeColor, valleyColor, creaseColor, showRidges, showValleys, showCreases }, concaveColor) {
  // The crease swatch: convex (the crease colour) | concave (its darker shade).
  const crease = `linear-gradient(90deg, ${creaseColor} 50%, ${concaveColor} 50%)`;
  for (const [id, color, shown] of [
    ['legend-ridge', ridgeColor, showRidges],
    ['legend-valley', valleyColor, showValleys],
    ['legend-crease', crease, showCreases],
  ]) {
    $(id).querySelector('.swatch').style.background = color;
    $(id).classList.toggle('off', !shown);
  }
}

/**
 * The colour scale of a colour map, or null to hide it: `name` (with its
 * unit), the value the colours saturate at, `positive`: the map runs 0…max.
 * @param {{name: string, scale: number, positive: boolean} | null} map
 */
export function showScale(map) {
  $('scale').hidden = !map;
  if (!map) return;
  $('scale-name').textContent = map.name;
  $('scale-min').textContent = map.positive ? '0' : `−${fmt(map.scale)}`;
  $('scale-max').textContent = `${map.positive ? '' : '+'}${fmt(map.scale)}`;
  $('scale-bar').style.background = colormapGradient(map.positive);
}
