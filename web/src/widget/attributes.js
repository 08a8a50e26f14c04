// The element's attributes, each reflected as a camelCase property, in the
// style of <model-viewer>. `parse` turns the attribute text (or null when
// absent) into the property value; `unparse` the other way. The pipeline's
// parameters are not here: they come from the core's table
// (defineParameterProperties, ../client/parameters.js).
import { ATTRIBUTE_ALIASES, attributeName, parseParameter, pipelineParameters } from '../client/parameters.js';

const number = (fallback) => ({
  parse: (text) => (text === null || text.trim() === '' || !Number.isFinite(Number(text)) ? fallback : Number(text)),
  unparse: String,
});
const text = (fallback) => ({ parse: (t) => t ?? fallback, unparse: String });
const shown = { parse: (t) => t === null || t.trim().toLowerCase() !== 'false', unparse: String };
const presence = { parse: (t) => t !== null, unparse: (v) => (v ? '' : null) };
const oneOf = (values) => ({
  parse: (t) => (values.includes(t?.toLowerCase()) ? t.toLowerCase() : values[0]),
  unparse: String,
});

/** attribute → {property, parse, unparse, kind}; kind says what a change re-does. */
export const ATTRIBUTES = {
  src: { ...text(''), kind: 'source' },
  alt: { ...text(''), kind: 'label' },
  ridges: { ...shown, kind: 'display' },
  valleys: { ...shown, kind: 'display' },
  creases: { ...shown, kind: 'display' },
  'ridge-color': { ...text(null), kind: 'display' },
  'valley-color': { ...text(null), kind: 'display' },
  'crease-color': { ...text(null), kind: 'display' },
  'line-width': { ...number(null), kind: 'display' },
  background: { ...text(null), kind: 'display' },
  'camera-orbit': { ...text('0deg 75deg 100%'), kind: 'orbit' },
  'up-axis': { ...oneOf(['y', 'z']), kind: 'orbit' },
  'auto-rotate': { ...presence, kind: 'motion' },
  interaction: { ...oneOf(['orbit', 'none']), kind: 'interaction' },
  loading: { ...oneOf(['eager', 'lazy']), kind: 'loading' },
  poster: { ...text(''), kind: 'poster' },
};

export const propertyName = (attribute) => attribute.replace(/-(\w)/g, (_, c) => c.toUpperCase());

/** Defines the reflecting properties on `klass.prototype`. */
export function reflectAttributes(klass) {
  for (const [attribute, { parse, unparse }] of Object.entries(ATTRIBUTES)) {
    Object.defineProperty(klass.prototype, propertyName(attribute), {
      get() {
        return parse(this.getAttribute(attribute));
      },
      set(value) {
        const text = value === null || value === undefined ? null : unparse(value);
        if (text === null) this.removeAttribute(attribute);
        else this.setAttribute(attribute, text);
      },
      configurable: true,
    });
  }
}

/**
 * One attribute and property per pipeline parameter of the table: the
 * attribute is the CLI flag ("smoothing-steps"), the property the table's
 * key ("smoothingSteps"); the older names `smoothing` and `fairing` stay as
 * aliases. A property reads the attribute's value, or the core's default
 * when it is absent or invalid. Returns the attribute names.
 * @param {Function} klass
 * @param {import('../client/parameters.js').Parameter[]} table
 */
export function defineParameterProperties(klass, table) {
  const byAttribute = new Map(pipelineParameters(table).map((p) => [attributeName(p), p]));
  const names = [...byAttribute.keys(), ...Object.keys(ATTRIBUTE_ALIASES)];
  for (const name of names) {
    const attribute = ATTRIBUTE_ALIASES[name] ?? name;
    const p = byAttribute.get(attribute);
    const property = attribute === name ? p.key : name;
    Object.defineProperty(klass.prototype, property, {
      get() {
        return parameterValue(this, p) ?? p.default;
      },
      set(value) {
        if (value === null || value === undefined) this.removeAttribute(name);
        else this.setAttribute(name, String(value));
      },
      configurable: true,
    });
  }
  return names;
}

/**
 * A parameter's value from the element's attributes (its own name first,
 * then an alias), or undefined.
 * @param {Element} element
 * @param {import('../client/parameters.js').Parameter} p
 */
export function parameterValue(element, p) {
  const own = attributeName(p);
  const alias = Object.keys(ATTRIBUTE_ALIASES).find((a) => ATTRIBUTE_ALIASES[a] === own);
  return parseParameter(p, element.getAttribute(own)) ?? (alias ? parseParameter(p, element.getAttribute(alias)) : undefined);
}

/** The properties defineParameterProperties made, for upgradeProperties. */
export const parameterProperties = (table) => [...pipelineParameters(table).map((p) => p.key), ...Object.keys(ATTRIBUTE_ALIASES)];

/**
 * Properties set on the element before its definition loaded are own
 * properties that hide the accessors: pass them through the setters.
 */
export function upgradeProperties(element, names = Object.keys(ATTRIBUTES).map(propertyName)) {
  for (const name of names) {
    if (!Object.prototype.hasOwnProperty.call(element, name)) continue;
    const value = element[name];
    delete element[name];
    element[name] = value;
  }
}

const ANGLE = /^(-?[\d.]+)(deg|rad)?$/;

/**
 * camera-orbit "θ φ r" as in <model-viewer>: azimuth and polar angle (deg or
 * rad, degrees when unitless) and distance as a percentage of the framing
 * distance ("auto" = 100%). Missing or bad parts keep the default.
 */
export function parseOrbit(text) {
  const [theta, phi, radius] = (text ?? '').trim().split(/\s+/);
  const angle = (part, fallback) => {
    const m = ANGLE.exec(part ?? '');
    if (!m || !Number.isFinite(Number(m[1]))) return fallback;
    return m[2] === 'rad' ? Number(m[1]) : (Number(m[1]) * Math.PI) / 180;
  };
  const r = /^([\d.]+)%$/.exec(radius ?? '');
  return {
    theta: angle(theta, 0),
    phi: Math.min(Math.PI - 1e-3, Math.max(1e-3, angle(phi, (75 * Math.PI) / 180))),
    radius: r && Number(r[1]) > 0 ? Number(r[1]) / 100 : 1,
  };
}
