// @ts-check
/**
 * Default line colours of the page, the widget and their exports, defined
 * once; the crease colour is the core writers' kCreaseColor (io/write_lines.h).
 */
export const LINE_COLORS = Object.freeze({ ridge: '#d62d20', valley: '#1f5fbf', crease: '#e08a00' });
