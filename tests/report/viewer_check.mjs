#!/usr/bin/env node
// Opens the interactive views of a `matforge report --viewer` page in headless Chromium (WebGL2
// on SwiftShader), from disk, as a reader does: each named material's card, its button clicked,
// the first frame of its view saved as a PNG (and, for --shapes, its frame on each other shape,
// chosen by the view's buttons). Then, for --variants, views opened again with something broken
// on purpose (the test shows that its bounds catch each).
// Prints one JSON line: {ok, frames: [{material, shape, png, samples, camera_diff}], variants:
// [{name, material, png}], requests (every URL the DevTools Network domain saw), problems}; exits 1 when
// the page failed (an exception, a console error, a view that did not open). The images are
// compared with the previews by tests/report/viewer_test.cpp.
//
// node tests/report/viewer_check.mjs --page REPORT/index.html --out DIR --materials JSON_ARRAY
//      [--shapes '["sphere", "plane", "shaderball"]'] [--variants JSON_OBJECT] [--chromium PATH] [--timeout S]
// --variants: {"name": {"material": NAME, "options": options of mfViewer.open (viewer.js:
//   debug.constants, debug.swapZ, output)}}
import { writeFileSync } from 'node:fs';
import { join, resolve } from 'node:path';
import { pathToFileURL } from 'node:url';

import { startChromium, WEBGL_FLAGS } from '../../scripts/devtools-pipe.mjs';

const args = { chromium: '/usr/bin/chromium', timeout: 150, variants: '{}', shapes: '["sphere"]' };
for (let i = 2; i < process.argv.length; i += 2) args[process.argv[i].replace(/^--/, '')] = process.argv[i + 1];
if (!args.page || !args.out || !args.materials) {
  console.error('usage: node viewer_check.mjs --page INDEX.html --out DIR --materials \'["name", ...]\' [--variants JSON]');
  process.exit(2);
}
const materials = JSON.parse(args.materials), variants = JSON.parse(args.variants), shapes = JSON.parse(args.shapes);
const pageUrl = pathToFileURL(resolve(args.page)).href;
const problems = [], requests = [], frames = [], shots = [];

const browser = startChromium({ name: 'viewer-check', binary: args.chromium, flags: [...WEBGL_FLAGS, '--disable-quic', '--mute-audio'] });
const { send, once } = browser;
let done = false;
const finish = (fatal) => {
  if (done) return;
  done = true;
  if (fatal) problems.push(fatal);
  const ok = problems.length === 0;
  console.log(JSON.stringify({ ok, frames, variants: shots, requests, problems }));
  if (!ok && fatal) console.error(browser.log.join('').split('\n').slice(-30).join('\n'));
  browser.close().then(() => process.exit(ok ? 0 : 1));
};
browser.child.on('error', (e) => finish(`cannot start ${args.chromium}: ${e.message}`));
setTimeout(() => finish(`no result within ${args.timeout} s`), Number(args.timeout) * 1000);

async function main() {
  const { targetId } = await send('Target.createTarget', { url: 'about:blank' });
  const { sessionId: s } = await send('Target.attachToTarget', { targetId, flatten: true });
  browser.listen((m) => {
    if (m.sessionId !== s) return;
    const p = m.params;
    if (m.method === 'Network.requestWillBeSent') requests.push(p.request.url);
    else if (m.method === 'Runtime.exceptionThrown') problems.push(`exception: ${p.exceptionDetails.exception?.description ?? p.exceptionDetails.text}`);
    else if (m.method === 'Runtime.consoleAPICalled' && (p.type === 'error' || p.type === 'warning'))
      problems.push(`console.${p.type}: ${p.args.map((a) => a.value ?? a.description).join(' ')}`);
    else if (m.method === 'Log.entryAdded' && p.entry.level === 'error') problems.push(`${p.entry.source}: ${p.entry.text} ${p.entry.url ?? ''}`);
    else if (m.method === 'Network.loadingFailed') problems.push(`load failed: ${p.errorText}`);
  });
  for (const d of ['Runtime', 'Log', 'Page', 'Network']) await send(`${d}.enable`, {}, s);
  const evaluate = async (expression) => {
    const r = await send('Runtime.evaluate', { expression, returnByValue: true, awaitPromise: true }, s);
    if (r.exceptionDetails) throw new Error(r.exceptionDetails.exception?.description ?? r.exceptionDetails.text);
    return r.result.value;
  };
  const loaded = once('Page.loadEventFired');
  const nav = await send('Page.navigate', { url: pageUrl }, s);
  if (nav.errorText) throw new Error(`${pageUrl}: ${nav.errorText}`);
  await loaded;
  const save = (name, dataUrl) => {
    const file = join(args.out, name);
    writeFileSync(file, Buffer.from(dataUrl.split(',')[1], 'base64'));
    return file;
  };
  // The card of `name`: shown (its page), its view opened by its button as a reader opens it.
  for (const [i, name] of materials.entries()) {
    const r = await evaluate(`(async () => {
      const card = [...document.querySelectorAll('section.card')].find((c) => c.getAttribute('data-material') === ${JSON.stringify(name)});
      if (!card) return { error: 'no card' };
      location.hash = '#' + card.id;
      const box = card.querySelector('div.viewer');
      if (!box || box.hidden) return { error: 'no view on the card' };
      box.querySelector('button.viewer-open').click();
      for (let t = 0; t < 1200; t++) {
        const v = window.mfViewer && window.mfViewer.active;
        if (v && v.box === box && v.ready) {
          return { png: v.canvas.toDataURL('image/png'), samples: v.samples, camera_diff: window.mfViewer.cameraCheck(),
                   frames: v.frames, width: v.canvas.width, height: v.canvas.height };
        }
        const status = box.querySelector('.viewer-status').textContent;
        if (status && !window.mfViewer?.active) return { error: status };
        await new Promise((ok) => setTimeout(ok, 100));
      }
      return { error: 'the view did not draw within 120 s' };
    })()`);
    if (r.error) { problems.push(`${name}: ${r.error}`); continue; }
    frames.push({ material: name, shape: 'sphere', png: save(`view-${i}.png`, r.png), samples: r.samples,
                  camera_diff: r.camera_diff, width: r.width, height: r.height });
    // The other shapes, by the view's own buttons.
    for (const shape of shapes.filter((x) => x !== 'sphere')) {
      const o = await evaluate(`(() => {
        const v = window.mfViewer.active, b = v.box.querySelector('button[data-shape="${shape}"]');
        if (!b) return { error: 'no ${shape} button' };
        b.click();
        return { png: v.canvas.toDataURL('image/png') };
      })()`);
      if (o.error) problems.push(`${name}: ${o.error}`);
      else frames.push({ material: name, shape, png: save(`view-${i}-${shape}.png`, o.png) });
    }
  }
  // Views opened again with something broken on purpose.
  for (const [vname, { material, options }] of Object.entries(variants)) {
    const r = await evaluate(`(async () => {
      const card = [...document.querySelectorAll('section.card')].find((c) => c.getAttribute('data-material') === ${JSON.stringify(material)});
      const v = await window.mfViewer.open(card.querySelector('div.viewer'), ${JSON.stringify(options)});
      return { png: v.canvas.toDataURL('image/png') };
    })()`);
    shots.push({ name: vname, material, png: save(`variant-${vname}.png`, r.png) });
  }
  finish(null);
}
main().catch((e) => finish(e.stack || String(e)));
