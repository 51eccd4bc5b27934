// The interactive view of a report card (lib/report/viewer.cpp): a material turned under the
// look-dev lighting of `matforge preview`, drawn in WebGL2 by the renderer's own shaders
// (shade.vert, shade.frag and the output transform, translated to ESSL 3.00 when matforge was
// built) with the renderer's own variant, uniform block, lighting maps and meshes. This file
// opens viewer/lookdev.js (the data of the page, given to mfViewer.lookdev) and each
// <stem>/viewer.js holds a material's (mfViewer.material); the page's loader (report/card.cpp)
// loads both when a card's view is opened and calls mfViewer.open. Nothing is fetched: file://
// pages may not, and the page works with no network.
(function () {
  "use strict";
  var V = (window.mfViewer = { materials: {}, data: null, active: null });
  V.lookdev = function (d) { V.data = d; };
  V.material = function (stem, d) { V.materials[stem] = d; };

  // ---- data

  function bytes(b64) {
    var s = atob(b64), a = new Uint8Array(s.length);
    for (var i = 0; i < s.length; i++) a[i] = s.charCodeAt(i);
    return a;
  }
  function typed(Type, b64) {
    var b = bytes(b64);
    return new Type(b.buffer, b.byteOffset, b.length / Type.BYTES_PER_ELEMENT);
  }

  // ---- the camera: frame.cpp's, turned on its orbit (preview::orbit_camera's angles)

  function sub(a, b) { return [a[0] - b[0], a[1] - b[1], a[2] - b[2]]; }
  function dot(a, b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
  function cross(a, b) { return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]; }
  function unit(a) { var l = Math.sqrt(dot(a, a)); return [a[0] / l, a[1] / l, a[2] / l]; }
  // Row-major 4x4 view matrix (rows right, up, -forward) and the basis, as frame.cpp forms them.
  function view(pos, target, worldUp) {
    var fwd = unit(sub(target, pos)), right = unit(cross(fwd, worldUp)), up = cross(right, fwd);
    return {
      fwd: fwd, right: right, up: up,
      m: [[right[0], right[1], right[2], -dot(right, pos)], [up[0], up[1], up[2], -dot(up, pos)],
          [-fwd[0], -fwd[1], -fwd[2], dot(fwd, pos)], [0, 0, 0, 1]],
    };
  }
  function mul(a, b) {
    var r = [[0, 0, 0, 0], [0, 0, 0, 0], [0, 0, 0, 0], [0, 0, 0, 0]];
    for (var i = 0; i < 4; i++) for (var j = 0; j < 4; j++) for (var k = 0; k < 4; k++) r[i][j] += a[i][k] * b[k][j];
    return r;
  }
  function rigidInverse(m) {  // rotation rows + translation
    var r = [[m[0][0], m[1][0], m[2][0], 0], [m[0][1], m[1][1], m[2][1], 0], [m[0][2], m[1][2], m[2][2], 0], [0, 0, 0, 1]];
    for (var i = 0; i < 3; i++) r[i][3] = -(r[i][0] * m[0][3] + r[i][1] * m[1][3] + r[i][2] * m[2][3]);
    return r;
  }
  // The camera of the exported frame: its projection recovered (P = VP V^-1), so the field of view,
  // aspect and depth range stay the renderer's; the ray scales are |ray_right| and |ray_up|.
  function Camera(frame, layout, cam) {
    var vp = [[], [], [], []], o = layout.view_proj;
    for (var c = 0; c < 4; c++) for (var r = 0; r < 4; r++) vp[r][c] = frame[o + c * 4 + r];
    this.proj = mul(vp, rigidInverse(view(cam.position, cam.target, cam.up).m));
    this.target = cam.target;
    this.up = cam.up;
    var d = sub(cam.position, cam.target);
    this.distance = Math.sqrt(dot(d, d));
    this.az = Math.atan2(d[0], d[2]);
    this.el = Math.asin(Math.max(-1, Math.min(1, d[1] / this.distance)));
    var rr = frame.subarray(layout.ray_right, layout.ray_right + 3), ru = frame.subarray(layout.ray_up, layout.ray_up + 3);
    this.sx = Math.sqrt(dot(rr, rr));
    this.sy = Math.sqrt(dot(ru, ru));
  }
  Camera.prototype.write = function (frame, layout, az, el) {
    var ce = Math.cos(el), t = this.target, r = this.distance;
    var pos = [t[0] + r * ce * Math.sin(az), t[1] + r * Math.sin(el), t[2] + r * ce * Math.cos(az)];
    var v = view(pos, t, this.up), vp = mul(this.proj, v.m);
    for (var c = 0; c < 4; c++) for (var k = 0; k < 4; k++) frame[layout.view_proj + c * 4 + k] = vp[k][c];
    frame.set([pos[0], pos[1], pos[2], 1], layout.camera_position);
    frame.set([v.right[0] * this.sx, v.right[1] * this.sx, v.right[2] * this.sx, 0], layout.ray_right);
    frame.set([v.up[0] * this.sy, v.up[1] * this.sy, v.up[2] * this.sy, 0], layout.ray_up);
    frame.set([v.fwd[0], v.fwd[1], v.fwd[2], 0], layout.ray_forward);
  };

  // ---- WebGL

  var FULLSCREEN_VERT = "#version 300 es\nvoid main() { vec2 p = vec2(gl_VertexID == 1 ? 3.0 : -1.0, gl_VertexID == 2 ? 3.0 : -1.0); gl_Position = vec4(p, 0.0, 1.0); }\n";
  // Units of the shaders' samplers: the material's slots first (textures[i] on unit i).
  var UNIT_LUT = 8, UNIT_SPECULAR = 9, UNIT_IRRADIANCE = 10, UNIT_RADIANCE = 11;

  function compile(gl, vs, fs) {
    var p = gl.createProgram();
    [[gl.VERTEX_SHADER, vs], [gl.FRAGMENT_SHADER, fs]].forEach(function (s) {
      var sh = gl.createShader(s[0]);
      gl.shaderSource(sh, s[1]);
      gl.compileShader(sh);
      if (!gl.getShaderParameter(sh, gl.COMPILE_STATUS)) throw new Error("shader: " + gl.getShaderInfoLog(sh));
      gl.attachShader(p, sh);
    });
    gl.linkProgram(p);
    if (!gl.getProgramParameter(p, gl.LINK_STATUS)) throw new Error("program: " + gl.getProgramInfoLog(p));
    return p;
  }
  // The translated shader with a variant's specialization constants defined after its #version line.
  function specialize(src, constants, overrides) {
    var lines = [];
    constants.forEach(function (c) {
      var id = c[0], v = overrides && overrides[id] !== undefined ? overrides[id] : c[1];
      lines.push("#define SPIRV_CROSS_CONSTANT_ID_" + id + " " + (c[2] ? (v ? "true" : "false") : String(v)));
    });
    var nl = src.indexOf("\n");
    return src.slice(0, nl + 1) + lines.join("\n") + "\n" + src.slice(nl + 1);
  }

  function View(box, stem, options) {
    var D = V.data, M = V.materials[stem];
    this.box = box;
    this.options = options || {};
    this.M = M;
    this.layout = D.frame_layout;
    this.shape = V.data.shape_order[0];
    var canvas = (this.canvas = document.createElement("canvas"));
    canvas.width = D.size[0];
    canvas.height = D.size[1];
    canvas.className = "viewer-canvas";
    canvas.style.cssText = "display:block;width:" + Math.min(D.size[0], 320) + "px;height:auto;touch-action:none;cursor:grab;background:#2e2e2e";
    var gl = (this.gl = canvas.getContext("webgl2", { alpha: false, antialias: false, depth: false, stencil: false,
      premultipliedAlpha: false, preserveDrawingBuffer: true }));
    if (!gl) throw new Error("this browser has no WebGL 2");
    if (!gl.getExtension("EXT_color_buffer_float")) throw new Error("this browser cannot render to float targets (EXT_color_buffer_float)");
    this.aniso = gl.getExtension("EXT_texture_filter_anisotropic");
    this.programs = {};
    this.setupTargets();
    this.setupLighting();
    this.encode = compile(gl, FULLSCREEN_VERT, D.shaders.encode);
    this.encodeParams = gl.createBuffer();
    var E = D.encode_layout, ep = new ArrayBuffer(E.bytes), u = new Uint32Array(ep), f = new Float32Array(ep);
    var out = this.options.output || D.output;  // the look-dev scene's exposure, transfer and tone mapping
    u[E.size] = D.size[0]; u[E.size + 1] = D.size[1]; f[E.exposure] = out.exposure; u[E.srgb] = out.srgb;
    u[E.tonemap] = out.tonemap; u[E.supersample] = 1;
    gl.bindBuffer(gl.UNIFORM_BUFFER, this.encodeParams);
    gl.bufferData(gl.UNIFORM_BUFFER, ep, gl.STATIC_DRAW);
    this.frameBuffer = gl.createBuffer();
    this.meshes = {};
  }

  // The shaded frame: RGBA32F as the renderer's target, multisampled as its look-dev scene is
  // (Scene::msaa) where the browser can; resolved (averaged) into a texture the encode pass reads.
  View.prototype.setupTargets = function () {
    var gl = this.gl, D = V.data, w = D.size[0], h = D.size[1];
    var counts = gl.getInternalformatParameter(gl.RENDERBUFFER, gl.RGBA32F, gl.SAMPLES) || [];
    var want = D.msaa, samples = 0;
    for (var i = 0; i < counts.length; i++) if (counts[i] <= want && counts[i] > samples) samples = counts[i];
    this.samples = want > 1 ? samples : 0;
    this.msaa = this.samples > 1;
    var color = gl.createRenderbuffer(), depth = gl.createRenderbuffer();
    gl.bindRenderbuffer(gl.RENDERBUFFER, color);
    if (this.msaa) gl.renderbufferStorageMultisample(gl.RENDERBUFFER, this.samples, gl.RGBA32F, w, h);
    else gl.renderbufferStorage(gl.RENDERBUFFER, gl.RGBA32F, w, h);
    gl.bindRenderbuffer(gl.RENDERBUFFER, depth);
    if (this.msaa) gl.renderbufferStorageMultisample(gl.RENDERBUFFER, this.samples, gl.DEPTH_COMPONENT32F, w, h);
    else gl.renderbufferStorage(gl.RENDERBUFFER, gl.DEPTH_COMPONENT32F, w, h);
    this.shadeFbo = gl.createFramebuffer();
    gl.bindFramebuffer(gl.FRAMEBUFFER, this.shadeFbo);
    gl.framebufferRenderbuffer(gl.FRAMEBUFFER, gl.COLOR_ATTACHMENT0, gl.RENDERBUFFER, color);
    gl.framebufferRenderbuffer(gl.FRAMEBUFFER, gl.DEPTH_ATTACHMENT, gl.RENDERBUFFER, depth);
    if (gl.checkFramebufferStatus(gl.FRAMEBUFFER) !== gl.FRAMEBUFFER_COMPLETE) throw new Error("the float target is not renderable here");
    this.radiance = gl.createTexture();
    gl.activeTexture(gl.TEXTURE0 + UNIT_RADIANCE);
    gl.bindTexture(gl.TEXTURE_2D, this.radiance);
    gl.texStorage2D(gl.TEXTURE_2D, 1, gl.RGBA32F, w, h);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MIN_FILTER, gl.NEAREST);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MAG_FILTER, gl.NEAREST);
    this.resolveFbo = gl.createFramebuffer();
    gl.bindFramebuffer(gl.FRAMEBUFFER, this.resolveFbo);
    gl.framebufferTexture2D(gl.FRAMEBUFFER, gl.COLOR_ATTACHMENT0, gl.TEXTURE_2D, this.radiance, 0);
    gl.bindFramebuffer(gl.FRAMEBUFFER, null);
  };

  // The renderer's BRDF table and prefiltered environment (half floats), as it samples them:
  // linear filtering, clamped, the specular cube's mips by roughness.
  View.prototype.setupLighting = function () {
    var gl = this.gl, L = V.data.lighting, dbg = this.options.debug || {};
    gl.pixelStorei(gl.UNPACK_ALIGNMENT, 1);
    var lut = gl.createTexture();
    gl.activeTexture(gl.TEXTURE0 + UNIT_LUT);
    gl.bindTexture(gl.TEXTURE_2D, lut);
    gl.texImage2D(gl.TEXTURE_2D, 0, gl.RGBA16F, L.lut.size, L.lut.size, 0, gl.RGBA, gl.HALF_FLOAT, typed(Uint16Array, L.lut.rgba16f));
    this.clampLinear(gl.TEXTURE_2D, false);
    var self = this;
    [[UNIT_SPECULAR, L.specular], [UNIT_IRRADIANCE, L.irradiance]].forEach(function (e) {
      var cube = e[1], data = typed(Uint16Array, cube.rgb16f), at = 0, tex = gl.createTexture();
      gl.activeTexture(gl.TEXTURE0 + e[0]);
      gl.bindTexture(gl.TEXTURE_CUBE_MAP, tex);
      for (var m = 0; m < cube.levels; m++) {
        var s = Math.max(1, cube.size >> m), n = s * s * 3;
        for (var face = 0; face < 6; face++, at += n) {
          var target = face ^ (dbg.swapZ && face >= 4 ? 1 : 0);  // tests: a wrongly oriented environment
          gl.texImage2D(gl.TEXTURE_CUBE_MAP_POSITIVE_X + target, m, gl.RGB16F, s, s, 0, gl.RGB, gl.HALF_FLOAT, data.subarray(at, at + n));
        }
      }
      gl.texParameteri(gl.TEXTURE_CUBE_MAP, gl.TEXTURE_MAX_LEVEL, cube.levels - 1);
      self.clampLinear(gl.TEXTURE_CUBE_MAP, cube.levels > 1);
    });
  };
  View.prototype.clampLinear = function (target, mips) {
    var gl = this.gl;
    gl.texParameteri(target, gl.TEXTURE_MIN_FILTER, mips ? gl.LINEAR_MIPMAP_LINEAR : gl.LINEAR);
    gl.texParameteri(target, gl.TEXTURE_MAG_FILTER, gl.LINEAR);
    gl.texParameteri(target, gl.TEXTURE_WRAP_S, gl.CLAMP_TO_EDGE);
    gl.texParameteri(target, gl.TEXTURE_WRAP_T, gl.CLAMP_TO_EDGE);
  };

  // The material's textures as the renderer samples them: sRGB color decoded by the sampler,
  // trilinear with the device's anisotropy, repeating. PNGs decoded as stored (no premultiplied
  // alpha, no color management).
  View.prototype.loadTextures = function () {
    var gl = this.gl, self = this, aniso = V.data.lighting.anisotropy;
    return Promise.all(this.M.textures.map(function (t, slot) {
      if (!t) return null;
      var blob = new Blob([bytes(t.png)], { type: "image/png" });
      return createImageBitmap(blob, { premultiplyAlpha: "none", colorSpaceConversion: "none" }).then(function (img) {
        var tex = gl.createTexture();
        gl.activeTexture(gl.TEXTURE0 + slot);
        gl.bindTexture(gl.TEXTURE_2D, tex);
        gl.pixelStorei(gl.UNPACK_PREMULTIPLY_ALPHA_WEBGL, false);
        gl.pixelStorei(gl.UNPACK_COLORSPACE_CONVERSION_WEBGL, gl.NONE);
        gl.texImage2D(gl.TEXTURE_2D, 0, t.srgb ? gl.SRGB8_ALPHA8 : gl.RGBA8, gl.RGBA, gl.UNSIGNED_BYTE, img);
        gl.generateMipmap(gl.TEXTURE_2D);
        gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MIN_FILTER, gl.LINEAR_MIPMAP_LINEAR);
        gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MAG_FILTER, gl.LINEAR);
        gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_WRAP_S, gl.REPEAT);
        gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_WRAP_T, gl.REPEAT);
        if (aniso > 1 && self.aniso) gl.texParameterf(gl.TEXTURE_2D, self.aniso.TEXTURE_MAX_ANISOTROPY_EXT, aniso);
        if (img.close) img.close();
      });
    }));
  };

  View.prototype.mesh = function (shape) {
    if (this.meshes[shape]) return this.meshes[shape];
    var gl = this.gl, src = V.data.shapes[shape].mesh;
    var vao = gl.createVertexArray(), vb = gl.createBuffer(), ib = gl.createBuffer();
    var wide = src.index_bits === 32, indices = typed(wide ? Uint32Array : Uint16Array, src.indices);
    gl.bindVertexArray(vao);
    gl.bindBuffer(gl.ARRAY_BUFFER, vb);
    gl.bufferData(gl.ARRAY_BUFFER, typed(Float32Array, src.vertices), gl.STATIC_DRAW);
    // shade.vert's inputs (interface.h kLocation*): position, normal, tangent, uv; 12 floats a vertex.
    var L = V.data.vertex_layout;
    [[L.position, 3, 0], [L.normal, 3, 3], [L.tangent, 4, 6], [L.uv, 2, 10]].forEach(function (a) {
      gl.enableVertexAttribArray(a[0]);
      gl.vertexAttribPointer(a[0], a[1], gl.FLOAT, false, 48, a[2] * 4);
    });
    gl.bindBuffer(gl.ELEMENT_ARRAY_BUFFER, ib);
    gl.bufferData(gl.ELEMENT_ARRAY_BUFFER, indices, gl.STATIC_DRAW);
    gl.bindVertexArray(null);
    return (this.meshes[shape] = { vao: vao, count: indices.length, type: wide ? gl.UNSIGNED_INT : gl.UNSIGNED_SHORT });
  };

  // The value of specialization constant `id` in the shape's variant (as this view draws it).
  View.prototype.constant = function (shape, id) {
    var o = (this.options.debug || {}).constants || {};
    if (o[id] !== undefined) return o[id];
    var c = this.M.shapes[shape].constants.filter(function (c) { return c[0] === id; })[0];
    return c ? c[1] : 0;
  };

  View.prototype.program = function (shape) {
    if (this.programs[shape]) return this.programs[shape];
    var gl = this.gl, D = V.data, dbg = this.options.debug || {};
    var constants = this.M.shapes[shape].constants;
    var overrides = Object.assign({}, dbg.constants || {});
    overrides[D.spec_ids.msaa] = this.msaa ? 1 : 0;  // the centroid ray only where samples are
    var p = compile(gl, specialize(D.shaders.vert, constants, overrides), specialize(D.shaders.frag, constants, overrides));
    var block = gl.getUniformBlockIndex(p, "FrameBlock");
    var size = gl.getActiveUniformBlockParameter(p, block, gl.UNIFORM_BLOCK_DATA_SIZE);
    if (size !== D.frame_bytes) throw new Error("FrameBlock is " + size + " bytes here, " + D.frame_bytes + " in the renderer");
    gl.uniformBlockBinding(p, block, 0);
    gl.useProgram(p);
    for (var i = 0; i < D.max_textures; i++) {
      var loc = gl.getUniformLocation(p, "textures[" + i + "]");
      if (loc) gl.uniform1i(loc, i);
    }
    [["brdf_lut", UNIT_LUT], ["env_specular", UNIT_SPECULAR], ["env_irradiance", UNIT_IRRADIANCE]].forEach(function (s) {
      var loc = gl.getUniformLocation(p, s[0]);
      if (loc) gl.uniform1i(loc, s[1]);
    });
    return (this.programs[shape] = p);
  };

  View.prototype.draw = function () {
    var gl = this.gl, D = V.data, w = D.size[0], h = D.size[1], shape = this.shape;
    var frame = this.frame;
    gl.bindFramebuffer(gl.FRAMEBUFFER, this.shadeFbo);
    gl.viewport(0, 0, w, h);
    var bg = frame.subarray(this.layout.background, this.layout.background + 3);
    gl.clearBufferfv(gl.COLOR, 0, [bg[0], bg[1], bg[2], 1]);
    gl.clearBufferfv(gl.DEPTH, 0, [1]);
    // As the renderer's pipeline: back faces culled, depth only where culling cannot order the
    // surfaces. Its projection (y down) puts each row where Vulkan does, but Vulkan's facing
    // counts a triangle's area with the opposite sign to GL's: its counter-clockwise front faces
    // are GL's clockwise ones here (gl_FrontFacing included).
    gl.enable(gl.CULL_FACE);
    gl.frontFace(gl.CW);
    if (D.shapes[shape].depth) gl.enable(gl.DEPTH_TEST); else gl.disable(gl.DEPTH_TEST);
    gl.depthFunc(gl.LESS);
    gl.useProgram(this.program(shape));
    gl.bindBuffer(gl.UNIFORM_BUFFER, this.frameBuffer);
    gl.bufferData(gl.UNIFORM_BUFFER, frame, gl.DYNAMIC_DRAW);
    gl.bindBufferBase(gl.UNIFORM_BUFFER, 0, this.frameBuffer);
    var mesh = this.mesh(shape);
    gl.bindVertexArray(mesh.vao);
    // A double-sided material as the renderer draws it (draw.cpp, pipelines.cpp): its far faces
    // first, then its near ones, each blended over the target as premultiplied radiance.
    if (this.constant(shape, D.spec_ids.double_sided)) {
      gl.enable(gl.BLEND);
      gl.blendFuncSeparate(gl.ONE, gl.ONE_MINUS_SRC_ALPHA, gl.ONE, gl.ONE_MINUS_SRC_ALPHA);
      gl.cullFace(gl.FRONT);
      gl.drawElements(gl.TRIANGLES, mesh.count, mesh.type, 0);
    }
    gl.cullFace(gl.BACK);
    gl.drawElements(gl.TRIANGLES, mesh.count, mesh.type, 0);
    gl.bindVertexArray(null);
    gl.disable(gl.BLEND);
    gl.disable(gl.CULL_FACE);
    gl.disable(gl.DEPTH_TEST);
    gl.bindFramebuffer(gl.READ_FRAMEBUFFER, this.shadeFbo);
    gl.bindFramebuffer(gl.DRAW_FRAMEBUFFER, this.resolveFbo);
    gl.blitFramebuffer(0, 0, w, h, 0, 0, w, h, gl.COLOR_BUFFER_BIT, gl.NEAREST);
    // The rows were shaded top row first (Vulkan's order); the canvas shows them the right way up.
    gl.bindFramebuffer(gl.FRAMEBUFFER, null);
    gl.viewport(0, 0, w, h);
    gl.useProgram(this.encode);
    gl.uniform1i(gl.getUniformLocation(this.encode, "radiance"), UNIT_RADIANCE);
    var eb = gl.getUniformBlockIndex(this.encode, "EncodeBlock");
    gl.uniformBlockBinding(this.encode, eb, 1);
    gl.bindBufferBase(gl.UNIFORM_BUFFER, 1, this.encodeParams);
    gl.drawArrays(gl.TRIANGLES, 0, 3);
    this.frames = (this.frames || 0) + 1;
  };

  View.prototype.setShape = function (shape) {
    this.shape = shape;
    var M = this.M.shapes[shape];
    this.frame = typed(Float32Array, M.frame).slice();
    // The target shaded is the canvas (where the renderer supersampled instead of multisampling,
    // its frame names a larger one).
    var w = V.data.size[0], h = V.data.size[1];
    this.frame.set([w, h, 1 / w, 1 / h], this.layout.viewport);
    this.camera = new Camera(this.frame, this.layout, V.data.camera);
    if (this.az !== undefined) this.camera.write(this.frame, this.layout, this.az, this.el);
    else { this.az = this.camera.az; this.el = this.camera.el; }
    var dbg = this.options.debug || {};
    if (dbg.frame) for (var k in dbg.frame) this.frame[Number(k)] = dbg.frame[k];
    this.box.querySelectorAll("button[data-shape]").forEach(function (b) {
      b.setAttribute("aria-pressed", String(b.getAttribute("data-shape") === shape));
    });
    this.draw();
  };

  View.prototype.controls = function () {
    var self = this, c = this.canvas, drag = null, pending = false;
    function redraw() {
      if (pending) return;
      pending = true;
      requestAnimationFrame(function () { pending = false; self.draw(); });
    }
    c.addEventListener("pointerdown", function (e) { drag = [e.clientX, e.clientY]; c.setPointerCapture(e.pointerId); c.style.cursor = "grabbing"; });
    c.addEventListener("pointerup", function () { drag = null; c.style.cursor = "grab"; });
    c.addEventListener("pointermove", function (e) {
      if (!drag) return;
      var k = Math.PI / Math.max(200, c.clientWidth);  // half a turn across the view
      self.az -= (e.clientX - drag[0]) * k;
      self.el = Math.max(-1.5, Math.min(1.5, self.el + (e.clientY - drag[1]) * k));  // short of the poles
      drag = [e.clientX, e.clientY];
      self.camera.write(self.frame, self.layout, self.az, self.el);
      redraw();
    });
    c.addEventListener("dblclick", function () { self.az = self.camera.az; self.el = self.camera.el; self.setShape(self.shape); });
  };

  // Opens the view in `box` (a card's div.viewer); resolves once the first frame is drawn.
  V.open = function (box, options) {
    V.close();
    var stem = box.getAttribute("data-stem"), status = box.querySelector(".viewer-status");
    var view;
    try {
      if (!V.data || !V.materials[stem]) throw new Error("the view's data did not load");
      view = new View(box, stem, options);
    } catch (e) {
      status.textContent = String(e.message || e);
      return Promise.reject(e);
    }
    V.active = view;
    box.querySelector("button.viewer-open").hidden = true;
    var stage = box.querySelector(".viewer-stage");
    stage.textContent = "";
    stage.appendChild(view.canvas);
    var bar = document.createElement("div");
    V.data.shape_order.forEach(function (shape) {
      var b = document.createElement("button");
      b.type = "button";
      b.textContent = shape;
      b.setAttribute("data-shape", shape);
      b.addEventListener("click", function () { view.setShape(shape); });
      bar.appendChild(b);
    });
    var close = document.createElement("button");
    close.type = "button";
    close.textContent = "close";
    close.addEventListener("click", V.close);
    bar.appendChild(close);
    stage.appendChild(bar);
    status.textContent = "drag to turn, double-click to reset · " + V.data.size[0] + "×" + V.data.size[1] +
      (view.msaa ? ", " + view.samples + "× MSAA" : "") + " · WebGL2";
    view.controls();
    return view.loadTextures().then(function () {
      view.setShape(V.data.shape_order[0]);
      view.ready = true;
      return view;
    }, function (e) { status.textContent = String(e.message || e); throw e; });
  };

  V.close = function () {
    var view = V.active;
    if (!view) return;
    V.active = null;
    var ext = view.gl.getExtension("WEBGL_lose_context");
    if (ext) ext.loseContext();
    var box = view.box;
    box.querySelector(".viewer-stage").textContent = "";
    box.querySelector(".viewer-status").textContent = "";
    box.querySelector("button.viewer-open").hidden = false;
  };

  // For tests: the camera fields this script computes at the exported camera's own angles, against
  // the exported ones (largest absolute difference).
  V.cameraCheck = function () {
    var view = V.active, L = view.layout;
    var mine = view.frame.slice();
    view.camera.write(mine, L, view.camera.az, view.camera.el);
    var ref = typed(Float32Array, view.M.shapes[view.shape].frame), worst = 0;
    for (var i = 0; i < L.camera_end; i++) worst = Math.max(worst, Math.abs(mine[i] - ref[i]));
    return worst;
  };
})();
