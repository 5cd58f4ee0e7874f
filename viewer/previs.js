// The previs page's code (docs/view.md): the scene, the flights and the lens of one plan, drawn with three.js.
// Written into the page by `cinepath view` (viewer/previs_page.h); everything it reads is in the page.
// A plan is a team of drones, one drone a team of one: every flight is drawn by the same code (its path,
// its camera and position now, its home), and the page shows one flight in detail (data.team.primary:
// the lens graphs, shots, keyframes and feasibility). With several drones each flight has its colour (the
// palette of `cinepath plan --plot`), a selector picks the drone the camera view looks through or "edit"
// (the drone live in the edit at that time), and the timeline shows the edit's cuts and the team's
// conflicts. Every flight is sampled on one clock: sample k is at k / frame rate; a flight that has ended
// holds its last sample.
// Coordinates are three.js's: x east, y up, z south (the plan's ENU (e, n, u) is (e, u, -n) here).
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';

THREE.ColorManagement.enabled = false;  // vertex colours are sRGB bytes: show them as they are

const moduleStartMs = performance.now();
const data = JSON.parse(document.getElementById('previs-data').textContent);
const meshInfo = JSON.parse(document.getElementById('previs-mesh-info').textContent);
const frames = JSON.parse(document.getElementById('previs-frames').textContent);
const S = data.samples;
const N = S.time_s.length;
const team = data.team;
const several = team.flights.length > 1;
const FPS = data.frame_rate_hz;
const FRUSTUM_INFINITY_M = 60;  // far plane drawn for focus at infinity
const FRUSTUM_MAX_M = 200;      // and the farthest one drawn
const LAYER_OVERLAY = 1;        // drawn in the 3D view only, not in the camera view
const LAYER_CAMERA_ONLY = 2;    // drawn in the camera view only
const SKY = 0x9cc3e4;

const $ = (id) => document.getElementById(id);
const fmt = (x, d) => (x === null || x === undefined ? '∞' : Number(x).toFixed(d));
const pos = (k) => new THREE.Vector3(S.position_m[3 * k], S.position_m[3 * k + 1], S.position_m[3 * k + 2]);
const quat = (k) => new THREE.Quaternion(S.quaternion[4 * k], S.quaternion[4 * k + 1], S.quaternion[4 * k + 2],
                                         S.quaternion[4 * k + 3]);
const dioptres = (focus) => (focus === null ? 0 : 1 / focus);

// ---- renderer, scene, cameras ----
const canvas = $('gl');
const renderer = new THREE.WebGLRenderer({ canvas, antialias: true, preserveDrawingBuffer: true });
renderer.outputColorSpace = THREE.LinearSRGBColorSpace;
renderer.setPixelRatio(window.devicePixelRatio || 1);
renderer.setScissorTest(true);
const scene = new THREE.Scene();
scene.add(new THREE.HemisphereLight(0xffffff, 0x606060, 1.6));
const sun = new THREE.DirectionalLight(0xffffff, 1.2);
sun.position.set(0.5, 1, 0.3);
scene.add(sun);

// The extent everything is sized by: the mesh's bounds, the flights' and the subjects' paths (what the
// cameras look at: a telephoto shot's subject may stand a kilometre from its drone, off the mesh).
const bounds = new THREE.Box3();
for (let k = 0; k < N; ++k) bounds.expandByPoint(pos(k));
for (const path of [...team.flights.map((f) => f.position_m || []), ...data.subjects.map((s) => s.position_m)]) {
  // (The primary flight's positions are the page's samples, above.)
  for (let j = 0; j + 2 < path.length; j += 3) {
    bounds.expandByPoint(new THREE.Vector3(path[j], path[j + 1], path[j + 2]));
  }
}
if (meshInfo) {
  bounds.expandByPoint(new THREE.Vector3(...meshInfo.min_m));
  bounds.expandByPoint(new THREE.Vector3(...meshInfo.max_m));
}
if (bounds.isEmpty()) bounds.set(new THREE.Vector3(-10, 0, -10), new THREE.Vector3(10, 10, 10));
const centre = bounds.getCenter(new THREE.Vector3());
const size = Math.max(bounds.getSize(new THREE.Vector3()).length(), 10);
const unit = size / 200;  // marker size
const groundY = meshInfo ? meshInfo.min_m[1] : Math.min(0, bounds.min.y);

const view = new THREE.PerspectiveCamera(50, 1, size / 2000, size * 20);
view.layers.enableAll();
view.layers.disable(LAYER_CAMERA_ONLY);
const controls = new OrbitControls(view, canvas);
controls.enableDamping = false;
// Far enough for the ground past the mesh's edge to reach its haze (below).
const shotCamera = new THREE.PerspectiveCamera(40, data.camera.width_px / data.camera.height_px, 0.1,
                                               Math.max(size * 20, 15000));
shotCamera.layers.set(0);
shotCamera.layers.enable(LAYER_CAMERA_ONLY);

function overlay(object) {
  object.traverse((o) => o.layers.set(LAYER_OVERLAY));
  scene.add(object);
  return object;
}

// ---- mesh ----
async function loadMesh() {
  if (!meshInfo) return 0;
  const text = $('previs-mesh').textContent;
  const binary = atob(text);
  const bytes = new Uint8Array(binary.length);
  for (let i = 0; i < binary.length; ++i) bytes[i] = binary.charCodeAt(i);
  const inflating = new Blob([bytes]).stream().pipeThrough(new DecompressionStream('deflate'));
  const buffer = await new Response(inflating).arrayBuffer();
  const V = meshInfo.vertices, T = meshInfo.triangles;
  const u8 = new Uint8Array(buffer);
  let offset = 0;
  // One stream (viewer/mesh_payload.h): `count` values of `width` bytes as byte planes of deltas at `stride`.
  // Typed arrays wrap on assignment, which is the modulo the deltas were taken in.
  function stream(count, width, stride, out) {
    const p0 = offset, p1 = offset + count, p2 = offset + 2 * count, p3 = offset + 3 * count;
    for (let i = 0; i < count; ++i) {
      let d = u8[p0 + i];
      if (width > 1) d |= u8[p1 + i] << 8;
      if (width > 2) d |= (u8[p2 + i] << 16) | (u8[p3 + i] << 24);
      out[i] = (i >= stride ? out[i - stride] : 0) + d;
    }
    offset += count * width;
    return out;
  }
  const q = stream(3 * V, 2, 3, new Uint16Array(3 * V));
  const positions = new Float32Array(3 * V);
  for (let a = 0; a < 3; ++a) {
    const lo = meshInfo.min_m[a], extent = meshInfo.max_m[a] - meshInfo.min_m[a];
    for (let v = 0; v < V; ++v) positions[3 * v + a] = lo + (q[3 * v + a] / 65535) * extent;
  }
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute('position', new THREE.BufferAttribute(positions, 3));
  let material;
  if (meshInfo.has_colors) {
    geometry.setAttribute('color', new THREE.BufferAttribute(stream(3 * V, 1, 3, new Uint8Array(3 * V)), 3, true));
  }
  if (meshInfo.has_texcoords) {
    // The photo texture (glTF convention: v down, so no flip), times the vertex colours as glTF says.
    const uv = stream(2 * V, 2, 2, new Uint16Array(2 * V));
    geometry.setAttribute('uv', new THREE.BufferAttribute(uv, 2, true));
    const map = await new THREE.TextureLoader().loadAsync(meshInfo.texture);
    map.flipY = false;
    map.colorSpace = THREE.SRGBColorSpace;
    map.anisotropy = renderer.capabilities.getMaxAnisotropy();
    material = new THREE.MeshBasicMaterial({ map, vertexColors: meshInfo.has_colors, side: THREE.DoubleSide });
  } else if (meshInfo.has_colors) {
    material = new THREE.MeshBasicMaterial({ vertexColors: true, side: THREE.DoubleSide });
  } else {
    material = new THREE.MeshLambertMaterial({ color: 0xb8b4aa, side: THREE.DoubleSide });
  }
  const width = meshInfo.index_bytes;
  const indices = stream(3 * T, width, 1, width === 2 ? new Uint16Array(3 * T) : new Uint32Array(3 * T));
  geometry.setIndex(new THREE.BufferAttribute(indices, 1));
  if (!meshInfo.has_colors) geometry.computeVertexNormals();
  const mesh = new THREE.Mesh(geometry, material);
  scene.add(mesh);
  addGroundPastEdge(geometry, material.map ? material.map.image : null);
  return T;
}

