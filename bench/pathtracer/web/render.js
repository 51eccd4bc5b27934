// Renders one scene of scenes.json with three.js or Filament into a float target and hands the
// linear radiance (box-averaged supersample x supersample, rows top to bottom, RGB float32) to the
// driver (render_web.mjs) as base64. Same camera, lights and units as matforge and Cycles:
// a directional light of intensity I gives irradiance I (three.js: physically based lights,
// the only mode in r155+; Filament: illuminance in lux with the camera's exposure set to 1).
import * as THREE from '/three/build/three.module.js';

const params = new URLSearchParams(location.search);
const which = params.get('renderer');
const sceneName = params.get('scene');
const doc = await (await fetch('/work/scenes.json')).json();
const common = doc.common;
const sc = doc.scenes.find((s) => s.name === sceneName);
const size = common.size, ss = common.supersample, N = size * ss;
const m = sc.material;
const [segW, segH] = common.sphere_segments;

function toBase64(f32) {
  const bytes = new Uint8Array(f32.buffer);
  let s = '';
  for (let i = 0; i < bytes.length; i += 0x8000) s += String.fromCharCode.apply(null, bytes.subarray(i, i + 0x8000));
  return btoa(s);
}

// RGBA float rows bottom-to-top (GL) -> RGB rows top-to-bottom, ss x ss box average.
function downsample(rgba) {
  const out = new Float32Array(size * size * 3);
  for (let y = 0; y < N; ++y) {
    const oy = Math.floor((N - 1 - y) / ss);
    for (let x = 0; x < N; ++x) {
      const ox = Math.floor(x / ss), i = (y * N + x) * 4, o = (oy * size + ox) * 3;
      out[o] += rgba[i]; out[o + 1] += rgba[i + 1]; out[o + 2] += rgba[i + 2];
    }
  }
  for (let i = 0; i < out.length; ++i) out[i] /= ss * ss;
  return out;
}

async function renderThree() {
  const canvas = document.getElementById('c');
  const renderer = new THREE.WebGLRenderer({ canvas, antialias: false });
  renderer.outputColorSpace = THREE.LinearSRGBColorSpace;
  renderer.toneMapping = THREE.NoToneMapping;
  const rt = new THREE.WebGLRenderTarget(N, N, {
    type: THREE.FloatType, format: THREE.RGBAFormat, colorSpace: THREE.LinearSRGBColorSpace,
    depthBuffer: true, samples: 0, minFilter: THREE.NearestFilter, magFilter: THREE.NearestFilter,
  });
  const scene = new THREE.Scene();
  scene.background = new THREE.Color().setRGB(...common.background, THREE.LinearSRGBColorSpace);
  const cam = new THREE.PerspectiveCamera(common.camera.yfov_deg, 1, 0.05, 100);
  cam.position.set(...common.camera.position);
  cam.up.set(...common.camera.up);
  cam.lookAt(...common.camera.target);
  const mat = new THREE.MeshStandardMaterial({ roughness: m.roughness, metalness: m.metalness ?? 0 });
  if (m.albedo) mat.color.setRGB(...m.albedo, THREE.LinearSRGBColorSpace);
  if (m.albedo_map) {
    const tex = await new THREE.TextureLoader().loadAsync('/work/' + m.albedo_map);
    tex.colorSpace = THREE.SRGBColorSpace;
    tex.wrapS = tex.wrapT = THREE.RepeatWrapping;
    tex.anisotropy = 1;
    mat.map = tex;
    mat.color.setRGB(1, 1, 1, THREE.LinearSRGBColorSpace);
  }
  scene.add(new THREE.Mesh(new THREE.SphereGeometry(common.radius, segW, segH), mat));
  for (const l of common.lights) {
    const light = new THREE.DirectionalLight(0xffffff, l.intensity);
    light.color.setRGB(...(l.color ?? [1, 1, 1]), THREE.LinearSRGBColorSpace);
    const d = new THREE.Vector3(...l.direction).normalize();
    light.position.copy(d.multiplyScalar(-10));   // shines from position toward its target (origin)
    scene.add(light);
  }
  renderer.setRenderTarget(rt);
  renderer.render(scene, cam);
  const px = new Float32Array(N * N * 4);
  renderer.readRenderTargetPixels(rt, 0, 0, N, N, px);
  return { pixels: downsample(px), info: `three.js r${THREE.REVISION}` };
}

