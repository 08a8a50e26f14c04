// The parameters panel (lil-gui). Pipeline parameters are made from the
// core's table (Session.describe(): range, default, automatic mode, help) and
// call onCompute; display parameters call onDisplay. Both receive the whole
// params object.
import GUI from 'lil-gui';
import { describeParameter, label, pipelineParameters } from '../client/parameters.js';
import { LINE_COLORS } from '../three/colors.js';
import { VIEW_PRESETS } from '../three/fit.js';

export const VIEWS = {
  shaded: 'shaded',
  'κ max (curvature)': 'kappaMax',
  'κ min (curvature)': 'kappaMin',
  '|extremality e max|': 'eMax',
  '|extremality e min|': 'eMin',
  'singular triangles (max dirs)': 'singularMax',
  'singular triangles (min dirs)': 'singularMin',
  'smoothing weights (brush)': 'weights',
};

/** params[autoKey(p)]: the parameter is in its automatic mode. @param {{key: string}} p */
export const autoKey = (p) => `auto${p.key[0].toUpperCase()}${p.key.slice(1)}`;

/**
 * The panel's values: every pipeline parameter at the table's default (an
 * automatic one with its switch on), then the display settings.
 * @param {import('../client/parameters.js').Parameter[]} table
 */
export function defaultParams(table) {
  const pipeline = {};
  for (const p of pipelineParameters(table)) {
    const automatic = p.default === 'auto';
    if (p.automatic) pipeline[autoKey(p)] = automatic;
    // An automatic parameter shows the value the core used once it ran.
    pipeline[p.key] = automatic ? p.min : p.default;
  }
  return {
    ...pipeline,
    showRidges: true,
    showValleys: true,
    showCreases: true,
    lineWidth: 2.5,
    ridgeColor: LINE_COLORS.ridge,
    valleyColor: LINE_COLORS.valley,
    creaseColor: LINE_COLORS.crease,
    dark: false,
    view: 'shaded',
    brush: false,
    brushRadius: 0.08,
    brushValue: 0,
    pngScale: 2,
    exportSilhouette: false,
    preset: 'front',
    upAxis: 'y',
  };
}

/** The options the worker passes to Session.setOptions. */
export function pipelineOptions(params, table) {
  const options = {};
  for (const p of pipelineParameters(table)) options[p.key] = p.automatic && params[autoKey(p)] ? 'auto' : params[p.key];
  return options;
}

/** PNG resolutions offered: multiples of the canvas's CSS size. */
export const PNG_SCALES = { '1× canvas': 1, '2× canvas': 2, '4× canvas': 4 };

/** Export buttons: format → label. */
export const EXPORTS = { svg: 'SVG (visible lines)', png: 'PNG', obj: 'OBJ (polylines)', json: 'JSON (lines + stats)', glb: 'GLB (mesh + lines)' };

/** What each export holds, for its tooltip. */
const EXPORT_TIPS = {
  svg: 'lines seen from this view as a vector drawing',
  png: 'picture of the view',
  obj: 'lines as 3D polylines (OBJ)',
  json: 'lines with their strength and the statistics (JSON)',
  glb: 'mesh with its lines as a glTF binary',
};

/** A plain-words tooltip on a panel control. */
const tip = (controller, text) => {
  controller.domElement.title = text;
  return controller;
};

/** Slider step: whole numbers for integers, else about a thousandth of the range. */
const stepOf = (p, max) => (p.kind === 'integer' ? 1 : Math.min(0.01, (max - p.min) / 1000));