// ---- the ground past the mesh's edge, as `cinepath render` draws it (docs/render.md, "The horizon") ----
// A plane at the height of the mesh's border, coloured by the border ring carried outward (each 5-degree sector
// of azimuth about the ring's centre takes the mean colour of its border faces, fading into their mean beyond
// the ring's radius), hazed toward the sky with distance (a 5 km visibility). The faces, their sectors, the
// height, centre and radius come from the page's data (scene/border_ring.h); the colours are taken here, at
// each face's centroid, from the mesh's colours and texture, and averaged in linear light. Drawn first and
// without depth, so the mesh covers it wherever the mesh is seen; in the camera view only, as render's frames.
const GROUND_BLEND_M = 150;
const GROUND_VISIBILITY_M = 5000;
const linearFromSrgb = (c) => (c <= 0.04045 ? c / 12.92 : Math.pow((c + 0.055) / 1.055, 2.4));
function borderFaceColors(geometry, image) {
  const g = meshInfo.ground, index = geometry.index.array;
  const colors = geometry.attributes.color ? geometry.attributes.color.array : null;
  const uv = geometry.attributes.uv ? geometry.attributes.uv.array : null;
  let texels = null, tw = 0, th = 0;
  if (image && uv) {
    // The texture at up to 1024 x 1024 (a box-filtered copy is plenty for a mean per sector).
    tw = Math.min(image.width, 1024);
    th = Math.min(image.height, 1024);
    const c = document.createElement('canvas');
    c.width = tw;
    c.height = th;
    const ctx = c.getContext('2d', { willReadFrequently: true });
    ctx.drawImage(image, 0, 0, tw, th);
    texels = ctx.getImageData(0, 0, tw, th).data;
  }
  return g.faces.map((f) => {
    const color = [0, 0, 0];
    const centroidUv = [0, 0];
    for (let corner = 0; corner < 3; ++corner) {
      const v = index[3 * f + corner];
      for (let a = 0; a < 3; ++a) color[a] += (colors ? linearFromSrgb(colors[3 * v + a] / 255) : 1) / 3;
      if (uv) for (let a = 0; a < 2; ++a) centroidUv[a] += uv[2 * v + a] / 65535 / 3;
    }
    if (!colors && !texels) color.fill(0.5);
    if (texels) {
      const x = Math.min(tw - 1, Math.max(0, Math.floor((centroidUv[0] - Math.floor(centroidUv[0])) * tw)));
      const y = Math.min(th - 1, Math.max(0, Math.floor((centroidUv[1] - Math.floor(centroidUv[1])) * th)));
      for (let a = 0; a < 3; ++a) color[a] *= linearFromSrgb(texels[4 * (y * tw + x) + a] / 255);
    }
    return color;
  });
}
function addGroundPastEdge(geometry, image) {
  const g = meshInfo.ground;
  if (!g || !g.faces.length) return;
  const faceColors = borderFaceColors(geometry, image);
  // Mean per sector (scene/border_ring.h, SectorColors); an empty sector takes the nearest filled one on each
  // side, weighted by nearness.
  const n = g.sectors, sum = Array.from({ length: n }, () => [0, 0, 0]), count = new Array(n).fill(0);
  const mean = [0, 0, 0];
  faceColors.forEach((c, i) => {
    for (let a = 0; a < 3; ++a) sum[g.face_sectors[i]][a] += c[a];
    ++count[g.face_sectors[i]];
    for (let a = 0; a < 3; ++a) mean[a] += c[a] / faceColors.length;
  });
  const sectorMean = (k) => sum[k].map((v) => v / count[k]);
  const sectors = [];
  for (let k = 0; k < n; ++k) {
    if (count[k] > 0) {
      sectors.push(sectorMean(k));
      continue;
    }
    let lo = 1, hi = 1;
    while (count[(k - lo + n) % n] === 0) ++lo;
    while (count[(k + hi) % n] === 0) ++hi;
    const a = sectorMean((k - lo + n) % n), b = sectorMean((k + hi) % n);
    sectors.push(a.map((v, i) => (hi * v + lo * b[i]) / (lo + hi)));
  }
  // Smoothed around the ring as render does (weights r + 1 - |d| over +-r sectors).
  const r = g.smooth_sectors, smooth = [];
  for (let k = 0; k < n; ++k) {
    const c = [0, 0, 0];
    let weight = 0;
    for (let d = -r; d <= r; ++d) {
      const w = r + 1 - Math.abs(d), s = sectors[(k + d + n) % n];
      for (let a = 0; a < 3; ++a) c[a] += w * s[a];
      weight += w;
    }
    smooth.push(new THREE.Vector3(c[0] / weight, c[1] / weight, c[2] / weight));
  }
  const sky = new THREE.Color(SKY);
  const material = new THREE.ShaderMaterial({
    uniforms: {
      sectors: { value: smooth },
      meanColor: { value: new THREE.Vector3(...mean) },
      centre: { value: new THREE.Vector2(g.centre_m[0], g.centre_m[1]) },
      radius: { value: g.radius_m },
      hazeColor: { value: new THREE.Vector3(linearFromSrgb(sky.r), linearFromSrgb(sky.g), linearFromSrgb(sky.b)) },
    },
    vertexShader: `varying vec3 vWorld;
      void main() {
        vec4 world = modelMatrix * vec4(position, 1.0);
        vWorld = world.xyz;
        gl_Position = projectionMatrix * viewMatrix * world;
      }`,
    fragmentShader: `uniform vec3 sectors[${n}];
      uniform vec3 meanColor, hazeColor;
      uniform vec2 centre;
      uniform float radius;
      varying vec3 vWorld;
      vec3 srgb(vec3 c) {
        return mix(c * 12.92, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(vec3(0.0031308), c));
      }
      void main() {
        vec2 d = vec2(vWorld.x - centre.x, -(vWorld.z - centre.y));  // east, north of the ring's centre
        float s = (atan(d.y, d.x) + 3.14159265) / 6.28318531 * ${n}.0 - 0.5;
        float k0 = floor(s);
        int a = int(mod(k0, ${n}.0)), b = int(mod(k0 + 1.0, ${n}.0));
        vec3 ring = mix(sectors[a], sectors[b], s - k0);
        vec3 color = mix(ring, meanColor, 1.0 - exp(-max(0.0, length(d) - radius) / ${GROUND_BLEND_M}.0));
        float haze = 1.0 - exp(-3.0 * distance(vWorld, cameraPosition) / ${GROUND_VISIBILITY_M}.0);
        gl_FragColor = vec4(srgb(mix(color, hazeColor, haze)), 1.0);
      }`,
    depthWrite: false,
    side: THREE.FrontSide,
  });
  const extent = 2 * shotCamera.far;
  const plane = new THREE.Mesh(new THREE.PlaneGeometry(extent, extent), material);
  plane.rotation.x = -Math.PI / 2;  // facing up: a camera below the plane does not see it
  plane.position.set(g.centre_m[0], g.height_m, g.centre_m[1]);
  plane.renderOrder = -1;
  plane.layers.set(LAYER_CAMERA_ONLY);
  scene.add(plane);
}

