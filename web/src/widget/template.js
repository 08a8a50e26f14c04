// The element's shadow DOM: the canvas, the poster, the progress bar and the
// error line, with the CSS custom properties it reads.
import { LINE_COLORS } from '../three/colors.js';

const STYLES = `
  :host {
    display: inline-block;
    position: relative;
    width: 300px;
    height: 150px;
    overflow: hidden;
    contain: layout paint;
    background: var(--crestline-background, transparent);
  }
  :host([hidden]) { display: none; }
  canvas { display: block; width: 100%; height: 100%; touch-action: none; outline: none; }
  canvas:focus-visible { box-shadow: inset 0 0 0 2px var(--crestline-focus-color, #2f6fde); }
  img[part=poster] { position: absolute; inset: 0; width: 100%; height: 100%; object-fit: contain; pointer-events: none; }
  img[part=poster]:not([src]), img[part=poster][hidden] { display: none; }
  [part=progress] {
    position: absolute; left: 0; bottom: 0; height: var(--crestline-progress-height, 3px);
    width: 100%; transform-origin: left; transform: scaleX(0);
    background: var(--crestline-progress-color, #2f6fde); transition: transform 0.15s;
  }
  [part=progress][hidden] { display: none; }
  [part=error] {
    position: absolute; inset: auto 0 0 0; margin: 0; padding: 4px 8px;
    font: 12px/1.3 system-ui, sans-serif; color: var(--crestline-error-color, #8a1c12);
    background: rgba(255, 255, 255, 0.85);
  }
  [part=error]:empty { display: none; }
  @media (prefers-reduced-motion: reduce) { [part=progress] { transition: none; } }
`;

const MARKUP = `
<canvas part="canvas" role="img"></canvas>
<img part="poster" alt="" />
<div part="progress" role="progressbar" aria-valuemin="0" aria-valuemax="1" hidden></div>
<p part="error" role="alert"></p>
`;

let sheet = null; // one constructed sheet, shared by every viewer of the document

/**
 * Fills a viewer's shadow root. The styles go in as a constructed sheet: a
 * page whose Content-Security-Policy has no style-src 'unsafe-inline' refuses
 * an inline <style>, but not a sheet built through the CSSOM. Browsers
 * without constructed sheets (Safari before 16.4) get the <style>.
 */
export function fillShadowRoot(root) {
  root.innerHTML = MARKUP;
  if ('adoptedStyleSheets' in root && 'replaceSync' in CSSStyleSheet.prototype) {
    if (!sheet) {
      sheet = new CSSStyleSheet();
      sheet.replaceSync(STYLES);
    }
    root.adoptedStyleSheets = [sheet];
  } else {
    const style = document.createElement('style');
    style.textContent = STYLES;
    root.prepend(style);
  }
}

/** Display defaults; the CSS custom properties (--crestline-ridge-color, …) override them, attributes override both. */
export const DISPLAY_DEFAULTS = {
  'ridge-color': LINE_COLORS.ridge,
  'valley-color': LINE_COLORS.valley,
  'crease-color': LINE_COLORS.crease,
  'line-width': 2,
  background: 'transparent',
};
