// A static file server for specs that host their own page: routes map URL
// prefixes to directories (or to in-memory files), on a free port.
import { readFile, stat } from 'node:fs/promises';
import { createServer } from 'node:http';
import { extname, join, normalize } from 'node:path';

const TYPES = {
  '.html': 'text/html; charset=utf-8',
  '.js': 'text/javascript; charset=utf-8',
  '.mjs': 'text/javascript; charset=utf-8',
  '.css': 'text/css; charset=utf-8',
  '.wasm': 'application/wasm',
  '.json': 'application/json',
  '.webmanifest': 'application/manifest+json',
  '.svg': 'image/svg+xml',
  '.stl': 'model/stl',
};

/**
 * Serves `files` ({ '/path': Buffer|string }) and `dirs` ({ '/prefix/': dir })
 * on 127.0.0.1; resolves with { url, port, close() }.
 */
export function serveStatic({ files = {}, dirs = {} }) {
  const server = createServer(async (req, res) => {
    const path = decodeURIComponent(new URL(req.url, 'http://x').pathname);
    try {
      let body = files[path];
      let type = TYPES[path.endsWith('/') ? '.html' : extname(path)] ?? 'application/octet-stream';
      if (body === undefined) {
        const prefix = Object.keys(dirs).find((p) => path.startsWith(p));
        if (!prefix) throw new Error('not found');
        const file = normalize(join(dirs[prefix], path.slice(prefix.length)));
        if (!file.startsWith(normalize(dirs[prefix]))) throw new Error('outside');
        if (!(await stat(file)).isFile()) throw new Error('not a file');
        body = await readFile(file);
        type = TYPES[extname(file)] ?? type;
      }
      res.writeHead(200, { 'content-type': type });
      res.end(body);
    } catch {
      res.writeHead(404, { 'content-type': 'text/plain' });
      res.end('not found');
    }
  });
  return new Promise((resolve) => {
    server.listen(0, '127.0.0.1', () => {
      const { port } = server.address();
      resolve({ url: `http://127.0.0.1:${port}/`, port, close: () => new Promise((r) => server.close(r)) });
    });
  });
}
