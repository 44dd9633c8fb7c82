// The 3D view of report.html (issue 39): the deployed lamellas' contact lines against the design
// surface, coloured by their distance to it (the error of Sections 2.6.2 and 3.5.2), with orbit,
// zoom, pan, a toggle per patch and the ids under the pointer. Bundled with three.js by build.mjs
// into one script that egg inlines into every report.html, so the page works offline.
//
// Data: <script type="application/json" id="egg-view-data">
//   {"surface": {"positions": [x,y,z,...], "triangles": [i,j,k,...]},
//    "rods": [{"patch": p, "rod": r, "points": [x,y,z,...], "distance_m": [...]}],
//    "scale_m": s, "caption": "..."}   (metres, z up)
import {
  AmbientLight,
  BufferAttribute,
  BufferGeometry,
  Color,
  DirectionalLight,
  DoubleSide,
  LineBasicMaterial,
  LineSegments,
  Mesh,
  MeshLambertMaterial,
  PerspectiveCamera,
  Raycaster,
  Scene,
  Spherical,
  Vector2,
  Vector3,
  WebGLRenderer,
} from 'three';

// The deviation ramp of deployed.svg (pipeline/deviation_plan.cpp deviationColour): blue, pale
// yellow at half the scale, red at the scale and beyond.
const STOPS = [[44, 123, 182], [255, 255, 191], [215, 25, 28]];
function rampColour(distance, scale) {
  const t = scale > 0 && Number.isFinite(distance) ? Math.min(Math.max(distance / scale, 0), 1) : 1;
  const k = t < 0.5 ? 0 : 1;
  const u = t < 0.5 ? t / 0.5 : (t - 0.5) / 0.5;
  return STOPS[k].map((c, i) => (c + u * (STOPS[k + 1][i] - c)) / 255);
}

function patchLines(rods, scale) {
  const positions = [];
  const colours = [];
  const segmentRod = [];  // per segment: index into rods
  rods.forEach(({ rod, index }) => {
    const p = rod.points;
    for (let i = 0; i + 1 < p.length / 3; ++i) {
      positions.push(p[3 * i], p[3 * i + 1], p[3 * i + 2], p[3 * i + 3], p[3 * i + 4], p[3 * i + 5]);
      colours.push(...rampColour(rod.distance_m[i], scale), ...rampColour(rod.distance_m[i + 1], scale));
      segmentRod.push(index);
    }
  });
  const geometry = new BufferGeometry();
  geometry.setAttribute('position', new BufferAttribute(new Float32Array(positions), 3));
  geometry.setAttribute('color', new BufferAttribute(new Float32Array(colours), 3));
  // Transparent (at full opacity) so it draws after the translucent surface, which writes no
  // depth: a lamella below the design surface stays visible.
  const lines = new LineSegments(geometry, new LineBasicMaterial({ vertexColors: true, transparent: true }));
  lines.renderOrder = 1;
  lines.userData.segmentRod = segmentRod;
  return lines;
}

function surfaceMesh(surface) {
  const geometry = new BufferGeometry();
  geometry.setAttribute('position', new BufferAttribute(new Float32Array(surface.positions), 3));
  geometry.setIndex(new BufferAttribute(new Uint32Array(surface.triangles), 1));
  geometry.computeVertexNormals();
  const material = new MeshLambertMaterial({
    color: 0xbbbbbb, side: DoubleSide, transparent: true, opacity: 0.35, depthWrite: false,
    polygonOffset: true, polygonOffsetFactor: 1, polygonOffsetUnits: 1,
  });
  return new Mesh(geometry, material);
}

function legend(scale) {
  const bar = document.createElement('div');
  bar.className = 'egg-view-legend';
  const stops = STOPS.map((c) => `rgb(${c.join(',')})`).join(',');
  const cm = (x) => `${+(x * 100).toPrecision(3)} cm`;
  bar.innerHTML = `<span>0</span><span class="egg-view-ramp" style="background:linear-gradient(90deg,${stops})"></span>` +
    `<span>${cm(scale)} and more: distance to the design surface</span>`;
  return bar;
}

