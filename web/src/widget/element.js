// <crestline-viewer>: a mesh and its ridges and valleys, computed client-side
// in the page's one worker (../client) and drawn by its one WebGL context.
import { sharedConnection } from '../client/browser.js';
import { overallFraction, selectLines } from '../client/client.js';
import { pipelineParameters } from '../client/parameters.js';
import { ATTRIBUTES, defineParameterProperties, parameterProperties, parameterValue, parseOrbit, reflectAttributes, upgradeProperties } from './attributes.js';
import { linesSummary, renderPng, svgView } from '../three/exports.js';
import { concaveShade } from '../three/line-layer.js';
import { DISPLAY_DEFAULTS, fillShadowRoot } from './template.js';
import { WidgetView } from '../three/widget-view.js';

const reducedMotion = globalThis.matchMedia?.('(prefers-reduced-motion: reduce)');

/** The file name messages use: the URL's last path segment ("model" for data: and blob:). @param {URL} url */
function nameOf(url) {
  if (url.protocol === 'data:' || url.protocol === 'blob:') return 'model';
  return decodeURIComponent(url.pathname.split('/').pop() || url.hostname);
}

/** The core's parameter table, asked once per page; its properties are defined when it arrives. */
let table = null;
let tableArrived = null;
let parameterAttributes = new Set();
function parameterTable() {
  tableArrived ??= sharedConnection()
    .describe()
    .then((t) => {
      table = t;
      parameterAttributes = new Set(defineParameterProperties(CrestlineViewer, t));
    });
  return tableArrived;
}

export class CrestlineViewer extends HTMLElement {
  /** The core's parameter table once it arrived (null before): the pipeline's attributes. */
  static get parameters() {
    return table;
  }

  static get observedAttributes() {
    return Object.keys(ATTRIBUTES);
  }

  constructor() {
    super();
    fillShadowRoot(this.attachShadow({ mode: 'open' }));
    const $ = (part) => this.shadowRoot.querySelector(`[part=${part}]`);
    this.parts = { canvas: $('canvas'), poster: $('poster'), progress: $('progress'), error: $('error') };
    this.view = new WidgetView(this.parts.canvas);
    this.session = null;
    this.loadedSrc = null; // the src whose mesh the worker holds (or is loading)
    this.result = null; // {lines: every faired line, kept}
    this.selected = null; // the kept lines as Lines, made on first use
    this.stats = null;
    this.near = false; // within the lazy-loading margin of the viewport
    this.changes = new Set();
    this.parts.canvas.addEventListener('keydown', (event) => {
      if (this.view.handleKey(event.key)) event.preventDefault();
    });
    reducedMotion?.addEventListener?.('change', () => this.queue('motion'));
  }

  connectedCallback() {
    clearTimeout(this.releaseTimer);
    upgradeProperties(this);
    this.resizeObserver = new ResizeObserver(([entry]) => {
      const { width, height } = entry.contentRect;
      this.view.resize(width, height, Math.min(globalThis.devicePixelRatio || 1, 2));
    });
    this.resizeObserver.observe(this);
    // Drawn only while on screen; lazy loading starts a screen ahead.
    this.onScreen = new IntersectionObserver(([entry]) => {
      this.view.visible = entry.isIntersecting;
      if (entry.isIntersecting) this.view.draw();
    });
    this.onScreen.observe(this);
    this.nearScreen = new IntersectionObserver(
      ([entry]) => {
        this.near = entry.isIntersecting;
        if (this.near) this.queue('loading');
      },
      { rootMargin: '100%' },
    );
    this.nearScreen.observe(this);
    // The pipeline's attributes are the table's: watched here, not in observedAttributes.
    this.parameterObserver = new MutationObserver((records) => {
      if (records.some((r) => parameterAttributes.has(r.attributeName))) this.queue('pipeline');
    });
    this.parameterObserver.observe(this, { attributes: true });
    parameterTable().then(
      () => {
        upgradeProperties(this, parameterProperties(table));
        this.queue('source'); // a load waits for the table
      },
      (error) => this.fail(error.message), // the engine cannot start here (no WASM SIMD, say)
    );
    for (const kind of ['label', 'display', 'orbit', 'motion', 'interaction', 'poster', 'source']) this.queue(kind);
  }

  disconnectedCallback() {
    this.resizeObserver.disconnect();
    this.onScreen.disconnect();
    this.nearScreen.disconnect();
    this.parameterObserver.disconnect();
    this.view.visible = false;
    // Moved elements come back at once; removed ones free their worker session.
    this.releaseTimer = setTimeout(() => this.release(), 0);
  }

