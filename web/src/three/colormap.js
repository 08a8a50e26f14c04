// Scalar field → vertex colours: a diverging blue–white–red map, symmetric
// around zero, scaled to the 95th percentile of |value| so a few extreme
// vertices do not wash everything out.
const BLUE = [0.13, 0.4, 0.75];
const WHITE = [0.93, 0.93, 0.93];
const RED = [0.78, 0.2, 0.17];

export function robustScale(values) {
  if (!values.length) return 1;
  const step = Math.max(1, Math.floor(values.length / 20000));
  const sample = [];
  for (let i = 0; i < values.length; i += step) if (Number.isFinite(values[i])) sample.push(Math.abs(values[i]));
  sample.sort((a, b) => a - b);
  return sample[Math.floor(0.95 * (sample.length - 1))] || 1;
}

/** Colours of `values`, saturated at ±`scale` (by default robustScale(values)); the page's colour scale shows the same scale. */
export function divergingColors(values, out = new Float32Array(values.length * 3), scale = robustScale(values)) {
  for (let i = 0; i < values.length; i++) divergingColor(values[i], scale, out, 3 * i);
  return out;
}

/** The colour of one value into out[offset…offset + 2]. */
export function divergingColor(value, scale, out, offset) {
  const t = Math.max(-1, Math.min(1, (value || 0) / scale));
  const to = t < 0 ? BLUE : RED;
  const a = Math.abs(t);
  for (let k = 0; k < 3; k++) out[offset + k] = WHITE[k] + (to[k] - WHITE[k]) * a;
}

/** The map as a CSS gradient from −1 (or 0 with `positive`) to +1, for a colour scale. */
export function colormapGradient(positive = false) {
  const css = (c) => `rgb(${c.map((x) => Math.round(255 * x)).join(' ')})`;
  return positive ? `linear-gradient(90deg, ${css(WHITE)}, ${css(RED)})` : `linear-gradient(90deg, ${css(BLUE)}, ${css(WHITE)}, ${css(RED)})`;
}