// ---- ground grid with metres, north arrow ----
function niceStep(span) {
  const raw = span / 12;
  const p = Math.pow(10, Math.floor(Math.log10(raw)));
  for (const m of [1, 2, 5, 10]) if (m * p >= raw) return m * p;
  return 10 * p;
}
function label(text, height = 0.03, color = '#ffffff') {
  const c = document.createElement('canvas');
  const ctx = c.getContext('2d');
  ctx.font = 'bold 40px DejaVu Sans, sans-serif';
  const w = Math.ceil(ctx.measureText(text).width) + 16;
  c.width = w;
  c.height = 56;
  ctx.font = 'bold 40px DejaVu Sans, sans-serif';
  ctx.fillStyle = '#00000090';
  ctx.fillRect(0, 0, w, 56);
  ctx.fillStyle = color;
  ctx.textBaseline = 'middle';
  ctx.fillText(text, 8, 29);
  const texture = new THREE.CanvasTexture(c);
  // A constant size on the screen (a fraction of the view's height), however near the camera.
  const sprite = new THREE.Sprite(new THREE.SpriteMaterial({ map: texture, depthTest: false, sizeAttenuation: false }));
  sprite.scale.set((height * w) / 56, height, 1);
  sprite.renderOrder = 10;
  return sprite;
}
const northArrow = new THREE.Group();  // placed by the view (topView, perspectiveView)
// The points the 3D view keeps in its picture (perspectiveView): the corners of `bounds`, then the grid's.
const framePoints = [];
for (const x of [bounds.min.x, bounds.max.x]) {
  for (const y of [bounds.min.y, bounds.max.y]) {
    for (const z of [bounds.min.z, bounds.max.z]) framePoints.push(new THREE.Vector3(x, y, z));
  }
}
const gridStep = niceStep(Math.max(bounds.max.x - bounds.min.x, bounds.max.z - bounds.min.z, 20));
{
  const x0 = Math.floor(bounds.min.x / gridStep) * gridStep, x1 = Math.ceil(bounds.max.x / gridStep) * gridStep;
  const z0 = Math.floor(bounds.min.z / gridStep) * gridStep, z1 = Math.ceil(bounds.max.z / gridStep) * gridStep;
  const points = [];
  for (let x = x0; x <= x1 + 1e-9; x += gridStep) points.push(x, groundY, z0, x, groundY, z1);
  for (let z = z0; z <= z1 + 1e-9; z += gridStep) points.push(x0, groundY, z, x1, groundY, z);
  const g = new THREE.BufferGeometry();
  g.setAttribute('position', new THREE.Float32BufferAttribute(points, 3));
  const grid = overlay(new THREE.LineSegments(g, new THREE.LineBasicMaterial({ color: 0xffffff, transparent: true,
                                                                                opacity: 0.35 })));
  if (!meshInfo) {
    // Without a mesh the camera view shows the grid on a plain ground, so that the horizon reads.
    grid.layers.enable(0);
    const ground = new THREE.Mesh(new THREE.PlaneGeometry(size * 40, size * 40),
                                  new THREE.MeshBasicMaterial({ color: 0x66735f }));
    ground.rotation.x = -Math.PI / 2;
    ground.position.set(centre.x, groundY - 0.02, centre.z);
    ground.layers.set(LAYER_CAMERA_ONLY);
    scene.add(ground);
  }
  const every = Math.max(1, Math.round((x1 - x0) / gridStep / 6));
  const h = gridStep * 0.35;
  for (let i = 0, x = x0; x <= x1 + 1e-9; x += gridStep, ++i) {
    if (i % every) continue;
    const s = label(`E ${Math.round(x)} m`);
    s.position.set(x, groundY, z1 + h);
    overlay(s);
  }
  for (let i = 0, z = z0; z <= z1 + 1e-9; z += gridStep, ++i) {
    if (i % every) continue;
    const s = label(`N ${Math.round(-z)} m`);
    s.position.set(x0 - 2 * h, groundY, z);
    overlay(s);
  }
  // North arrow on the ground, pointing along -z: east of the grid's northern corner in the top view (right of
  // the grid), north of the grid's middle in the 3D views (east of the grid it falls under the panel there).
  const length = 2 * gridStep;
  northArrow.add(new THREE.ArrowHelper(new THREE.Vector3(0, 0, -1), new THREE.Vector3(0, 0, length), length,
                                       0xff5a4e, length * 0.3, length * 0.18));
  const n = label('N', 0.045, '#ff8a80');
  n.position.set(0, 0, -gridStep * 0.4);
  northArrow.add(n);
  northArrow.userData.top = new THREE.Vector3(x1 + gridStep, groundY, z0);
  northArrow.userData.side = new THREE.Vector3(0.5 * (x0 + x1), groundY, z0 - length - gridStep);
  // The grid's corners, its labels' rows (west and south of it) and the arrow's tip, with its letter.
  for (const x of [x0 - 2 * h, x1]) {
    for (const z of [z0 - length - 1.4 * gridStep, z1 + h]) framePoints.push(new THREE.Vector3(x, groundY, z));
  }
  northArrow.position.copy(northArrow.userData.side);
  overlay(northArrow);
  $('hud-grid').textContent = `grid ${gridStep} m · labels: metres east / north of the origin`;
}

