// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// The viewer page's script: plays the frames the library computed (canvas 2D, no framework).
// For tests it declares its view transform (world -> screen px, a 2 x 4 matrix), the drawn
// particle centres and the drawn curves and surfaces (screen px): window.dalView.transform /
// .drawn / .shapes and the scene canvas's data-transform / data-drawn / data-shapes / data-t
// attributes, the phase plot's data-sections-shown; console errors are counted in body's
// data-errors.
(function () {
  'use strict';
  var V = (window.dalView = { errors: [], drawn: [], transform: null });
  var body = document.body;
  function note(msg) {
    V.errors.push(String(msg));
    body.setAttribute('data-errors', String(V.errors.length));
    document.getElementById('errors').textContent = V.errors.join('\n');
  }
  body.setAttribute('data-errors', '0');
  window.addEventListener('error', function (ev) { note(ev.message); });
  var cerr = console.error;
  console.error = function () {
    note(Array.prototype.join.call(arguments, ' '));
    cerr.apply(console, arguments);
  };

  // the data: series quantized over each component's range, row-to-row differences as zigzag
  // varints of the misses of a linear prediction, in base64 (view.c: put_series); x = lo + k step,
  // k = 65535 marks a missing value
  var D = JSON.parse(document.getElementById('dal-data').textContent);
  function decode(e, rows) {
    var s = atob(e.b64), w = e.w, out = new Float64Array(rows * w), live = [], p = 0;
    var k1 = new Array(w).fill(0), k2 = new Array(w).fill(0); // k of the rows r - 1, r - 2
    for (var c = 0; c < w; c++) {
      if (e.step[c] > 0) live.push(c);
      else for (var r = 0; r < rows; r++) out[r * w + c] = e.lo[c] === null ? NaN : e.lo[c];
    }
    for (r = 0; r < rows; r++) {
      for (var j = 0; j < live.length; j++) {
        var z = 0, mul = 1, b;
        do { b = s.charCodeAt(p++); z += (b & 127) * mul; mul *= 128; } while (b & 128);
        c = live[j];
        var k = (r >= 2 ? 2 * k1[c] - k2[c] : k1[c]) + (z % 2 ? -(z + 1) / 2 : z / 2);
        k2[c] = k1[c];
        k1[c] = k;
        out[r * w + c] = k === 65535 ? NaN : e.lo[c] + k * e.step[c];
      }
    }
    return out;
  }
  var N = D.N, d = D.dim, K = D.K, F = D.frames;
  var pos = decode(D.pos, F), xs = decode(D.xs, F), pq = decode(D.pq, D.nplot);
  var pqd = decode(D.pqd, D.nplot), pe2 = decode(D.pe, D.nplot), pf = decode(D.pf, D.nplot);
  var pe = new Float64Array(D.nplot), ph = new Float64Array(D.nplot); // E - E(0), h - h(0)
  for (var s0 = 0; s0 < D.nplot; s0++) {
    pe[s0] = pe2[2 * s0];
    ph[s0] = pe2[2 * s0 + 1];
  }
  var sceneCv = document.getElementById('scene'), ctx = sceneCv.getContext('2d');
  var W = 640, H = 480;
  document.getElementById('title').textContent = D.title;
  document.getElementById('hint').textContent = d === 3
    ? 'drag to rotate, wheel to zoom; FILE.html#t=1.25 opens paused at t = 1.25'
    : 'FILE.html#t=1.25 opens paused at t = 1.25';

  // the world position of point i (a particle, or an extra point N + j) at frame f
  function pt(f, i) {
    if (i < N) {
      var o = (f * N + i) * d;
      return [pos[o], pos[o + 1], d === 3 ? pos[o + 2] : 0];
    }
    var x = (f * K + i - N) * 3;
    return [xs[x], xs[x + 1], xs[x + 2]];
  }
  // extra points that are directions (a circle's plane, a line's direction), not places
  // (a circle's u may be a particle's index: the direction from the centre to it)
  var isDir = {};
  D.circles.forEach(function (c) { isDir[c[1]] = c[1] >= N; isDir[c[2]] = c[2] >= N; });
  D.lines.forEach(function (l) { isDir[l[1]] = true; });
  D.planes.forEach(function (p) { isDir[p[1]] = true; });

  // the bounding box of everything drawn
  var lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
  function grow(p, r) {
    for (var b = 0; b < 3; b++) {
      if (!isFinite(p[b])) return;
    }
    for (b = 0; b < 3; b++) {
      lo[b] = Math.min(lo[b], p[b] - r);
      hi[b] = Math.max(hi[b], p[b] + r);
    }
  }
  for (var f = 0; f < F; f++) {
    for (var i = 0; i < N; i++) grow(pt(f, i), 0);
    for (i = 0; i < K; i++) if (!isDir[N + i]) grow(pt(f, N + i), 0);
    D.circles.forEach(function (c) { grow(pt(f, c[0]), c[3]); });
    D.spheres.forEach(function (c) { grow(pt(f, c[0]), c[1]); });
  }
  if (d === 2) lo[2] = hi[2] = 0;
  var centre = [0, 1, 2].map(function (b) { return (lo[b] + hi[b]) / 2; });
  var ext = Math.max(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2], 1e-9);
  var view = { yaw: d === 3 ? -0.6 : 0, pitch: d === 3 ? 0.35 : 0, zoom: 1 };

  // the view transform: px = A0 . (x, y, z, 1), py = A1 . (x, y, z, 1)
  function transform() {
    var s, R0, R1;
    if (d === 2) {
      s = 0.9 * Math.min(W / Math.max(hi[0] - lo[0], 1e-9), H / Math.max(hi[1] - lo[1], 1e-9));
      R0 = [1, 0, 0];
      R1 = [0, 1, 0];
    } else {
      var cy = Math.cos(view.yaw), sy = Math.sin(view.yaw);
      var cp = Math.cos(view.pitch), sp = Math.sin(view.pitch);
      s = 0.5 * Math.min(W, H) / (0.5 * Math.sqrt(3) * ext);
      R0 = [cy, -sy, 0];
      R1 = [sp * sy, sp * cy, cp];
    }
    s *= view.zoom;
    var c0 = R0[0] * centre[0] + R0[1] * centre[1] + R0[2] * centre[2];
    var c1 = R1[0] * centre[0] + R1[1] * centre[1] + R1[2] * centre[2];
    return [[s * R0[0], s * R0[1], s * R0[2], W / 2 - s * c0],
      [-s * R1[0], -s * R1[1], -s * R1[2], H / 2 + s * c1]];
  }
  var A = transform();
  function px(p) {
    return [A[0][0] * p[0] + A[0][1] * p[1] + A[0][2] * p[2] + A[0][3],
      A[1][0] * p[0] + A[1][1] * p[1] + A[1][2] * p[2] + A[1][3]];
  }
  function dir(p) { // a direction on screen (no translation)
    return [A[0][0] * p[0] + A[0][1] * p[1] + A[0][2] * p[2],
      A[1][0] * p[0] + A[1][1] * p[1] + A[1][2] * p[2]];
  }

  var mmax = 0;
  D.particles.forEach(function (p) { mmax = Math.max(mmax, p.m); });
  var palette = ['#1f77b4', '#d62728', '#2ca02c', '#9467bd', '#ff7f0e', '#8c564b', '#17becf'];

  function sub(a, b) { return [a[0] - b[0], a[1] - b[1], a[2] - b[2]]; }
  function add(a, b) { return [a[0] + b[0], a[1] + b[1], a[2] + b[2]]; }
  function scale(a, s) { return [a[0] * s, a[1] * s, a[2] * s]; }
  function dot(a, b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
  function cross(a, b) {
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
  }
  function unit(a) { return scale(a, 1 / (Math.hypot(a[0], a[1], a[2]) || 1)); }
  // the circle C + R (cos a u + sin a w) on screen; returns the screen points C, C + R u, C + R w
  function ring(C, u, w, R) {
    ctx.beginPath();
    for (var k = 0; k <= 96; k++) {
      var a = 2 * Math.PI * k / 96, q = px(add(C, add(scale(u, Math.cos(a) * R), scale(w, Math.sin(a) * R))));
      if (k) ctx.lineTo(q[0], q[1]); else ctx.moveTo(q[0], q[1]);
    }
    ctx.stroke();
    return [px(C), px(add(C, scale(u, R))), px(add(C, scale(w, R)))];
  }
  function line(a, b) {
    ctx.beginPath();
    ctx.moveTo(a[0], a[1]);
    ctx.lineTo(b[0], b[1]);
    ctx.stroke();
  }
  function coil(a, b) { // a spring: straight ends, a zigzag between
    var dx = b[0] - a[0], dy = b[1] - a[1], L = Math.hypot(dx, dy) || 1;
    var nx = -dy / L, ny = dx / L, turns = 12;
    ctx.beginPath();
    ctx.moveTo(a[0], a[1]);
    for (var k = 0; k <= turns; k++) {
      var u = 0.1 + 0.8 * k / turns, w = k === 0 || k === turns ? 0 : (k % 2 ? 6 : -6);
      ctx.lineTo(a[0] + dx * u + nx * w, a[1] + dy * u + ny * w);
    }
    ctx.lineTo(b[0], b[1]);
    ctx.stroke();
  }
  function dashpot(a, b) { // a damper: a cylinder on one side, a piston on the other
    var dx = b[0] - a[0], dy = b[1] - a[1], L = Math.hypot(dx, dy) || 1;
    var ux = dx / L, uy = dy / L, nx = -uy, ny = ux, m = [a[0] + dx / 2, a[1] + dy / 2];
    line(a, [m[0] - ux * 8, m[1] - uy * 8]);
    ctx.beginPath();
    ctx.moveTo(m[0] - ux * 8 + nx * 6, m[1] - uy * 8 + ny * 6);
    ctx.lineTo(m[0] + ux * 10 + nx * 6, m[1] + uy * 10 + ny * 6);
    ctx.moveTo(m[0] - ux * 8 - nx * 6, m[1] - uy * 8 - ny * 6);
    ctx.lineTo(m[0] + ux * 10 - nx * 6, m[1] + uy * 10 - ny * 6);
    ctx.moveTo(m[0] - ux * 8 + nx * 6, m[1] - uy * 8 + ny * 6);
    ctx.lineTo(m[0] - ux * 8 - nx * 6, m[1] - uy * 8 - ny * 6);
    ctx.stroke();
    line([m[0] + nx * 4, m[1] + ny * 4], [m[0] - nx * 4, m[1] - ny * 4]);
    line(m, b);
  }

  var frame = 0, playing = false, speed = 1, last = null;
  function drawScene() {
    var dpr = window.devicePixelRatio || 1;
    if (sceneCv.width !== W * dpr) {
      sceneCv.width = W * dpr;
      sceneCv.height = H * dpr;
    }
    ctx.setTransform(dpr, 0, 0, dpr, 0, 0);
    ctx.clearRect(0, 0, W, H);
    A = transform();
    var f = frame;
    // curves and surfaces of the constraints and placements, in their frame at this time;
    // each declared (screen px) for the tests in V.shapes
    ctx.strokeStyle = '#bbb';
    ctx.lineWidth = 1;
    V.shapes = [];
    D.circles.forEach(function (c) {
      var C = pt(f, c[0]), u = [1, 0, 0], w = [0, 1, 0]; // 2-D (c[1] < 0): the page's plane
      if (c[1] >= 0 && c[1] < N) u = unit(sub(pt(f, c[1]), C));
      else if (c[1] >= 0) u = pt(f, c[1]);
      if (c[2] >= 0) w = pt(f, c[2]);
      var p = ring(C, u, w, c[3]);
      V.shapes.push(['circle', p[0][0], p[0][1], p[1][0], p[1][1], p[2][0], p[2][1]]);
    });
    D.spheres.forEach(function (sp) { // the outline, the equator and a meridian
      var C = pt(f, sp[0]), R = sp[1], s = Math.hypot(A[0][0], A[0][1], A[0][2]);
      var c = px(C);
      ctx.beginPath();
      ctx.arc(c[0], c[1], s * R, 0, 2 * Math.PI);
      ctx.stroke();
      ctx.strokeStyle = '#ddd';
      ring(C, [1, 0, 0], [0, 1, 0], R);
      ring(C, [1, 0, 0], [0, 0, 1], R);
      ctx.strokeStyle = '#bbb';
      V.shapes.push(['sphere', c[0], c[1], s * R]);
    });
    D.planes.forEach(function (pl) { // a square of the scene's size about the scene's centre
      var P = pt(f, pl[0]), n = unit(pt(f, pl[1]));
      var a = Math.abs(n[0]) < 0.9 ? [1, 0, 0] : [0, 1, 0], u = unit(cross(a, n)), w = cross(n, u);
      var o = sub(centre, scale(n, dot(sub(centre, P), n))), h = 0.5 * ext, corners = [], dec = [];
      ctx.strokeStyle = '#ccc';
      for (var k = 0; k <= 4; k++) { // a grid of 4 x 4 squares
        var e = h * (k / 2 - 1);
        line(px(add(o, add(scale(u, e), scale(w, -h)))), px(add(o, add(scale(u, e), scale(w, h)))));
        line(px(add(o, add(scale(w, e), scale(u, -h)))), px(add(o, add(scale(w, e), scale(u, h)))));
      }
      ctx.strokeStyle = '#bbb';
      [[-1, -1], [1, -1], [1, 1], [-1, 1]].forEach(function (sg) {
        var x = add(o, add(scale(u, sg[0] * h), scale(w, sg[1] * h)));
        corners.push(x[0], x[1], x[2]);
        var q = px(x);
        dec.push(q[0], q[1]);
      });
      V.shapes.push(['plane'].concat(corners, dec));
    });
    D.lines.forEach(function (l) {
      var c = px(pt(f, l[0])), a = dir(unit(pt(f, l[1]))), L = Math.hypot(a[0], a[1]) || 1;
      var e = 2 * (W + H) / L;
      line([c[0] - a[0] * e, c[1] - a[1] * e], [c[0] + a[0] * e, c[1] + a[1] * e]);
      V.shapes.push(['line', c[0], c[1], c[0] + a[0], c[1] + a[1]]);
    });
    // trails
    var nt = Math.round(D.trail / D.dt);
    ctx.lineWidth = 1.5;
    for (var i = 0; i < N && nt > 0; i++) {
      ctx.strokeStyle = palette[i % palette.length] + '55';
      ctx.beginPath();
      for (var g = Math.max(0, f - nt); g <= f; g++) {
        var q = px(pt(g, i));
        if (g > Math.max(0, f - nt)) ctx.lineTo(q[0], q[1]); else ctx.moveTo(q[0], q[1]);
      }
      ctx.stroke();
    }
    // links: rods, springs, dampers; pivots and anchors as small squares
    ctx.strokeStyle = '#444';
    ctx.lineWidth = 2;
    D.links.forEach(function (l) {
      var a = px(pt(f, l[0])), b = px(pt(f, l[1]));
      if (l[2] === 'spring') coil(a, b);
      else if (l[2] === 'damper') dashpot(a, b);
      else line(a, b);
      if (l[0] >= N) {
        ctx.fillStyle = '#444';
        ctx.fillRect(a[0] - 4, a[1] - 4, 8, 8);
      }
    });
    // particles, sized by mass (radius as the cube root)
    V.drawn = [];
    for (i = 0; i < N; i++) {
      var c = px(pt(f, i)), r = Math.max(3, 10 * Math.cbrt(D.particles[i].m / mmax));
      ctx.fillStyle = palette[i % palette.length];
      ctx.beginPath();
      ctx.arc(c[0], c[1], r, 0, 2 * Math.PI);
      ctx.fill();
      V.drawn.push([c[0], c[1]]);
    }
    var t = D.t0 + f * D.dt;
    V.transform = A;
    V.t = t;
    sceneCv.setAttribute('data-transform', JSON.stringify(A));
    sceneCv.setAttribute('data-drawn', JSON.stringify(V.drawn));
    sceneCv.setAttribute('data-shapes', JSON.stringify(V.shapes));
    sceneCv.setAttribute('data-t', String(t));
    sceneCv.setAttribute('data-frame', String(f));
    document.getElementById('time').textContent = 't = ' + t.toFixed(3);
    document.getElementById('slider').value = String(f);
  }

  // the plots: q(t), a phase portrait with the section points, E - E(0), constraint forces
  var plotT = function (s) { return D.t0 + s * D.pstride * D.dt; };
  function axes(cv, title) {
    var c = cv.getContext('2d'), dpr = window.devicePixelRatio || 1, w = 380, h = 112;
    if (cv.width !== w * dpr) {
      cv.width = w * dpr;
      cv.height = h * dpr;
    }
    c.setTransform(dpr, 0, 0, dpr, 0, 0);
    c.clearRect(0, 0, w, h);
    c.fillStyle = '#555';
    c.font = '11px system-ui, sans-serif';
    c.fillText(title, 6, 12);
    return c;
  }
  function range(arr, stride, off, n) {
    var a = Infinity, b = -Infinity;
    for (var s = 0; s < n; s++) {
      var v = arr[s * stride + off];
      if (isFinite(v)) { a = Math.min(a, v); b = Math.max(b, v); }
    }
    if (!(b > a)) { a -= 1e-12 + Math.abs(a) * 1e-6; b += 1e-12 + Math.abs(b) * 1e-6; }
    return [a, b];
  }
  function series(c, xOf, yArr, stride, off, n, col, yr) {
    c.strokeStyle = col;
    c.lineWidth = 1;
    c.beginPath();
    for (var s = 0; s < n; s++) {
      var y = 104 - 88 * (yArr[s * stride + off] - yr[0]) / (yr[1] - yr[0]);
      if (s) c.lineTo(xOf(s), y); else c.moveTo(xOf(s), y);
    }
    c.stroke();
  }
  function timePlot(id, title, arr, names, stride) {
    var c = axes(document.getElementById(id), title), n = D.nplot, T = plotT(n - 1) - D.t0 || 1;
    var xOf = function (s) { return 6 + 368 * (plotT(s) - D.t0) / T; };
    var leg = 14 + c.measureText(title).width, yr = [Infinity, -Infinity];
    for (var j = 0; j < stride; j++) { // one scale for the plot's series
      var rj = range(arr, stride, j, n);
      yr = [Math.min(yr[0], rj[0]), Math.max(yr[1], rj[1])];
    }
    for (j = 0; j < stride; j++) {
      var col = palette[j % palette.length];
      series(c, xOf, arr, stride, j, n, col, yr);
      c.fillStyle = col;
      c.fillText(names[j] || '', leg, 12);
      leg += 8 + c.measureText(names[j] || '').width;
    }
    c.fillStyle = '#888'; // the scale: the largest and smallest value shown
    c.textAlign = 'right';
    c.fillText(yr[1].toPrecision(3), 374, 27);
    c.fillText(yr[0].toPrecision(3), 374, 108);
    c.fillText('t = ' + plotT(n - 1).toPrecision(3), 374, 12);
    c.textAlign = 'left';
    var x = 6 + 368 * (frame * D.dt) / T;
    c.strokeStyle = '#000';
    c.beginPath();
    c.moveTo(x, 16);
    c.lineTo(x, 108);
    c.stroke();
  }
  function phasePlot() {
    var cv = document.getElementById('plot-phase'), kinds = [0, 0];
    D.sections.forEach(function (p) { kinds[p[3]] = 1; });
    var c = axes(cv, 'phase: ' + D.coords[0] + ' vs rate' + (kinds[0] ? '; red: strobe' : '') +
      (kinds[1] ? '; orange: section crossings' : ''));
    var n = D.nplot, xr = range(pq, D.n, 0, n), yr = range(pqd, D.n, 0, n);
    var X = function (v) { return 6 + 368 * (v - xr[0]) / (xr[1] - xr[0]); };
    var Y = function (v) { return 104 - 88 * (v - yr[0]) / (yr[1] - yr[0]); };
    var now = Math.floor(frame / D.pstride), t = D.t0 + frame * D.dt;
    c.strokeStyle = '#ccc';
    c.beginPath();
    for (var s = 0; s < n; s++) {
      if (s) c.lineTo(X(pq[s * D.n]), Y(pqd[s * D.n])); else c.moveTo(X(pq[0]), Y(pqd[0]));
    }
    c.stroke();
    c.strokeStyle = palette[0];
    c.beginPath();
    for (s = 0; s <= now && s < n; s++) {
      if (s) c.lineTo(X(pq[s * D.n]), Y(pqd[s * D.n])); else c.moveTo(X(pq[0]), Y(pqd[0]));
    }
    c.stroke();
    var shown = 0; // the section points filling in: those up to the time shown
    D.sections.forEach(function (p) {
      if (p[0] > t + 1e-9) return;
      c.fillStyle = p[3] ? '#ff7f0e' : '#d62728';
      c.fillRect(X(p[1]) - 1.5, Y(p[2]) - 1.5, 3, 3);
      shown++;
    });
    cv.setAttribute('data-sections-shown', String(shown));
    if (now < n) {
      c.fillStyle = '#000';
      c.beginPath();
      c.arc(X(pq[now * D.n]), Y(pqd[now * D.n]), 3, 0, 2 * Math.PI);
      c.fill();
    }
  }
  function drawPlots() {
    timePlot('plot-q', 'q(t)', pq, D.coords, D.n);
    phasePlot();
    timePlot('plot-energy', 'E - E(0)', pe, [''], 1);
    if (D.jacobi) timePlot('plot-jacobi', 'h - h(0): the Jacobi integral\'s drift', ph, [''], 1);
    timePlot('plot-force', D.forces.length && D.forces[0].charAt(0) === 'l'
      ? 'constraint forces' : 'reaction magnitudes', pf, D.forces, D.forces.length);
  }
  function draw() {
    drawScene();
    drawPlots();
  }

  // controls
  var slider = document.getElementById('slider'), playBtn = document.getElementById('play');
  slider.max = String(F - 1);
  function go(f) {
    frame = Math.max(0, Math.min(F - 1, f));
    draw();
  }
  function setPlaying(p) {
    playing = p;
    playBtn.textContent = p ? 'pause' : 'play';
    last = null;
    if (p) requestAnimationFrame(tick);
  }
  var clock = 0;
  function tick(ms) {
    if (!playing) return;
    if (last !== null) clock += (ms - last) / 1000 * speed;
    last = ms;
    var f = Math.floor(clock / D.dt);
    if (f >= F - 1) { go(F - 1); setPlaying(false); return; }
    if (f !== frame) go(f);
    requestAnimationFrame(tick);
  }
  playBtn.addEventListener('click', function () {
    if (!playing && frame >= F - 1) frame = 0;
    clock = frame * D.dt;
    setPlaying(!playing);
  });
  document.getElementById('prev').addEventListener('click', function () { setPlaying(false); go(frame - 1); });
  document.getElementById('next').addEventListener('click', function () { setPlaying(false); go(frame + 1); });
  slider.addEventListener('input', function () { setPlaying(false); go(parseInt(slider.value, 10)); });
  document.getElementById('speed').addEventListener('change', function (ev) {
    speed = parseFloat(ev.target.value);
  });
  // 3-D: drag to rotate, wheel to zoom
  var drag = null;
  sceneCv.addEventListener('mousedown', function (ev) { drag = [ev.clientX, ev.clientY]; });
  window.addEventListener('mouseup', function () { drag = null; });
  window.addEventListener('mousemove', function (ev) {
    if (!drag || d !== 3) return;
    view.yaw += 0.01 * (ev.clientX - drag[0]);
    view.pitch = Math.max(-1.5, Math.min(1.5, view.pitch + 0.01 * (ev.clientY - drag[1])));
    drag = [ev.clientX, ev.clientY];
    draw();
  });
  sceneCv.addEventListener('wheel', function (ev) {
    ev.preventDefault();
    view.zoom *= Math.exp(-0.001 * ev.deltaY);
    draw();
  }, { passive: false });

  // FILE.html#t=1.25 opens paused at t = 1.25 (drag=DX,DY and wheel=DY replay a drag and a wheel
  // turn: the tests' hooks)
  function fromHash() {
    var h = {}, parts = location.hash.replace(/^#/, '').split('&');
    parts.forEach(function (p) { var kv = p.split('='); if (kv[0]) h[kv[0]] = kv[1]; });
    if (h.drag) {
      var dd = h.drag.split(',').map(parseFloat), r = sceneCv.getBoundingClientRect();
      var x0 = r.left + 100, y0 = r.top + 100;
      sceneCv.dispatchEvent(new MouseEvent('mousedown', { clientX: x0, clientY: y0, bubbles: true }));
      window.dispatchEvent(new MouseEvent('mousemove', { clientX: x0 + dd[0], clientY: y0 + dd[1] }));
      window.dispatchEvent(new MouseEvent('mouseup', { clientX: x0 + dd[0], clientY: y0 + dd[1] }));
    }
    if (h.wheel) { // wheel=DY replays a wheel turn (the tests' hook)
      sceneCv.dispatchEvent(new WheelEvent('wheel', { deltaY: parseFloat(h.wheel), bubbles: true,
        cancelable: true }));
    }
    if (h.t !== undefined) {
      setPlaying(false);
      go(Math.round((parseFloat(h.t) - D.t0) / D.dt));
      return true;
    }
    return false;
  }
  if (D.jacobi) document.getElementById('plot-jacobi').hidden = false;
  window.addEventListener('hashchange', fromHash);
  go(0);
  if (!fromHash()) setPlaying(true);
})();