// A glTF 2.0 of three.js's SphereGeometry (same vertices, normals, (u, v); glTF's v = 1 - three's
// v, since glTF's texture origin is the image's top left) with the scene's metallic-roughness
// material: Filament renders it with gltfio's prebuilt ubershaders (the npm package has no matc).
function sphereGltf() {
  const g = new THREE.SphereGeometry(common.radius, segW, segH);
  const pos = g.attributes.position.array, nrm = g.attributes.normal.array, uv = g.attributes.uv.array.slice();
  for (let i = 1; i < uv.length; i += 2) uv[i] = 1 - uv[i];
  const idx = new Uint32Array(g.index.array);
  const parts = [pos, nrm, uv, idx];
  const total = parts.reduce((a, p) => a + p.byteLength, 0);
  const bin = new Uint8Array(total);
  const views = [];
  let off = 0;
  for (const p of parts) {
    bin.set(new Uint8Array(p.buffer, p.byteOffset, p.byteLength), off);
    views.push({ buffer: 0, byteOffset: off, byteLength: p.byteLength });
    off += p.byteLength;
  }
  let s = '';
  for (let i = 0; i < bin.length; i += 0x8000) s += String.fromCharCode.apply(null, bin.subarray(i, i + 0x8000));
  const nv = pos.length / 3, r = common.radius;
  const pbr = { metallicFactor: m.metalness ?? 0, roughnessFactor: m.roughness,
                baseColorFactor: m.albedo ? [...m.albedo, 1] : [1, 1, 1, 1] };
  const gltf = {
    asset: { version: '2.0' }, scene: 0, scenes: [{ nodes: [0] }], nodes: [{ mesh: 0 }],
    meshes: [{ primitives: [{ attributes: { POSITION: 0, NORMAL: 1, TEXCOORD_0: 2 }, indices: 3, material: 0 }] }],
    materials: [{ pbrMetallicRoughness: pbr }],
    buffers: [{ byteLength: total, uri: 'data:application/octet-stream;base64,' + btoa(s) }],
    bufferViews: views,
    accessors: [
      { bufferView: 0, componentType: 5126, count: nv, type: 'VEC3', min: [-r, -r, -r], max: [r, r, r] },
      { bufferView: 1, componentType: 5126, count: nv, type: 'VEC3' },
      { bufferView: 2, componentType: 5126, count: nv, type: 'VEC2' },
      { bufferView: 3, componentType: 5125, count: idx.length, type: 'SCALAR' },
    ],
  };
  if (m.albedo_map) {
    pbr.baseColorTexture = { index: 0 };
    gltf.textures = [{ source: 0, sampler: 0 }];
    gltf.images = [{ uri: m.albedo_map }];
    gltf.samplers = [{ magFilter: 9729, minFilter: 9987, wrapS: 10497, wrapT: 10497 }];
  }
  return new TextEncoder().encode(JSON.stringify(gltf));
}