// ---- the flight: path coloured by speed, keyframes, frustums, violations ----
const speeds = S.speed_m_s;
const maxSpeed = speeds.reduce((a, b) => Math.max(a, b), 1e-6);  // no spread: plans have 10^5 samples
function speedColor(v) {
  const stops = [[0x2b, 0x6c, 0xff], [0x18, 0xc4, 0xa0], [0xe8, 0xd8, 0x2a], [0xff, 0x3b, 0x2f]];
  const t = Math.min(1, Math.max(0, v / maxSpeed)) * (stops.length - 1);
  const i = Math.min(stops.length - 2, Math.floor(t)), f = t - i;
  return stops[i].map((c, j) => (c + (stops[i + 1][j] - c) * f) / 255);
}
$('speed-min').textContent = '0';
$('speed-max').textContent = `${fmt(maxSpeed, 1)} m/s`;
// Every flight: its samples (the primary's are the page's own), the colour of its path at sample j (one
// drone: by speed; several: the flight's colour) and of its camera (one drone: orange).
const flights = team.flights.map((f, i) => {
  const s = i === team.primary ? S : f;
  const n = s.time_s.length;
  // Its shots with their times and its broken limits (the primary's are the page's own).
  const shots = i === team.primary ? data.shots : f.shot_spans;
  const violations = i === team.primary ? data.violations : f.violations;
  const keyframes = i === team.primary ? data.keyframes : f.keyframes;
  const color = new THREE.Color(several ? f.colour : 0xff9d2e);
  const pathColor = several ? () => color.toArray() : (j) => speedColor(speeds[j]);
  return {
    f, s, n, shots, violations, keyframes, color, pathColor,
    pos: (j) => new THREE.Vector3(s.position_m[3 * j], s.position_m[3 * j + 1], s.position_m[3 * j + 2]),
    quat: (j) => new THREE.Quaternion(s.quaternion[4 * j], s.quaternion[4 * j + 1], s.quaternion[4 * j + 2],
                                      s.quaternion[4 * j + 3]),
  };
});
let flightPaths = 0;
for (const flight of flights) {
  // Segments between consecutive samples, none across a cut (the drone does not fly there).
  const cuts = new Set(flight.f.cuts_before_sample);
  const p = [], c = [];
  for (let j = 0; j + 1 < flight.n; ++j) {
    if (cuts.has(j + 1)) continue;
    p.push(...flight.pos(j).toArray(), ...flight.pos(j + 1).toArray());
    c.push(...flight.pathColor(j), ...flight.pathColor(j + 1));
  }
  const g = new THREE.BufferGeometry();
  g.setAttribute('position', new THREE.Float32BufferAttribute(p, 3));
  g.setAttribute('color', new THREE.Float32BufferAttribute(c, 3));
  overlay(new THREE.LineSegments(g, new THREE.LineBasicMaterial({ vertexColors: true }))).name =
    `flight ${flight.f.name}`;
  if (flight.n > 1) ++flightPaths;
}
// Every flight's samples inside its broken ranges, as red points on its path.
const badPoints = [];
for (const flight of flights) {
  for (let j = 0; j < flight.n; ++j) {
    const t = flight.s.time_s[j];
    if (flight.violations.some((v) => t >= v.start_time_s - 1e-9 && t <= v.end_time_s + 1e-9)) {
      badPoints.push(...flight.pos(j).toArray());
    }
  }
}
if (badPoints.length) {
  const p = badPoints;
  const g = new THREE.BufferGeometry();
  g.setAttribute('position', new THREE.Float32BufferAttribute(p, 3));
  overlay(new THREE.Points(g, new THREE.PointsMaterial({ color: 0xff2a1a, size: 5, sizeAttenuation: false })));
}
{
  const geometry = new THREE.OctahedronGeometry(unit * 1.2);
  const material = new THREE.MeshBasicMaterial({ color: 0xffd34d });
  for (const flight of flights) {  // every drone's
    for (const key of flight.keyframes) {
      const m = new THREE.Mesh(geometry, material);
      m.position.set(...key.position_m);
      overlay(m);
    }
  }
}
// Frustum lines of a camera at `o` turned by `q` (looking along its -z) to the far plane at the focus:
// every flight's camera is drawn by this one function.
function cameraFrustumPoints(o, q, verticalFovDeg, aspect, focus, out) {
  const far = focus === null ? FRUSTUM_INFINITY_M : Math.min(focus, FRUSTUM_MAX_M);
  const tanV = Math.tan(THREE.MathUtils.degToRad(verticalFovDeg / 2));
  const tanH = tanV * aspect;
  const corners = [[-1, -1], [1, -1], [1, 1], [-1, 1]].map(([sx, sy]) =>
    new THREE.Vector3(sx * tanH * far, sy * tanV * far, -far).applyQuaternion(q).add(o));
  for (let i = 0; i < 4; ++i) {
    out.push(...o.toArray(), ...corners[i].toArray());
    out.push(...corners[i].toArray(), ...corners[(i + 1) % 4].toArray());
  }
  // A tick on the top edge shows which way is up in the picture.
  const up = new THREE.Vector3(0, tanV * far * 1.25, -far).applyQuaternion(q).add(o);
  out.push(...corners[2].toArray(), ...up.toArray(), ...up.toArray(), ...corners[3].toArray());
  return out;
}
// The plan's camera at sample k.
function frustumPoints(k, out) {
  return cameraFrustumPoints(pos(k), quat(k), S.vertical_fov_deg[k], data.camera.width_px / data.camera.height_px,
                             S.focus_distance_m[k], out);
}
{
  const stride = Math.max(1, Math.round(2 * FPS));
  const p = [];
  for (let k = 0; k < N; k += stride) frustumPoints(k, p);
  const g = new THREE.BufferGeometry();
  g.setAttribute('position', new THREE.Float32BufferAttribute(p, 3));
  overlay(new THREE.LineSegments(g, new THREE.LineBasicMaterial({ color: 0xffffff, transparent: true,
                                                                   opacity: 0.3 })));
}
// Where the photos that built the scene were taken (scene.json's cameras), as small blue points.
if (data.photos && data.photos.length) {
  const g = new THREE.BufferGeometry();
  g.setAttribute('position', new THREE.Float32BufferAttribute(data.photos.flatMap((p) => p.position_m), 3));
  overlay(new THREE.Points(g, new THREE.PointsMaterial({ color: 0x4db8ff, size: 6, sizeAttenuation: false })));
}
// Each flight's camera and position now (placed by setSample), its name with several drones, its home.
for (const flight of flights) {
  const { color } = flight;
  flight.frustum = new THREE.LineSegments(new THREE.BufferGeometry(), new THREE.LineBasicMaterial({ color }));
  flight.marker = new THREE.Mesh(new THREE.SphereGeometry(unit * 1.5, 16, 12), new THREE.MeshBasicMaterial({ color }));
  if (several) {
    const tag = label(flight.f.name, 0.026, flight.f.colour);
    tag.center.set(0.5, -0.6);
    flight.marker.add(tag);
  }
  const group = new THREE.Group();
  group.add(flight.frustum);
  group.add(flight.marker);
  overlay(group);
  if (flight.f.home_m) {
    const home = new THREE.Mesh(new THREE.BoxGeometry(unit * 2, unit * 0.6, unit * 2),
                                new THREE.MeshBasicMaterial({ color }));
    home.position.set(...flight.f.home_m);
    overlay(home);
  }
}
const flightIndex = (name) => team.flights.findIndex((f) => f.name === name);
// Which flight is live in the edit at time t, or -1 without an edit.
function liveFlightAt(t) {
  if (!team.edit.length) return -1;
  let live = flightIndex(team.edit[0].drone);
  for (const cut of team.edit) if (cut.at_s <= t + 1e-9) live = flightIndex(cut.drone);
  return live;
}

// The edit as intervals [from, to) with the flight live in each (none without an edit).
const editIntervals = team.edit.map((cut, c) => ({
  from: cut.at_s,
  to: c + 1 < team.edit.length ? team.edit[c + 1].at_s : Infinity,
  live: Math.max(0, flightIndex(cut.drone)),
}));
// The shots the edit shows: each live drone's shots within its intervals, clipped to them.
function editShots() {
  const out = [];
  for (const { from, to, live } of editIntervals) {
    for (const shot of flights[live].shots) {
      const a = Math.max(from, shot.start_time_s), b = Math.min(to, shot.end_time_s);
      if (a < b) out.push({ ...shot, start_time_s: a, end_time_s: b, drone: flights[live].f.name });
    }
  }
  return out;
}

// ---- subjects: paths and where they are now (seen by the camera view too) ----
// The colours `cinepath render` gives subject i (its palette, sRGB-encoded), so that the live camera view
// and the rendered frames agree.
const SUBJECT_COLORS = [0xf39527, 0xe73fcb, 0x27d3e7, 0xf3e727, 0xaa6cf3, 0x95ed3f];
const subjectMarkers = data.subjects.map((subject, i) => {
  const color = SUBJECT_COLORS[i % SUBJECT_COLORS.length];
  const p = new Float32Array(subject.position_m);
  const g = new THREE.BufferGeometry();
  g.setAttribute('position', new THREE.BufferAttribute(p, 3));
  overlay(new THREE.Line(g, new THREE.LineBasicMaterial({ color })));
  const h = subject.height_m;
  const body = new THREE.Mesh(new THREE.CylinderGeometry(h * 0.18, h * 0.18, h, 16),
                              new THREE.MeshBasicMaterial({ color }));
  body.geometry.translate(0, h / 2, 0);
  scene.add(body);
  const tag = label(subject.name, 0.028, '#' + color.toString(16).padStart(6, '0'));
  tag.layers.set(LAYER_OVERLAY);
  tag.center.set(0.5, -0.4);
  body.add(tag);
  return { subject, body };
});

// ---- panels ----
const cameraBox = $('camera-box');
cameraBox.style.aspectRatio = `${data.camera.width_px} / ${data.camera.height_px}`;
const origin = data.origin;
const shotCount = flights.reduce((sum, flight) => sum + flight.shots.length, 0);  // every drone's
$('hud-plan').textContent = `${data.plan} · ${N} samples at ${FPS} fps · ${shotCount} ` +
  `shot${shotCount === 1 ? '' : 's'}` +
  (meshInfo ? ` · ${meshInfo.source}: ${meshInfo.triangles} triangles` : ' · no scene mesh') +
  (data.photos && data.photos.length ? ` · ${data.photos.length} photos (blue)` : '');
