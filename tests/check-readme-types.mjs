// Type-checks the README's JavaScript example as TypeScript against the
// package's own types (web/types/crestline.d.ts, found through package.json
// "exports" from inside the package). Run by tests/run-lint.sh.
import { execFileSync } from 'node:child_process';
import { mkdirSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { ROOT } from './node/helpers.mjs';
import { readmeExample } from './node/readme-example.mjs';

const dir = join(ROOT, 'test-results', 'readme-types');
mkdirSync(dir, { recursive: true });
writeFileSync(join(dir, 'example.ts'), readmeExample());
const compilerOptions = {
  strict: true,
  noEmit: true,
  target: 'es2022',
  module: 'esnext',
  moduleResolution: 'bundler',
  lib: ['es2022', 'dom'],
  types: [],
  skipLibCheck: true,
};
writeFileSync(join(dir, 'tsconfig.json'), JSON.stringify({ compilerOptions, include: ['example.ts'] }, null, 2));
execFileSync(join(ROOT, 'node_modules/.bin/tsc'), ['-p', dir], { stdio: 'inherit' });
console.log('lint: the README example type-checks against web/types/crestline.d.ts');
