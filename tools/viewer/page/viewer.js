// The viewer page: one scene, one set of lights, one camera rule for every tree, so a Sylva GLB
// and an ez-tree preset are drawn the same way. Driven by tools/viewer/lib/harness.mjs through
// window.viewer.show(); opened in a browser by hand (?glb=/file/0 or ?ez=Oak%20Medium) it shows
// the tree with orbit controls.
import * as THREE from 'three';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';
import { MeshoptDecoder } from 'three/addons/libs/meshopt_decoder.module.js';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';
import { Tree, TreePreset } from '@dgreenheck/ez-tree';
import { computeCoverage, overlayRGBA } from '../lib/coverage.js';

const BACKGROUND = 0xe8ecef;
const FOV = 30;
const FILL = 0.9; // the fitted box spans 90% of the frame
const VIEWS = {
  iso: { elevation: 35, azimuth: 45 },
  front: { elevation: 0, azimuth: 0 },
  side: { elevation: 0, azimuth: 90 },
  top: { elevation: 89.9, azimuth: 0 },
};

const canvas = document.getElementById('view');
const renderer = new THREE.WebGLRenderer({ canvas, antialias: true, preserveDrawingBuffer: true });
renderer.setPixelRatio(1);
renderer.outputColorSpace = THREE.SRGBColorSpace;
renderer.toneMapping = THREE.NoToneMapping;
renderer.info.autoReset = false;

const scene = new THREE.Scene();
scene.background = new THREE.Color(BACKGROUND);
const camera = new THREE.PerspectiveCamera(FOV, 1, 0.01, 1000);

// Lights: a sky/ground hemisphere and one sun from the upper front-left of the iso camera.
// They are parented to the camera rig so every view is lit the same way relative to the viewer.
const hemi = new THREE.HemisphereLight(0xf2f6ff, 0x6b5a48, 1.6);
scene.add(hemi);
const sun = new THREE.DirectionalLight(0xffffff, 2.4);
scene.add(sun);
scene.add(sun.target);

let current = null; // { root, leaves: Mesh[], bark: Mesh[], label }

function isLeafMesh(mesh) {
  const mats = Array.isArray(mesh.material) ? mesh.material : [mesh.material];
  const re = /lea(f|ves)/i;
  if (re.test(mesh.name || '')) return true;
  return mats.some((m) => m && (m.alphaTest > 0 || re.test(m.name || '')));
}

function meshesOf(root) {
  const out = [];
  root.traverse((o) => {
    if (o.isMesh) out.push(o);
  });
  return out;
}

function clear() {
  if (!current) return;
  scene.remove(current.root);
  current.root.traverse((o) => {
    if (o.geometry) o.geometry.dispose();
  });
  current = null;
}

async function loadGLB(url) {
  // `sylva export --compact` files are EXT_meshopt_compression: three's decoder unpacks them.
  const gltf = await new GLTFLoader().setMeshoptDecoder(MeshoptDecoder).loadAsync(url);
  const root = gltf.scene;
  const meshes = meshesOf(root);
  return {
    root,
    leaves: meshes.filter(isLeafMesh),
    bark: meshes.filter((m) => !isLeafMesh(m)),
    animations: gltf.animations || [],
  };
}

function texturesOf(meshes) {
  const out = [];
  for (const mesh of meshes) {
    const mats = Array.isArray(mesh.material) ? mesh.material : [mesh.material];
    for (const m of mats) {
      for (const key of ['map', 'normalMap', 'aoMap', 'roughnessMap', 'alphaMap']) {
        if (m && m[key] && m[key].isTexture) out.push(m[key]);
      }
    }
  }
  return out;
}

