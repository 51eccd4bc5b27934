#!/usr/bin/env node
// An independent render of matforge's MaterialX documents: three.js (npm `three`, pinned by
// scripts/npm-checkers.sh) in headless Chromium, WebGL 2 on SwiftShader, renders each material
// twice on the same sphere under the same lights: its .mtlx through three's MaterialXLoader (which
// builds the node graph itself: image, extract, normalmap, gltf_pbr) and its .gltf through
// GLTFLoader, and compares the two pictures. Both single-sided: MaterialX has no double-sided
// attribute, so the glTF's doubleSided is left out of the comparison.
//   node mtlx_render.mjs NPM_DIR ROOT OUT_DIR NAME...   (ROOT/NAME/NAME.mtlx and NAME.gltf)
// prints one JSON line per material: {name, ok, error, materials (in the .mtlx), mtlx: {lit, mean},
// gltf: {lit, mean}, psnr_db, copyright} (lit: pixels brighter than black; mean: their sRGB-encoded
// RGB, 0-1; PSNR of the two 192² pictures; copyright: the asset.copyright GLTFLoader gives in
// gltf.asset, null when none) and writes OUT_DIR/NAME.mtlx.png and NAME.gltf.png.
// Served over a local HTTP server (three's loaders fetch; file:// cannot), Chromium driven over
// the DevTools protocol on a pipe (scripts/devtools-pipe.mjs).
import { writeFileSync } from 'node:fs';
import { join, resolve } from 'node:path';

import { openPage, startChromium, WEBGL_FLAGS } from '../../../scripts/devtools-pipe.mjs';
import { serve } from '../../../scripts/loopback-server.mjs';

const [npmDir, rootDir, outDir, ...names] = process.argv.slice(2);
const modules = resolve(npmDir, 'node_modules');
const root = resolve(rootDir);
const page = `<!doctype html><html><body style="margin:0;background:#000">
<canvas id="c" width="192" height="192"></canvas>
<script type="importmap">{"imports": {"three": "/npm/three/build/three.webgpu.js",
  "three/webgpu": "/npm/three/build/three.webgpu.js", "three/tsl": "/npm/three/build/three.tsl.js",
  "three/addons/": "/npm/three/examples/jsm/"}}</script>
<script type="module">
import * as THREE from 'three/webgpu';
import { MaterialXLoader } from 'three/addons/loaders/MaterialXLoader.js';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';
const canvas = document.getElementById('c');
const renderer = new THREE.WebGPURenderer({ canvas, antialias: false, forceWebGL: true });
renderer.setSize(192, 192, false);
renderer.toneMapping = THREE.NoToneMapping;
renderer.outputColorSpace = THREE.SRGBColorSpace;
await renderer.init();
const camera = new THREE.PerspectiveCamera(30, 1, 0.1, 10);
camera.position.set(0, 0, 2.2);
function scene(material) {
  const s = new THREE.Scene();
  s.background = new THREE.Color(0, 0, 0);
  const light = new THREE.DirectionalLight(0xffffff, 2.5);
  light.position.set(1, 1.5, 2);
  s.add(light, new THREE.AmbientLight(0xffffff, 0.6));
  const geometry = new THREE.SphereGeometry(0.5, 64, 32);
  geometry.computeTangents();
  s.add(new THREE.Mesh(geometry, material));
  return s;
}
async function shot(material) {
  await renderer.renderAsync(scene(material), camera);
  const url = canvas.toDataURL('image/png');
  const img = new Image(); img.src = url; await img.decode();
  const c2 = document.createElement('canvas'); c2.width = 192; c2.height = 192;
  const g = c2.getContext('2d'); g.drawImage(img, 0, 0);
  return { url, px: g.getImageData(0, 0, 192, 192).data };
}
window.renderOne = async (name) => {
  const mx = await new MaterialXLoader().setPath('/root/' + name + '/').loadAsync(name + '.mtlx');
  const mxMaterial = Object.values(mx.materials)[0];
  const gltf = await new GLTFLoader().loadAsync('/root/' + name + '/' + name + '.gltf');
  let glMaterial = null;
  gltf.scene.traverse((o) => { if (o.isMesh && !glMaterial) glMaterial = o.material; });
  glMaterial.side = THREE.FrontSide;
  const a = await shot(mxMaterial), b = await shot(glMaterial);
  return { mtlx: a.url, gltf: b.url, count: Object.keys(mx.materials).length,
           copyright: gltf.asset.copyright ?? null, pa: Array.from(a.px), pb: Array.from(b.px) };
};
window.ready = true;
</script></body></html>`;

const { server, port } = await serve({ page, folders: { '/npm/': modules, '/root/': root } });

const browser = startChromium({
  name: 'mtlx-render', flags: WEBGL_FLAGS,
});
const { log } = browser;
browser.listen((msg) => {
  if (msg.method === 'Runtime.consoleAPICalled' || msg.method === 'Runtime.exceptionThrown') log.push(JSON.stringify(msg.params).slice(0, 400));
});
const finish = async (code) => {
  await browser.close();
  server.close();
  process.exit(code);
};
setTimeout(() => { console.error('timeout\n' + log.join('\n')); finish(1); }, 240000);

const { evaluate, waitFor } = await openPage(browser, `http://127.0.0.1:${port}/`);
await waitFor('window.ready === true');
let failed = false;
for (const name of names) {
  const out = { name, ok: false, error: '' };
  try {
    const r = await evaluate(`renderOne(${JSON.stringify(name)})`);
    const stats = (px) => {
      const sum = [0, 0, 0]; let lit = 0;
      for (let i = 0; i < px.length; i += 4) if (px[i] + px[i + 1] + px[i + 2] > 3) { ++lit; for (let c = 0; c < 3; ++c) sum[c] += px[i + c] / 255; }
      return { lit, mean: sum.map((s) => s / Math.max(lit, 1)) };
    };
    let se = 0;
    for (let i = 0; i < r.pa.length; i += 4) for (let c = 0; c < 3; ++c) se += ((r.pa[i + c] - r.pb[i + c]) / 255) ** 2;
    const mse = se / (r.pa.length / 4 * 3);
    out.mtlx = stats(r.pa); out.gltf = stats(r.pb); out.materials = r.count;
    out.psnr_db = mse > 0 ? 10 * Math.log10(1 / mse) : 100;
    out.copyright = r.copyright;
    writeFileSync(join(outDir, name + '.mtlx.png'), Buffer.from(r.mtlx.split(',')[1], 'base64'));
    writeFileSync(join(outDir, name + '.gltf.png'), Buffer.from(r.gltf.split(',')[1], 'base64'));
    out.ok = true;
  } catch (e) { out.error = String(e.message || e).slice(0, 1000) + '\n' + log.slice(-10).join('\n'); failed = true; }
  console.log(JSON.stringify(out));
}
finish(failed ? 1 : 0);