$('hud-origin').textContent = origin
  ? `WGS84 origin ${fmt(Math.abs(origin.lat_deg), 7)}°${origin.lat_deg >= 0 ? 'N' : 'S'} ` +
    `${fmt(Math.abs(origin.lon_deg), 7)}°${origin.lon_deg >= 0 ? 'E' : 'W'} ${fmt(origin.height_m, 2)} m ellipsoidal`
  : 'no WGS84 origin: local metres';
{
  // One line per broken limit: how many ranges, the worst value; every range in the tooltip. With several
  // drones every drone's limits, each line naming its drone (a drone with none: one ✔ line for it).
  const linesOf = (violations) => {
    const byLimit = new Map();
    for (const v of violations) {
      if (!byLimit.has(v.limit)) byLimit.set(v.limit, []);
      byLimit.get(v.limit).push(v);
    }
    return [...byLimit].map(([limit, list]) => {
      const worst = list.reduce((a, b) => (b.minimum ? b.worst_value < a.worst_value : b.worst_value > a.worst_value)
        ? b : a);
      return `${limit}: ${list.length} range${list.length > 1 ? 's' : ''}, worst ${fmt(worst.worst_value, 2)} ` +
             `${worst.minimum ? '<' : '>'} ` +
             `${fmt(worst.limit_value, 2)} ${worst.unit} at ${fmt(worst.start_time_s, 2)} s`;
    });
  };
  const broken = flights.some((flight) => flight.violations.length > 0);
  const lines = [], tips = [];
  for (const flight of flights) {
    const who = several ? `${flight.f.name}: ` : '';
    for (const line of linesOf(flight.violations)) lines.push(`✖ ${who}${line}`);
    if (broken && several && !flight.violations.length) lines.push(`✔ ${who}no violations`);
    for (const v of flight.violations) {
      tips.push(`${who}${v.limit} ${fmt(v.start_time_s, 2)}–${fmt(v.end_time_s, 2)} s (${v.shot})`);
    }
  }
  const box = $('violations');
  box.textContent = broken ? lines.join('\n')
    : `✔ feasibility: no violations${several ? ` (${flights.length} drones)` : ''}`;
  box.title = tips.join('\n');
  box.style.color = broken ? '' : '#9be59b';
}
const t0 = S.time_s[0] ?? 0, t1 = S.time_s[N - 1] ?? 0;
const span = Math.max(t1 - t0, 1e-9);
const slider = $('slider');
slider.max = String(Math.max(0, N - 1));
{
  const track = $('track');
  // The shots on the timeline: with an edit, the ones it shows (each named with its drone in the tooltip).
  for (const shot of team.edit.length ? editShots() : data.shots) {
    const d = document.createElement('div');
    d.className = 'shot';
    d.style.left = `${((shot.start_time_s - t0) / span) * 100}%`;
    d.style.width = `${((shot.end_time_s - shot.start_time_s) / span) * 100}%`;
    d.textContent = shot.name;
    d.title = `${shot.drone ? shot.drone + ': ' : ''}${shot.name} (${shot.type})`;
    track.appendChild(d);
  }
  // Keyframes as yellow ticks under the slider, rendered frames (--frames) as grey ones above them.
  const tick = (t, cls, title) => {
    const d = document.createElement('div');
    d.className = cls;
    d.style.left = `${((t - t0) / span) * 100}%`;
    d.title = title;
    track.appendChild(d);
  };
  for (const flight of flights) {
    for (const key of flight.keyframes) {
      tick(key.time_s, 'key', `keyframe ${several ? flight.f.name + ' ' : ''}${key.shot} ${fmt(key.time_s, 2)} s`);
    }
  }
  for (const k of Object.keys(frames)) tick(S.time_s[Number(k)], 'frame', `rendered frame ${k}`);
  for (const flight of flights) {
    for (const v of flight.violations) {
      const d = document.createElement('div');
      d.className = 'bad';
      d.style.left = `${((v.start_time_s - t0) / span) * 100}%`;
      d.style.width = `${Math.max(0.2, ((v.end_time_s - v.start_time_s) / span) * 100)}%`;
      d.title = several ? `${flight.f.name}: ${v.limit}` : v.limit;
      track.insertBefore(d, slider);
    }
  }
}

// ---- several drones: the selector, the edit's cuts and the team's conflicts ----
// The drone the camera view looks through: "edit" (the live drone, when the plan has an edit) or a flight.
let selected = team.edit.length ? 'edit' : team.primary;
if (several) {
  const box = document.createElement('div');
  box.id = 'drones';
  box.className = 'line';
  box.appendChild(document.createTextNode('camera view: '));
  const buttons = [];
  const add = (value, text, colour) => {
    const b = document.createElement('button');
    b.dataset.drone = String(value);
    if (colour) {
      const chip = document.createElement('span');
      chip.className = 'chip';
      chip.style.background = colour;
      b.appendChild(chip);
    }
    b.appendChild(document.createTextNode(text));
    b.addEventListener('click', () => {
      selected = value;
      for (const other of buttons) other.classList.toggle('on', other === b);
      setSample(k);
    });
    b.classList.toggle('on', value === selected);
    buttons.push(b);
    box.appendChild(b);
  };
  if (team.edit.length) add('edit', 'edit (live drone)', null);
  team.flights.forEach((f, i) => add(i, f.name, f.colour));
  $('hud').appendChild(box);
  // (a no-break space keeps the count with its word where the line wraps)
  $('hud-plan').textContent += ` · ${team.flights.length}\u00a0drones: ` +
    team.flights.map((f, i) => `${f.name} (${f.drone}, ${flights[i].n}\u00a0samples)`).join(', ');
  $('legend').style.display = 'none';  // the paths are in the drones' colours, not by speed
}
{
  // The edit's cuts (bars in the live drone's colour above the track) and the conflicts (separation red, a
  // drone in another's shot orange); none for one drone.
  const track = $('track');
  for (let c = 0; c < team.edit.length; ++c) {
    const cut = team.edit[c];
    const end = c + 1 < team.edit.length ? team.edit[c + 1].at_s : t1;
    const d = document.createElement('div');
    d.className = 'edit';
    d.style.left = `${((cut.at_s - t0) / span) * 100}%`;
    d.style.width = `${Math.max(0.2, ((end - cut.at_s) / span) * 100)}%`;
    const i = flightIndex(cut.drone);
    d.style.background = i >= 0 ? team.flights[i].colour : '#888';
    d.title = `${fmt(cut.at_s, 2)} s: cut to ${cut.drone}${cut.match_focus ? ' (focus matched)' : ''}`;
    track.appendChild(d);
  }
  for (const v of team.conflicts) {
    const d = document.createElement('div');
    d.className = 'conflict';
    d.dataset.limit = v.limit;
    d.style.left = `${((v.start_time_s - t0) / span) * 100}%`;
    d.style.width = `${Math.max(0.2, ((v.end_time_s - v.start_time_s) / span) * 100)}%`;
    d.style.background = v.limit === 'separation' ? '#ff3b2f66' : '#ff9d2e66';
    d.title = v.limit === 'separation'
      ? `separation ${v.drone}–${v.other}: ${fmt(v.worst_value, 2)} m < ${fmt(v.limit_value, 2)} m, ` +
        `${fmt(v.start_time_s, 2)}–${fmt(v.end_time_s, 2)} s`
      : `${v.other} in ${v.drone}'s shot (${fmt(v.worst_value, 1)} px), ` +
        `${fmt(v.start_time_s, 2)}–${fmt(v.end_time_s, 2)} s`;
    track.insertBefore(d, slider);
  }
  if (several) {
    const box = $('violations');
    const lines = team.conflicts.map((v) => (v.limit === 'separation'
      ? `✖ separation ${v.drone}–${v.other}: ${fmt(v.worst_value, 2)} < ${fmt(v.limit_value, 2)} m`
      : `✖ ${v.other} in ${v.drone}'s shot`) + ` at ${fmt(v.start_time_s, 2)}–${fmt(v.end_time_s, 2)} s`);
    box.textContent = (lines.length ? lines.join('\n') : `✔ team: every pair ≥ ${fmt(team.min_separation_m, 1)} m ` +
                       'apart, no drone in another\'s shot') + '\n' + box.textContent;
    box.style.color = lines.length ? '#ffb27a' : box.style.color;
  }
}