export function createGui(params, table, { onCompute, onDisplay, onFit, onCamera, onOpen, onBrush, onClearWeights, onExport }) {
  const gui = new GUI({ title: 'Crestline' });
  const lines = gui.addFolder('Feature lines');
  const more = lines.addFolder('More parameters');
  more.close();
  const unbounded = []; // controllers of parameters without a maximum: their slider follows the values used
  for (const p of pipelineParameters(table)) {
    // The three the paper's figures vary stay in view; the others fold away.
    const folder = ['smoothingSteps', 'threshold', 'hausdorffBound', 'presmoothSteps', 'creaseAngle'].includes(p.key) ? lines : more;
    if (p.automatic) {
      folder
        .add(params, autoKey(p))
        .name(`automatic ${label(p)}`)
        .onChange(onCompute).domElement.title = describeParameter(p);
    }
    const max = Number.isFinite(p.max) ? p.max : Math.max(1, p.min * 10);
    const controller = p.kind === 'boolean' ? folder.add(params, p.key) : folder.add(params, p.key, p.min, max, stepOf(p, max));
    controller.name(label(p)).domElement.title = describeParameter(p);
    controller.onFinishChange(() => {
      // Moving an automatic parameter's slider leaves its automatic mode.
      if (p.automatic) params[autoKey(p)] = false;
      gui.controllersRecursive().forEach((c) => c.updateDisplay());
      onCompute();
    });
    controller.parameter = p;
    if (!Number.isFinite(p.max)) unbounded.push(controller);
  }
  const display = gui.addFolder('Display');
  tip(display.add(params, 'showRidges').name('ridges'), 'Show the ridges: lines where the surface bends most sharply outward (crests)').onChange(onDisplay);
  tip(display.add(params, 'showValleys').name('valleys'), 'Show the valleys: lines where the surface bends most sharply inward (grooves)').onChange(onDisplay);
  tip(
    display.add(params, 'showCreases').name('creases'),
    'Show the creases: sharp edges of the mesh (convex in the crease colour, concave in a darker shade)',
  ).onChange(onDisplay);
  tip(display.add(params, 'lineWidth', 0.5, 8, 0.1).name('line width (px)'), 'Width of the drawn lines, in screen pixels').onChange(onDisplay);
  tip(display.addColor(params, 'ridgeColor').name('ridge colour'), 'Colour of the ridges, on the page and in the exports').onChange(onDisplay);
  tip(display.addColor(params, 'valleyColor').name('valley colour'), 'Colour of the valleys, on the page and in the exports').onChange(onDisplay);
  tip(
    display.addColor(params, 'creaseColor').name('crease colour'),
    'Colour of the convex creases (concave ones are a darker shade), on the page and in the exports',
  ).onChange(onDisplay);
  tip(
    display.add(params, 'view', VIEWS).name('surface'),
    'What the surface shows: plain shading, a principal curvature κ or extremality (how fast κ changes along its direction), the triangles where the directions cannot be ordered consistently (singular), or the brushed smoothing weights',
  ).onChange(onDisplay);
  tip(display.add(params, 'dark').name('dark background'), 'Dark or light background').onChange(onDisplay);
  const brush = gui.addFolder('Smoothing brush (paper Fig. 6)');
  tip(
    brush.add(params, 'brush').name('paint (drag on surface)'),
    'Drag on the surface to paint how much smoothing each area gets (the smoothing weight): 0 turns it off there, 1 is normal',
  ).onChange(onBrush);
  tip(brush.add(params, 'brushRadius', 0.01, 0.5, 0.01).name('radius (of model size)'), 'Brush radius, as a fraction of the model’s size').onChange(onBrush);
  tip(
    brush.add(params, 'brushValue', 0, 3, 0.05).name('strength painted'),
    'Smoothing weight the brush paints: 0 none, 1 the normal amount, above 1 more',
  ).onChange(onBrush);
  tip(brush.add({ clear: onClearWeights }, 'clear').name('clear weights'), 'Forget the painted weights: every vertex smoothed normally again');
  brush.close();
  const exports = gui.addFolder('Export');
  tip(exports.add(params, 'exportSilhouette').name('SVG: silhouette'), 'Add the model’s outline to the SVG export');
  tip(exports.add(params, 'pngScale', PNG_SCALES).name('PNG resolution'), 'Size of the PNG export, as a multiple of the canvas');
  for (const [format, label] of Object.entries(EXPORTS))
    tip(exports.add({ [format]: () => onExport(format) }, format).name(label), `Download the ${EXPORT_TIPS[format]}`);
  exports.close(); // with it closed the panel fits a 1280×800 window without scrolling
  const camera = gui.addFolder('Camera');
  tip(
    camera.add(params, 'preset', VIEW_PRESETS).name('view from'),
    'Look at the model from the front, back, left, right, top, bottom or at an angle (iso), relative to its up axis',
  ).onChange(onCamera);
  tip(
    camera.add(params, 'upAxis', { 'Y up (glTF)': 'y', 'Z up (CAD, scans)': 'z' }).name('up axis'),
    'Which axis of the file points up: glTF says Y; many CAD and scanned models use Z (seen from the top with Y)',
  ).onChange(onCamera);
  camera.close();
  tip(gui.add({ fit: onFit }, 'fit').name('fit to view'), 'Frame the whole model in the part of the view the panels leave free');
  tip(gui.add({ open: onOpen }, 'open').name('open mesh…'), 'Open a mesh file: glTF/GLB (with its .bin), OBJ, PLY, STL or OFF');

  return {
    gui,
    /**
     * After a run: automatic parameters show the value the core used (stats
     * `threshold`, `presmoothStepsUsed`); an unbounded one gets a slider
     * range around it for a new mesh (`rescale`).
     */
    showUsed(stats, rescale) {
      for (const p of pipelineParameters(table)) {
        const used = stats[p.key] ?? stats[`${p.key}Used`];
        if (!p.automatic || typeof used !== 'number') continue;
        if (params[autoKey(p)]) params[p.key] = used;
      }
      for (const controller of unbounded) {
        const used = stats[controller.parameter.key];
        if (rescale && used > 0) controller.max(Math.max(1, Math.ceil(used * 4)));
      }
      gui.controllersRecursive().forEach((c) => c.updateDisplay());
    },
  };
}
