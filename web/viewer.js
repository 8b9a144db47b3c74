// The viewer page of `radiosity serve`: the lit scene drawn from the server's display mesh and
// per-vertex radiance (README, "serve" API), orbit controls, the lights to drag or edit by number
// and the light groups to dim; every change goes to the server, which relights and answers the
// new colours. One request at a time: changes made meanwhile go in the next one, so dragging
// never queues a backlog. Dynamic objects are placed and lit by the server at the time the
// slider (or Play) shows, the same way.
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';
import { TransformControls } from 'three/addons/controls/TransformControls.js';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';

const statusLine = document.getElementById('status');
// What the browser test waits on: frames drawn, relights answered, requests failed.
window.viewerState = { frames: 0, relights: 0, errors: 0, lastRelightMs: 0, objectUpdates: 0, objectTime: 0,
  sensor: null, sensorSets: null };

function report(text, isError = false) {
  statusLine.textContent = text;
  statusLine.classList.toggle('error', isError);
  if (isError) {
    window.viewerState.errors += 1;
    console.error(text);
  }
}

async function fetchOk(path, options) {
  const response = await fetch(path, options);
  if (!response.ok) {
    let message = `${path}: HTTP ${response.status}`;
    try { message += `: ${(await response.json()).error}`; } catch (_) { /* not JSON */ }
    throw new Error(message);
  }
  return response;
}

const canvas = document.getElementById('view');
const renderer = new THREE.WebGLRenderer({ canvas, antialias: true, preserveDrawingBuffer: true });
renderer.setPixelRatio(window.devicePixelRatio);
// The colours are linear radiance: times 2^EV, clamped, sRGB-encoded, as the CLI's PNGs.
renderer.toneMapping = THREE.LinearToneMapping;
renderer.outputColorSpace = THREE.SRGBColorSpace;
const scene3d = new THREE.Scene();
scene3d.background = new THREE.Color(0x000000);
const camera = new THREE.PerspectiveCamera(40, 1, 0.01, 1000);
const orbit = new OrbitControls(camera, canvas);
const gizmo = new TransformControls(camera, canvas);
gizmo.addEventListener('dragging-changed', (event) => { orbit.enabled = !event.value; });
scene3d.add(gizmo.getHelper());

let summary = null;
const meshes = [];      // the display mesh's parts, in the .glb's vertex order
const lights = [];      // the lights' state as the page has it
const groupScales = {}; // light group name -> scale
const markers = [];     // a marker per light, for the gizmo

function resize() {
  const width = canvas.clientWidth, height = canvas.clientHeight;
  renderer.setSize(width, height, false);
  camera.aspect = width / height;
  camera.updateProjectionMatrix();
}

// The false-colour ramp (after Google's Turbo), 0 to 1, and the legend's stops.
const ramp = ['#30123b', '#4686fb', '#1ae4b6', '#a2fc3c', '#faba39', '#e4460a', '#7a0403']
  .map((hex) => new THREE.Color(hex).convertSRGBToLinear());
function rampColor(t) {
  const x = Math.min(Math.max(t, 0), 1) * (ramp.length - 1);
  const k = Math.min(Math.floor(x), ramp.length - 2);
  return ramp[k].clone().lerp(ramp[k + 1], x - k);
}
let radiance = null;   // the last colours from the server (linear radiance)
let falseColour = false;

// Irradiance per vertex as the legend's unit: W/m^2 from W per square scene unit, lux at the
// server's efficacy (179 lm/W, the one candela are read with) of its luminance.
async function falseColours() {
  const h = new Float32Array(await (await fetchOk('api/irradiance')).arrayBuffer());
  const metres = Number(document.getElementById('unit-metres').value) || 1;
  const lux = document.getElementById('false-unit').value === 'lux';
  const values = new Float32Array(h.length / 3);
  for (let v = 0; v < values.length; ++v) {
    const wm2 = (0.2126 * h[3 * v] + 0.7152 * h[3 * v + 1] + 0.0722 * h[3 * v + 2]) / (metres * metres);
    values[v] = lux ? summary.lumens_per_watt * wm2 : wm2;
  }
  const sorted = Float32Array.from(values).sort();
  const top = sorted[Math.floor(0.98 * (sorted.length - 1))] || 1;
  const out = new Float32Array(h.length);
  values.forEach((value, v) => { rampColor(value / top).toArray(out, 3 * v); });
  document.getElementById('legend-max').textContent = `${top.toPrecision(3)} ${lux ? 'lx' : 'W/m²'}`;
  return out.buffer;
}

