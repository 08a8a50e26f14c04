// A tiny static server for the browser tests: web/dist at /, the shared test
// meshes at /meshes/, with the cross-origin isolation headers of vite preview.
import { createServer } from 'node:http';
import { readFile } from 'node:fs/promises';
import { extname, join, normalize } from 'node:path';

const TYPES = {
  '.html': 'text/html',
  '.js': 'text/javascript',
  '.mjs': 'text/javascript',
  '.css': 'text/css',
  '.wasm': 'application/wasm',
  '.json': 'application/json',
};

/** `headers` (optional) are added to every response; a null value drops a default header. */
export function serve(roots, headers = {}) {
  const server = createServer(async (req, res) => {
    const path = decodeURIComponent(new URL(req.url, 'http://x').pathname);
    const [prefix, root] = Object.entries(roots).find(([p]) => path.startsWith(p)) ?? [];
    const relative = normalize(path.slice(prefix?.length ?? 0) || 'index.html').replace(/^(\.\.[/\\])+/, '');
    try {
      const body = await readFile(join(root, relative.endsWith('/') ? `${relative}index.html` : relative));
      const head = {
        'Content-Type': TYPES[extname(relative)] ?? 'application/octet-stream',
        'Cross-Origin-Opener-Policy': 'same-origin',
        'Cross-Origin-Embedder-Policy': 'require-corp',
        'Cross-Origin-Resource-Policy': 'same-origin',
        ...headers,
      };
      for (const [name, value] of Object.entries(head)) if (value === null) delete head[name];
      res.writeHead(200, head);
      res.end(body);
    } catch {
      res.writeHead(404).end('not found');
    }
  });
  return new Promise((resolve) => server.listen(0, '127.0.0.1', () => resolve(server)));
}