// ---- lens graphs ----
const graphs = $('graphs');
// They show the lens of the drone the camera view looks through: a drone's own, or with "edit" selected the
// lens of the drone live at each time (the sequence as it is cut), with the edit's cuts for shot lines.
const seriesKinds = [
  { name: 'focal length', unit: 'mm', value: (s, j) => s.focal_length_mm[j], digits: 1 },
  { name: 'focus', unit: 'dpt (1/m)', value: (s, j) => dioptres(s.focus_distance_m[j]), digits: 3 },
  { name: 'f-number', unit: '', value: (s, j) => s.f_number[j], digits: 1 },
];
// The flight and its sample whose lens the graphs show at page sample i.
function lensSampleAt(i) {
  const f = selected === 'edit' ? liveFlightAt(S.time_s[i]) : selected;
  const flight = flights[f >= 0 ? f : team.primary];
  return [flight, Math.min(i, flight.n - 1)];
}
let graphKey = null, series = [], graphLines = [], graphBad = [], graphBreaks = new Set();
// The graphs' series (each value per page sample), shot lines and shaded ranges for the current selection.
function graphData() {
  const key = String(selected);
  if (key === graphKey) return;
  graphKey = key;
  series = seriesKinds.map((kind) => {
    const values = new Float64Array(N);
    let lo = Infinity, hi = -Infinity;
    for (let i = 0; i < N; ++i) {
      const [flight, j] = lensSampleAt(i);
      values[i] = kind.value(flight.s, j);
      lo = Math.min(lo, values[i]);
      hi = Math.max(hi, values[i]);
    }
    if (!(hi > lo)) { lo -= 1; hi += 1; }
    const pad = (hi - lo) * 0.08;
    // Focal length, dioptres and f-number are never negative: neither is an axis (a constant focus of
    // 0.05 dpt would otherwise span -1.1 .. 1.2).
    return { ...kind, value: (i) => values[i], lo: Math.max(0, lo - pad), hi: hi + pad };
  });
  graphBreaks = new Set();  // the samples where the graphed drone changes (a cut of the edit): no line across
  for (let i = 1; i < N; ++i) if (lensSampleAt(i)[0] !== lensSampleAt(i - 1)[0]) graphBreaks.add(i);
  if (selected === 'edit') {
    // The cuts and the shots the edit shows; each live drone's broken ranges while it is live.
    graphLines = [...new Set([...team.edit.map((cut) => cut.at_s), ...editShots().map((shot) => shot.start_time_s)])];
    graphBad = [];
    for (const { from, to, live } of editIntervals) {
      for (const v of flights[live].violations) {
        const a = Math.max(from, v.start_time_s), b = Math.min(to, v.end_time_s);
        if (a <= b) graphBad.push([a, b]);
      }
    }
  } else {
    const flight = flights[selected];
    graphLines = flight.shots.map((shot) => shot.start_time_s);
    graphBad = flight.violations.map((v) => [v.start_time_s, v.end_time_s]);
  }
  if (several) {
    $('lens-title').textContent = `Lens · ${selected === 'edit' ? 'edit (live drone)' : flights[selected].f.name}`;
  }
  graphs.dataset.drone = selected === 'edit' ? 'edit' : flights[selected].f.name;
}
function drawGraphs(k) {
  const dpr = window.devicePixelRatio || 1;
  const w = graphs.clientWidth, h = graphs.clientHeight;
  if (graphs.width !== Math.round(w * dpr) || graphs.height !== Math.round(h * dpr)) {
    graphs.width = Math.round(w * dpr);
    graphs.height = Math.round(h * dpr);
  }
  graphData();
  const ctx = graphs.getContext('2d');
  ctx.setTransform(dpr, 0, 0, dpr, 0, 0);
  ctx.clearRect(0, 0, w, h);
  const rowH = h / series.length, left = 46, right = w - 6;
  const x = (t) => left + ((t - t0) / span) * (right - left);
  series.forEach((s, r) => {
    const top = r * rowH + 16, bottom = (r + 1) * rowH - 6;
    const y = (v) => bottom - ((v - s.lo) / (s.hi - s.lo)) * (bottom - top);
    ctx.fillStyle = '#1e2229';
    ctx.fillRect(left, top, right - left, bottom - top);
    ctx.fillStyle = '#ff3b2f44';
    for (const [a, b] of graphBad) ctx.fillRect(x(a), top, Math.max(1, x(b) - x(a)), bottom - top);
    ctx.strokeStyle = '#4a5360';
    ctx.lineWidth = 1;
    for (const t of graphLines) {
      ctx.beginPath();
      ctx.moveTo(Math.round(x(t)) + 0.5, top);
      ctx.lineTo(Math.round(x(t)) + 0.5, bottom);
      ctx.stroke();
    }
    ctx.strokeStyle = ['#6fb7ff', '#7ee0a1', '#ffd166'][r];
    ctx.lineWidth = 1.5;
    ctx.beginPath();
    for (let i = 0; i < N; ++i) {
      (i && !graphBreaks.has(i) ? ctx.lineTo : ctx.moveTo).call(ctx, x(S.time_s[i]), y(s.value(i)));
    }
    ctx.stroke();
    ctx.fillStyle = '#c4cad3';
    ctx.font = '11px DejaVu Sans, sans-serif';
    ctx.textBaseline = 'alphabetic';
    ctx.fillText(`${s.name} ${s.unit ? '(' + s.unit + ')' : ''}: ${fmt(s.value(k), s.digits)}`, left, top - 4);
    ctx.fillStyle = '#8c95a3';
    ctx.fillText(fmt(s.hi, s.digits), 2, top + 9);
    ctx.fillText(fmt(s.lo, s.digits), 2, bottom);
  });
  ctx.strokeStyle = '#ff9d2e';
  ctx.lineWidth = 1.5;
  ctx.beginPath();
  ctx.moveTo(x(S.time_s[k]), 0);
  ctx.lineTo(x(S.time_s[k]), h);
  ctx.stroke();
  graphs.dataset.focal = fmt(series[0].value(k), 3);  // what the graphs read now (tests/viewer/browser_team.sh)
}
function seekFromGraph(event) {
  const r = graphs.getBoundingClientRect();
  const t = t0 + ((event.clientX - r.left - 46) / (r.width - 52)) * span;
  setSample(sampleAtTime(t));
}
graphs.addEventListener('pointerdown', (e) => { seekFromGraph(e); graphs.setPointerCapture(e.pointerId); });
graphs.addEventListener('pointermove', (e) => { if (e.buttons) seekFromGraph(e); });