async function renderFilament() {
  // The float colour texture Filament allocates for our render target is found by watching
  // texStorage2D: the JS API has no readPixels, the WebGL context does.
  let rtTexture = null;
  const proto = WebGL2RenderingContext.prototype, orig = proto.texStorage2D;
  proto.texStorage2D = function (target, levels, ifmt, w, h) {
    orig.apply(this, arguments);
    if ((ifmt === this.RGBA16F || ifmt === this.RGBA32F) && w === N && h === N)
      rtTexture = this.getParameter(this.TEXTURE_BINDING_2D);
  };
  await new Promise((ok) => Filament.init([], ok));
  const canvas = document.getElementById('c');
  canvas.width = canvas.height = N;
  const engine = Filament.Engine.create(canvas);
  const gl = canvas.getContext('webgl2');
  gl.getExtension('EXT_color_buffer_float');
  const scene = engine.createScene();
  const renderer = engine.createRenderer();
  const camera = engine.createCamera(Filament.EntityManager.get().create());
  const view = engine.createView();
  const swapChain = engine.createSwapChain();
  view.setCamera(camera);
  view.setScene(scene);
  view.setViewport([0, 0, N, N]);
  view.setPostProcessingEnabled(false);   // no tone mapping, dithering, AA: linear radiance out
  renderer.setClearOptions({ clearColor: [...common.background, 1], clear: true });
  camera.setProjectionFov(common.camera.yfov_deg, 1, 0.05, 100, Filament.Camera$Fov.VERTICAL);
  camera.lookAt(common.camera.position, common.camera.target, common.camera.up);
  camera.setExposureDirect(1.0);
  // Filament shades one directional light only (the first in the scene: a second one is ignored),
  // so each light gets its own frame and the linear frames are summed (exact: no tone mapping).
  if (common.lights.length > 1 && common.background.some((c) => c !== 0))
    throw new Error('summing one frame per light needs a black background');
  const lights = common.lights.map((l) => {
    const e = Filament.EntityManager.get().create();
    const d = l.direction, n = Math.hypot(...d);
    Filament.LightManager.Builder(Filament.LightManager$Type.DIRECTIONAL)
      .color(l.color ?? [1, 1, 1]).intensity(l.intensity).direction(d.map((x) => x / n))
      .castShadows(false).build(engine, e);
    return e;
  });
  const loader = engine.createAssetLoader();
  const asset = loader.createAsset(sphereGltf());
  await new Promise((ok) => asset.loadResources(ok, null, location.origin + '/work/', 1));
  scene.addEntities(asset.getEntities());
  const T = Filament.Texture, usage = 1 /* COLOR_ATTACHMENT */ | 16 /* SAMPLEABLE */;
  const color = T.Builder().width(N).height(N).levels(1).sampler(Filament.Texture$Sampler.SAMPLER_2D)
    .format(Filament.Texture$InternalFormat.RGBA16F).usage(usage).build(engine);
  const depth = T.Builder().width(N).height(N).levels(1).sampler(Filament.Texture$Sampler.SAMPLER_2D)
    .format(Filament.Texture$InternalFormat.DEPTH32F).usage(2 /* DEPTH_ATTACHMENT */).build(engine);
  const rt = Filament.RenderTarget.Builder().texture(Filament.RenderTarget$AttachmentPoint.COLOR, color)
    .texture(Filament.RenderTarget$AttachmentPoint.DEPTH, depth).build(engine);
  view.setRenderTarget(rt);
  const px = new Float32Array(N * N * 4), one = new Float32Array(N * N * 4);
  for (const e of lights) {
    scene.addEntity(e);
    // Textures upload asynchronously: render a few frames before reading.
    for (let i = 0; i < 4; ++i) {
      renderer.render(swapChain, view);
      engine.execute();
      await new Promise((ok) => requestAnimationFrame(ok));
    }
    gl.finish();
    if (!rtTexture) throw new Error('Filament render target texture not found');
    const prev = gl.getParameter(gl.FRAMEBUFFER_BINDING);
    const fb = gl.createFramebuffer();
    gl.bindFramebuffer(gl.FRAMEBUFFER, fb);
    gl.framebufferTexture2D(gl.FRAMEBUFFER, gl.COLOR_ATTACHMENT0, gl.TEXTURE_2D, rtTexture, 0);
    const st = gl.checkFramebufferStatus(gl.FRAMEBUFFER);
    if (st !== gl.FRAMEBUFFER_COMPLETE) throw new Error('read framebuffer incomplete: ' + st);
    gl.readPixels(0, 0, N, N, gl.RGBA, gl.FLOAT, one);
    gl.bindFramebuffer(gl.FRAMEBUFFER, prev);
    gl.deleteFramebuffer(fb);
    for (let i = 0; i < px.length; ++i) px[i] += one[i];
    scene.remove(e);
  }
  return { pixels: downsample(px), info: `Filament (npm filament), ${gl.getParameter(gl.VERSION)}` };
}

try {
  const t0 = performance.now();
  const r = which === 'three' ? await renderThree() : await renderFilament();
  window.__result = { ok: true, size, info: r.info, ms: performance.now() - t0, data: toBase64(r.pixels) };
} catch (e) {
  window.__result = { ok: false, error: String(e && e.stack || e) };
}
