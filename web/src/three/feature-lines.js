// FeatureLines: a three.js Object3D (wide LineSegments2 lines) with the
// ridges and valleys of a mesh, computed in the worker. Add it to the mesh
// (it draws in the mesh's own coordinates); update(options) re-runs only the
// stages the options change, and a threshold change only shows or hides
// lines (line-layer.js).
import { Group } from 'three';
import { meshArrays, pipelineOptions } from '../client/api.js';
import { LINE_COLORS } from './colors.js';

const DISPLAY = ['ridgeColor', 'valleyColor', 'lineWidth'];
import { LineLayer } from './line-layer.js';

const ORIGIN = [0, 0, 0];

export class FeatureLines extends Group {
  /**
   * `source`: a Mesh, a BufferGeometry or {positions, indices}; `options`:
   * the parameter table's keys plus ridgeColor, valleyColor, lineWidth (CSS
   * pixels). `ready` resolves with the first lines.
   */
  constructor(source, options = {}) {
    super();
    this.name = 'FeatureLines';
    const connection = FeatureLines.connection?.();
    if (!connection) throw new Error('FeatureLines: import it from "crestline" (its entry starts the worker).');
    const { ridgeColor = LINE_COLORS.ridge, valleyColor = LINE_COLORS.valley, lineWidth = 2.5 } = options;
    this.layer = new LineLayer({ ridgeColor, valleyColor, width: lineWidth });
    this.add(this.layer.group);
    this.options = pipelineOptions(options, DISPLAY);
    this.stats = null;
    this.ridgeCount = 0;
    this.valleyCount = 0;
    this.waiting = [];
    this.session = connection.session({
      onResult: (result) => this.show(result),
      onError: ({ message }) => this.settle(new Error(message)),
      onCancelled: () => this.settle(new Error('FeatureLines: cancelled.')),
    });
    this.ready = this.next();
    const geometry = source.isMesh ? source.geometry : source;
    this.session.load({ name: 'mesh', ...meshArrays(geometry) }, this.options);
  }

  /** A promise of the next result (or its error). */
  next() {
    return new Promise((resolve, reject) => this.waiting.push({ resolve, reject }));
  }

  /** @param {Error | null} error */
  settle(error) {
    for (const { resolve, reject } of this.waiting.splice(0)) error ? reject(error) : resolve(this);
    if (error) this.dispatchEvent({ type: 'error', message: error.message });
  }

  show({ lines, kept, linesChanged, stats }) {
    if (linesChanged) this.layer.setLines(lines, ORIGIN, kept);
    else this.layer.setKept(kept);
    this.stats = stats;
    this.ridgeCount = stats.ridges;
    this.valleyCount = stats.valleys;
    this.dispatchEvent({ type: 'change' });
    this.settle(null);
  }

  /** New options (merged with the current ones); resolves when the lines are shown. */
  update(options) {
    if (DISPLAY.some((k) => k in options)) {
      const { ridgeColor, valleyColor, lineWidth } = options;
      if (ridgeColor || valleyColor)
        this.layer.setColors(ridgeColor ?? this.layer.objects[0].material.color, valleyColor ?? this.layer.objects[1].material.color);
      if (lineWidth) this.layer.setWidth(lineWidth);
    }
    const pipeline = pipelineOptions(options, DISPLAY);
    if (!Object.keys(pipeline).length) return Promise.resolve(this);
    this.options = { ...this.options, ...pipeline };
    const done = this.next();
    this.session.setOptions(this.options);
    return done;
  }

  /**
   * Draws the lines through the points that keep them within a fifth of a
   * pixel of all their points in `camera`'s view, `height` pixels high:
   * far fewer segments for a large mesh seen whole. Call it before each
   * render; without it every point is drawn.
   */
  fitDetail(camera, height) {
    this.layer.fitDetail(camera, height);
  }

  /** Stops a running computation; the lines shown stay. */
  cancel() {
    this.session.cancel();
  }

  dispose() {
    this.session.dispose();
    this.layer.dispose();
    this.removeFromParent();
  }
}

/** Set by the package's entry: returns the Connection FeatureLines use. */
FeatureLines.connection = null;
