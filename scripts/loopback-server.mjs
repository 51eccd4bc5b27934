// A web server on 127.0.0.1 (a free port) for the browser checkers (tests/texture/checkers:
// mtlx_render.mjs, godot_load.mjs), whose pages fetch their files (file:// cannot). `/` is the
// page; a path starting with one of `folders`' prefixes is looked up in that prefix's folder and
// never outside it (a `..` that climbs out is a 404); `files` name single files by path.
//   const { server, port } = await serve({ page, folders: { '/npm/': dir }, files: { '/x': path },
//                                         headers: { ... } });   // headers on every answer
import { createServer } from 'node:http';
import { existsSync, readFileSync, statSync } from 'node:fs';
import { extname, resolve, sep } from 'node:path';

const TYPES = {
  '.js': 'text/javascript', '.mjs': 'text/javascript', '.html': 'text/html', '.wasm': 'application/wasm',
  '.png': 'image/png', '.mtlx': 'application/xml', '.gltf': 'model/gltf+json',
};

export async function serve({ page, folders = {}, files = {}, headers = {} }) {
  const server = createServer((req, res) => {
    const url = decodeURIComponent(req.url.split('?')[0]);
    if (url === '/') {
      res.writeHead(200, { ...headers, 'content-type': 'text/html' });
      return res.end(page);
    }
    let file = files[url] ?? null;
    for (const [prefix, dir] of Object.entries(folders)) {
      if (file || !url.startsWith(prefix)) continue;
      const base = resolve(dir), candidate = resolve(base, '.' + sep + url.slice(prefix.length));
      if (candidate.startsWith(base + sep)) file = candidate;
    }
    if (!file || !existsSync(file) || !statSync(file).isFile()) {
      res.writeHead(404, headers);
      return res.end();
    }
    res.writeHead(200, { ...headers, 'content-type': TYPES[extname(file)] || 'application/octet-stream' });
    res.end(readFileSync(file));
  });
  await new Promise((r) => server.listen(0, '127.0.0.1', r));
  return { server, port: server.address().port };
}
