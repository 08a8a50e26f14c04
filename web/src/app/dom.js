// The page's text: file name, progress, the one-sentence error, stats.
const $ = (id) => document.getElementById(id);

export function setState(state) {
  document.body.dataset.state = state;
}

export function showFile(text) {
  $('file').firstChild.textContent = `${text} — drop another mesh or `;
}

export function showProgress(stage, fraction) {
  $('progress').hidden = stage === null;
  if (stage === null) return;
  $('progress-bar').value = fraction;
  $('progress-text').textContent = stage;
}

/** One clear sentence, or null to clear. */
export function showError(message) {
  $('error').hidden = !message;
  $('error').textContent = message ?? '';
}

export function showNotes(notes) {
  $('notes').textContent = notes.join(' ');
}

const fmt = (x, digits = 3) => (Number.isFinite(x) ? Number(x.toPrecision(digits)).toString() : '–');

/** Pipeline statistics; `mesh` adds the time to read the file and to repair the mesh. */
export function showStats({ stats, ran, milliseconds }, mesh = {}) {
  const times = ran
    .map((stage) => `${stage} ${(1000 * (stats.seconds[stage] ?? 0)).toFixed(1)} ms`)
    .join(', ');
  $('stats').textContent = [
    `${stats.vertices.toLocaleString()} vertices, ${stats.triangles.toLocaleString()} triangles`,
    `ridges  ${stats.ridges} (length ${fmt(stats.ridgeLength)})`,
    `valleys ${stats.valleys} (length ${fmt(stats.valleyLength)})`,
    `creases ${stats.creases ?? 0} (length ${fmt(stats.creaseLength)}, angle ${fmt(stats.creaseAngle)}°)`,
    `threshold ${fmt(stats.threshold)}, singular triangles ${stats.singularMax} max / ${stats.singularMin} min`,
    `ran: ${times} — ${milliseconds.toFixed(1)} ms in total`,
    mesh.loadMs === undefined ? '' : `read and repair ${mesh.loadMs.toFixed(0)} ms`,
  ].filter(Boolean).join('\n');
}

/** The legend: each line kind in its colour, struck through when hidden. */
export function showLegend({ ridgeColor, valleyColor, creaseColor, showRidges, showValleys, showCreases }, concaveColor) {
  // The crease swatch: convex (the crease colour) | concave (its darker shade).
  const crease = `linear-gradient(90deg, ${creaseColor} 50%, ${concaveColor} 50%)`;
  for (const [id, color, shown] of [['legend-ridge', ridgeColor, showRidges], ['legend-valley', valleyColor, showValleys], ['legend-crease', crease, showCreases]]) {
    $(id).querySelector('.swatch').style.background = color;
    $(id).classList.toggle('off', !shown);
  }
}