// The lux meter: what a sensor on the clicked surface reads (facing the viewer), computed by the
// server as `--sensors` computes it, with the moving objects where the slider puts them.
const sensorMarker = new THREE.Mesh(new THREE.SphereGeometry(1, 12, 6),
  new THREE.MeshBasicMaterial({ color: 0xff3366 }));
async function readSensor(hit, viewDirection) {
  const normal = hit.face.normal.clone().transformDirection(hit.object.matrixWorld);
  if (normal.dot(viewDirection) > 0) normal.negate();
  const triple = (v) => v.toArray().map((x) => Number(x.toPrecision(7))).join(',');
  const time = document.getElementById('time').value;
  const reading = await (await fetchOk(`api/sensor?position=${triple(hit.point)}&normal=${triple(normal)}` +
    `&t=${summary.paths_end_s > 0 ? time : 0}`)).json();
  const h = reading.irradiance;
  document.getElementById('sensor-reading').textContent = reading.illuminance_lux === null
    ? `${(0.2126 * h[0] + 0.7152 * h[1] + 0.0722 * h[2]).toPrecision(4)} W per square scene unit`
    : `${reading.illuminance_lux.toPrecision(4)} lx at (${reading.position.map((x) => x.toPrecision(4)).join(', ')})`;
  sensorMarker.position.copy(hit.point);
  scene3d.add(sensorMarker);
  window.viewerState.sensor = reading;
}

// The scene's sensor sets (its calculation grids), read anew after every relight: a dot a point
// in the false colours' ramp up to the brightest point, and a line a set in the Lux meter panel.
const sensorDots = new THREE.Group();
async function showSensorSets() {
  if (!summary.sensor_sets.length) return;
  const time = summary.paths_end_s > 0 ? document.getElementById('time').value : 0;
  const answer = await (await fetchOk(`api/sensors?t=${time}`)).json();
  for (const dots of sensorDots.children) dots.geometry.dispose();
  sensorDots.clear();
  const sets = Object.entries(answer.sets);
  const top = Math.max(0, ...sets.map(([, set]) => set.max_lux ?? 0));
  const lines = [];
  for (const [name, set] of sets) {
    const positions = [], colors = [];
    for (const point of set.points) {
      positions.push(...point.position);
      rampColor(top > 0 ? (point.illuminance_lux ?? 0) / top : 0).toArray(colors, colors.length);
    }
    const geometry = new THREE.BufferGeometry();
    geometry.setAttribute('position', new THREE.Float32BufferAttribute(positions, 3));
    geometry.setAttribute('color', new THREE.Float32BufferAttribute(colors, 3));
    sensorDots.add(new THREE.Points(geometry, new THREE.PointsMaterial(
      { size: 7, sizeAttenuation: false, vertexColors: true, toneMapped: false })));
    lines.push(set.mean_lux === null ? `${name}: ${set.points.length} points (no unit, no lux)`
      : `${name}: ${set.points.length === 1 ? '' : 'mean '}${set.mean_lux.toPrecision(4)} lx` +
        (set.points.length === 1 ? '' : `, min ${set.min_lux.toPrecision(3)}, uniformity ${set.uniformity.toFixed(2)}`));
  }
  document.getElementById('sensor-sets').textContent = lines.join('\n');
  window.viewerState.sensorSets = answer;
}

async function showColours() {
  const falseMode = falseColour;
  renderer.toneMapping = falseMode ? THREE.NoToneMapping : THREE.LinearToneMapping;
  document.getElementById('legend').hidden = !falseMode;
  for (const mesh of meshes) mesh.material.needsUpdate = true;
  applyColors(falseMode ? await falseColours() : radiance);
}

function applyColors(buffer) {
  const colors = new Float32Array(buffer);
  let at = 0;
  for (const mesh of meshes) {
    const attribute = mesh.geometry.getAttribute('color');
    attribute.array.set(colors.subarray(at, at + attribute.array.length));
    attribute.needsUpdate = true;
    at += attribute.array.length;
  }
  if (at !== colors.length) report(`colours for ${colors.length / 3} vertices, mesh has ${at / 3}`, true);
}

// --- talking to the server -------------------------------------------------------------------
let inFlight = false, pending = false;

function lightState() {
  const state = { groups: { ...groupScales } };
  if (summary.relights)  // a voxel solution takes group scales only
    state.lights = lights.map((l) => (l.type === 'sky' ? { id: l.id, intensity: l.intensity } : {
      id: l.id, direction: l.direction, intensity: l.intensity,
      ...(l.type === 'directional' ? {} : { position: l.position }),  // the sun has none
    }));
  return state;
}