  attributeChangedCallback(name, previous, value) {
    if (previous !== value) this.queue(ATTRIBUTES[name].kind);
  }

  /** Changes are applied together, once per task. */
  queue(kind) {
    if (!this.changes.size) queueMicrotask(() => this.applyChanges());
    this.changes.add(kind);
  }

  applyChanges() {
    const changes = this.changes;
    this.changes = new Set();
    if (!this.isConnected) return;
    const canvas = this.parts.canvas;
    if (changes.has('label')) canvas.setAttribute('aria-label', this.alt || 'A 3D model with its ridge and valley lines');
    if (changes.has('display')) this.applyDisplay();
    if (changes.has('orbit')) this.view.setOrbit(parseOrbit(this.cameraOrbit), this.upAxis);
    if (changes.has('motion')) this.view.setAutoRotate(this.autoRotate && !reducedMotion?.matches);
    if (changes.has('interaction')) {
      const orbit = this.interaction === 'orbit';
      this.view.setInteractive(orbit);
      if (orbit) canvas.tabIndex = 0;
      else canvas.removeAttribute('tabindex');
      canvas.setAttribute('aria-roledescription', orbit ? '3D view: arrow keys turn the model, + and - zoom' : '3D view');
    }
    if (changes.has('poster')) {
      if (this.poster) this.parts.poster.src = new URL(this.poster, document.baseURI).href;
      else this.parts.poster.removeAttribute('src');
    }
    // A load sends the current parameters along; otherwise a change re-runs.
    const started = (changes.has('source') || changes.has('loading')) && this.maybeLoad();
    if (changes.has('pipeline') && !started) this.compute();
  }

  /** Colours and widths: attribute, else CSS custom property, else default. */
  displayStyle() {
    const css = getComputedStyle(this);
    const value = (attribute) => this.getAttribute(attribute) ?? (css.getPropertyValue(`--crestline-${attribute}`).trim() || DISPLAY_DEFAULTS[attribute]);
    return {
      ridges: this.ridges,
      valleys: this.valleys,
      creases: this.creases,
      ridgeColor: value('ridge-color'),
      valleyColor: value('valley-color'),
      creaseColor: value('crease-color'),
      lineWidth: Number(value('line-width')) || DISPLAY_DEFAULTS['line-width'],
      background: value('background'),
    };
  }

  applyDisplay() {
    const style = this.displayStyle();
    this.view.lines.setShown(style.ridges, style.valleys);
    this.view.lines.setColors(style.ridgeColor, style.valleyColor);
    this.view.lines.setWidth(style.lineWidth);
    // Convex creases in the crease colour, concave ones in its darker shade.
    this.view.creases.setShown(style.creases, style.creases);
    this.view.creases.setColors(style.creaseColor, concaveShade(style.creaseColor));
    this.view.creases.setWidth(style.lineWidth);
    this.view.setBackground(style.background);
  }

  /** Every pipeline parameter: its attribute's value, else the core's default (a removed attribute resets it). */
  pipelineOptions() {
    return Object.fromEntries(pipelineParameters(table).map((p) => [p.key, parameterValue(this, p) ?? p.default]));
  }

  /** Starts loading `src` unless it is loaded or lazy and far away; true when it started. */
  maybeLoad() {
    if (!table || !this.src || this.src === this.loadedSrc) return false;
    if (this.loading === 'lazy' && !this.near) return false;
    this.load(this.src);
    return true;
  }

  /** Sends the mesh's URL to the worker, which fetches and reads it and runs the pipeline. */
  load(src) {
    this.loadedSrc = src;
    this.result = null;
    this.selected = null;
    this.shownLoad = false;
    this.showError('');
    this.parts.poster.hidden = false;
    this.meshName = fileName(src);
    let url;
    try {
      url = new URL(src, document.baseURI).href;
    } catch {
      this.fail(`${src}: is not a valid URL.`);
      return;
    }
    this.session ??= sharedConnection().session({
      onProgress: (stage, fraction) => this.progress(stage, overallFraction(stage, fraction)),
      onResult: (result) => this.showResult(result),
      onCancelled: () => {
        this.progress(null);
        this.dispatchEvent(new CustomEvent('cancel'));
      },
      onError: ({ message }) => this.fail(message),
    });
    this.progress('fetch', 0);
    this.session.openUrl(url, this.meshName, this.pipelineOptions());
  }

