// The page of `grainshock view`: particles of every frame through WebGL2, the time series, the
// report and pictures, all from the data embedded above. Hand-written, no library; texts from
// the data are only ever set as text (textContent), never parsed as markup.
(function () {
  'use strict';
  const $ = (id) => document.getElementById(id);
  const H = JSON.parse($('gs-header').textContent);

  function bytesOf(id) {
    const s = atob($(id).textContent);
    const b = new Uint8Array(s.length);
    for (let i = 0; i < s.length; ++i) b[i] = s.charCodeAt(i);
    return b;
  }
  function el(tag, text, cls) {
    const e = document.createElement(tag);
    if (text !== undefined && text !== null) e.textContent = String(text);
    if (cls) e.className = cls;
    return e;
  }
  function fmt(v) {
    if (v === null || v === undefined || !isFinite(v)) return String(v);
    const a = Math.abs(v);
    return a !== 0 && (a < 1e-3 || a >= 1e5) ? v.toExponential(4) : String(+v.toPrecision(6));
  }

  $('gs-title').textContent = 'grainshock view: ' + H.title;
  document.title = 'grainshock: ' + H.title;
  for (const n of H.notes) $('gs-notes').appendChild(el('li', n));

  // ---- frames -----------------------------------------------------------------------------
  const LUT = bytesOf('gs-lut');
  const cache = new Map();
  // Sections as page_frame.h lays them out, each starting 4-byte aligned.
  function frameData(k) {
    if (cache.has(k)) return cache.get(k);
    const f = H.frames[k], n = f.count, d = H.dim;
    const buf = bytesOf('gs-frame-' + k).buffer;
    let at = 0;
    const take = (Type, len) => {
      const a = new Type(buf, at, len);
      at += Math.ceil(len * Type.BYTES_PER_ELEMENT / 4) * 4;
      return a;
    };
    const data = { pos: take(Uint16Array, n * d), colour: take(Uint8Array, n), index: take(Uint32Array, n) };
    data.radius = f.uniform_radius ? null : take(Uint16Array, n);
    data.columns = f.columns.map((c, k) => f.column_exact[k] ? take(Float32Array, n) : take(Uint16Array, n));
    if (cache.size > 6) cache.delete(cache.keys().next().value);
    cache.set(k, data);
    return data;
  }
  // A binary16 value (the hover columns).
  function half(h) {
    const e = (h >> 10) & 31, m = h & 1023;
    const v = e === 0 ? m * Math.pow(2, -24) : e === 31 ? (m ? NaN : Infinity) : (1 + m / 1024) * Math.pow(2, e - 15);
    return h & 0x8000 ? -v : v;
  }
  // Particle i of frame k relative to the frame's origin.
  function relPos(f, data, i) {
    const p = [0, 0, 0];
    for (let a = 0; a < H.dim; ++a) p[a] = f.lo[a] + data.pos[i * H.dim + a] / 65535 * (f.hi[a] - f.lo[a]);
    return p;
  }
  function radiusOf(f, data, i) { return data.radius ? data.radius[i] / 65535 * f.r_max : f.r_max; }

  // ---- WebGL2 ------------------------------------------------------------------------------
  const VS2 = `#version 300 es
layout(location = 0) in vec2 qpos;
layout(location = 1) in uint cidx;
layout(location = 2) in float rad;
uniform vec2 lo, span, shift, canvas;
uniform float ppu, rmax;
uniform sampler2D lut;
out vec2 local;
out float rad_px;
flat out vec4 col;
void main() {
  vec2 corner = vec2((gl_VertexID & 1) != 0 ? 1.0 : -1.0, (gl_VertexID & 2) != 0 ? 1.0 : -1.0);
  vec2 p = (lo + qpos * span + shift) * ppu;
  rad_px = rad * rmax * ppu;
  local = corner * (rad_px + 1.0);
  gl_Position = vec4((p + local) / (0.5 * canvas), 0.0, 1.0);
  col = texelFetch(lut, ivec2(int(cidx), 0), 0);
}`;
  // The PNG's disc shader: coverage from the distance to the rim, one pixel wide.
  const FS2 = `#version 300 es
precision highp float;
in vec2 local;
in float rad_px;
flat in vec4 col;
out vec4 frag;
void main() {
  float a = clamp(rad_px + 0.5 - length(local), 0.0, 1.0);
  if (a <= 0.0) discard;
  frag = vec4(col.rgb, a);
}`;
  // The PNG's sphere impostor: the billboard and the fragment shader are render/renderer.cpp's
  // (assets/shaders, which the page carries in script elements), the slab cut done per instance.
  const shader = (id) => document.getElementById(id).textContent;
  const VS3 = `#version 300 es
${shader('gs-sphere-billboard')}
layout(location = 0) in vec3 qpos;
layout(location = 1) in uint cidx;
layout(location = 2) in float rad;
uniform vec3 lo, span, shift, fwd;
uniform mat4 view, proj;
uniform float px_per_depth, rmax, slab;
uniform sampler2D lut;
out vec3 vpos;
flat out vec3 centre;
flat out float radius;
flat out vec4 col;
void main() {
  vec3 pw = lo + qpos * span + shift;
  if (slab > 0.0 && abs(dot(pw, fwd)) > 0.5 * slab) { gl_Position = vec4(2.0, 2.0, 2.0, 1.0); return; }
  vec2 corner = vec2((gl_VertexID & 1) != 0 ? 1.0 : -1.0, (gl_VertexID & 2) != 0 ? 1.0 : -1.0);
  vec3 c = (view * vec4(pw, 1.0)).xyz;
  float r = rad * rmax;
  vpos = sphere_billboard(c, r, corner, px_per_depth);
  gl_Position = proj * vec4(vpos, 1.0);
  centre = c;
  radius = r;
  col = texelFetch(lut, ivec2(int(cidx), 0), 0);
}`;
  const FS3 = `#version 300 es
precision highp float;
${shader('gs-sphere-frag')}`;

  const canvas = $('gs-canvas');
  const state = {
    frame: 0, gl: null, prog: null, vao: null, bufs: null, uploaded: -1, fitted: true,
    // 2D: the view's centre (world) and half width; 3D: orbit angles, distance and target.
    cx: 0, cy: 0, halfW: 1, az: 30, el: 20, dist: 0, target: [0, 0, 0], slab: 6, fixed: null,
    playing: false, timer: null, pixelsDrawn: 0,
  };

  function compile(gl, vs, fs) {
    const p = gl.createProgram();
    for (const [type, src] of [[gl.VERTEX_SHADER, vs], [gl.FRAGMENT_SHADER, fs]]) {
      const s = gl.createShader(type);
      gl.shaderSource(s, src);
      gl.compileShader(s);
      if (!gl.getShaderParameter(s, gl.COMPILE_STATUS)) throw new Error(gl.getShaderInfoLog(s));
      gl.attachShader(p, s);
    }
    gl.linkProgram(p);
    if (!gl.getProgramParameter(p, gl.LINK_STATUS)) throw new Error(gl.getProgramInfoLog(p));
    return p;
  }

  function initGL() {
    const gl = canvas.getContext('webgl2', { antialias: true, preserveDrawingBuffer: true });
    if (!gl) {
      const m = $('gs-nogl');
      m.hidden = false;
      m.textContent = 'This browser offers no WebGL2 (or has it turned off), which the particles ' +
        'are drawn with. The plots, report, pictures and movie of this page are below; the ' +
        'particles show in a recent Chromium, Firefox or Safari with hardware acceleration on.';
      return false;
    }
    state.gl = gl;
    state.prog = H.dim === 3 ? compile(gl, VS3, FS3) : compile(gl, VS2, FS2);
    const tex = gl.createTexture();
    gl.bindTexture(gl.TEXTURE_2D, tex);
    const rgba = new Uint8Array(256 * 4);
    for (let i = 0; i < 256; ++i) { rgba.set(LUT.subarray(3 * i, 3 * i + 3), 4 * i); rgba[4 * i + 3] = 255; }
    gl.texImage2D(gl.TEXTURE_2D, 0, gl.RGBA8, 256, 1, 0, gl.RGBA, gl.UNSIGNED_BYTE, rgba);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MIN_FILTER, gl.NEAREST);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MAG_FILTER, gl.NEAREST);
    state.vao = gl.createVertexArray();
    gl.bindVertexArray(state.vao);
    state.bufs = [gl.createBuffer(), gl.createBuffer(), gl.createBuffer()];
    return true;
  }

  // One frame's buffers: the stored bytes as they are, the GPU unpacks them.
  function upload(k) {
    const gl = state.gl, d = frameData(k), f = H.frames[k];
    gl.bindVertexArray(state.vao);
    gl.bindBuffer(gl.ARRAY_BUFFER, state.bufs[0]);
    gl.bufferData(gl.ARRAY_BUFFER, d.pos, gl.STATIC_DRAW);
    gl.enableVertexAttribArray(0);
    gl.vertexAttribPointer(0, H.dim === 3 ? 3 : 2, gl.UNSIGNED_SHORT, true, 0, 0);
    gl.vertexAttribDivisor(0, 1);
    gl.bindBuffer(gl.ARRAY_BUFFER, state.bufs[1]);
    gl.bufferData(gl.ARRAY_BUFFER, d.colour, gl.STATIC_DRAW);
    gl.enableVertexAttribArray(1);
    gl.vertexAttribIPointer(1, 1, gl.UNSIGNED_BYTE, 0, 0);
    gl.vertexAttribDivisor(1, 1);
    if (d.radius) {
      gl.bindBuffer(gl.ARRAY_BUFFER, state.bufs[2]);
      gl.bufferData(gl.ARRAY_BUFFER, d.radius, gl.STATIC_DRAW);
      gl.enableVertexAttribArray(2);
      gl.vertexAttribPointer(2, 1, gl.UNSIGNED_SHORT, true, 0, 0);
      gl.vertexAttribDivisor(2, 1);
    } else {
      gl.disableVertexAttribArray(2);
      gl.vertexAttrib1f(2, 1.0);
    }
    state.uploaded = k;
    void f;
  }

  function canvasSize() {
    if (state.fixed) return state.fixed;
    const r = window.devicePixelRatio || 1;
    return [Math.max(1, Math.round(canvas.clientWidth * r)), Math.max(1, Math.round(canvas.clientHeight * r))];
  }

  // render's framing (render/camera.cpp, no colour bar reserved): the fitted particles with a
  // margin of 8% of the larger extent plus the largest radius, centred.
  function fit2d(f, w, h) {
    const sx = f.fit_hi[0] - f.fit_lo[0], sy = f.fit_hi[1] - f.fit_lo[1];
    const aspect = w / h, pad = 0.08 * Math.max(sx, sy) + f.r_max;
    state.halfW = Math.max(1e-6, Math.max(sx / 2 + pad, (sy / 2 + pad) * aspect));
    state.cx = f.origin[0] + (f.fit_lo[0] + f.fit_hi[0]) / 2;
    state.cy = f.origin[1] + (f.fit_lo[1] + f.fit_hi[1]) / 2;
  }
  function fit3d(f, w, h) {
    const tanY = Math.tan(15 * Math.PI / 180), tanX = tanY * w / h;
    const half = Math.atan(Math.min(tanX, tanY));
    state.target = f.origin.slice();
    state.dist = Math.max(f.sphere, 1e-6) * 1.08 / Math.sin(half);
    state.az = 30; state.el = 20;
  }

  // The orbit camera of render/camera.cpp: z up, azimuth about it, elevation above the xy plane.
  function camera3d(w, h) {
    const deg = Math.PI / 180, az = state.az * deg, el = state.el * deg, dist = state.dist;
    const eye = [dist * Math.cos(el) * Math.cos(az), dist * Math.cos(el) * Math.sin(az), dist * Math.sin(el)];
    const fwd = eye.map((v) => -v / dist);
    let up = [0, 0, 1];
    if (Math.abs(fwd[2]) > 0.999) up = [0, 1, 0];
    const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
    const norm = (a) => { const l = Math.hypot(a[0], a[1], a[2]); return a.map((v) => v / l); };
    const right = norm(cross(fwd, up)), camUp = cross(right, fwd);
    const rows = [right, camUp, fwd.map((v) => -v)];
    const view = new Float32Array(16);  // column-major
    for (let r = 0; r < 3; ++r) {
      for (let c = 0; c < 3; ++c) view[c * 4 + r] = rows[r][c];
      view[12 + r] = -(rows[r][0] * eye[0] + rows[r][1] * eye[1] + rows[r][2] * eye[2]);
    }
    view[15] = 1;
    const f = H.frames[state.frame], radius = Math.max(f.sphere, 1e-6);
    const reach = state.slab > 0 ? Math.min(radius, state.slab / 2 + 1) : radius;
    const near = Math.max(dist - reach - 1, dist * 1e-3), far = dist + radius + 1;
    const tanY = Math.tan(15 * deg), tanX = tanY * w / h;
    const proj = new Float32Array(16);
    proj[0] = 1 / tanX; proj[5] = 1 / tanY;
    proj[10] = -(far + near) / (far - near); proj[14] = -2 * far * near / (far - near); proj[11] = -1;
    return { view, proj, fwd, tanY, tanX, eye };
  }

  function draw() {
    const gl = state.gl;
    if (!gl || !H.frames.length) return;
    const k = state.frame, f = H.frames[k];
    if (state.uploaded !== k) upload(k);
    const [w, h] = canvasSize();
    if (canvas.width !== w || canvas.height !== h) { canvas.width = w; canvas.height = h; }
    if (state.fitted) (H.dim === 3 ? fit3d : fit2d)(f, w, h);
    gl.viewport(0, 0, w, h);
    const bg = H.background;
    gl.clearColor(bg[0] / 255, bg[1] / 255, bg[2] / 255, 1);
    gl.clearDepth(1);
    gl.clear(gl.COLOR_BUFFER_BIT | gl.DEPTH_BUFFER_BIT);
    const p = state.prog, u = (n) => gl.getUniformLocation(p, n);
    gl.useProgram(p);
    gl.uniform1i(u('lut'), 0);
    gl.uniform1f(u('rmax'), f.r_max);
    if (H.dim === 3) {
      const cam = camera3d(w, h);
      gl.disable(gl.BLEND);
      gl.enable(gl.DEPTH_TEST);
      gl.depthFunc(gl.LESS);
      gl.enable(gl.SAMPLE_ALPHA_TO_COVERAGE);
      gl.uniform3f(u('lo'), f.lo[0], f.lo[1], f.lo[2]);
      gl.uniform3f(u('span'), f.hi[0] - f.lo[0], f.hi[1] - f.lo[1], f.hi[2] - f.lo[2]);
      gl.uniform3f(u('shift'), f.origin[0] - state.target[0], f.origin[1] - state.target[1], f.origin[2] - state.target[2]);
      gl.uniform3f(u('fwd'), cam.fwd[0], cam.fwd[1], cam.fwd[2]);
      gl.uniformMatrix4fv(u('view'), false, cam.view);
      gl.uniformMatrix4fv(u('proj'), false, cam.proj);
      gl.uniform1f(u('px_per_depth'), 2 * cam.tanY / h);
      gl.uniform1f(u('slab'), state.slab);
      const l = [-0.4, 0.55, 0.75], n = Math.hypot(l[0], l[1], l[2]);
      gl.uniform3f(u('light'), l[0] / n, l[1] / n, l[2] / n);
      state.cam = cam;
    } else {
      gl.disable(gl.DEPTH_TEST);
      gl.enable(gl.BLEND);
      gl.blendFuncSeparate(gl.SRC_ALPHA, gl.ONE_MINUS_SRC_ALPHA, gl.ONE, gl.ONE_MINUS_SRC_ALPHA);
      gl.uniform2f(u('lo'), f.lo[0], f.lo[1]);
      gl.uniform2f(u('span'), f.hi[0] - f.lo[0], f.hi[1] - f.lo[1]);
      gl.uniform2f(u('shift'), f.origin[0] - state.cx, f.origin[1] - state.cy);
      gl.uniform2f(u('canvas'), w, h);
      gl.uniform1f(u('ppu'), w / (2 * state.halfW));
    }
    gl.drawArraysInstanced(gl.TRIANGLE_STRIP, 0, 4, f.count);
    state.drawnFrame = k;
  }

  // ---- frame choice, labels, colour bar ---------------------------------------------------
  function frameLabel(f) {
    if (f.label) return f.label;
    if (f.t !== null) return 't = ' + fmt(f.t);
    return f.step !== null ? 'step ' + f.step : '';
  }
  function drawBar(f) {
    const bar = $('gs-bar');
    bar.hidden = !H.colorbar || !f.colorbar || state.fixed !== null;
    if (bar.hidden) return;
    const c = $('gs-bar-canvas'), g = c.getContext('2d'), img = g.createImageData(24, 256);
    for (let y = 0; y < 256; ++y) {
      const k = Math.round((255 - y) / 255 * 254);
      for (let x = 0; x < 24; ++x) img.data.set([LUT[3 * k], LUT[3 * k + 1], LUT[3 * k + 2], 255], 4 * (y * 24 + x));
    }
    g.putImageData(img, 0, 0);
    $('gs-bar-label').textContent = f.bar_label;
    $('gs-bar-note').textContent = f.bar_note;
    const ticks = $('gs-bar-ticks');
    ticks.textContent = '';
    const [lo, hi] = f.range, log = / \(log\)$/.test(f.bar_label);
    for (const s of [0, 0.25, 0.5, 0.75, 1]) {
      const v = log ? lo * Math.pow(hi / lo, s) : lo + s * (hi - lo);
      const t = el('span', fmt(+v.toPrecision(3)));
      t.style.top = (100 * (1 - s)) + '%';
      ticks.appendChild(t);
    }
  }
  function setFrame(k) {
    if (!H.frames.length) return;
    state.frame = Math.max(0, Math.min(H.frames.length - 1, k));
    const f = H.frames[state.frame];
    $('gs-slider').value = String(state.frame);
    $('gs-time').textContent = frameLabel(f);
    $('gs-frame-info').textContent = 'frame ' + (state.frame + 1) + ' of ' + H.frames.length +
      (f.source ? ' (' + f.source + ')' : '') + ': ' +
      f.count + ' particles drawn; positions stored to ' + fmt(f.error_diameters) +
      ' diameters (16 bits in the frame\'s bounding box)';
    drawBar(f);
    draw();
    $('gs-picked').textContent = '';
  }

  // ---- picking ----------------------------------------------------------------------------
  // The particle under canvas pixel (px, py) (CSS pixels), or -1.
  function pick(px, py) {
    const f = H.frames[state.frame], d = frameData(state.frame), [w, h] = canvasSize();
    const sx = px * w / canvas.clientWidth, sy = py * h / canvas.clientHeight;
    let best = -1, bestKey = Infinity;
    if (H.dim !== 3) {
      const ppu = w / (2 * state.halfW);
      const x = state.cx + (sx - w / 2) / ppu - f.origin[0], y = state.cy - (sy - h / 2) / ppu - f.origin[1];
      for (let i = 0; i < f.count; ++i) {
        const p = relPos(f, d, i), r = radiusOf(f, d, i);
        const d2 = (p[0] - x) ** 2 + (p[1] - y) ** 2;
        if (d2 <= r * r && d2 <= bestKey) { best = i; bestKey = d2; }  // the last drawn is on top
      }
      return best;
    }
    const cam = state.cam || camera3d(w, h), V = cam.view;
    for (let i = 0; i < f.count; ++i) {
      const q = relPos(f, d, i);
      for (let a = 0; a < 3; ++a) q[a] += f.origin[a] - state.target[a];
      if (state.slab > 0 && Math.abs(q[0] * cam.fwd[0] + q[1] * cam.fwd[1] + q[2] * cam.fwd[2]) > state.slab / 2) continue;
      const e = [0, 1, 2].map((r) => V[r] * q[0] + V[4 + r] * q[1] + V[8 + r] * q[2] + V[12 + r]);
      const depth = -e[2];
      if (depth <= 0) continue;
      const X = w / 2 + e[0] / (depth * cam.tanX) * w / 2, Y = h / 2 - e[1] / (depth * cam.tanY) * h / 2;
      const rp = radiusOf(f, d, i) / (depth * cam.tanY) * h / 2;
      if ((X - sx) ** 2 + (Y - sy) ** 2 <= rp * rp && depth < bestKey) { best = i; bestKey = depth; }
    }
    return best;
  }
  function describe(i) {
    const f = H.frames[state.frame], d = frameData(state.frame), p = relPos(f, d, i);
    const lines = ['particle ' + d.index[i] + ' (index in the file)',
      'position ' + p.slice(0, H.dim).map((v, a) => fmt(v + f.origin[a])).join(', ') +
      '  (± ' + fmt(f.error_diameters) + ' diameters)'];
    f.columns.forEach((name, c) => lines.push(name + ' = ' + (f.column_exact[c] ? String(d.columns[c][i])
      : fmt(+half(d.columns[c][i]).toPrecision(4)))));
    return lines.join('\n');
  }

  // ---- interaction ------------------------------------------------------------------------
  function setupViewer() {
    $('gs-viewer').hidden = false;
    const slider = $('gs-slider');
    slider.max = String(H.frames.length - 1);
    slider.addEventListener('input', () => setFrame(+slider.value));
    $('gs-play').addEventListener('click', () => togglePlay());
    $('gs-reset').addEventListener('click', () => { state.fitted = true; draw(); });
    document.addEventListener('keydown', (e) => {
      if (e.target && e.target.tagName === 'INPUT' && e.target !== slider) return;
      if (e.key === 'ArrowRight') { setFrame(state.frame + 1); e.preventDefault(); }
      else if (e.key === 'ArrowLeft') { setFrame(state.frame - 1); e.preventDefault(); }
      else if (e.key === ' ') { togglePlay(); e.preventDefault(); }
    });
    if (H.dim === 3) {
      $('gs-slab-box').hidden = false;
      const s = $('gs-slab'), f = H.frames[H.frames.length - 1];
      s.max = String(Math.ceil(2 * Math.max(f.sphere, 6)));
      const show = () => { $('gs-slab-value').textContent = state.slab > 0 ? fmt(state.slab) + ' diameters' : 'off (all)'; };
      s.addEventListener('input', () => { state.slab = +s.value; show(); draw(); });
      show();
    }
    let drag = null;
    canvas.addEventListener('pointerdown', (e) => { drag = [e.clientX, e.clientY]; canvas.setPointerCapture(e.pointerId); });
    canvas.addEventListener('pointerup', (e) => {
      if (drag && Math.hypot(e.clientX - drag[0], e.clientY - drag[1]) < 3) {
        const i = pick(e.offsetX, e.offsetY);
        $('gs-picked').textContent = i >= 0 ? describe(i) : '';
      }
      drag = null;
    });
    canvas.addEventListener('pointermove', (e) => {
      if (drag) {
        const dx = e.clientX - drag[0], dy = e.clientY - drag[1];
        drag = [e.clientX, e.clientY];
        state.fitted = false;
        if (H.dim === 3) { state.az -= dx * 0.4; state.el = Math.max(-89, Math.min(89, state.el + dy * 0.4)); }
        else { const s = 2 * state.halfW / canvas.clientWidth; state.cx -= dx * s; state.cy += dy * s; }
        draw();
        return;
      }
      hover(e);
    });
    canvas.addEventListener('pointerleave', () => { $('gs-tip').hidden = true; });
    canvas.addEventListener('wheel', (e) => {
      e.preventDefault();
      const z = Math.exp(e.deltaY * 0.0015);
      state.fitted = false;
      if (H.dim === 3) state.dist *= z;
      else {
        const s = 2 * state.halfW / canvas.clientWidth;
        const mx = state.cx + (e.offsetX - canvas.clientWidth / 2) * s, my = state.cy - (e.offsetY - canvas.clientHeight / 2) * s;
        state.halfW *= z;
        state.cx = mx + (state.cx - mx) * z; state.cy = my + (state.cy - my) * z;
      }
      draw();
    }, { passive: false });
    window.addEventListener('resize', () => draw());
  }
  let hoverPending = false;
  function hover(e) {
    if (hoverPending) return;
    hoverPending = true;
    requestAnimationFrame(() => {
      hoverPending = false;
      const i = pick(e.offsetX, e.offsetY), tip = $('gs-tip');
      if (i < 0) { tip.hidden = true; return; }
      tip.textContent = describe(i);
      tip.style.left = (e.offsetX + 14) + 'px';
      tip.style.top = (e.offsetY + 14) + 'px';
      tip.hidden = false;
    });
  }
  function togglePlay() {
    state.playing = !state.playing;
    $('gs-play').textContent = state.playing ? 'Pause' : 'Play';
    clearInterval(state.timer);
    if (state.playing)
      state.timer = setInterval(() => setFrame(state.frame + 1 < H.frames.length ? state.frame + 1 : 0), 400);
  }

  // ---- plots ------------------------------------------------------------------------------
  function parseCsv(text) {
    const lines = text.split(/\r?\n/).filter((l) => l.length && l[0] !== '#');
    const names = lines.length ? lines[0].split(',').map((s) => s.trim()) : [];
    const cols = names.map(() => []);
    for (const l of lines.slice(1)) l.split(',').forEach((v, c) => { if (c < cols.length) cols[c].push(parseFloat(v)); });
    return { names, cols, rows: Math.max(0, lines.length - 1) };
  }
  // A log-log plot of y against x on a canvas: wheel zooms about the mouse, drag pans, double
  // click resets; hovering shows the nearest sample's values.
  function Plot(parent, spec) {
    const box = el('div', undefined, 'gs-plot'), cv = el('canvas'), tip = el('div', undefined, 'gs-plot-tip');
    tip.hidden = true;
    box.appendChild(cv); box.appendChild(tip); parent.appendChild(box);
    const pts = [];
    for (let i = 0; i < spec.x.length; ++i)
      if (spec.x[i] > 0 && spec.y[i] > 0 && isFinite(spec.x[i]) && isFinite(spec.y[i])) pts.push(i);
    const lx = pts.map((i) => Math.log10(spec.x[i])), ly = pts.map((i) => Math.log10(spec.y[i]));
    const full = lx.length ? [Math.min(...lx), Math.max(...lx), Math.min(...ly), Math.max(...ly)] : [0, 1, 0, 1];
    if (full[1] - full[0] < 1e-9) { full[0] -= 0.5; full[1] += 0.5; }
    if (full[3] - full[2] < 1e-9) { full[2] -= 0.5; full[3] += 0.5; }
    // Room round the data, so that the samples at the ends are drawn whole.
    const padX = 0.03 * (full[1] - full[0]), padY = 0.05 * (full[3] - full[2]);
    full[0] -= padX; full[1] += padX; full[2] -= padY; full[3] += padY;
    let v = full.slice();
    const M = { l: 62, r: 12, t: 24, b: 36 };
    const api = { name: spec.name, samples: spec.x.length, drawn: pts.length, screen: [] };
    function draw() {
      const r = window.devicePixelRatio || 1, W = cv.clientWidth, Hh = cv.clientHeight;
      cv.width = Math.round(W * r); cv.height = Math.round(Hh * r);
      const g = cv.getContext('2d');
      g.setTransform(r, 0, 0, r, 0, 0);
      g.fillStyle = '#fff'; g.fillRect(0, 0, W, Hh);
      const X = (a) => M.l + (a - v[0]) / (v[1] - v[0]) * (W - M.l - M.r);
      const Y = (b) => Hh - M.b - (b - v[2]) / (v[3] - v[2]) * (Hh - M.t - M.b);
      api.X = X; api.Y = Y;
      g.strokeStyle = '#888'; g.strokeRect(M.l, M.t, W - M.l - M.r, Hh - M.t - M.b);
      g.fillStyle = '#222'; g.font = '12px sans-serif';
      for (let e = Math.ceil(v[0]); e <= v[1]; ++e) { g.fillText('1e' + e, X(e) - 10, Hh - M.b + 16); g.fillRect(X(e), Hh - M.b, 1, 4); }
      for (let e = Math.ceil(v[2]); e <= v[3]; ++e) { g.fillText('1e' + e, 8, Y(e) + 4); g.fillRect(M.l - 4, Y(e), 4, 1); }
      g.fillText(spec.name + ' against ' + spec.xname, M.l, 16);
      g.save();
      g.beginPath(); g.rect(M.l, M.t, W - M.l - M.r, Hh - M.t - M.b); g.clip();
      if (spec.err) {  // the error band: mean +- standard error
        g.fillStyle = 'rgba(0,114,178,0.2)'; g.beginPath();
        const up = [], down = [];
        for (const i of pts) {
          up.push([X(Math.log10(spec.x[i])), Y(Math.log10(spec.y[i] + spec.err[i]))]);
          const lo = spec.y[i] - spec.err[i];
          down.push([X(Math.log10(spec.x[i])), Y(lo > 0 ? Math.log10(lo) : v[2] - 10)]);
        }
        up.concat(down.reverse()).forEach(([a, b], j) => (j ? g.lineTo(a, b) : g.moveTo(a, b)));
        g.fill();
      }
      if (spec.slope !== null && lx.length > 1) {  // the paper's power law through the last decade's mean
        const n = lx.length, from = lx.findIndex((a) => a >= lx[n - 1] - 1);
        let mx = 0, my = 0;
        for (let j = from; j < n; ++j) { mx += lx[j]; my += ly[j]; }
        mx /= n - from; my /= n - from;
        g.strokeStyle = '#d55e00'; g.setLineDash([6, 4]); g.beginPath();
        g.moveTo(X(v[0]), Y(my + spec.slope * (v[0] - mx))); g.lineTo(X(v[1]), Y(my + spec.slope * (v[1] - mx)));
        g.stroke(); g.setLineDash([]);
      }
      g.strokeStyle = '#0072b2'; g.fillStyle = '#0072b2'; g.beginPath();
      api.screen = [];
      lx.forEach((a, j) => { const sx = X(a), sy = Y(ly[j]); api.screen.push([sx, sy]); j ? g.lineTo(sx, sy) : g.moveTo(sx, sy); });
      g.stroke();
      for (const [sx, sy] of api.screen) g.fillRect(sx - 2, sy - 2, 4, 4);
      g.restore();
      if (spec.slope !== null) { g.fillStyle = '#d55e00'; g.fillText('paper: slope ' + fmt(spec.slope), W - M.r - 130, 16); }
    }
    api.draw = draw;
    const logAt = (e) => [v[0] + (e.offsetX - M.l) / (cv.clientWidth - M.l - M.r) * (v[1] - v[0]),
      v[2] + (cv.clientHeight - M.b - e.offsetY) / (cv.clientHeight - M.t - M.b) * (v[3] - v[2])];
    cv.addEventListener('wheel', (e) => {
      e.preventDefault();
      const z = Math.exp(e.deltaY * 0.0015), [a, b] = logAt(e);
      v = [a + (v[0] - a) * z, a + (v[1] - a) * z, b + (v[2] - b) * z, b + (v[3] - b) * z];
      draw();
    }, { passive: false });
    let drag = null;
    cv.addEventListener('pointerdown', (e) => { drag = logAt(e); cv.setPointerCapture(e.pointerId); });
    cv.addEventListener('pointerup', () => { drag = null; });
    cv.addEventListener('dblclick', () => { v = full.slice(); draw(); });
    cv.addEventListener('pointermove', (e) => {
      if (drag) {
        const [a, b] = logAt(e);
        v = [v[0] - (a - drag[0]), v[1] - (a - drag[0]), v[2] - (b - drag[1]), v[3] - (b - drag[1])];
        draw();
        return;
      }
      let best = -1, bd = 100;
      api.screen.forEach(([sx, sy], j) => { const d = Math.hypot(sx - e.offsetX, sy - e.offsetY); if (d < bd) { bd = d; best = j; } });
      if (best < 0) { tip.hidden = true; return; }
      const i = pts[best];
      tip.textContent = spec.xname + ' = ' + fmt(spec.x[i]) + '\n' + spec.name + ' = ' + fmt(spec.y[i]) +
        (spec.err ? ' ± ' + fmt(spec.err[i]) : '');
      tip.style.left = (e.offsetX + 12) + 'px'; tip.style.top = (e.offsetY + 12) + 'px';
      tip.hidden = false;
    });
    cv.addEventListener('pointerleave', () => { tip.hidden = true; });
    return api;
  }
  const plots = [];
  function setupPlots() {
    if (!H.timeseries) return;
    const t = parseCsv(H.timeseries), col = (n) => t.names.indexOf(n);
    if (col('t') < 0) return;
    $('gs-plots').hidden = false;
    const a = H.alpha, d = H.dim;
    const want = [['active', 'N_t', a ? d * a : null], ['energy', 'E_t', a ? d * a + 2 * a - 2 : null],
      ['radius_rms', 'R_t', a || null], ['speed_rms', 'v_t', a ? a - 1 : null], ['anisotropy', 'A(t)', null]];
    const grid = $('gs-plot-grid');
    for (const [c, name, slope] of want) {
      if (col(c) < 0) continue;
      const err = H.mean && col(c + '_sem') >= 0 ? t.cols[col(c + '_sem')] : null;
      plots.push(Plot(grid, { name: H.mean ? name + ' (mean)' : name, xname: 't', x: t.cols[col('t')], y: t.cols[col(c)], err, slope }));
    }
    plots.forEach((p) => p.draw());
    window.addEventListener('resize', () => plots.forEach((p) => p.draw()));
  }

  // ---- report.md, pictures, movie -----------------------------------------------------------
  const imageIds = new Map();
  function setupImages() {
    if (!H.images.length) return;
    const sec = $('gs-images');
    sec.hidden = false;
    H.images.forEach((name, k) => {
      const fig = el('figure'), img = el('img');
      fig.id = 'gs-img-' + k;
      img.alt = name;
      img.src = 'data:image/png;base64,' + $('gs-image-' + k).textContent;
      fig.appendChild(img);
      fig.appendChild(el('figcaption', name));
      sec.appendChild(fig);
      imageIds.set(name, fig.id);
    });
  }
  // Inline markdown: `code`, **bold**, [text](target), and the names of embedded pictures linked
  // to them. A link's target is followed only to a picture of the page (nothing is fetched).
  function inline(parent, text) {
    const re = /(`[^`]*`|\*\*[^*]+\*\*|\[[^\]]*\]\([^)]*\)|[A-Za-z0-9_.\-]+\.png)/g;
    let last = 0, m;
    while ((m = re.exec(text))) {
      if (m.index > last) parent.appendChild(document.createTextNode(text.slice(last, m.index)));
      const s = m[0];
      if (s[0] === '`') parent.appendChild(el('code', s.slice(1, -1)));
      else if (s[0] === '*') parent.appendChild(el('strong', s.slice(2, -2)));
      else if (s[0] === '[') {
        const [, label, target] = /^\[([^\]]*)\]\(([^)]*)\)$/.exec(s);
        if (imageIds.has(target)) { const a = el('a', label); a.href = '#' + imageIds.get(target); parent.appendChild(a); }
        else parent.appendChild(document.createTextNode(label));
      }
      else if (imageIds.has(s)) { const a = el('a', s); a.href = '#' + imageIds.get(s); parent.appendChild(a); }
      else parent.appendChild(document.createTextNode(s));
      last = m.index + s.length;
    }
    if (last < text.length) parent.appendChild(document.createTextNode(text.slice(last)));
  }
  function setupReport() {
    if (!H.report) return;
    const sec = $('gs-report');
    sec.hidden = false;
    const lines = H.report.split(/\r?\n/);
    let list = null, para = null;
    const cells = (l) => l.trim().replace(/^\||\|$/g, '').split('|').map((c) => c.trim());
    for (let i = 0; i < lines.length; ++i) {
      const l = lines[i];
      if (!/^\s*[-*] /.test(l)) list = null;
      if (!l.trim()) { para = null; continue; }
      const h = /^(#{1,6})\s+(.*)$/.exec(l);
      if (h) { para = null; const e = el('h' + Math.min(6, h[1].length + 1)); inline(e, h[2]); sec.appendChild(e); continue; }
      if (/^\s*\|/.test(l) && i + 1 < lines.length && /^\s*\|[\s\-:|]+\|\s*$/.test(lines[i + 1])) {
        para = null;
        const table = el('table'), head = el('tr');
        for (const c of cells(l)) { const th = el('th'); inline(th, c); head.appendChild(th); }
        table.appendChild(head);
        i += 2;
        for (; i < lines.length && /^\s*\|/.test(lines[i]); ++i) {
          const tr = el('tr');
          for (const c of cells(lines[i])) { const td = el('td'); inline(td, c); tr.appendChild(td); }
          table.appendChild(tr);
        }
        --i;
        sec.appendChild(table);
        continue;
      }
      const li = /^\s*[-*] (.*)$/.exec(l);
      if (li) {
        para = null;
        if (!list) { list = el('ul'); sec.appendChild(list); }
        const e = el('li'); inline(e, li[1]); list.appendChild(e);
        continue;
      }
      if (!para) { para = el('p'); sec.appendChild(para); } else para.appendChild(document.createTextNode(' '));
      inline(para, l);
    }
  }
  function setupMovie() {
    if (!H.movie) return;
    const sec = $('gs-movie');
    sec.hidden = false;
    const video = el('video');
    video.controls = true;
    video.preload = 'metadata';
    video.src = H.movie;
    video.addEventListener('error', () => {
      const note = el('p', 'The movie ' + H.movie + ' is not beside this page (a page moved or shown alone ' +
        'has no movie); everything else here is in the page itself.', 'gs-missing');
      sec.replaceChild(note, video);
    });
    sec.appendChild(video);
  }

  setupImages();
  setupReport();
  setupPlots();
  setupMovie();
  if (H.frames.length) {
    setupViewer();
    initGL();
    setFrame(H.frames.length - 1);
  }
  // For tests and scripts: the state, and a fixed canvas size (render's --width --height).
  window.gsView = {
    header: H, plots, state, setFrame, pick, describe, frameData,
    fixSize(w, h) {
      state.fixed = [w, h];
      $('gs-stage').classList.add('fixed');
      canvas.style.width = (w / (window.devicePixelRatio || 1)) + 'px';
      canvas.style.height = (h / (window.devicePixelRatio || 1)) + 'px';
      $('gs-bar').hidden = true;
      state.fitted = true;
      draw();
    },
  };
})();