async function sendState() {
  if (inFlight) { pending = true; return; }
  inFlight = true;
  try {
    const response = await fetchOk('api/lights', {
      method: 'POST', headers: { 'Content-Type': 'application/json' }, body: JSON.stringify(lightState()),
    });
    const ms = Number(response.headers.get('X-Relight-Ms'));
    radiance = await response.arrayBuffer();
    await showColours();
    await showSensorSets();
    if (summary.dynamic_objects.length) showObjects();  // lit by the new light too
    window.viewerState.relights += 1;
    window.viewerState.lastRelightMs = ms;
    report(`relit in ${ms.toFixed(1)} ms`);
  } catch (error) {
    report(error.message, true);
  } finally {
    inFlight = false;
    if (pending) { pending = false; sendState(); }
  }
}

// Dynamic objects: their triangles at the time asked, lit by probes of the solution (the colours
// are linear radiance, as the scene's). One request at a time, the newest time wins.
const objectParts = new THREE.Group();
const objectMaterial = new THREE.MeshBasicMaterial({ vertexColors: true, side: THREE.FrontSide });
let objectTime = 0, objectsBusy = false, objectsAgain = false;

async function showObjects() {
  if (objectsBusy) { objectsAgain = true; return; }
  objectsBusy = true;
  try {
    do {
      objectsAgain = false;
      const answer = await (await fetchOk(`api/dynamic?t=${objectTime}`)).json();
      for (const part of objectParts.children) part.geometry.dispose();
      objectParts.clear();
      for (const object of answer.objects) {
        const geometry = new THREE.BufferGeometry();
        geometry.setAttribute('position', new THREE.Float32BufferAttribute(object.positions, 3));
        geometry.setAttribute('color', new THREE.Float32BufferAttribute(object.colors, 3));
        const part = new THREE.Mesh(geometry, objectMaterial);
        part.name = object.name;
        objectParts.add(part);
      }
      window.viewerState.objectUpdates += 1;
      window.viewerState.objectTime = answer.t;
    } while (objectsAgain);
  } catch (error) {
    report(error.message, true);
  } finally {
    objectsBusy = false;
  }
}

function setUpTime() {
  document.getElementById('time-section').hidden = false;
  const slider = document.getElementById('time'), play = document.getElementById('play');
  const end = Math.max(summary.paths_end_s, 0.01);
  slider.max = String(end);
  const show = (t) => {
    objectTime = t;
    slider.value = String(t);
    document.getElementById('time-value').textContent = `${t.toFixed(2)} s`;
    showObjects();
  };
  slider.addEventListener('input', () => show(Number(slider.value)));
  let playing = false, last = 0;
  play.addEventListener('click', () => {
    playing = !playing;
    play.textContent = playing ? 'Pause' : 'Play';
    last = performance.now();
  });
  // Played in real time, looping over the paths; the server answers as fast as it can.
  return () => {
    if (!playing) return;
    const now = performance.now();
    show((objectTime + (now - last) / 1000) % end);
    last = now;
  };
}

// --- the panel -------------------------------------------------------------------------------
function numberInputs(label, values, onChange) {
  const row = document.createElement('label');
  row.textContent = label + ' ';
  values.forEach((value, k) => {
    const input = document.createElement('input');
    input.type = 'number';
    input.step = 'any';
    input.value = Number(value.toPrecision(6));
    input.dataset.component = String(k);
    input.addEventListener('change', () => {
      const v = Number(input.value);
      if (Number.isFinite(v)) onChange(k, v);
    });
    row.appendChild(input);
  });
  return row;
}

