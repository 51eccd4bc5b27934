#!/usr/bin/env node
// An independent render of a glTF material's two sides: three.js (npm `three`, pinned by
// scripts/npm-checkers.sh; its classic WebGLRenderer on SwiftShader in headless Chromium) draws
// the material GLTFLoader reads from each .gltf on a sphere in matforge's reference scene (camera
// at (0, 0, 4) with a 35° vertical field, a unit sphere of three's SphereGeometry(1, 128, 64), one
// white directional light of intensity 3 travelling along (1, −1, −1)/√3, black background, no
// tone mapping, sRGB output, no multisampling), twice: as the file asks (`doubleSided` honoured)
// and front faces only. A test compares both with matforge's preview of the same material: where a
// cut-out shows its far side, the preview must agree with the first and not the second.
//   node gltf_sides.mjs NPM_DIR ROOT OUT_DIR SIZE NAME...   (ROOT/NAME/NAME.gltf)
// writes OUT_DIR/NAME.sides.png (as the file asks) and NAME.front.png and prints one JSON line per
// material: {name, ok, error, double_sided (the file's flag), alpha_mode, alpha_test}.
import { writeFileSync } from 'node:fs';
import { join, resolve } from 'node:path';

import { openPage, startChromium, WEBGL_FLAGS } from '../../../scripts/devtools-pipe.mjs';
import { serve } from '../../../scripts/loopback-server.mjs';

const [npmDir, rootDir, outDir, sizeArg, ...names] = process.argv.slice(2);
const size = Number(sizeArg);
const modules = resolve(npmDir, 'node_modules');
const page = `<!doctype html><html><body style="margin:0;background:#000">
<canvas id="c" width="${size}" height="${size}"></canvas>
<script type="importmap">{"imports": {"three": "/npm/three/build/three.module.js",
  "three/addons/": "/npm/three/examples/jsm/"}}</script>
<script type="module">
import * as THREE from 'three';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';
const canvas = document.getElementById('c');
const renderer = new THREE.WebGLRenderer({ canvas, antialias: false, preserveDrawingBuffer: true });
renderer.setPixelRatio(1);
renderer.setSize(${size}, ${size}, false);
renderer.toneMapping = THREE.NoToneMapping;
renderer.outputColorSpace = THREE.SRGBColorSpace;
const camera = new THREE.PerspectiveCamera(35, 1, 0.01, 100);
camera.position.set(0, 0, 4);
camera.lookAt(0, 0, 0);
// The glTF's textures keep glTF's orientation (GLTFLoader: flipY false, (0, 0) the first row):
// the sphere's v turned to match, as a glTF mesh's would be. The tangent frame then comes from
// the (u, v) derivatives in the shader, as three does for a mesh without tangents.
const geometry = new THREE.SphereGeometry(1, 128, 64);
const uv = geometry.attributes.uv;
for (let i = 0; i < uv.count; ++i) uv.setY(i, 1 - uv.getY(i));
function shot(material) {
  const scene = new THREE.Scene();
  scene.background = new THREE.Color(0, 0, 0);
  const light = new THREE.DirectionalLight(0xffffff, 3);
  light.position.set(-1, 1, 1);
  scene.add(light, new THREE.Mesh(geometry, material));
  renderer.render(scene, camera);
  return canvas.toDataURL('image/png');
}
window.renderOne = async (name) => {
  const gltf = await new GLTFLoader().loadAsync('/root/' + name + '/' + name + '.gltf');
  let material = null;
  gltf.scene.traverse((o) => { if (o.isMesh && !material) material = o.material; });
  const asked = material.side;
  const sides = shot(material);
  material.side = THREE.FrontSide;
  material.needsUpdate = true;
  const front = shot(material);
  return { sides, front, double_sided: asked === THREE.DoubleSide, alpha_test: material.alphaTest,
           transparent: material.transparent };
};
window.ready = true;
</script></body></html>`;

const { server, port } = await serve({ page, folders: { '/npm/': modules, '/root/': resolve(rootDir) } });
const browser = startChromium({ name: 'gltf-sides', flags: WEBGL_FLAGS });
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
    writeFileSync(join(outDir, name + '.sides.png'), Buffer.from(r.sides.split(',')[1], 'base64'));
    writeFileSync(join(outDir, name + '.front.png'), Buffer.from(r.front.split(',')[1], 'base64'));
    Object.assign(out, { double_sided: r.double_sided, alpha_test: r.alpha_test, transparent: r.transparent, ok: true });
  } catch (e) { out.error = String(e.message || e).slice(0, 1000) + '\n' + log.slice(-10).join('\n'); failed = true; }
  console.log(JSON.stringify(out));
}
finish(failed ? 1 : 0);