async function loadEz(preset) {
  if (!TreePreset[preset]) {
    throw new Error(`ez-tree has no preset "${preset}"; it has: ${Object.keys(TreePreset).join(', ')}`);
  }
  const tree = new Tree();
  tree.loadPreset(preset); // copies the options and calls generate()
  const leaves = [tree.leavesMesh];
  const bark = meshesOf(tree).filter((m) => m !== tree.leavesMesh);
  // ez-tree's textures are loaded by its module from images built into it; wait until each has
  // its image so the leaf alpha test sees the real leaf shapes.
  const textures = texturesOf([...leaves, ...bark]);
  const t0 = performance.now();
  while (textures.some((t) => !t.image || (t.image.complete === false))) {
    if (performance.now() - t0 > 20000) throw new Error('ez-tree textures did not load in 20 s');
    await new Promise((r) => setTimeout(r, 20));
  }
  for (const t of textures) t.needsUpdate = true;
  return { root: tree, leaves, bark };
}

// World-space points that outline the tree: every vertex of every mesh (every 2nd, 3rd, ...
// when there are more than 300k), or the geometry's box corners per instance for instanced meshes.
function outlinePoints(root) {
  const meshes = meshesOf(root);
  let total = 0;
  for (const m of meshes) total += m.geometry.attributes.position.count;
  const stride = Math.max(1, Math.ceil(total / 300000));
  const pts = [];
  const v = new THREE.Vector3();
  const im = new THREE.Matrix4();
  for (const m of meshes) {
    const pos = m.geometry.attributes.position;
    if (m.isInstancedMesh) {
      m.geometry.computeBoundingBox();
      const b = m.geometry.boundingBox;
      for (let k = 0; k < m.count; k++) {
        m.getMatrixAt(k, im);
        for (let i = 0; i < 8; i++) {
          v.set(i & 1 ? b.max.x : b.min.x, i & 2 ? b.max.y : b.min.y, i & 4 ? b.max.z : b.min.z);
          pts.push(v.clone().applyMatrix4(im).applyMatrix4(m.matrixWorld));
        }
      }
      continue;
    }
    for (let i = 0; i < pos.count; i += stride) {
      pts.push(v.fromBufferAttribute(pos, i).clone().applyMatrix4(m.matrixWorld));
    }
  }
  return pts;
}

// Camera on the view's direction, pulled back until every outline point (see outlinePoints) lies
// within FILL of the frame, then moved sideways/up so the projected tree is centred; three rounds.
// Fitting the points rather than the bounding box keeps the empty corners of the box (its
// ground corners in the iso view) from shrinking the tree.
// Unit vector from the target toward a camera at this elevation and azimuth (degrees).
function viewDirection(elevation, azimuth) {
  const el = THREE.MathUtils.degToRad(elevation);
  const az = THREE.MathUtils.degToRad(azimuth);
  return new THREE.Vector3(Math.cos(el) * Math.sin(az), Math.sin(el), Math.cos(el) * Math.cos(az));
}

// Sun from the upper left, in front of the tree as seen from a camera looking along -dir.
function placeSun(target, dir, radius) {
  const up = new THREE.Vector3(0, 1, 0);
  const right = new THREE.Vector3().crossVectors(up, dir).normalize();
  sun.position.copy(target).addScaledVector(dir, radius).addScaledVector(right, -radius).addScaledVector(up, radius * 1.5);
  sun.target.position.copy(target);
}