// ---- the current sample ----
let k = 0;
function sampleAtTime(t) {
  let lo = 0, hi = N - 1;
  while (lo < hi) {
    const mid = (lo + hi) >> 1;
    if (S.time_s[mid] < t) lo = mid + 1; else hi = mid;
  }
  if (lo > 0 && Math.abs(S.time_s[lo - 1] - t) <= Math.abs(S.time_s[lo] - t)) lo -= 1;
  return lo;
}
// The readout of the primary flight (its shot, speed and lens) or of another drone (its camera and focus).
function readoutText(flight, j, live) {
  const t = S.time_s[k];
  const p = flight.pos(j), focus = flight.s.focus_distance_m[j];
  const drone = several ? `   drone ${flight.f.name}` : '';
  const liveText = live >= 0 ? '   live in the edit: ' + team.flights[live].name : '';
  const position = `camera  E ${fmt(p.x, 2)}  N ${fmt(-p.z, 2)}  U ${fmt(p.y, 2)} m`;
  if (flight === flights[team.primary]) {
    const shot = data.shots[S.shot[k]];
    return `t ${fmt(t, 3)} s   frame ${k} / ${N - 1}   shot ${shot ? shot.name + ' (' + shot.type + ')' : '—'}` +
      `${drone}${liveText}\n${position}   speed ${fmt(S.speed_m_s[k], 2)} m/s\n` +
      `lens    ${fmt(S.focal_length_mm[k], 1)} mm  f/${fmt(S.f_number[k], 1)}  focus ${fmt(focus, 2)} m ` +
      `(${fmt(dioptres(focus), 3)} dpt)  vFOV ${fmt(S.vertical_fov_deg[k], 1)}°`;
  }
  const shot = flight.shots.find((span, i) => span.start_time_s <= t &&
                                  (t < span.end_time_s || i === flight.shots.length - 1));
  return `t ${fmt(t, 3)} s   frame ${k} / ${N - 1}   shot ${shot ? shot.name + ' (' + shot.type + ')' : '—'}` +
    `${drone}${liveText}\n` +
    `${position}${j < k ? '   (flight ended: holding)' : ''}\n` +
    `lens    ${fmt(flight.s.focal_length_mm[j], 1)} mm  f/${fmt(flight.s.f_number[j], 1)}  focus ${fmt(focus, 2)} m ` +
    `(${fmt(dioptres(focus), 3)} dpt)  vFOV ${fmt(flight.s.vertical_fov_deg[j], 1)}°`;
}
// Every flight at sample k (a flight that has ended holds its last sample), the camera view through the
// selected drone (or the one live in the edit), the subjects, the readout and the lens graphs.
function setSample(index) {
  k = Math.max(0, Math.min(N - 1, index));
  if (N === 0) return;
  slider.value = String(k);
  for (const flight of flights) {
    const j = Math.min(k, flight.n - 1);
    flight.marker.position.copy(flight.pos(j));
    flight.frustum.geometry.dispose();
    flight.frustum.geometry = new THREE.BufferGeometry();
    flight.frustum.geometry.setAttribute('position', new THREE.Float32BufferAttribute(
      cameraFrustumPoints(flight.pos(j), flight.quat(j), flight.s.vertical_fov_deg[j], flight.f.aspect,
                          flight.s.focus_distance_m[j], []), 3));
  }
  const live = liveFlightAt(S.time_s[k]);
  const viewed = selected === 'edit' ? live : selected;
  const flight = flights[viewed >= 0 ? viewed : team.primary];
  const j = Math.min(k, flight.n - 1);
  shotCamera.position.copy(flight.pos(j));
  shotCamera.quaternion.copy(flight.quat(j));
  shotCamera.fov = flight.s.vertical_fov_deg[j];
  shotCamera.aspect = flight.f.aspect;
  shotCamera.updateProjectionMatrix();
  for (const { subject, body } of subjectMarkers) {
    body.position.set(subject.position_m[3 * k], subject.position_m[3 * k + 1], subject.position_m[3 * k + 2]);
  }
  const p = flight.pos(j);
  const readout = $('readout');
  readout.dataset.k = String(k);
  readout.dataset.time = fmt(S.time_s[k], 6);
  readout.dataset.drone = flight.f.name;
  readout.dataset.e = fmt(p.x, 3);
  readout.dataset.n = fmt(-p.z, 3);
  readout.dataset.u = fmt(p.y, 3);
  // The camera view's lens is the viewed drone's (and so are the lens graphs').
  readout.dataset.focal = fmt(flight.s.focal_length_mm[j], 3);
  readout.textContent = readoutText(flight, j, live);
  const focus = flight.s.focus_distance_m[j];
  $('lens-overlay').textContent = `${fmt(flight.s.focal_length_mm[j], 1)} mm  f/${fmt(flight.s.f_number[j], 1)}  ` +
    `focus ${focus === null ? '∞' : fmt(focus, 2) + ' m'}  ${fmt(S.time_s[k], 2)} s`;
  $('time').textContent = `${fmt(S.time_s[k], 2)} s / ${fmt(t1, 2)} s · ${k}`;
  // Rendered frames (--frames) belong to one sequence: the edit's when the plan has one, else the primary's.
  const framesOf = team.edit.length ? selected === 'edit' : selected === team.primary;
  const image = framesOf ? frames[String(k)] : undefined;
  const img = $('frame-img');
  if (image) {
    if (img.dataset.k !== String(k)) { img.src = image; img.dataset.k = String(k); }
    img.style.display = 'block';
    $('camera-label').textContent = `rendered frame ${k}`;
  } else {
    img.style.display = 'none';
    $('camera-label').textContent = !several ? 'live preview'
      : `${flight.f.name}${selected === 'edit' ? ' (live in the edit)' : ''}${j < k ? ', holding its last sample' : ''}`;
  }
  if (follow) placeFollowCamera();
  drawGraphs(k);
  requestRender();
}
slider.addEventListener('input', () => setSample(Number(slider.value)));

// ---- views of the main camera ----
let follow = false;
function setButtons(id) {
  for (const b of ['view-persp', 'view-top', 'view-follow']) $(b).classList.toggle('on', b === id);
}
// The share of the picture's height the header (#hud) covers at its top (at most 35 %).
function hudCoveredShare() {
  const hud = $('hud');
  return Math.min(0.35, (hud.offsetTop + hud.offsetHeight) / Math.max(1, canvas.clientHeight - 64));
}
function perspectiveView() {
  follow = false;
  setButtons('view-persp');
  northArrow.position.copy(northArrow.userData.side);
  // From the south-east and above, at the distance where everything the view draws around the scene (the
  // grid with its labels, the north arrow, the flights and the mesh: framePoints) fits in the picture
  // below the header, with a margin for the labels, which stand centred on their points.
  const dir = new THREE.Vector3(0.35, 0.45, 0.7).normalize();  // from the target to the camera
  const right = new THREE.Vector3(0, 1, 0).cross(dir).normalize(), up = dir.clone().cross(right);
  const tanHalf = Math.tan(THREE.MathUtils.degToRad(view.fov / 2));
  const aspect = Math.max(0.1, view.aspect);
  const top = 1 - 2 * hudCoveredShare();  // the header's lower edge, in the picture's -1..1 heights
  const xMax = 0.85, yMin = -0.92, yMax = 0.95 * top;  // the picture's part the points must stay in
  // The distance from `target` at which every point is inside, and the points' extent there (-1..1).
  const fit = (target) => {
    let distance = 0.3 * size;
    for (const p of framePoints) {
      const q = p.clone().sub(target);
      const z = q.dot(dir), x = q.dot(right), y = q.dot(up);
      distance = Math.max(distance, z + Math.abs(x) / (xMax * tanHalf * aspect),
                          z + (y > 0 ? y / (yMax * tanHalf) : y / (yMin * tanHalf)));
    }
    const lo = new THREE.Vector2(Infinity, Infinity), hi = new THREE.Vector2(-Infinity, -Infinity);
    for (const p of framePoints) {
      const q = p.clone().sub(target);
      const depth = distance - q.dot(dir);
      const at = new THREE.Vector2(q.dot(right) / (depth * tanHalf * aspect), q.dot(up) / (depth * tanHalf));
      lo.min(at);
      hi.max(at);
    }
    return { distance, lo, hi };
  };
  // Centred in that part: the target moved across the view by the extent's offset, a few times (each
  // move lets the camera come nearer).
  const target = centre.clone();
  let framing = fit(target);
  for (let round = 0; round < 4; ++round) {
    const dx = 0.5 * (framing.lo.x + framing.hi.x), dy = 0.5 * (framing.lo.y + framing.hi.y) - 0.5 * (yMin + yMax);
    target.addScaledVector(right, dx * framing.distance * tanHalf * aspect)
      .addScaledVector(up, dy * framing.distance * tanHalf);
    framing = fit(target);
  }
  controls.target.copy(target);
  view.position.copy(target).addScaledVector(dir, framing.distance);
  controls.update();
  requestRender();
}
function topView() {
  follow = false;
  setButtons('view-top');
  northArrow.position.copy(northArrow.userData.top);
  // Straight down, north (-z) up on the screen (the camera sits a hair south of the target), at the height
  // where the scene's east-west and north-south extents both fit below the header (#hud), which covers
  // the picture's top: the grid's northern labels and the north arrow would sit under its text.
  const tanHalf = Math.tan(THREE.MathUtils.degToRad(view.fov / 2));
  const aspect = Math.max(0.1, view.aspect);
  const covered = hudCoveredShare();
  const height = 1.3 * Math.max((bounds.max.z - bounds.min.z) / 2 / tanHalf / (1 - covered),
                                (bounds.max.x - bounds.min.x) / 2 / (tanHalf * aspect));
  const north = covered * height * tanHalf;  // the view's centre moved north by half the covered strip
  controls.target.set(centre.x, groundY, centre.z - north);
  view.position.set(centre.x, groundY + height, centre.z - north + height * 1e-4);
  controls.update();
  requestRender();
}
function placeFollowCamera() {
  const p = pos(k), back = new THREE.Vector3(0, 0, 1).applyQuaternion(quat(k));
  back.y = Math.max(back.y, 0.3);
  view.position.copy(p).addScaledVector(back.normalize(), size * 0.12);
  controls.target.copy(p);
  controls.update();
}
$('view-persp').addEventListener('click', perspectiveView);
$('view-top').addEventListener('click', topView);
$('view-follow').addEventListener('click', () => {
  follow = true;
  setButtons('view-follow');
  northArrow.position.copy(northArrow.userData.side);
  placeFollowCamera();
  requestRender();
});
controls.addEventListener('change', requestRender);

