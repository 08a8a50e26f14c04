// The parameters panel (lil-gui). Pipeline parameters call onCompute;
// display parameters call onDisplay. Both receive the whole params object.
import GUI from 'lil-gui';

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

export function defaultParams() {
  return {
    smoothingSteps: 3,
    autoThreshold: true,
    threshold: 1,
    hausdorffBound: 0.25,
    autoPresmooth: true,
    presmoothSteps: 3,
    showRidges: true,
    showValleys: true,
    lineWidth: 2.5,
    ridgeColor: '#d62d20',
    valleyColor: '#1f5fbf',
    dark: false,
    view: 'shaded',
    brush: false,
    brushRadius: 0.08,
    brushValue: 0,
    pngScale: 2,
    exportSilhouette: false,
  };
}

/** The options the worker passes to Session.setOptions. */
export function pipelineOptions(params) {
  return {
    smoothingSteps: params.smoothingSteps,
    presmoothSteps: params.autoPresmooth ? 'auto' : params.presmoothSteps,
    hausdorffBound: params.hausdorffBound,
    threshold: params.autoThreshold ? 'auto' : params.threshold,
  };
}

/** PNG resolutions offered: multiples of the canvas's CSS size. */
export const PNG_SCALES = { '1× canvas': 1, '2× canvas': 2, '4× canvas': 4 };

/** Export buttons: format → label. */
export const EXPORTS = { svg: 'SVG (visible lines)', png: 'PNG', obj: 'OBJ (polylines)', json: 'JSON (lines + stats)', glb: 'GLB (mesh + lines)' };

export function createGui(params, { onCompute, onDisplay, onFit, onOpen, onBrush, onClearWeights, onExport }) {
  const gui = new GUI({ title: 'Crestline' });
  const lines = gui.addFolder('Feature lines');
  lines.add(params, 'smoothingSteps', 0, 10, 1).name('smoothing steps').onFinishChange(onCompute);
  lines.add(params, 'autoThreshold').name('automatic threshold').onChange(onCompute);
  const threshold = lines.add(params, 'threshold', 0, 10, 0.01).name('threshold ∫|κ|ds').onChange(() => {
    params.autoThreshold = false;
    gui.controllersRecursive().forEach((c) => c.updateDisplay());
    onCompute();
  });
  lines.add(params, 'hausdorffBound', 0, 1, 0.01).name('fairing bound (edges)').onFinishChange(onCompute);
  lines.add(params, 'autoPresmooth').name('automatic pre-smoothing').onChange(onCompute);
  lines.add(params, 'presmoothSteps', 0, 10, 1).name('pre-smoothing steps').onFinishChange(() => {
    params.autoPresmooth = false;
    gui.controllersRecursive().forEach((c) => c.updateDisplay());
    onCompute();
  });
  const display = gui.addFolder('Display');
  display.add(params, 'showRidges').name('ridges').onChange(onDisplay);
  display.add(params, 'showValleys').name('valleys').onChange(onDisplay);
  display.add(params, 'lineWidth', 0.5, 8, 0.1).name('line width (px)').onChange(onDisplay);
  display.addColor(params, 'ridgeColor').name('ridge colour').onChange(onDisplay);
  display.addColor(params, 'valleyColor').name('valley colour').onChange(onDisplay);
  display.add(params, 'view', VIEWS).name('surface').onChange(onDisplay);
  display.add(params, 'dark').name('dark background').onChange(onDisplay);
  const brush = gui.addFolder('Smoothing brush (paper Fig. 6)');
  brush.add(params, 'brush').name('paint (drag on surface)').onChange(onBrush);
  brush.add(params, 'brushRadius', 0.01, 0.5, 0.01).name('radius (of model size)').onChange(onBrush);
  brush.add(params, 'brushValue', 0, 3, 0.05).name('strength painted').onChange(onBrush);
  brush.add({ clear: onClearWeights }, 'clear').name('clear weights');
  brush.close();
  const exports = gui.addFolder('Export');
  exports.add(params, 'exportSilhouette').name('SVG: silhouette');
  exports.add(params, 'pngScale', PNG_SCALES).name('PNG resolution');
  for (const [format, label] of Object.entries(EXPORTS)) exports.add({ [format]: () => onExport(format) }, format).name(label);
  gui.add({ fit: onFit }, 'fit').name('fit to view');
  gui.add({ open: onOpen }, 'open').name('open mesh…');

  return {
    gui,
    /** After a run with the automatic threshold: show the value used, and a useful slider range. */
    showThreshold(value, rescale) {
      if (rescale && value > 0) threshold.max(Math.max(1, Math.ceil(value * 4)));
      if (params.autoThreshold) params.threshold = value;
      threshold.updateDisplay();
    },
  };
}