function fitCamera(points, box, viewName, aspect) {
  // A named view, or "ELEVATION,AZIMUTH" in degrees.
  const m = /^(-?[\d.]+),(-?[\d.]+)$/.exec(viewName);
  const v = m ? { elevation: Number(m[1]), azimuth: Number(m[2]) } : VIEWS[viewName];
  if (!v) throw new Error(`unknown view ${viewName}; views: ${Object.keys(VIEWS).join(', ')} or ELEVATION,AZIMUTH`);
  const dir = viewDirection(v.elevation, v.azimuth);
  const up = new THREE.Vector3(0, 1, 0);
  const right = new THREE.Vector3().crossVectors(up, dir).normalize();
  const camUp = new THREE.Vector3().crossVectors(dir, right).normalize();
  const tv = Math.tan(THREE.MathUtils.degToRad(FOV / 2)) * FILL;
  const th = tv * aspect;
  // Camera-frame coordinates of the points relative to the box centre.
  const c = box.getCenter(new THREE.Vector3());
  const n = points.length;
  const px = new Float64Array(n);
  const py = new Float64Array(n);
  const pz = new Float64Array(n);
  for (let i = 0; i < n; i++) {
    const q = points[i].clone().sub(c);
    px[i] = q.dot(right);
    py[i] = q.dot(camUp);
    pz[i] = q.dot(dir);
  }
  let ox = 0; // target offset from the box centre along right, camUp
  let oy = 0;
  let dist = 0;
  for (let round = 0; round < 3; round++) {
    dist = 0;
    for (let i = 0; i < n; i++) {
      dist = Math.max(dist, Math.abs(px[i] - ox) / th + pz[i], Math.abs(py[i] - oy) / tv + pz[i]);
    }
    let lx = Infinity, hx = -Infinity, ly = Infinity, hy = -Infinity;
    for (let i = 0; i < n; i++) {
      const depth = dist - pz[i];
      const sx = (px[i] - ox) / depth;
      const sy = (py[i] - oy) / depth;
      lx = Math.min(lx, sx); hx = Math.max(hx, sx);
      ly = Math.min(ly, sy); hy = Math.max(hy, sy);
    }
    ox += ((lx + hx) / 2) * dist;
    oy += ((ly + hy) / 2) * dist;
  }
  const target = c.clone().addScaledVector(right, ox).addScaledVector(camUp, oy);
  camera.aspect = aspect;
  camera.position.copy(target).addScaledVector(dir, dist);
  camera.up.copy(up);
  camera.lookAt(target);
  const radius = box.getSize(new THREE.Vector3()).length();
  camera.near = Math.max(0.01, dist - radius * 1.5);
  camera.far = dist + radius * 1.5;
  camera.updateProjectionMatrix();
  placeSun(target, dir, radius);
  return { target, dist };
}