  /** A parameter changed: the client runs the latest parameters once the running job is done. */
  compute() {
    if (table) this.session?.setOptions(this.pipelineOptions());
  }

  /** Stops the running computation ('cancel' event); the lines shown stay. */
  cancel() {
    this.session?.cancel();
  }

  /** The lines shown (those passing the filter), as Lines; null before the first result. */
  get lines() {
    if (!this.result) return null;
    this.selected ??= selectLines(this.result.lines, this.result.kept);
    return this.selected;
  }

  showResult({ surface, lines, kept, creases, stats }) {
    if (surface) this.view.setSurface(surface);
    const drawn = this.result;
    this.result = { lines, kept, creases };
    this.selected = null;
    this.stats = stats;
    this.applyDisplay();
    // A threshold change shows other lines of the same geometry; lines not
    // drawn yet (new, or a run that finished after a cancel) are drawn.
    if (surface || lines !== drawn?.lines) this.view.setLines(lines, kept);
    else this.view.setKept(kept);
    if (creases && (surface || creases !== drawn?.creases)) this.view.setCreases(creases);
    this.progress(null);
    if (!this.shownLoad) {
      this.shownLoad = true;
      this.parts.poster.hidden = true;
      this.dispatchEvent(new CustomEvent('load', { detail: { src: this.loadedSrc } }));
    }
    this.dispatchEvent(new CustomEvent('lines', { detail: linesSummary(lines, kept, stats) }));
  }

  progress(stage, fraction) {
    const bar = this.parts.progress;
    bar.hidden = stage === null;
    this.parts.canvas.setAttribute('aria-busy', String(stage !== null));
    if (stage === null) return;
    bar.style.transform = `scaleX(${fraction})`;
    bar.setAttribute('aria-valuenow', fraction.toFixed(2));
    this.dispatchEvent(new CustomEvent('progress', { detail: { stage, fraction } }));
  }

  showError(message) {
    this.parts.error.textContent = message;
  }

  fail(message) {
    this.progress(null);
    this.showError(message);
    this.dispatchEvent(new CustomEvent('error', { detail: { message } }));
  }

  release() {
    if (this.isConnected) return;
    this.session?.dispose();
    this.session = null;
    this.loadedSrc = null;
    this.result = null;
    this.selected = null;
    this.view.dispose();
    this.view = new WidgetView(this.parts.canvas);
  }

  requireLines() {
    if (!this.result) throw new Error('crestline-viewer: no lines yet (wait for the "lines" event).');
  }

  /**
   * SVG text of the lines shown in the current view, the parts hidden by the
   * surface removed, sized like the element. {silhouette: true or a colour}
   * adds the surface's outline.
   */
  async toSVG({ silhouette = false } = {}) {
    this.requireLines();
    const { width, height } = this.getBoundingClientRect();
    const css = getComputedStyle(this).getPropertyValue('--crestline-silhouette-color').trim();
    const style = { ...this.displayStyle(), silhouette: silhouette === true ? css || '#3a3a3a' : silhouette || null };
    return /** @type {Promise<string>} */ (
      this.session.exportFile('svg', svgView(this.view, style, Math.max(1, Math.round(width)), Math.max(1, Math.round(height))))
    );
  }

  /** PNG of the current view; {width, height} in pixels (default: the element's size × devicePixelRatio). */
  async toPNG(options = {}) {
    this.requireLines();
    const { width, height } = this.getBoundingClientRect();
    return renderPng(this.view, { cssWidth: width, cssHeight: height, ...options });
  }

  /** GLB Blob by the CLI's writer: the surface and the shown lines (nodes "surface", "ridges", "valleys", "creases"). */
  async toGLB() {
    this.requireLines();
    const { ridges, valleys, creases } = this.displayStyle();
    return new Blob([await this.session.exportFile('glb', { ridges, valleys, creases })], { type: 'model/gltf-binary' });
  }

  /** The lines as OBJ polylines, creases included (the CLI's format). */
  async toOBJ() {
    this.requireLines();
    return this.session.exportText('obj');
  }

  /** The lines, creases and stats as JSON text (the CLI's format). */
  async toJSON() {
    this.requireLines();
    return this.session.exportText('json');
  }
}

function fileName(src) {
  try {
    return nameOf(new URL(src, document.baseURI));
  } catch {
    return src;
  }
}

reflectAttributes(CrestlineViewer);
