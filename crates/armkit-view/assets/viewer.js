// armkit's 3-D viewer: draws a scene that armkit computed (link world
// transforms per frame, from armkit's own forward kinematics) with the
// vendored three.js (the global THREE of three.bundle.js). The page does no
// kinematics: it places each link's group at the transform of the frame
// shown. World frame z up, metres.
//
// Scene data (JSON, written by crates/armkit-view/src/scene.rs):
//   title, joints[names], times[s], q[frame][joint],
//   links[{name, shapes[...]}], poses[frame][link] = [px,py,pz,qx,qy,qz,qw],
//   meshes[{positions: base64 f32 xyz, indices: base64 u32}],
//   path[[x,y,z]], path_flags[0|1 per point], markers[{at:[x,y,z], color, label}],
//   beam (optional): {joint, magnification, samples[frame][[x,y,z]...]}, reach (m).
//
// window.armkitView (the test hook) reads the transforms back from the
// scene graph (each link group's matrixWorld), not from the data.
(function () {
  'use strict';
  var ROBOT_COLOR = 0xe07b39;
  var PATH_COLOR = [0.85, 0.2, 0.6];
  var SINGULAR_COLOR = [0.85, 0.1, 0.1];

  function decode(base64, Type) {
    var bytes = atob(base64);
    var buffer = new ArrayBuffer(bytes.length);
    var view = new Uint8Array(buffer);
    for (var i = 0; i < bytes.length; i++) view[i] = bytes.charCodeAt(i);
    return new Type(buffer);
  }

  function colorOf(shape) {
    if (shape.color) return new THREE.Color(shape.color[0], shape.color[1], shape.color[2]);
    return new THREE.Color(ROBOT_COLOR);
  }

  function material(shape) {
    var opacity = shape.color && shape.color.length > 3 ? shape.color[3] : 1;
    return new THREE.MeshStandardMaterial({
      color: colorOf(shape), metalness: 0.1, roughness: 0.6,
      transparent: opacity < 1, opacity: opacity, side: THREE.DoubleSide,
    });
  }

  // A shape's placement in its link frame: [x,y,z, qx,qy,qz,qw].
  function place(object, origin) {
    if (!origin) return object;
    object.position.set(origin[0], origin[1], origin[2]);
    object.quaternion.set(origin[3], origin[4], origin[5], origin[6]);
    return object;
  }

  function shapeObject(shape, meshes) {
    var m = material(shape);
    if (shape.kind === 'capsule') {
      var a = new THREE.Vector3().fromArray(shape.from);
      var b = new THREE.Vector3().fromArray(shape.to);
      var length = a.distanceTo(b);
      var capsule = new THREE.Mesh(new THREE.CapsuleGeometry(shape.radius, length, 6, 16), m);
      capsule.position.copy(a).add(b).multiplyScalar(0.5);
      if (length > 0) {
        capsule.quaternion.setFromUnitVectors(new THREE.Vector3(0, 1, 0), b.clone().sub(a).normalize());
      }
      return capsule;
    }
    var object;
    if (shape.kind === 'box') {
      object = new THREE.Mesh(new THREE.BoxGeometry(shape.size[0], shape.size[1], shape.size[2]), m);
    } else if (shape.kind === 'cylinder') {
      // URDF cylinders run along z, three.js's along y.
      var geometry = new THREE.CylinderGeometry(shape.radius, shape.radius, shape.length, 24);
      geometry.rotateX(Math.PI / 2);
      object = new THREE.Mesh(geometry, m);
    } else if (shape.kind === 'sphere') {
      object = new THREE.Mesh(new THREE.SphereGeometry(shape.radius, 24, 16), m);
    } else if (shape.kind === 'mesh') {
      var source = meshes[shape.mesh];
      var g = new THREE.BufferGeometry();
      g.setAttribute('position', new THREE.BufferAttribute(decode(source.positions, Float32Array), 3));
      g.setIndex(new THREE.BufferAttribute(decode(source.indices, Uint32Array), 1));
      g.computeVertexNormals();
      object = new THREE.Mesh(g, m);
      if (shape.scale) object.scale.set(shape.scale[0], shape.scale[1], shape.scale[2]);
    } else {
      return null;
    }
    return place(object, shape.origin);
  }

  function textSprite(text, size) {
    var canvas = document.createElement('canvas');
    canvas.width = 128; canvas.height = 64;
    var ctx = canvas.getContext('2d');
    ctx.fillStyle = '#333';
    ctx.font = '36px sans-serif';
    ctx.textAlign = 'center';
    ctx.textBaseline = 'middle';
    ctx.fillText(text, 64, 32);
    var sprite = new THREE.Sprite(new THREE.SpriteMaterial({ map: new THREE.CanvasTexture(canvas), depthTest: false }));
    sprite.scale.set(size, size / 2, 1);
    return sprite;
  }

  // Floor grid in the xy plane with a label every metre (every 0.5 m when
  // the robot is small), world axes at the origin.
  function addFloor(scene, reach, root) {
    var half = Math.max(1, Math.ceil(reach * 1.2));
    // Squares of 0.1 m on a robot's scale, 0.5 m on a gantry's.
    var cell = half <= 2 ? 0.1 : 0.5;
    var grid = new THREE.GridHelper(2 * half, Math.round(2 * half / cell), 0x999999, 0xdddddd);
    grid.rotation.x = Math.PI / 2;
    scene.add(grid);
    var step = half <= 1 ? 0.5 : half <= 5 ? 1 : 2;
    var label = Math.max(0.12, 0.15 * half);
    for (var v = step; v <= half + 1e-9; v += step) {
      var tx = textSprite(v + ' m', label); tx.position.set(v, -0.06 * half, 0); scene.add(tx);
      var ty = textSprite(v + ' m', label); ty.position.set(-0.06 * half, v, 0); scene.add(ty);
    }
    scene.add(worldAxes(Math.max(0.25, 0.3 * reach)));
    var legend = root.querySelector('.armkit-cell');
    if (legend) legend.textContent = cell + ' m';
  }

  // The world axes as thick bars (x red, y green, z blue): a line helper's
  // one-pixel lines vanish against the grid.
  function worldAxes(length) {
    var group = new THREE.Group();
    var radius = length / 40;
    [[0xd62728, new THREE.Vector3(1, 0, 0)], [0x2ca02c, new THREE.Vector3(0, 1, 0)],
     [0x1f77b4, new THREE.Vector3(0, 0, 1)]].forEach(function (axis) {
      var bar = new THREE.Mesh(new THREE.CylinderGeometry(radius, radius, length, 12),
        new THREE.MeshStandardMaterial({ color: axis[0] }));
      bar.quaternion.setFromUnitVectors(new THREE.Vector3(0, 1, 0), axis[1]);
      bar.position.copy(axis[1]).multiplyScalar(length / 2);
      group.add(bar);
    });
    return group;
  }

  function pathLine(data) {
    if (!data.path || data.path.length < 2) return null;
    var positions = new Float32Array(data.path.length * 3);
    var colors = new Float32Array(data.path.length * 3);
    data.path.forEach(function (p, i) {
      positions.set(p, 3 * i);
      var flagged = data.path_flags && data.path_flags[i];
      colors.set(flagged ? SINGULAR_COLOR : PATH_COLOR, 3 * i);
    });
    var g = new THREE.BufferGeometry();
    g.setAttribute('position', new THREE.BufferAttribute(positions, 3));
    g.setAttribute('color', new THREE.BufferAttribute(colors, 3));
    return new THREE.Line(g, new THREE.LineBasicMaterial({ vertexColors: true }));
  }

  function frameAt(times, t) {
    var k = 0;
    while (k + 1 < times.length && times[k + 1] <= t) k++;
    return k;
  }

  function mount(root, data) {
    var canvasBox = root.querySelector('.armkit-canvas');
    var width = canvasBox.clientWidth || 760, height = canvasBox.clientHeight || 480;
    var renderer;
    try {
      renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
    } catch (e) {
      root.querySelector('.armkit-status').textContent = '3-D view unavailable (no WebGL): ' + e.message;
      var fallback = root.querySelector('.armkit-fallback');
      if (fallback) fallback.style.display = 'block';
      return null;
    }
    renderer.setPixelRatio(1);
    renderer.setSize(width, height);
    renderer.setClearColor(0xfbfbfd);
    canvasBox.appendChild(renderer.domElement);

    var scene = new THREE.Scene();
    scene.add(new THREE.HemisphereLight(0xffffff, 0x888899, 1.6));
    var sun = new THREE.DirectionalLight(0xffffff, 1.6);
    sun.position.set(2, -3, 5);
    scene.add(sun);
    var reach = data.reach || 1;
    addFloor(scene, reach, root);

    var camera = new THREE.PerspectiveCamera(40, width / height, 0.01, 100);
    camera.up.set(0, 0, 1);
    camera.position.set(1.5 * reach, -1.9 * reach, 1.15 * reach);
    var controls = new THREE.OrbitControls(camera, renderer.domElement);
    controls.target.set(0, 0, 0.35 * reach);
    controls.update();

    var frames = [];
    var robot = new THREE.Group();
    scene.add(robot);
    var links = data.links.map(function (link) {
      var group = new THREE.Group();
      group.name = link.name;
      link.shapes.forEach(function (shape) {
        var object = shapeObject(shape, data.meshes || []);
        if (object) group.add(object);
      });
      var axes = new THREE.AxesHelper(Math.max(0.05, 0.08 * reach));
      axes.visible = false;
      group.add(axes);
      frames.push(axes);
      robot.add(group);
      return group;
    });
    var path = pathLine(data);
    if (path) scene.add(path);
    (data.markers || []).forEach(function (marker) {
      var sphere = new THREE.Mesh(new THREE.SphereGeometry(0.015 * reach + 0.005, 16, 12),
        new THREE.MeshStandardMaterial({ color: new THREE.Color(marker.color[0], marker.color[1], marker.color[2]) }));
      sphere.position.fromArray(marker.at);
      scene.add(sphere);
    });
    var beam = null;
    if (data.beam) {
      var beamGeometry = new THREE.BufferGeometry();
      beamGeometry.setAttribute('position', new THREE.BufferAttribute(new Float32Array(data.beam.samples[0].length * 3), 3));
      beam = new THREE.Line(beamGeometry, new THREE.LineBasicMaterial({ color: 0x1f4e79, linewidth: 3 }));
      scene.add(beam);
    }

    var slider = root.querySelector('.armkit-slider');
    var playButton = root.querySelector('.armkit-play');
    var speedSelect = root.querySelector('.armkit-speed');
    var timeLabel = root.querySelector('.armkit-time');
    var jointsLabel = root.querySelector('.armkit-joints');
    var framesBox = root.querySelector('.armkit-frames');
    var beamBox = root.querySelector('.armkit-beam');
    slider.max = String(Math.max(0, data.times.length - 1));

    var current = 0;
    function show(k) {
      current = k;
      var poses = data.poses[k];
      links.forEach(function (group, i) {
        var p = poses[i];
        group.position.set(p[0], p[1], p[2]);
        group.quaternion.set(p[3], p[4], p[5], p[6]);
      });
      if (beam) {
        var magnified = !beamBox || beamBox.checked;
        var attribute = beam.geometry.getAttribute('position');
        var samples = data.beam.samples[k];
        var straight = data.beam.straight[k];
        for (var s = 0; s < samples.length; s++) {
          var m = magnified ? data.beam.magnification : 1;
          for (var c = 0; c < 3; c++) attribute.array[3 * s + c] = straight[s][c] + m * (samples[s][c] - straight[s][c]);
        }
        attribute.needsUpdate = true;
      }
      robot.updateMatrixWorld(true);
      slider.value = String(k);
      timeLabel.textContent = 't = ' + data.times[k].toFixed(3) + ' s';
      jointsLabel.textContent = data.joints.map(function (name, j) {
        return name + ' = ' + data.q[k][j].toFixed(4);
      }).join(', ');
    }
    function render() { renderer.render(scene, camera); }

    var playing = data.times.length > 1, speed = 1, clock = data.times[0] || 0, last = null;
    var duration = data.times[data.times.length - 1] - data.times[0];
    function loop(now) {
      if (playing && last !== null && duration > 0) {
        clock += speed * (now - last) / 1000;
        if (clock > data.times[data.times.length - 1]) clock = data.times[0];
        var k = frameAt(data.times, clock);
        if (k !== current) show(k);
      }
      last = now;
      controls.update();
      render();
      requestAnimationFrame(loop);
    }
    playButton.textContent = playing ? 'pause' : 'play';
    playButton.addEventListener('click', function () {
      playing = !playing;
      playButton.textContent = playing ? 'pause' : 'play';
    });
    speedSelect.addEventListener('change', function () { speed = parseFloat(speedSelect.value); });
    slider.addEventListener('input', function () {
      playing = false;
      playButton.textContent = 'play';
      var k = parseInt(slider.value, 10);
      clock = data.times[k];
      show(k);
    });
    if (framesBox) framesBox.addEventListener('change', function () {
      frames.forEach(function (a) { a.visible = framesBox.checked; });
    });
    if (beamBox) beamBox.addEventListener('change', function () { show(current); });
    show(0);
    render();
    var firstRender = performance.now();
    requestAnimationFrame(loop);

    // Pixels that change when the robot is hidden: the robot is drawn.
    function robotPixels() {
      var gl = renderer.getContext();
      var w = gl.drawingBufferWidth, h = gl.drawingBufferHeight;
      var withRobot = new Uint8Array(w * h * 4), without = new Uint8Array(w * h * 4);
      render();
      gl.readPixels(0, 0, w, h, gl.RGBA, gl.UNSIGNED_BYTE, withRobot);
      robot.visible = false;
      render();
      gl.readPixels(0, 0, w, h, gl.RGBA, gl.UNSIGNED_BYTE, without);
      robot.visible = true;
      render();
      var count = 0;
      for (var i = 0; i < w * h * 4; i += 4) {
        if (Math.abs(withRobot[i] - without[i]) + Math.abs(withRobot[i + 1] - without[i + 1]) +
            Math.abs(withRobot[i + 2] - without[i + 2]) > 24) count++;
      }
      return count;
    }

    return {
      title: data.title,
      times: data.times,
      joints: data.joints,
      linkNames: data.links.map(function (l) { return l.name; }),
      firstRenderMs: firstRender,
      // The frame shown at time t (the last frame at or before t), its
      // configuration and every link's world transform read from the scene
      // graph (column-major 4x4, three.js's order).
      at: function (t) {
        playing = false;
        playButton.textContent = 'play';
        var k = frameAt(data.times, t);
        show(k);
        return {
          frame: k, t: data.times[k], q: data.q[k].slice(),
          links: links.map(function (group) {
            return { name: group.name, matrix: group.matrixWorld.elements.slice() };
          }),
        };
      },
      robotPixels: robotPixels,
    };
  }

  // The test mode (#armkit-test): the page writes what the hook returns at
  // a few times, the robot's pixel count and the time to the first render
  // into <pre id="armkit-test-result">, for a headless browser's --dump-dom.
  function selfTest(view) {
    var n = view.times.length;
    var picks = [0, Math.floor(n / 3), Math.floor((2 * n) / 3), n - 1];
    var result = {
      title: view.title,
      firstRenderMs: view.firstRenderMs,
      robotPixels: view.robotPixels(),
      samples: picks.map(function (k) { return view.at(view.times[k]); }),
    };
    var pre = document.createElement('pre');
    pre.id = 'armkit-test-result';
    pre.textContent = JSON.stringify(result);
    document.body.appendChild(pre);
  }

  function start() {
    var views = [];
    var roots = document.querySelectorAll('.armkit-view');
    for (var i = 0; i < roots.length; i++) {
      var source = document.getElementById(roots[i].getAttribute('data-scene'));
      var view = mount(roots[i], JSON.parse(source.textContent));
      if (view) views.push(view);
    }
    // #armkit-view-only: the first view alone on the page (for screenshots).
    if (roots.length && location.hash === '#armkit-view-only') {
      var children = document.body.children;
      for (var c = 0; c < children.length; c++) {
        if (!children[c].contains(roots[0]) && children[c].tagName !== 'SCRIPT') children[c].style.display = 'none';
      }
    }
    window.armkitView = views[0] || null;
    window.armkitViews = views;
    if (views.length && location.hash.indexOf('#armkit-test') === 0) selfTest(views[0]);
  }
  if (document.readyState === 'loading') document.addEventListener('DOMContentLoaded', start);
  else start();
})();