// Close-up views for the recognition plates, as a field guide pairs the whole tree with its
// leaves and its bark: "detail_leaves" frames about 1.4 m of the crown's surface at mid-height on
// the side facing the camera, "detail_bark" the trunk at breast height (1.3 m, or a tenth of a
// smaller tree's height), 1.6 trunk widths across. Both look from 10 degrees up at azimuth 30, lit like the
// other views. Returns false for any other view name.
const DETAIL_VIEW = { elevation: 10, azimuth: 30 };
function worldPoints(mesh, filter, out) {
  const pos = mesh.geometry && mesh.geometry.attributes.position;
  if (!pos) return;
  const v = new THREE.Vector3();
  const m = new THREE.Matrix4();
  const instances = mesh.isInstancedMesh ? mesh.count : 0;
  if (instances) {
    for (let k = 0; k < instances; k++) {
      mesh.getMatrixAt(k, m);
      v.set(0, 0, 0).applyMatrix4(m).applyMatrix4(mesh.matrixWorld);
      if (filter(v)) out.push(v.clone());
    }
    return;
  }
  for (let i = 0; i < pos.count; i++) {
    v.fromBufferAttribute(pos, i).applyMatrix4(mesh.matrixWorld);
    if (filter(v)) out.push(v.clone());
  }
}
function detailCamera(viewName, box) {
  if (viewName !== 'detail_leaves' && viewName !== 'detail_bark') return false;
  const dir = viewDirection(DETAIL_VIEW.elevation, DETAIL_VIEW.azimuth);
  const h = box.max.y - box.min.y;
  const c = box.getCenter(new THREE.Vector3());
  let target = null;
  let half = 0.7;
  if (viewName === 'detail_leaves') {
    const lo = box.min.y + 0.4 * h, hi = box.min.y + 0.75 * h;
    const pts = [];
    for (const mesh of current.leaves) worldPoints(mesh, (p) => p.y >= lo && p.y <= hi, pts);
    // The leaf point nearest the camera, then the mean of the points within half a frame of it
    // (a cluster's middle rather than one stray leaf tip).
    let best = null, bestD = -Infinity;
    for (const p of pts) { const d = p.clone().sub(c).dot(dir); if (d > bestD) { bestD = d; best = p; } }
    if (!best) throw new Error('detail_leaves: the tree has no leaves at mid-crown height');
    const near = pts.filter((p) => p.distanceTo(best) < half);
    target = near.reduce((a, p) => a.add(p), new THREE.Vector3()).multiplyScalar(1 / near.length);
  } else {
    const y = box.min.y + Math.min(1.3, 0.1 * h);
    const pts = [];
    // Rings can stand metres apart on a clear bole: take those within 0.5 m of that height, or
    // within 1, 2 or 4 m where there are none.
    for (let w = 0.5; !pts.length && w <= 4; w *= 2) {
      for (const mesh of current.bark) worldPoints(mesh, (p) => Math.abs(p.y - y) < w, pts);
    }
    if (!pts.length) throw new Error('detail_bark: no bark at breast height');
    // The trunk's centre: the middle of the box of the points within 1.5 m of the tree's axis
    // (a ring's vertices crowd its seam and its texture-wrap columns, so a mean or median drifts).
    const near = pts.filter((p) => Math.hypot(p.x - c.x, p.z - c.z) < 1.5);
    const use = near.length ? near : pts;
    const lo = new THREE.Vector3(Infinity, y, Infinity), hi = new THREE.Vector3(-Infinity, y, -Infinity);
    for (const p of use) { lo.min(p); hi.max(p); }
    target = new THREE.Vector3((lo.x + hi.x) / 2, y, (lo.z + hi.z) / 2);
    // Frame the trunk with some background either side: 1.6 trunk widths, 0.6 to 1.6 m.
    half = THREE.MathUtils.clamp(0.8 * Math.max(hi.x - lo.x, hi.z - lo.z), 0.3, 0.8);
  }
  const dist = half / Math.tan(THREE.MathUtils.degToRad(FOV / 2));
  camera.position.copy(target).addScaledVector(dir, dist);
  camera.up.set(0, 1, 0);
  camera.lookAt(target);
  camera.near = Math.max(0.01, dist * 0.2);
  const radius = box.getSize(new THREE.Vector3()).length();
  camera.far = dist + radius * 1.5;
  camera.aspect = 1;
  camera.updateProjectionMatrix();
  placeSun(target, dir, radius);
  return target.toArray();
}

function setPass(pass) {
  for (const m of current.leaves) m.visible = pass === 'whole' || pass === 'leaf';
  for (const m of current.bark) m.visible = pass === 'whole' || pass === 'bark';
}

// One pass into an off-screen target without multisampling, cleared to alpha 0: a pixel is
// covered where a fragment survived (opaque and alpha-tested materials write alpha 1; a
// blended one counts where its alpha is at least 0.5).
function renderMask(pass, size, target, buf) {
  setPass(pass);
  const bg = scene.background;
  scene.background = null;
  renderer.setRenderTarget(target);
  renderer.setClearColor(0x000000, 0);
  renderer.clear();
  renderer.render(scene, camera);
  renderer.readRenderTargetPixels(target, 0, 0, size, size, buf);
  renderer.setRenderTarget(null);
  scene.background = bg;
  const mask = new Uint8Array(size * size);
  for (let y = 0; y < size; y++) {
    const src = (size - 1 - y) * size; // GL rows start at the bottom
    for (let x = 0; x < size; x++) mask[y * size + x] = buf[(src + x) * 4 + 3] >= 128 ? 1 : 0;
  }
  return mask;
}

function rgbaToDataURL(rgba, size) {
  const c = document.createElement('canvas');
  c.width = size;
  c.height = size;
  c.getContext('2d').putImageData(new ImageData(rgba, size, size), 0, 0);
  return c.toDataURL('image/png');
}