function lightPanel(light) {
  const box = document.createElement('div');
  box.className = 'light';
  box.id = `light-${light.id}`;
  const name = document.createElement('div');
  name.className = 'name';
  name.textContent = `#${light.id} ${light.type}` + (light.group ? ` (group ${light.group})` : '');
  box.appendChild(name);
  const update = () => {
    markers[light.id].position.fromArray(light.position);
    markers[light.id].userData.arrow?.position.fromArray(light.position);
    sendState();
  };
  light.showDirection = () => {
    const inputs = box.querySelectorAll('.direction input');
    inputs.forEach((input, k) => { input.value = Number(light.direction[k].toPrecision(6)); });
    markers[light.id].userData.arrow?.setDirection(new THREE.Vector3().fromArray(light.direction).normalize());
  };
  // A directional light (the sun) has no position: its marker only shows where its light comes from.
  // A sky has neither: its radiance alone.
  const position = numberInputs('position', light.position, (k, v) => { light.position[k] = v; update(); });
  position.classList.add('position');
  if (light.type !== 'directional' && light.type !== 'sky') box.appendChild(position);
  if (light.type !== 'point' && light.type !== 'sky') {
    const direction = numberInputs('direction', light.direction, (k, v) => {
      light.direction[k] = v;
      light.showDirection();
      sendState();
    });
    direction.classList.add('direction');
    box.appendChild(direction);
  }
  const unit = { directional: 'W/unit²', sky: 'W/(sr unit²)' }[light.type] ?? 'W/sr';
  const intensity = numberInputs(unit, light.intensity, (k, v) => { light.intensity[k] = Math.max(0, v); sendState(); });
  intensity.classList.add('intensity');
  box.appendChild(intensity);
  // A voxel solution is not relit: its lights are shown, not edited.
  if (!summary.relights) box.querySelectorAll('input').forEach((input) => { input.disabled = true; });
  light.positionInputs = position.querySelectorAll('input');
  return box;
}

function groupPanel(group) {
  const row = document.createElement('label');
  row.id = `group-${group.name}`;
  const on = document.createElement('input');
  on.type = 'checkbox';
  on.checked = true;
  const dimmer = document.createElement('input');
  dimmer.type = 'range';
  dimmer.min = '0'; dimmer.max = '2'; dimmer.step = '0.01'; dimmer.value = String(group.scale[0]);
  const apply = () => { groupScales[group.name] = on.checked ? Number(dimmer.value) : 0; sendState(); };
  on.addEventListener('change', apply);
  dimmer.addEventListener('input', apply);
  row.append(on, ` ${group.name} `, dimmer);
  return row;
}

// --- start -----------------------------------------------------------------------------------
// While the server solves, its API answers 503: show the solve's progress until it is ready.
async function waitForSolve() {
  for (;;) {
    const state = await (await fetchOk('api/progress')).json();
    if (state.ready) return;
    report(`solving: ${Math.round(100 * state.progress)}%`);
    await new Promise((resolve) => setTimeout(resolve, 300));
  }
}

// The scene's length unit, when the scene says it (built-in scenes, glTF, a scene file's "unit"):
// the false colours' square metres; else 1 m until the user gives it.
function showSceneUnit(unit) {
  if (unit) document.getElementById('unit-metres').value = unit.metres;
  document.getElementById('unit-source').textContent = unit ? `(the scene is in ${unit.name})`
    : '(the scene does not say: give it)';
}

