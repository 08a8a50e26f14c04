// The widget's entry (built to web/dist/crestline-viewer.js): defines
// <crestline-viewer> once, even when the script is included twice.
import { CrestlineViewer } from './element.js';

if (!customElements.get('crestline-viewer')) customElements.define('crestline-viewer', CrestlineViewer);

export { CrestlineViewer };