// ---- playback: the plan's frame rate, one frame per arrow key ----
let playing = false, last = 0, carry = 0;
function setPlaying(on) {
  playing = on && N > 1;
  $('play').textContent = playing ? '❚❚ Pause' : '▶ Play';
  last = performance.now();
  carry = 0;
  if (playing) requestAnimationFrame(tick);
}
function tick(now) {
  if (!playing) return;
  carry += ((now - last) / 1000) * FPS;
  last = now;
  const steps = Math.floor(carry);
  if (steps > 0) {
    carry -= steps;
    setSample(k + steps >= N ? 0 : k + steps);
  }
  requestAnimationFrame(tick);
}
$('play').addEventListener('click', () => setPlaying(!playing));
window.addEventListener('keydown', (e) => {
  if (e.key === 'ArrowRight' || e.key === 'ArrowLeft') {
    setPlaying(false);
    setSample(k + (e.key === 'ArrowRight' ? 1 : -1));
    e.preventDefault();
  } else if (e.key === ' ') {
    setPlaying(!playing);
    e.preventDefault();
  } else if (e.key === 'Home' || e.key === 'End') {
    setSample(e.key === 'Home' ? 0 : N - 1);
  }
});

// ---- drawing ----
let pending = false;
function requestRender() {
  if (pending) return;
  pending = true;
  requestAnimationFrame(() => { pending = false; render(); });
}
function viewportOf(rect) {
  const H = canvas.clientHeight;
  return [rect.left, H - rect.bottom, rect.width, rect.height];
}
function render() {
  const W = canvas.clientWidth, H = canvas.clientHeight;
  const dpr = window.devicePixelRatio || 1;
  if (canvas.width !== Math.round(W * dpr) || canvas.height !== Math.round(H * dpr)) renderer.setSize(W, H, false);
  const panel = $('panel').getBoundingClientRect();
  const mainW = Math.max(1, panel.left), mainH = Math.max(1, H - 64);
  // The panel is transparent over the canvas (the camera view shows through it): clear it first.
  renderer.setViewport(0, 0, W, H);
  renderer.setScissor(0, 0, W, H);
  renderer.setClearColor(0x262b33);
  renderer.clear();
  renderer.setViewport(0, H - mainH, mainW, mainH);
  renderer.setScissor(0, H - mainH, mainW, mainH);
  renderer.setClearColor(0x2a3038);
  view.aspect = mainW / mainH;
  view.updateProjectionMatrix();
  renderer.render(scene, view);
  const box = viewportOf(cameraBox.getBoundingClientRect());
  renderer.setViewport(...box);
  renderer.setScissor(...box);
  renderer.setClearColor(SKY);
  renderer.render(scene, shotCamera);
  // The compass: where north is on the screen of the 3D view.
  const c = $('compass');
  c.style.left = `${mainW - 74}px`;
  const north = new THREE.Vector3(0, 0, -1).transformDirection(view.matrixWorldInverse);
  const angle = Math.atan2(north.x, north.y) * 180 / Math.PI;
  $('compass-needle').setAttribute('transform', `rotate(${angle.toFixed(2)})`);
}
window.addEventListener('resize', () => { drawGraphs(k); requestRender(); });

// ---- start: #t=SECONDS, #k=SAMPLE, #view=top|3d|chase and #drone=NAME|edit pick the first picture ----
const params = new URLSearchParams(location.hash.slice(1));
view.aspect = Math.max(1, canvas.clientWidth - 420) / Math.max(1, canvas.clientHeight - 64);
const triangles = await loadMesh();
const meshReadyMs = performance.now();
if (params.get('view') === 'top') topView(); else perspectiveView();
if (params.get('view') === 'chase') $('view-follow').click();
// #t, #k and #drone move the slider and press the selector as a person would, so the tests exercise that path.
setSample(0);
if (several && params.has('drone')) {
  const value = params.get('drone') === 'edit' ? 'edit' : String(flightIndex(params.get('drone')));
  const button = [...document.querySelectorAll('#drones button')].find((b) => b.dataset.drone === value);
  if (button) button.click();
}
if (params.has('k') || params.has('t')) {
  slider.value = String(params.has('k') ? Number(params.get('k')) : sampleAtTime(Number(params.get('t'))));
  slider.dispatchEvent(new Event('input'));
}
render();
// Where the time went, in ms since the navigation: the module started (three.js parsed), the mesh
// decoded, the first picture drawn (shaders compiled).
document.body.dataset.timing = [moduleStartMs, meshReadyMs, performance.now()].map((t) => Math.round(t)).join(',');
document.body.dataset.triangles = String(triangles);
document.body.dataset.samples = String(N);
// The subjects the first picture shows (their base at its sample inside the 3D view), of all of them.
const subjectsInView = subjectMarkers.filter(({ body }) => {
  const p = body.position.clone().project(view);
  return Math.abs(p.x) <= 1 && Math.abs(p.y) <= 1 && Math.abs(p.z) <= 1;
}).length;
document.body.dataset.subjectsInView = `${subjectsInView}/${subjectMarkers.length}`;
// The points the 3D view frames (the grid's corners, its label rows and the north arrow, the scene's box)
// inside the first picture, below the header, of all of them (tests/viewer/browser_test.sh).
const headerBottom = 1 - 2 * hudCoveredShare();
const framedInView = framePoints.filter((point) => {
  const p = point.clone().project(view);
  return Math.abs(p.x) <= 1 && p.y >= -1 && p.y <= headerBottom && Math.abs(p.z) <= 1;
}).length;
document.body.dataset.framedInView = `${framedInView}/${framePoints.length}`;
document.body.dataset.flights = String(flights.length);
document.body.dataset.keyframes = String(flights.reduce((sum, flight) => sum + flight.keyframes.length, 0));
document.body.dataset.graphRanges = series.map((s) => `${fmt(s.lo, 3)}..${fmt(s.hi, 3)}`).join(' ');
document.body.dataset.flightPaths = String(flightPaths);
document.body.dataset.editCuts = String(team.edit.length);
document.body.dataset.conflicts = String(team.conflicts.length);
// Text that runs out of its place: a line of the HUD past the compass (into the panel), the readout past the
// panel's width (tests/viewer/browser_team.sh asserts none).
const compassLeft = $('compass').getBoundingClientRect().left;
const hudOverflow = [...$('hud').querySelectorAll('h1, .line')].filter(
  (e) => e.scrollWidth > e.clientWidth + 1 || e.getBoundingClientRect().right > compassLeft);
const readout = $('readout');
document.body.dataset.textOverflow = String(hudOverflow.length + (readout.scrollWidth > readout.clientWidth + 1 ? 1 : 0));
document.body.dataset.errors = String(window.previsErrors.length);
document.body.dataset.state = window.previsErrors.length ? 'error' : 'ready';
document.title = `cinepath view: ${window.previsErrors.length ? 'error' : 'ready'}, ${triangles} triangles`;