async function start() {
  await waitForSolve();
  summary = await (await fetchOk('api/scene')).json();
  document.getElementById('title').textContent = summary.scene;
  showSceneUnit(summary.unit);
  const gltf = await new GLTFLoader().parseAsync(await (await fetchOk('api/mesh.glb')).arrayBuffer(), '');
  gltf.scene.traverse((object) => {
    if (!object.isMesh) return;
    object.material = new THREE.MeshBasicMaterial({ vertexColors: true, side: THREE.FrontSide });
    meshes.push(object);
  });
  scene3d.add(gltf.scene);
  scene3d.add(objectParts);
  radiance = await (await fetchOk('api/colors')).arrayBuffer();
  applyColors(radiance);
  scene3d.add(sensorDots);
  await showSensorSets();
  const advanceTime = summary.dynamic_objects.length ? setUpTime() : () => {};
  if (summary.dynamic_objects.length) await showObjects();

  const c = summary.camera;
  camera.fov = c.fov_deg;
  camera.position.fromArray(c.eye);
  camera.up.fromArray(c.up);
  orbit.target.fromArray(c.target);
  const size = new THREE.Vector3().fromArray(summary.bounds.max).sub(new THREE.Vector3().fromArray(summary.bounds.min));
  const diagonal = size.length();
  camera.near = diagonal * 1e-3;
  camera.far = diagonal * 20;
  orbit.update();

  const markerGeometry = new THREE.SphereGeometry(diagonal * 0.012, 16, 8);
  sensorMarker.scale.setScalar(diagonal * 0.006);
  for (const light of summary.lights) {
    lights.push(light);
    if (light.type === 'sky') {  // everywhere above: no marker to drag
      document.getElementById('lights').appendChild(lightPanel(light));
      continue;
    }
    const marker = new THREE.Mesh(markerGeometry, new THREE.MeshBasicMaterial({ color: 0xffdd55 }));
    marker.position.fromArray(light.position);
    if (light.type === 'directional') {  // up the light's way from the scene's centre
      const centre = new THREE.Vector3().fromArray(summary.bounds.min)
        .add(new THREE.Vector3().fromArray(summary.bounds.max)).multiplyScalar(0.5);
      marker.position.copy(centre).addScaledVector(new THREE.Vector3().fromArray(light.direction), -0.6 * diagonal);
    }
    marker.userData.light = light;
    if (light.type !== 'point') {  // the axis a spot or IES light points along
      const arrow = new THREE.ArrowHelper(new THREE.Vector3().fromArray(light.direction).normalize(),
        new THREE.Vector3(), diagonal * 0.08, 0xffdd55);
      scene3d.add(arrow);
      arrow.position.copy(marker.position);
      marker.userData.arrow = arrow;
    }
    markers[light.id] = marker;
    scene3d.add(marker);
    document.getElementById('lights').appendChild(lightPanel(light));
  }
  for (const group of summary.groups) {
    groupScales[group.name] = group.scale[0];
    document.getElementById('groups').appendChild(groupPanel(group));
  }
  // Move drags the marker; Aim turns it, and the light's axis turns with it from where it
  // pointed when the turn began.
  gizmo.addEventListener('mouseDown', () => {
    const marker = gizmo.object;
    marker.userData.startDirection = new THREE.Vector3().fromArray(marker.userData.light.direction);
    marker.userData.startTurn = marker.quaternion.clone().invert();
  });
  gizmo.addEventListener('objectChange', () => {
    const marker = gizmo.object;
    const light = marker.userData.light;
    if (gizmo.getMode() === 'rotate') {
      if (light.type === 'point' || !marker.userData.startDirection) return;
      const turn = marker.quaternion.clone().multiply(marker.userData.startTurn);
      light.direction = marker.userData.startDirection.clone().applyQuaternion(turn).normalize().toArray();
      light.showDirection();
    } else if (light.type !== 'directional') {
      light.position = marker.position.toArray();
      light.positionInputs.forEach((input, k) => { input.value = Number(light.position[k].toPrecision(6)); });
      marker.userData.arrow?.position.copy(marker.position);
    }
    sendState();
  });
  const setMode = (mode) => gizmo.setMode(mode);
  document.getElementById('mode-move').addEventListener('click', () => setMode('translate'));
  document.getElementById('mode-aim').addEventListener('click', () => setMode('rotate'));
  window.addEventListener('keydown', (event) => {
    if (event.target.tagName === 'INPUT') return;
    if (event.key === 't') setMode('translate');
    if (event.key === 'r') setMode('rotate');
  });
  const pointer = new THREE.Vector2(), raycaster = new THREE.Raycaster();
  canvas.addEventListener('pointerdown', (event) => {
    if (gizmo.dragging) return;
    const rect = canvas.getBoundingClientRect();
    pointer.set(((event.clientX - rect.left) / rect.width) * 2 - 1, -((event.clientY - rect.top) / rect.height) * 2 + 1);
    raycaster.setFromCamera(pointer, camera);
    if (event.shiftKey) {
      const surface = raycaster.intersectObjects(meshes)[0];
      if (surface) readSensor(surface, raycaster.ray.direction).catch((e) => report(e.message, true));
      return;
    }
    const hit = raycaster.intersectObjects(markers.filter(Boolean))[0];
    if (hit && summary.relights) gizmo.attach(hit.object);
  });

  const exposure = document.getElementById('exposure');
  const showExposure = () => {
    renderer.toneMappingExposure = Math.pow(2, Number(exposure.value));
    document.getElementById('exposure-value').textContent = `${exposure.value} EV`;
  };
  exposure.addEventListener('input', showExposure);
  showExposure();
  const toggle = document.getElementById('false-colour');
  const refresh = () => { falseColour = toggle.checked; showColours().catch((e) => report(e.message, true)); };
  for (const id of ['false-colour', 'false-unit', 'unit-metres'])
    document.getElementById(id).addEventListener('change', refresh);
  document.getElementById('download-png').addEventListener('click', () => {
    const link = document.createElement('a');
    link.href = canvas.toDataURL('image/png');
    link.download = `${summary.scene.replace(/[^A-Za-z0-9_-]/g, '_')}.png`;
    link.click();
  });
  window.addEventListener('resize', resize);
  resize();
  report(summary.relights ? `${summary.patches} patches, ${summary.vertices} vertices`
    : `voxel solution (${summary.patches} voxel sides): light groups dim, lights stay`);
  renderer.setAnimationLoop(() => {
    advanceTime();
    orbit.update();
    renderer.render(scene3d, camera);
    window.viewerState.frames += 1;
  });
}

start().catch((error) => report(error.message, true));