function mount(container, data) {
  const width = Math.max(container.clientWidth, 320);
  const height = Math.round(Math.min(640, width * 0.62));
  let renderer;
  try {
    renderer = new WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
  } catch (error) {
    container.textContent = `The 3D view needs WebGL, which this browser does not offer (${error.message}).`;
    container.dataset.ink = '0';
    return;
  }
  renderer.setPixelRatio(window.devicePixelRatio || 1);
  renderer.setSize(width, height);
  renderer.setClearColor(0xffffff, 1);
  container.appendChild(renderer.domElement);

  const scene = new Scene();
  scene.add(new AmbientLight(0xffffff, 1.6));
  const sun = new DirectionalLight(0xffffff, 1.4);
  scene.add(sun);

  // Bounding sphere of everything drawn: the view starts from the south-west, 30 degrees up.
  const all = [];
  const box = { min: new Vector3(Infinity, Infinity, Infinity), max: new Vector3(-Infinity, -Infinity, -Infinity) };
  const grow = (p) => { for (let i = 0; i < p.length; i += 3) { const v = new Vector3(p[i], p[i + 1], p[i + 2]); box.min.min(v); box.max.max(v); } };
  if (data.surface) grow(data.surface.positions);
  data.rods.forEach((r) => grow(r.points));
  const centre = box.min.clone().add(box.max).multiplyScalar(0.5);
  const radius = Math.max(box.max.clone().sub(box.min).length() / 2, 1e-3);

  let surface = null;
  if (data.surface && data.surface.triangles.length) {
    surface = surfaceMesh(data.surface);
    scene.add(surface);
  }
  const byPatch = new Map();
  data.rods.forEach((rod, index) => {
    if (!byPatch.has(rod.patch)) byPatch.set(rod.patch, []);
    byPatch.get(rod.patch).push({ rod, index });
  });
  const patchObjects = new Map();
  [...byPatch.keys()].sort((a, b) => a - b).forEach((patch) => {
    const lines = patchLines(byPatch.get(patch), data.scale_m);
    lines.userData.patch = patch;
    scene.add(lines);
    patchObjects.set(patch, lines);
    all.push(lines);
  });

  const camera = new PerspectiveCamera(35, width / height, radius / 100, radius * 100);
  camera.up.set(0, 0, 1);
  const target = centre.clone();
  const orbit = new Spherical(radius / Math.sin((35 / 2) * Math.PI / 180) * 0.8, Math.PI / 3, -Math.PI * 3 / 4);
  function place() {
    // Spherical about z up: theta from +y in three's convention, so map by hand.
    const r = orbit.radius, polar = orbit.phi, azimuth = orbit.theta;
    camera.position.set(target.x + r * Math.sin(polar) * Math.cos(azimuth),
      target.y + r * Math.sin(polar) * Math.sin(azimuth), target.z + r * Math.cos(polar));
    camera.lookAt(target);
    sun.position.copy(camera.position);
  }
  function render() { place(); renderer.render(scene, camera); }

  // Orbit (drag), pan (shift- or right-drag), zoom (wheel).
  const canvas = renderer.domElement;
  let drag = null;
  canvas.addEventListener('contextmenu', (e) => e.preventDefault());
  canvas.addEventListener('pointerdown', (e) => { drag = { x: e.clientX, y: e.clientY, pan: e.shiftKey || e.button === 2 }; canvas.setPointerCapture(e.pointerId); });
  canvas.addEventListener('pointerup', () => { drag = null; });
  canvas.addEventListener('pointermove', (e) => {
    if (drag) {
      const dx = e.clientX - drag.x, dy = e.clientY - drag.y;
      drag.x = e.clientX; drag.y = e.clientY;
      if (drag.pan) {
        const scale = orbit.radius * 2 * Math.tan((camera.fov / 2) * Math.PI / 180) / height;
        const right = new Vector3().setFromMatrixColumn(camera.matrix, 0);
        const up = new Vector3().setFromMatrixColumn(camera.matrix, 1);
        target.addScaledVector(right, -dx * scale).addScaledVector(up, dy * scale);
      } else {
        orbit.theta -= dx * 0.008;
        orbit.phi = Math.min(Math.max(orbit.phi - dy * 0.008, 0.01), Math.PI - 0.01);
      }
      render();
    } else {
      hover(e);
    }
  });
  canvas.addEventListener('wheel', (e) => {
    e.preventDefault();
    orbit.radius = Math.min(Math.max(orbit.radius * Math.exp(e.deltaY * 0.001), radius * 0.05), radius * 20);
    render();
  }, { passive: false });

  // Ids under the pointer: the nearest lamella stretch within a few pixels.
  const tip = document.createElement('div');
  tip.className = 'egg-view-tip';
  const raycaster = new Raycaster();
  function hover(e) {
    const rect = canvas.getBoundingClientRect();
    const ndc = new Vector2(((e.clientX - rect.left) / rect.width) * 2 - 1, -((e.clientY - rect.top) / rect.height) * 2 + 1);
    raycaster.setFromCamera(ndc, camera);
    raycaster.params.Line.threshold = orbit.radius * 2 * Math.tan((camera.fov / 2) * Math.PI / 180) / height * 4;
    const hits = raycaster.intersectObjects(all.filter((o) => o.visible), false);
    if (!hits.length) { tip.style.display = 'none'; return; }
    const hit = hits[0];
    const segment = Math.floor(hit.index / 2);
    const rod = data.rods[hit.object.userData.segmentRod[segment]];
    const first = hit.object.userData.segmentRod.indexOf(hit.object.userData.segmentRod[segment]);
    const d = rod.distance_m[segment - first];
    tip.textContent = `patch P${rod.patch}, lamella ${rod.rod}: ${(d * 100).toFixed(1)} cm from the design surface`;
    tip.style.display = 'block';
    tip.style.left = `${e.clientX - rect.left + 12}px`;
    tip.style.top = `${e.clientY - rect.top + 12}px`;
  }

  // Controls: the design surface and each patch on or off.
  const controls = document.createElement('div');
  controls.className = 'egg-view-controls';
  const toggle = (label, object) => {
    const box_ = document.createElement('label');
    const input = document.createElement('input');
    input.type = 'checkbox';
    input.checked = true;
    input.addEventListener('change', () => { object.visible = input.checked; render(); });
    box_.append(input, ` ${label}`);
    controls.appendChild(box_);
  };
  if (surface) toggle('design surface', surface);
  patchObjects.forEach((object, patch) => toggle(`P${patch}`, object));

  const frame = document.createElement('div');
  frame.className = 'egg-view-frame';
  frame.append(canvas, tip);
  container.append(frame, controls, legend(data.scale_m));
  render();

  // The page's own check that the canvas drew (issue 39's test reads it with --dump-dom): pixels
  // that are not the white background.
  const gl = renderer.getContext();
  const pixels = new Uint8Array(gl.drawingBufferWidth * gl.drawingBufferHeight * 4);
  gl.readPixels(0, 0, gl.drawingBufferWidth, gl.drawingBufferHeight, gl.RGBA, gl.UNSIGNED_BYTE, pixels);
  let ink = 0;
  for (let i = 0; i < pixels.length; i += 4) if (pixels[i] < 250 || pixels[i + 1] < 250 || pixels[i + 2] < 250) ++ink;
  container.dataset.ink = String(ink);
  container.dataset.pixels = String(pixels.length / 4);
}

function start() {
  const container = document.getElementById('egg-view');
  const source = document.getElementById('egg-view-data');
  if (!container || !source) return;
  try {
    mount(container, JSON.parse(source.textContent));
  } catch (error) {
    container.textContent = `The 3D view could not be drawn: ${error.message}`;
    container.dataset.ink = '0';
  }
}

if (document.readyState === 'loading') document.addEventListener('DOMContentLoaded', start);
else start();
