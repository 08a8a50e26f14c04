// Writes the built-in sample mesh (npm `bunny`, public domain) as OBJ.
import { writeFileSync } from 'node:fs';
import { createRequire } from 'node:module';

const require = createRequire(import.meta.url);
const bunny = require('bunny');
const out = process.argv[2] ?? 'bunny.obj';
const lines = ['# Stanford bunny from the npm package "bunny" (public domain)'];
for (const [x, y, z] of bunny.positions) lines.push(`v ${x} ${y} ${z}`);
for (const [a, b, c] of bunny.cells) lines.push(`f ${a + 1} ${b + 1} ${c + 1}`);
writeFileSync(out, lines.join('\n') + '\n');
