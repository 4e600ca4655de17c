// The medax viewer: the page's data (a <script type="application/json">) drawn with three.js.
// One BufferGeometry and one draw call per layer. Settings come from the URL query, so that
// `medax snapshot` and a bookmarked page show the same scene:
//   field=NAME|vertex:NAME|face:NAME|edge:NAME|none   colour map (default: radius)
//   layers=surface,triangles,curves,vertices,spheres,reconstruction,...   shown layers
//   view=iso|front|back|left|right|top|bottom   camera preset;  zoom=F   closer (>1) or farther
//   min=, max=   colour range;  pick=I   show medial vertex I's sphere
//   w=, h=   canvas size in pixels (default: the window);  ui=0   no panel;  legend=0   no legend
//   bench=N   render N frames orbiting the shape and record the mean frame time in #status
// #status (hidden) records for tests and measurements: state, errors, field, triangles, load and frame ms.
(function () {
  'use strict';
  const status = { state: 'loading', errors: 0, messages: [] };
  const statusElement = document.getElementById('status');
  function writeStatus() {
    statusElement.dataset.state = status.state;
    statusElement.dataset.errors = String(status.errors);
    statusElement.textContent = status.messages.join('\n');
  }
  // Every error is counted in #status and logged with a prefix `medax snapshot` looks for.
  const consoleError = console.error.bind(console);
  function recordError(text) {
    status.errors += 1;
    status.messages.push(text);
    writeStatus();
    consoleError('medax-viewer error: ' + text);
  }
  window.addEventListener('error', (e) => recordError('Uncaught ' + e.message));
  console.error = (...args) => recordError(args.join(' '));

  const query = new URLSearchParams(location.search);
  const data = JSON.parse(document.getElementById('medax-data').textContent);

  // ---- decoding ----
  function decode(base64, Type) {
    if (!base64) return new Type(0);
    const text = atob(base64);
    const bytes = new Uint8Array(text.length);
    for (let i = 0; i < text.length; ++i) bytes[i] = text.charCodeAt(i);
    return new Type(bytes.buffer);
  }
  const medial = {
    positions: decode(data.medial.positions, Float32Array),
    radii: decode(data.medial.radii, Float32Array),
    triangles: decode(data.medial.triangles, Uint32Array),
    curves: decode(data.medial.curves, Uint32Array),
  };
  const fields = data.medial.fields.map((f) => ({
    key: f.element + ':' + f.name, name: f.name, element: f.element, label: f.label,
    values: decode(f.values, Float32Array),
  }));

  // ---- colours ----
  const kViridis = [[0.267, 0.005, 0.329], [0.283, 0.141, 0.458], [0.254, 0.265, 0.530], [0.207, 0.372, 0.553],
    [0.164, 0.471, 0.558], [0.128, 0.567, 0.551], [0.135, 0.659, 0.518], [0.267, 0.749, 0.441],
    [0.478, 0.821, 0.318], [0.741, 0.873, 0.150], [0.993, 0.906, 0.144]];
  const kNoValue = [0.6, 0.6, 0.6];
  const kPlain = { triangles: [0.35, 0.55, 0.85], curves: [0.85, 0.2, 0.15], vertices: [0.15, 0.15, 0.15] };
  function viridis(t) {
    const x = Math.min(Math.max(t, 0), 1) * (kViridis.length - 1);
    const i = Math.min(Math.floor(x), kViridis.length - 2);
    const f = x - i;
    return [0, 1, 2].map((c) => kViridis[i][c] * (1 - f) + kViridis[i + 1][c] * f);
  }
  // Labels (sheet id, cluster id, ...) get distinct hues, the same for the same label everywhere.
  function labelColour(v) {
    const hue = ((v * 0.618033988749895) % 1 + 1) % 1;
    const c = new THREE.Color().setHSL(hue, 0.7, 0.5);
    return [c.r, c.g, c.b];
  }
  function fieldRange(field) {
    let lo = Infinity, hi = -Infinity;
    for (const v of field.values) if (Number.isFinite(v)) { lo = Math.min(lo, v); hi = Math.max(hi, v); }
    return lo <= hi ? [lo, hi] : [0, 1];
  }
  function colourOf(field, range) {
    if (field.label) return (v) => (Number.isFinite(v) ? labelColour(v) : kNoValue);
    const span = range[1] - range[0] || 1;
    return (v) => (Number.isFinite(v) ? viridis((v - range[0]) / span) : kNoValue);
  }

  // ---- the scene ----
  const width = Number(query.get('w')) || window.innerWidth;
  const height = Number(query.get('h')) || window.innerHeight;
  const renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
  renderer.setPixelRatio(query.has('w') ? 1 : window.devicePixelRatio);
  renderer.setSize(width, height);
  document.body.appendChild(renderer.domElement);
  const scene = new THREE.Scene();
  scene.background = new THREE.Color(0xffffff);
  scene.add(new THREE.HemisphereLight(0xffffff, 0x666666, 0.7));
  const camera = new THREE.PerspectiveCamera(35, width / height, 1e-3, 1e3);
  const headLight = new THREE.DirectionalLight(0xffffff, 0.6);
  camera.add(headLight);
  scene.add(camera);

  // Medial triangles and curves: their own copy of each corner (not indexed), so that a face or
  // edge field colours its element flat.
  function expandedGeometry(positions, corners) {
    const p = new Float32Array(corners.length * 3);
    for (let k = 0; k < corners.length; ++k)
      for (let c = 0; c < 3; ++c) p[3 * k + c] = positions[3 * corners[k] + c];
    const g = new THREE.BufferGeometry();
    g.setAttribute('position', new THREE.BufferAttribute(p, 3));
    g.setAttribute('color', new THREE.BufferAttribute(new Float32Array(p.length), 3));
    return g;
  }
  const layers = {};
  function addLayer(id, name, object, visible) {
    object.visible = visible;
    layers[id] = { name, object };
    scene.add(object);
  }
  const medialMaterial = { vertexColors: THREE.VertexColors, side: THREE.DoubleSide, flatShading: true };
  addLayer('triangles', 'medial triangles', new THREE.Mesh(expandedGeometry(medial.positions, medial.triangles),
    new THREE.MeshPhongMaterial(Object.assign({ shininess: 10 }, medialMaterial))), true);
  addLayer('curves', 'medial curves', new THREE.LineSegments(expandedGeometry(medial.positions, medial.curves),
    new THREE.LineBasicMaterial({ vertexColors: THREE.VertexColors })), true);
  const pointGeometry = new THREE.BufferGeometry();
  pointGeometry.setAttribute('position', new THREE.BufferAttribute(medial.positions, 3));
  pointGeometry.setAttribute('color', new THREE.BufferAttribute(new Float32Array(medial.positions.length), 3));
  addLayer('vertices', 'medial vertices', new THREE.Points(pointGeometry,
    new THREE.PointsMaterial({ size: 3, sizeAttenuation: false, vertexColors: THREE.VertexColors })),
  medial.triangles.length === 0 && medial.curves.length === 0);

  // A surface or point set of the run: plain, in its own per-vertex colours, or coloured by its
  // field over the field's range (named in the panel). A face field needs a copy per corner.
  function shortNumber(v) {
    return Math.abs(v) >= 1e4 || (Math.abs(v) < 1e-3 && v !== 0) ? v.toExponential(3) : v.toPrecision(4);
  }
  function surfaceLayer(surface) {
    const positions = decode(surface.positions, Float32Array), triangles = decode(surface.triangles, Uint32Array);
    const field = surface.field &&
      Object.assign({}, surface.field, { values: decode(surface.field.values, Float32Array) });
    const perFace = field && field.element === 'face';
    let g;
    if (perFace) {
      g = expandedGeometry(positions, triangles);
    } else {
      g = new THREE.BufferGeometry();
      g.setAttribute('position', new THREE.BufferAttribute(positions, 3));
      if (triangles.length) g.setIndex(new THREE.BufferAttribute(triangles, 1));
    }
    const count = g.attributes.position.count;
    let name = surface.name;
    if (surface.colors) {
      const rgb = decode(surface.colors, Uint8Array);
      g.setAttribute('color', new THREE.BufferAttribute(Float32Array.from(rgb, (c) => c / 255), 3));
    } else if (field) {
      const range = fieldRange(field), colour = colourOf(field, range);
      g.setAttribute('color', new THREE.BufferAttribute(new Float32Array(3 * count), 3));
      paint(g.attributes.color, count,
        perFace ? (k) => colour(field.values[Math.floor(k / 3)]) : (i) => colour(field.values[i]));
      name += field.label ? `: ${field.name} (labels)`
        : `: ${field.name} ${shortNumber(range[0])} to ${shortNumber(range[1])}`;
    }
    const coloured = Boolean(g.attributes.color);
    if (!triangles.length)
      return [name, new THREE.Points(g, new THREE.PointsMaterial({ size: 2, sizeAttenuation: false,
        color: coloured ? 0xffffff : surface.color, vertexColors: coloured ? THREE.VertexColors : THREE.NoColors }))];
    if (!perFace) g.computeVertexNormals();
    const material = new THREE.MeshPhongMaterial({ color: coloured ? 0xffffff : surface.color,
      vertexColors: coloured ? THREE.VertexColors : THREE.NoColors, side: THREE.DoubleSide, flatShading: perFace,
      transparent: surface.opacity < 1, opacity: surface.opacity, depthWrite: surface.opacity >= 1 });
    const mesh = new THREE.Mesh(g, material);
    mesh.renderOrder = 1;  // translucent surfaces after the opaque medial layers
    return [name, mesh];
  }
  for (const surface of data.surfaces) {
    const [name, object] = surfaceLayer(surface);
    addLayer(surface.id, name, object, surface.visible);
  }

  // Every sphere: one instanced draw call.
  const vertexCount = medial.radii.length;
  const sphereMaterial = new THREE.MeshPhongMaterial({ color: 0x4a90d9, transparent: true, opacity: 0.25,
    depthWrite: false });
  // Coarser spheres when there are many: 10^5 spheres of 16x10 would be 3x10^7 triangles.
  const sphere = vertexCount > 20000 ? new THREE.SphereBufferGeometry(1, 8, 6)
    : new THREE.SphereBufferGeometry(1, 16, 10);
  const allSpheres = new THREE.InstancedMesh(sphere, sphereMaterial, vertexCount);
  {
    const m = new THREE.Matrix4();
    for (let i = 0; i < vertexCount; ++i) {
      const r = medial.radii[i];
      const p = medial.positions;
      m.makeScale(r, r, r).setPosition(p[3 * i], p[3 * i + 1], p[3 * i + 2]);
      allSpheres.setMatrixAt(i, m);
    }
  }
  allSpheres.renderOrder = 2;
  addLayer('spheres', 'all medial spheres', allSpheres, false);
  const pickedSphere = new THREE.Mesh(new THREE.SphereBufferGeometry(1, 32, 20),
    new THREE.MeshPhongMaterial({ color: 0xe0a030, transparent: true, opacity: 0.45, depthWrite: false }));
  pickedSphere.visible = false;
  pickedSphere.renderOrder = 3;
  scene.add(pickedSphere);

  // ---- camera ----
  // The camera frames the input surface; without one, the medial vertices between the 1st and
  // 99th percentile on each axis (far poles of a raw Voronoi axis would shrink the shape to a dot).
  function percentileBox(positions) {
    const n = positions.length / 3, step = Math.max(1, Math.floor(n / 100000));
    const b = new THREE.Box3();
    if (n === 0) return b;
    for (let c = 0; c < 3; ++c) {
      const values = [];
      for (let i = 0; i < n; i += step) values.push(positions[3 * i + c]);
      values.sort((x, y) => x - y);
      b.min.setComponent(c, values[Math.floor(0.01 * (values.length - 1))]);
      b.max.setComponent(c, values[Math.ceil(0.99 * (values.length - 1))]);
    }
    return b;
  }
  const box = layers.surface
    ? new THREE.Box3().setFromBufferAttribute(layers.surface.object.geometry.attributes.position)
    : percentileBox(medial.positions);
  if (box.isEmpty()) box.set(new THREE.Vector3(-1, -1, -1), new THREE.Vector3(1, 1, 1));
  const bounds = box.getBoundingSphere(new THREE.Sphere());
  const controls = new THREE.OrbitControls(camera, renderer.domElement);
  const kPresets = { iso: [1, 0.7, 1.3], front: [0, 0, 1], back: [0, 0, -1], left: [-1, 0, 0], right: [1, 0, 0],
    top: [0, 1, 0.0001], bottom: [0, -1, 0.0001] };
  function setView(name) {
    const direction = new THREE.Vector3(...(kPresets[name] || kPresets.iso)).normalize();
    const zoom = Number(query.get('zoom')) || 1;
    const distance = bounds.radius / Math.sin((camera.fov * Math.PI) / 360) / zoom;
    camera.position.copy(bounds.center).addScaledVector(direction, distance * 0.85);
    camera.near = distance / 100;
    camera.far = distance * 10;
    camera.updateProjectionMatrix();
    controls.target.copy(bounds.center);
    controls.update();
  }

  function render() { renderer.render(scene, camera); }
  controls.addEventListener('change', render);

  // ---- colouring ----
  function paint(attribute, count, colourAt) {
    const a = attribute.array;
    for (let i = 0; i < count; ++i) {
      const c = colourAt(i);
      a[3 * i] = c[0]; a[3 * i + 1] = c[1]; a[3 * i + 2] = c[2];
    }
    attribute.needsUpdate = true;
  }
  // Colours every medial layer by `field` over `range`; layers the field is not on stay plain.
  function colourBy(field, range) {
    const colour = field ? colourOf(field, range) : null;
    const on = (element) => field && field.element === element;
    const plain = (layer) => () => kPlain[layer];
    const tri = medial.triangles, cur = medial.curves;
    const triColour = on('vertex') ? (k) => colour(field.values[tri[k]])
      : on('face') ? (k) => colour(field.values[Math.floor(k / 3)]) : plain('triangles');
    paint(layers.triangles.object.geometry.attributes.color, tri.length, triColour);
    const curveColour = on('vertex') ? (k) => colour(field.values[cur[k]])
      : on('edge') ? (k) => colour(field.values[k >> 1]) : plain('curves');
    paint(layers.curves.object.geometry.attributes.color, cur.length, curveColour);
    paint(pointGeometry.attributes.color, vertexCount,
      on('vertex') ? (i) => colour(field.values[i]) : plain('vertices'));
    showLegend(field, range);
    render();
  }
  // The colours of the labels in `range` (at most 24 of them, evenly picked), side by side.
  function labelSwatches(range) {
    const count = Math.min(24, Math.round(range[1] - range[0]) + 1);
    const swatches = [];
    for (let k = 0; k < count; ++k) {
      const label = Math.round(range[0] + (count > 1 ? (k * (range[1] - range[0])) / (count - 1) : 0));
      const rgb = labelColour(label).map((x) => Math.round(255 * x)).join(',');
      swatches.push(`rgb(${rgb}) ${(100 * k) / count}% ${(100 * (k + 1)) / count}%`);
    }
    return `linear-gradient(90deg, ${swatches.join(', ')})`;
  }
  function showLegend(field, range) {
    const legend = document.getElementById('legend');
    legend.hidden = !field;
    if (!field) return;
    document.getElementById('legend-name').textContent = field.key + (field.label ? ' (labels)' : '');
    const stops = field.label ? [] : kViridis.map((c, i) =>
      `rgb(${c.map((x) => Math.round(255 * x)).join(',')}) ${(100 * i / (kViridis.length - 1)).toFixed(0)}%`);
    document.getElementById('legend-bar').style.background = field.label ? labelSwatches(range)
      : `linear-gradient(90deg, ${stops.join(', ')})`;
    const tick = field.label ? (v) => String(Math.round(v)) : shortNumber;
    document.getElementById('legend-min').textContent = tick(range[0]);
    document.getElementById('legend-max').textContent = tick(range[1]);
  }

  // ---- picking: click a medial vertex (or a triangle/curve near it) ----
  const raycaster = new THREE.Raycaster();
  raycaster.params.Points.threshold = bounds.radius * 0.01;
  raycaster.params.Line.threshold = bounds.radius * 0.01;
  function nearestCorner(corners, point) {
    let best = corners[0], bestDistance = Infinity;
    for (const v of corners) {
      const d = point.distanceToSquared(new THREE.Vector3().fromArray(medial.positions, 3 * v));
      if (d < bestDistance) { best = v; bestDistance = d; }
    }
    return best;
  }
  function pickedVertex(hit) {
    if (hit.object === layers.vertices.object) return hit.index;
    if (hit.object === layers.triangles.object) {
      const k = 3 * hit.faceIndex;
      return nearestCorner([medial.triangles[k], medial.triangles[k + 1], medial.triangles[k + 2]], hit.point);
    }
    const e = hit.index - (hit.index % 2);
    return nearestCorner([medial.curves[e], medial.curves[e + 1]], hit.point);
  }
  function pick(v) {
    const info = document.getElementById('pick');
    if (!(v >= 0 && v < vertexCount)) { pickedSphere.visible = false; render(); return; }
    const centre = new THREE.Vector3().fromArray(medial.positions, 3 * v);
    const r = medial.radii[v];
    pickedSphere.position.copy(centre);
    pickedSphere.scale.set(r, r, r);
    pickedSphere.visible = true;
    const lines = [`vertex ${v}`, `centre ${centre.toArray().map((x) => x.toPrecision(6)).join(' ')}`,
      `radius ${r.toPrecision(6)}`];
    for (const f of fields) if (f.element === 'vertex' && f.name !== 'radius') lines.push(`${f.name} ${f.values[v]}`);
    info.textContent = lines.join('\n');
    render();
  }
  let pressedAt = null;
  renderer.domElement.addEventListener('pointerdown', (e) => { pressedAt = [e.clientX, e.clientY]; });
  renderer.domElement.addEventListener('pointerup', (e) => {
    if (!pressedAt || Math.hypot(e.clientX - pressedAt[0], e.clientY - pressedAt[1]) > 3) return;
    const rect = renderer.domElement.getBoundingClientRect();
    raycaster.setFromCamera(new THREE.Vector2(((e.clientX - rect.left) / rect.width) * 2 - 1,
      -((e.clientY - rect.top) / rect.height) * 2 + 1), camera);
    const targets = ['vertices', 'triangles', 'curves'].map((id) => layers[id].object).filter((o) => o.visible);
    const hits = raycaster.intersectObjects(targets);
    pick(hits.length ? pickedVertex(hits[0]) : -1);
  });

  // ---- the panel ----
  function buildPanel() {
    document.getElementById('title').textContent = data.title;
    document.title = data.title;
    const shown = query.get('layers');
    if (shown !== null) {
      const wanted = new Set(shown.split(',').filter((s) => s));
      for (const id of Object.keys(layers)) layers[id].object.visible = wanted.has(id);
    }
    const box = document.getElementById('layers');
    for (const id of Object.keys(layers)) {
      const label = document.createElement('label');
      const check = document.createElement('input');
      check.type = 'checkbox';
      check.checked = layers[id].object.visible;
      check.dataset.layer = id;
      check.addEventListener('change', () => { layers[id].object.visible = check.checked; render(); });
      label.append(check, ' ' + layers[id].name);
      box.appendChild(label);
    }
    const presets = document.getElementById('presets');
    for (const name of Object.keys(kPresets)) {
      const b = document.createElement('button');
      b.textContent = name;
      b.addEventListener('click', () => { setView(name); render(); });
      presets.appendChild(b);
    }
  }
  function chosenField() {
    const wanted = query.get('field') || 'vertex:radius';
    if (wanted === 'none') return null;
    const found = fields.find((f) => f.key === wanted) || fields.find((f) => f.name === wanted);
    if (!found) recordError(`no field '${wanted}' in this run; fields: ${fields.map((f) => f.key).join(', ')}`);
    return found || null;
  }
  function buildFieldControls(initial) {
    const select = document.getElementById('field');
    const minInput = document.getElementById('range-min'), maxInput = document.getElementById('range-max');
    select.add(new Option('none (plain colours)', 'none'));
    for (const f of fields) select.add(new Option(`${f.key}${f.label ? ' (labels)' : ''}`, f.key));
    const current = () => fields.find((f) => f.key === select.value) || null;
    const apply = () => colourBy(current(), [Number(minInput.value), Number(maxInput.value)]);
    const reset = () => {
      const f = current();
      const range = f ? fieldRange(f) : [0, 1];
      minInput.value = range[0];
      maxInput.value = range[1];
      apply();
    };
    select.addEventListener('change', reset);
    minInput.addEventListener('change', apply);
    maxInput.addEventListener('change', apply);
    document.getElementById('range-reset').addEventListener('click', reset);
    select.value = initial ? initial.key : 'none';
    const range = initial ? fieldRange(initial) : [0, 1];
    minInput.value = query.has('min') ? Number(query.get('min')) : range[0];
    maxInput.value = query.has('max') ? Number(query.get('max')) : range[1];
    apply();
  }

  // Mean milliseconds per frame over `frames` frames orbiting the shape (finished with a pixel read).
  function benchmark(frames) {
    const gl = renderer.getContext();
    const pixel = new Uint8Array(4);
    const start = performance.now();
    for (let i = 0; i < frames; ++i) {
      controls.autoRotate = true;
      controls.autoRotateSpeed = 60;
      controls.update();
      render();
      gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, pixel);
    }
    return (performance.now() - start) / frames;
  }

  if (query.get('ui') === '0') document.body.classList.add('bare');
  if (query.get('legend') === '0') document.body.classList.add('nolegend');
  buildPanel();
  setView(query.get('view') || 'iso');
  buildFieldControls(chosenField());
  if (query.has('pick')) pick(Number(query.get('pick')));
  render();
  statusElement.dataset.loadMs = performance.now().toFixed(0);  // since navigation: parse, decode, first frame
  if (query.has('bench')) statusElement.dataset.frameMs = benchmark(Number(query.get('bench')) || 30).toFixed(2);
  statusElement.dataset.field = document.getElementById('field').value;
  statusElement.dataset.triangles = String(medial.triangles.length / 3);
  status.state = 'ready';
  writeStatus();
})();