async function show(spec, opts = {}) {
  const size = opts.size || 768;
  const view = opts.view || 'iso';
  const key = JSON.stringify(spec);
  const t0 = performance.now();
  if (!current || current.key !== key) {
    clear();
    current = spec.kind === 'ez' ? await loadEz(spec.preset) : await loadGLB(spec.url);
    current.key = key;
    scene.add(current.root);
  }
  current.root.updateMatrixWorld(true);
  const box = new THREE.Box3().setFromObject(current.root, true);
  const loadMs = performance.now() - t0;

  renderer.setSize(size, size, false);
  const detail = detailCamera(view, box);
  if (!detail) fitCamera(outlinePoints(current.root), box, view, 1);
  // An animation clip posed at opts.time seconds (issue 17's wind), after the camera is fitted to
  // the rest pose so that two moments are seen from the same place.
  let animation = null;
  if (opts.animation) {
    const clip = (current.animations || []).find((a) => a.name === opts.animation);
    if (!clip) throw new Error(`no animation "${opts.animation}"; the file has: ${(current.animations || []).map((a) => a.name).join(', ')}`);
    const mixer = new THREE.AnimationMixer(current.root);
    mixer.clipAction(clip).play();
    mixer.setTime(opts.time || 0);
    current.root.updateMatrixWorld(true);
    animation = { name: clip.name, duration: clip.duration, tracks: clip.tracks.length, time: opts.time || 0 };
  }

  // Beauty pass: the whole tree on the plain background, to the canvas.
  setPass('whole');
  renderer.setRenderTarget(null);
  renderer.setClearColor(BACKGROUND, 1);
  renderer.info.reset();
  renderer.render(scene, camera);
  const triangles = renderer.info.render.triangles;
  const drawCalls = renderer.info.render.calls;
  const result = {
    triangles,
    draw_calls: drawCalls,
    leaf_meshes: current.leaves.length,
    bark_meshes: current.bark.length,
    bbox: { min: box.min.toArray(), max: box.max.toArray() },
    load_ms: Math.round(loadMs),
    view,
    size,
    animations: (current.animations || []).map((a) => a.name),
    animation,
    detail_target: detail || undefined,
  };
  if (opts.image !== false) result.image = canvas.toDataURL('image/png');

  if (opts.measure) {
    const target = new THREE.WebGLRenderTarget(size, size, { samples: 0 });
    const buf = new Uint8Array(size * size * 4);
    const masks = {
      width: size,
      height: size,
      whole: renderMask('whole', size, target, buf),
      leaf: renderMask('leaf', size, target, buf),
      bark: renderMask('bark', size, target, buf),
    };
    target.dispose();
    setPass('whole');
    const cov = computeCoverage(masks);
    const { hullMask, ...numbers } = cov;
    Object.assign(result, numbers);
    // Diagnostic only: the same ratio over the hull of the leaf pixels alone (bare branch tips
    // sticking out of the foliage do not widen it).
    result.coverage_leaf_hull = computeCoverage({ ...masks, whole: masks.leaf }).coverage;
    if (opts.overlay) result.overlay = rgbaToDataURL(overlayRGBA(masks, hullMask, cov.crown_base_row), size);
  }
  return result;
}

window.viewer = { show, views: Object.keys(VIEWS), presets: Object.keys(TreePreset), ready: true };

// Opened by hand: ?glb=URL or ?ez=PRESET, with orbit controls.
const params = new URLSearchParams(location.search);
if (params.has('glb') || params.has('ez')) {
  const size = Math.min(window.innerWidth, window.innerHeight);
  const spec = params.has('ez') ? { kind: 'ez', preset: params.get('ez') } : { kind: 'glb', url: params.get('glb') };
  show(spec, { size, view: params.get('view') || 'iso', image: false }).then(() => {
    const controls = new OrbitControls(camera, canvas);
    const box = new THREE.Box3().setFromObject(current.root, true);
    controls.target.copy(box.getCenter(new THREE.Vector3()));
    controls.update();
    renderer.setAnimationLoop(() => renderer.render(scene, camera));
  });
}
