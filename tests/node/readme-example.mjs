// The README's JavaScript example, for the tests that run it as written
// (tests/node/api.test.mjs, tests/browser/api.test.mjs).
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { join } from 'node:path';
import { ROOT } from './helpers.mjs';

/** The first ```js block of the README's "JavaScript API" section. */
export function readmeExample() {
  const readme = readFileSync(join(ROOT, 'README.md'), 'utf8');
  const section = readme.slice(readme.indexOf('## JavaScript API'));
  const match = /```js\n([\s\S]*?)```/.exec(section);
  assert.ok(match, 'README.md has a ```js example under "## JavaScript API"');
  return match[1];
}
