// A Markdown table of the benchmark's rows (first row: the header), the
// first column left-aligned and the others right-aligned, as README shows them.
export function table(rows) {
  const widths = rows[0].map((_, c) => Math.max(...rows.map((r) => String(r[c]).length)));
  const line = (r) => `| ${r.map((cell, c) => (c ? String(cell).padStart(widths[c]) : String(cell).padEnd(widths[c]))).join(' | ')} |`;
  const rule = `|${widths.map((w, c) => (c ? '-'.repeat(w + 1) + ':' : ':' + '-'.repeat(w + 1))).join('|')}|`;
  return [line(rows[0]), rule, ...rows.slice(1).map(line)].join('\n');
}

/** The median of the finite numbers of a list (the mean of the middle two for an even count; NaN if none). */
export const median = (values) => {
  const s = values.filter(Number.isFinite).sort((a, b) => a - b);
  const n = s.length;
  if (!n) return NaN;
  return n % 2 ? s[(n - 1) / 2] : 0.5 * (s[n / 2 - 1] + s[n / 2]);
};
