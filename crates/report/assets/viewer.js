// The report's 3-D view: the body as shaded tubes (WebGL 1, no library), one frame at a
// time from the embedded run data, orbit by mouse drag, zoom by wheel, a time slider; then
// the checks that set the body's data-status: every image decoded, the GL view drew without
// GL error and shows the body, no error recorded.
(function () {
  "use strict";
  var SIDES = 12;
  var canvas = document.getElementById("view");
  var slider = document.getElementById("frame");
  var label = document.getElementById("time");
  var checks = { webgl: "pending" };

  function finish() {
    var check = function () {
      var images = Array.prototype.slice.call(document.querySelectorAll("img.check"));
      var loaded = images.filter(function (img) { return img.complete && img.naturalWidth > 0; });
      var animation = document.getElementById("animation");
      document.body.dataset.plots = loaded.length + "/" + images.length;
      document.body.dataset.animation = animation.complete && animation.naturalWidth > 0 ? "ok" : "missing";
      document.body.dataset.webgl = checks.webgl;
      var problems = [];
      if (loaded.length !== images.length) problems.push("images " + loaded.length + "/" + images.length);
      if (checks.webgl !== "ok") problems.push("webgl: " + checks.webgl);
      if (window.reportErrors.length) problems.push(window.reportErrors.length + " errors");
      var status = problems.length ? "error: " + problems.join("; ") : "ok";
      document.body.dataset.status = status;
      document.getElementById("status-text").textContent = status;
    };
    if (document.readyState === "complete") check(); else window.addEventListener("load", check);
  }

  function decodeFloats(base64) {
    var text = atob(base64);
    var bytes = new Uint8Array(text.length);
    for (var i = 0; i < text.length; i++) bytes[i] = text.charCodeAt(i);
    return new Float32Array(bytes.buffer);
  }

  function viridis(t) {
    var stops = [[68, 1, 84], [65, 68, 135], [42, 120, 142], [34, 168, 132], [122, 209, 81], [253, 231, 37]];
    var x = Math.min(Math.max(t, 0), 1) * (stops.length - 1);
    var i = Math.min(Math.floor(x), stops.length - 2), w = x - i;
    return [0, 1, 2].map(function (c) { return (stops[i][c] * (1 - w) + stops[i + 1][c] * w) / 255; });
  }

  // --- small vector and matrix helpers (column-major 4×4) ---
  function sub(a, b) { return [a[0] - b[0], a[1] - b[1], a[2] - b[2]]; }
  function dot(a, b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
  function cross(a, b) { return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]; }
  function normalise(a) { var n = Math.sqrt(dot(a, a)) || 1; return [a[0] / n, a[1] / n, a[2] / n]; }
  function perspective(fovy, aspect, near, far) {
    var f = 1 / Math.tan(fovy / 2), d = near - far;
    return [f / aspect, 0, 0, 0, 0, f, 0, 0, 0, 0, (far + near) / d, -1, 0, 0, 2 * far * near / d, 0];
  }
  function lookAt(eye, target, up) {
    var z = normalise(sub(eye, target)), x = normalise(cross(up, z)), y = cross(z, x);
    return [x[0], y[0], z[0], 0, x[1], y[1], z[1], 0, x[2], y[2], z[2], 0,
      -dot(x, eye), -dot(y, eye), -dot(z, eye), 1];
  }
  function multiply(a, b) {
    var r = new Array(16);
    for (var c = 0; c < 4; c++) for (var row = 0; row < 4; row++) {
      var s = 0;
      for (var k = 0; k < 4; k++) s += a[k * 4 + row] * b[c * 4 + k];
      r[c * 4 + row] = s;
    }
    return r;
  }

  function start() {
    var data = JSON.parse(document.getElementById("run-data").textContent);
    var frames = data.frames, bodies = data.bodies;
    var points = decodeFloats(data.points);
    var gl = canvas.getContext("webgl", { antialias: true });
    if (!gl) { checks.webgl = "no WebGL context"; return; }

    function point(f, b) { var i = 3 * (f * bodies + b); return [points[i], points[i + 1], points[i + 2]]; }

    // Tube vertices of frame f: a ring of SIDES vertices per body (rotation-minimising
    // frames), then the centres of the head and tail caps.
    function tube(f, positions, normals) {
      var n = null, ends = [];
      for (var b = 0; b < bodies; b++) {
        var p = point(f, b);
        var t = normalise(sub(point(f, Math.min(b + 1, bodies - 1)), point(f, Math.max(b - 1, 0))));
        if (n === null) n = Math.abs(t[2]) < 0.9 ? [0, 0, 1] : [1, 0, 0];
        var k = dot(n, t);
        n = normalise([n[0] - k * t[0], n[1] - k * t[1], n[2] - k * t[2]]);
        var m = cross(t, n), r = data.radii[b];
        if (b === 0) ends.push([p, [-t[0], -t[1], -t[2]]]);
        if (b === bodies - 1) ends.push([p, t]);
        for (var s = 0; s < SIDES; s++) {
          var a = 2 * Math.PI * s / SIDES, c = Math.cos(a), d = Math.sin(a);
          var dir = [c * n[0] + d * m[0], c * n[1] + d * m[1], c * n[2] + d * m[2]];
          var i = 3 * (b * SIDES + s);
          for (var j = 0; j < 3; j++) { positions[i + j] = p[j] + r * dir[j]; normals[i + j] = dir[j]; }
        }
      }
      ends.forEach(function (end, e) {
        positions.set(end[0], 3 * (bodies * SIDES + e));
        normals.set(end[1], 3 * (bodies * SIDES + e));
      });
    }


    var vertexSource =
      "attribute vec3 position; attribute vec3 normal; attribute vec3 colour;" +
      "uniform mat4 transform; uniform vec3 eye; varying vec3 v_normal; varying vec3 v_colour; varying vec3 v_view;" +
      "void main() { v_normal = normal; v_colour = colour; v_view = eye - position; gl_Position = transform * vec4(position, 1.0); }";
    var fragmentSource =
      "precision mediump float; varying vec3 v_normal; varying vec3 v_colour; varying vec3 v_view; uniform float alpha;" +
      "void main() { vec3 n = normalize(v_normal); vec3 l = normalize(vec3(0.3, -0.5, 0.8));" +
      " float headlight = abs(dot(n, normalize(v_view)));" +
      " float light = 0.25 + 0.45 * max(dot(n, l), 0.0) + 0.35 * headlight;" +
      " gl_FragColor = vec4(v_colour * light, alpha); }";
    function compile(type, source) {
      var shader = gl.createShader(type);
      gl.shaderSource(shader, source);
      gl.compileShader(shader);
      if (!gl.getShaderParameter(shader, gl.COMPILE_STATUS)) throw new Error(gl.getShaderInfoLog(shader));
      return shader;
    }
    var program = gl.createProgram();
    gl.attachShader(program, compile(gl.VERTEX_SHADER, vertexSource));
    gl.attachShader(program, compile(gl.FRAGMENT_SHADER, fragmentSource));
    gl.linkProgram(program);
    if (!gl.getProgramParameter(program, gl.LINK_STATUS)) throw new Error(gl.getProgramInfoLog(program));
    gl.useProgram(program);
    var at = {
      position: gl.getAttribLocation(program, "position"),
      normal: gl.getAttribLocation(program, "normal"),
      colour: gl.getAttribLocation(program, "colour"),
      transform: gl.getUniformLocation(program, "transform"),
      eye: gl.getUniformLocation(program, "eye"),
      alpha: gl.getUniformLocation(program, "alpha")
    };

    // Bounds over all frames: the orbit centre and the wall's extent.
    var low = [Infinity, Infinity, Infinity], high = [-Infinity, -Infinity, -Infinity];
    for (var i = 0; i < points.length; i++) {
      low[i % 3] = Math.min(low[i % 3], points[i]);
      high[i % 3] = Math.max(high[i % 3], points[i]);
    }
    var centre = [0, 1, 2].map(function (a) { return (low[a] + high[a]) / 2; });
    var size = Math.max(high[0] - low[0], high[1] - low[1], high[2] - low[2], 1);

    function buffer(target, array, usage) {
      var b = gl.createBuffer();
      gl.bindBuffer(target, b);
      gl.bufferData(target, array, usage);
      return b;
    }
    // The body: static colours and indices, positions and normals per frame.
    var vertices = bodies * SIDES + 2, head = bodies * SIDES, tail = head + 1;
    var tubePositions = new Float32Array(3 * vertices), tubeNormals = new Float32Array(3 * vertices);
    var tubeColours = new Float32Array(3 * vertices), tubeIndices = [];
    for (var b = 0; b < bodies; b++) {
      var c = viridis(b / Math.max(bodies - 1, 1));
      for (var s = 0; s < SIDES; s++) tubeColours.set(c, 3 * (b * SIDES + s));
      if (b + 1 < bodies) for (s = 0; s < SIDES; s++) {
        var p0 = b * SIDES + s, p1 = b * SIDES + (s + 1) % SIDES;
        tubeIndices.push(p0, p0 + SIDES, p1, p1, p0 + SIDES, p1 + SIDES);
      }
    }
    tubeColours.set(viridis(0), 3 * head);
    tubeColours.set(viridis(1), 3 * tail);
    for (s = 0; s < SIDES; s++) {
      var next = (s + 1) % SIDES, last = (bodies - 1) * SIDES;
      tubeIndices.push(head, next, s, tail, last + s, last + next);
    }
    var body = {
      position: buffer(gl.ARRAY_BUFFER, tubePositions, gl.DYNAMIC_DRAW),
      normal: buffer(gl.ARRAY_BUFFER, tubeNormals, gl.DYNAMIC_DRAW),
      colour: buffer(gl.ARRAY_BUFFER, tubeColours, gl.STATIC_DRAW),
      index: buffer(gl.ELEMENT_ARRAY_BUFFER, new Uint16Array(tubeIndices), gl.STATIC_DRAW),
      count: tubeIndices.length
    };
    // The wall x = 0: a grey square around the run's y–z extent.
    var h = 0.6 * size, wc = [0, centre[1], centre[2]];
    var wallPositions = new Float32Array([0, wc[1] - h, wc[2] - h, 0, wc[1] + h, wc[2] - h, 0, wc[1] + h, wc[2] + h, 0, wc[1] - h, wc[2] + h]);
    var wall = {
      position: buffer(gl.ARRAY_BUFFER, wallPositions, gl.STATIC_DRAW),
      normal: buffer(gl.ARRAY_BUFFER, new Float32Array([1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0]), gl.STATIC_DRAW),
      colour: buffer(gl.ARRAY_BUFFER, new Float32Array([0.5, 0.5, 0.55, 0.5, 0.5, 0.55, 0.5, 0.5, 0.55, 0.5, 0.5, 0.55]), gl.STATIC_DRAW),
      index: buffer(gl.ELEMENT_ARRAY_BUFFER, new Uint16Array([0, 1, 2, 0, 2, 3]), gl.STATIC_DRAW),
      count: 6
    };

    // The obstacles: grey line segments, moved to each frame's pose (R row by row, then t)
    // when they move or turn.
    var obstacles = (data.obstacles || []).map(function (o) {
      var base = new Float32Array(o.segments), n = base.length / 3;
      var up = new Float32Array(3 * n), index = new Uint16Array(n);
      for (var v = 0; v < n; v++) { up[3 * v + 2] = 1; index[v] = v; }
      return {
        base: base, poses: o.poses, moved: new Float32Array(base.length),
        position: buffer(gl.ARRAY_BUFFER, base, gl.DYNAMIC_DRAW),
        normal: buffer(gl.ARRAY_BUFFER, up, gl.STATIC_DRAW),
        colour: buffer(gl.ARRAY_BUFFER, new Float32Array(3 * n).fill(0.35), gl.STATIC_DRAW),
        index: buffer(gl.ELEMENT_ARRAY_BUFFER, index, gl.STATIC_DRAW),
        count: n
      };
    });

    var yaw = -1.0, pitch = 0.5, distance = 1.2 * size, frame = 0;

    function bind(mesh) {
      [["position", mesh.position], ["normal", mesh.normal], ["colour", mesh.colour]].forEach(function (pair) {
        gl.bindBuffer(gl.ARRAY_BUFFER, pair[1]);
        gl.enableVertexAttribArray(at[pair[0]]);
        gl.vertexAttribPointer(at[pair[0]], 3, gl.FLOAT, false, 0, 0);
      });
      gl.bindBuffer(gl.ELEMENT_ARRAY_BUFFER, mesh.index);
    }

    function draw() {
      tube(frame, tubePositions, tubeNormals);
      gl.bindBuffer(gl.ARRAY_BUFFER, body.position);
      gl.bufferSubData(gl.ARRAY_BUFFER, 0, tubePositions);
      gl.bindBuffer(gl.ARRAY_BUFFER, body.normal);
      gl.bufferSubData(gl.ARRAY_BUFFER, 0, tubeNormals);
      var eye = [centre[0] + distance * Math.cos(pitch) * Math.cos(yaw),
        centre[1] + distance * Math.cos(pitch) * Math.sin(yaw),
        centre[2] + distance * Math.sin(pitch)];
      var transform = multiply(perspective(0.8, canvas.width / canvas.height, 0.05 * size, 20 * size), lookAt(eye, centre, [0, 0, 1]));
      gl.viewport(0, 0, canvas.width, canvas.height);
      gl.clearColor(1, 1, 1, 1);
      gl.clear(gl.COLOR_BUFFER_BIT | gl.DEPTH_BUFFER_BIT);
      gl.enable(gl.DEPTH_TEST);
      gl.uniformMatrix4fv(at.transform, false, new Float32Array(transform));
      gl.uniform3fv(at.eye, new Float32Array(eye));
      gl.disable(gl.BLEND);
      gl.uniform1f(at.alpha, 1.0);
      bind(body);
      gl.drawElements(gl.TRIANGLES, body.count, gl.UNSIGNED_SHORT, 0);
      obstacles.forEach(function (o) {
        if (o.poses.length) {
          var p = o.poses.slice(12 * frame, 12 * frame + 12);
          for (var i = 0; i < o.base.length; i += 3) {
            var x = o.base[i], y = o.base[i + 1], z = o.base[i + 2];
            for (var a = 0; a < 3; a++) o.moved[i + a] = p[3 * a] * x + p[3 * a + 1] * y + p[3 * a + 2] * z + p[9 + a];
          }
          gl.bindBuffer(gl.ARRAY_BUFFER, o.position);
          gl.bufferSubData(gl.ARRAY_BUFFER, 0, o.moved);
        }
        bind(o);
        gl.drawElements(gl.LINES, o.count, gl.UNSIGNED_SHORT, 0);
      });
      gl.enable(gl.BLEND);
      gl.blendFunc(gl.SRC_ALPHA, gl.ONE_MINUS_SRC_ALPHA);
      gl.uniform1f(at.alpha, 0.5);
      bind(wall);
      gl.drawElements(gl.TRIANGLES, wall.count, gl.UNSIGNED_SHORT, 0);
      var state = frame < data.states.length ? ", " + data.states[frame] : "";
      label.textContent = "t = " + data.times[frame].toFixed(2) + " s (frame " + frame + " of " + (frames - 1) + state + ")";
    }

    // Counts pixels that differ from the white background: the body must cover some.
    function drawnPixels() {
      var pixels = new Uint8Array(4 * canvas.width * canvas.height);
      gl.readPixels(0, 0, canvas.width, canvas.height, gl.RGBA, gl.UNSIGNED_BYTE, pixels);
      var count = 0;
      for (var i = 0; i < pixels.length; i += 4) if (pixels[i] < 200 || pixels[i + 1] < 200 || pixels[i + 2] < 200) count++;
      return count;
    }

    slider.max = String(frames - 1);
    slider.addEventListener("input", function () { frame = Number(slider.value); draw(); });
    var dragging = null;
    canvas.addEventListener("mousedown", function (e) { dragging = [e.clientX, e.clientY]; });
    window.addEventListener("mouseup", function () { dragging = null; });
    window.addEventListener("mousemove", function (e) {
      if (!dragging) return;
      yaw -= 0.01 * (e.clientX - dragging[0]);
      pitch = Math.max(-1.5, Math.min(1.5, pitch + 0.01 * (e.clientY - dragging[1])));
      dragging = [e.clientX, e.clientY];
      draw();
    });
    canvas.addEventListener("wheel", function (e) {
      e.preventDefault();
      distance = Math.max(0.3 * size, Math.min(10 * size, distance * Math.exp(0.001 * e.deltaY)));
      draw();
    }, { passive: false });
    var playing = null;
    document.getElementById("play").addEventListener("click", function (e) {
      if (playing) { clearInterval(playing); playing = null; e.target.textContent = "play"; return; }
      e.target.textContent = "pause";
      playing = setInterval(function () {
        frame = (frame + 1) % frames; slider.value = String(frame); draw();
      }, 40);
    });

    frame = frames - 1;
    slider.value = String(frame);
    draw();
    var error = gl.getError(), drawn = drawnPixels();
    checks.webgl = error !== gl.NO_ERROR ? "GL error " + error : drawn < 100 ? "only " + drawn + " pixels drawn" : "ok";
    canvas.dataset.drawnPixels = String(drawn);
  }

  try {
    start();
  } catch (e) {
    window.recordError("3-D view: " + (e && e.message ? e.message : e));
    checks.webgl = "exception";
  }
  finish();
})();
