// Drives headless Chromium (Debian's /usr/bin/chromium, WebGL2 on SwiftShader) through
// playwright-core: renders every scene of WORK/scenes.json with three.js and Filament
// (web/render.js) and writes WORK/out/web/<scene>__<renderer>.f32 (RGB float32, rows top to
// bottom, common.size^2) plus WORK/out/web/info.json (versions, timings).
// usage: node render_web.mjs WORK NODE_MODULES [renderer...]
import { createServer } from 'node:http';
import { readFileSync, writeFileSync, mkdirSync, existsSync, statSync } from 'node:fs';
import { join, dirname, extname, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';

const [work, nodeModules, ...which] = process.argv.slice(2);
if (!work || !nodeModules) { console.error('usage: node render_web.mjs WORK NODE_MODULES [three|filament ...]'); process.exit(2); }
const renderers = which.length ? which : ['three', 'filament'];
const here = dirname(fileURLToPath(import.meta.url));
const { chromium } = await import(join(resolve(nodeModules), 'playwright-core', 'index.mjs'));

const roots = { '/work/': resolve(work), '/three/': join(resolve(nodeModules), 'three'),
                '/filament/': join(resolve(nodeModules), 'filament'), '/page/': join(here, 'web') };
const types = { '.html': 'text/html', '.js': 'text/javascript', '.mjs': 'text/javascript', '.json': 'application/json',
                 '.wasm': 'application/wasm', '.png': 'image/png' };
const server = createServer((req, res) => {
  const url = decodeURIComponent(req.url.split('?')[0]);
  if (url === '/favicon.ico') { res.writeHead(204); res.end(); return; }
  let file = null;
  for (const [p, dir] of Object.entries(roots)) if (url.startsWith(p)) file = join(dir, url.slice(p.length));
  if (url.startsWith('/filament.wasm')) file = join(roots['/filament/'], 'filament.wasm');
  if (!file || !existsSync(file) || !statSync(file).isFile()) { res.writeHead(404); res.end(); return; }
  res.writeHead(200, { 'Content-Type': types[extname(file)] || 'application/octet-stream' });
  res.end(readFileSync(file));
});
await new Promise((ok) => server.listen(0, '127.0.0.1', ok));
const base = `http://127.0.0.1:${server.address().port}`;

const browser = await chromium.launch({
  executablePath: '/usr/bin/chromium', headless: true,
  args: ['--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--ignore-gpu-blocklist'],
});
const doc = JSON.parse(readFileSync(join(work, 'scenes.json'), 'utf8'));
const outDir = join(work, 'out', 'web');
mkdirSync(outDir, { recursive: true });
const info = {};
let failed = 0;
for (const r of renderers) {
  for (const sc of doc.scenes) {
    const page = await browser.newPage();
    const logs = [];
    page.on('console', (m) => logs.push(`${m.type()}: ${m.text()}`));
    page.on('pageerror', (e) => logs.push(`pageerror: ${e.message}`));
    const t0 = Date.now();
    await page.goto(`${base}/page/render.html?renderer=${r}&scene=${sc.name}`);
    await page.waitForFunction(() => window.__result !== undefined, null, { timeout: 300000 });
    const res = await page.evaluate(() => window.__result);
    await page.close();
    if (!res.ok) { console.error(`${r} ${sc.name}: ${res.error}\n${logs.join('\n')}`); failed++; continue; }
    writeFileSync(join(outDir, `${sc.name}__${r}.f32`), Buffer.from(res.data, 'base64'));
    info[`${sc.name}__${r}`] = { info: res.info, render_ms: Math.round(res.ms), page_ms: Date.now() - t0,
                                 warnings: logs.filter((l) => !l.startsWith('log:') && !l.startsWith('debug:')).slice(0, 5) };
    console.log(`${r} ${sc.name}: ${res.info}, ${Math.round(res.ms)} ms`);
  }
}
writeFileSync(join(outDir, 'info.json'), JSON.stringify(info, null, 1));
await browser.close();
server.close();
process.exit(failed ? 1 : 0);
