// A still .glb whose lines are instances of one tube (EXT_mesh_gpu_instancing), drawn by
// three.js's own GLTFLoader in headless Chromium (Debian's, driven by playwright-core),
// as a web viewer draws it. The model is a grid of short dashes, one per cell of
// COLUMNS x ROWS, with a rectangular hole and the right-hand columns in another colour:
// more dashes than the writer bakes, so each colour is one instanced mesh. Most dashes
// stand up the page; some lie along x and some lean out of the page (turned 30 degrees,
// pitched 40), so that every instance's rotation is checked, not only its translation.
//
// Checks, against the grid the test wrote (not against what the writer reports):
// - three.js finds one InstancedMesh per colour, with as many instances as dashes of that
//   colour, and each instance's matrix puts the unit tube's axis on its dash;
// - through an orthographic camera fitted to the grid, every dash's middle is drawn in
//   its colour's hue and every gap between dashes, and the hole, show the background;
// - through the file's own camera, the model covers the picture in its colours' hues;
// - the file brings no light (docs/LANGUAGE.md 5.2): the page is a plain three.js scene
//   that keeps everything the loader made and adds its own lights, as a viewer does, and
//   no picture is washed out to white. A light in lux right for Blender (2049 lux, a sun
//   of 3 W/m^2 there) drawn by three.js without exposure control turns every lit pixel
//   white, so the white-pixel checks fail if such a light comes back.
//   node three_instanced_test.mjs ONTOGEN_EXECUTABLE THREE_FOLDER OUTPUT_DIR
// THREE_FOLDER: the `three` npm package (build/ and examples/jsm/ are served to the page).
// Exit 0: passed; 1: failed; 77: a checker is missing (a failure when CI=true).

import { spawnSync } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';
import { createRequire } from 'node:module';

const [executable, threeFolder, outputDir] = process.argv.slice(2);
const ci = process.env.CI === 'true';
const chromiumPath = '/usr/bin/chromium';

function missing(what) {
  console.error(`three.js instancing test: ${what} is missing (bash .ci/setup --checkers installs it)`);
  process.exit(ci ? 1 : 77);
}
if (!fs.existsSync(chromiumPath)) missing('Chromium (/usr/bin/chromium)');
if (!fs.existsSync(path.join(threeFolder, 'examples/jsm/loaders/GLTFLoader.js'))) missing(`three.js (${threeFolder})`);
let chromium;
try {
  chromium = createRequire(import.meta.url)('playwright-core').chromium;
} catch {
  missing('playwright-core (NODE_PATH=.tools/node_modules)');
}

let failures = 0;
function check(condition, message) {
  console.log(`${condition ? 'ok  ' : 'FAIL'} ${message}`);
  if (!condition) failures += 1;
  return condition;
}

// The grid: column c, row r has a dash from (c, r, 0) to (c, r, 0) + DASH * its direction
// unless (c, r) is in the hole; columns from SPLIT on are red (palette 2), the rest stem
// grey-brown (0).
const COLUMNS = 72, ROWS = 64, DASH = 0.6, SPLIT = 48;
const HOLE = { c0: 20, c1: 35, r0: 20, r1: 31 };  // inclusive
const inHole = (c, r) => c >= HOLE.c0 && c <= HOLE.c1 && r >= HOLE.r0 && r <= HOLE.r1;
const colourOf = (c) => (c >= SPLIT ? 2 : 0);
const palette = { 0: [0.62, 0.55, 0.45], 2: [0.85, 0.2, 0.2] };

// The turtle starts at the origin heading H = +y with L = -x and U = +z
// (interpreters/geometry/turtle.h); `-` turns H away from L, `^` pitches it towards U.
// Each column is a branch up the y axis, each dash a branch of its own.
const rad = Math.PI / 180;
const kinds = [
  { turtle: '', direction: [0, 1, 0] },
  { turtle: '- ', direction: [1, 0, 0] },
  { turtle: '-(30) ^(40) ', direction: [Math.sin(30 * rad) * Math.cos(40 * rad), Math.cos(30 * rad) * Math.cos(40 * rad), Math.sin(40 * rad)] },
];
const kindOf = (c, r) => [0, 1, 0, 2, 0][(3 * c + r) % 5];
let axiom = '';
const dashes = { 0: [], 2: [] };
for (let c = 0; c < COLUMNS; ++c) {
  axiom += `[ color(${colourOf(c)})`;
  for (let r = 0; r < ROWS; ++r) {
    if (!inHole(c, r)) {
      const kind = kinds[kindOf(c, r)];
      axiom += ` [ ${kind.turtle}F(${DASH}) ]`;
      dashes[colourOf(c)].push({ c, r, d: kind.direction });
    }
    axiom += ' f(1)';
  }
  axiom += ' ] - f(1) + ';
}
const program = `// a grid of dashes with a hole, written by three_instanced_test.mjs
lsystem grid {
  #angle 90
  axiom ${axiom}}
`;
fs.mkdirSync(outputDir, { recursive: true });
const cellFile = path.join(outputDir, 'grid.cell');
fs.writeFileSync(cellFile, program);
const ran = spawnSync(executable, ['run', cellFile, '--format', 'glb', '--out', outputDir, '--until', '0'], { encoding: 'utf8' });
if (!check(ran.status === 0, `ontogen run --format glb exits 0 (${ran.status}) ${ran.stderr}`)) process.exit(1);
const glb = fs.readFileSync(path.join(outputDir, 'grid.glb'));
const total = dashes[0].length + dashes[2].length;
console.log(`grid.glb: ${glb.length} bytes, ${total} dashes`);

// The page: three.js and its loaders served from THREE_FOLDER, the file from memory, all
// on one made-up origin that the page's requests never leave.
const origin = 'http://ontogen.test';
const page_ = `<!doctype html><html><body style="margin:0;background:#000">
<canvas id="canvas" width="900" height="800"></canvas>
<script type="importmap">{"imports":{"three":"${origin}/three/build/three.module.js",
"three/addons/":"${origin}/three/examples/jsm/"}}</script>
<script type="module">
import * as THREE from 'three';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';
const renderer = new THREE.WebGLRenderer({ canvas: document.getElementById('canvas'), preserveDrawingBuffer: true });
renderer.setClearColor(0x000000);
const gltf = await new GLTFLoader().loadAsync('${origin}/grid.glb');
const meshes = [];
gltf.scene.traverse((o) => { if (o.isInstancedMesh) meshes.push(o); });
// The file's lights, if any, are read and kept; the page adds its own (white, so hues stay).
window.lights = [];
gltf.scene.traverse((o) => { if (o.isLight) window.lights.push({ type: o.type, intensity: o.intensity }); });
gltf.scene.add(new THREE.AmbientLight(0xffffff, 1.0));
const key = new THREE.DirectionalLight(0xffffff, 1.5);
key.position.set(0.3, 0.5, 1);
gltf.scene.add(key);
gltf.scene.updateMatrixWorld(true);
// Per instanced mesh: its colour and, per instance, the unit tube's axis ends (0, +-1, 0)
// in world coordinates.
window.instances = meshes.map((mesh) => {
  const m = new THREE.Matrix4(), ends = [];
  for (let i = 0; i < mesh.count; ++i) {
    mesh.getMatrixAt(i, m);
    m.premultiply(mesh.matrixWorld);
    const a = new THREE.Vector3(0, -1, 0).applyMatrix4(m), b = new THREE.Vector3(0, 1, 0).applyMatrix4(m);
    ends.push([a.x, a.y, a.z, b.x, b.y, b.z]);
  }
  return { name: mesh.name, colour: mesh.material.color.toArray(), ends };
});
function pixels() {
  const gl = renderer.getContext();
  const data = new Uint8Array(gl.drawingBufferWidth * gl.drawingBufferHeight * 4);
  gl.readPixels(0, 0, gl.drawingBufferWidth, gl.drawingBufferHeight, gl.RGBA, gl.UNSIGNED_BYTE, data);
  return { width: gl.drawingBufferWidth, height: gl.drawingBufferHeight, data };
}
// The grid seen straight on through an orthographic camera that spans x in [-1, ${COLUMNS}],
// y in [-1, ${ROWS}] over the canvas.
const ortho = new THREE.OrthographicCamera(-1, ${COLUMNS}, ${ROWS}, -1, 0.1, 1000);
ortho.position.set(0, 0, 100);
renderer.render(gltf.scene, ortho);
window.orthographic = pixels();
// The file's own camera, as a viewer opens it.
const camera = gltf.cameras[0];
camera.aspect = 900 / 800;
camera.updateProjectionMatrix();
renderer.render(gltf.scene, camera);
window.ownCamera = pixels();
window.cameras = gltf.cameras.length;
document.body.dataset.ready = 'true';
</script></body></html>`;

const browser = await chromium.launch({
  executablePath: chromiumPath,
  args: ['--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run', '--disable-background-networking',
    '--disable-component-update', '--disable-sync', '--enable-unsafe-swiftshader', '--use-angle=swiftshader'],
});
try {
  const page = await browser.newPage({ viewport: { width: 900, height: 800 } });
  const errors = [];
  page.on('pageerror', (error) => errors.push(String(error)));
  page.on('console', (message) => { if (message.type() === 'error') errors.push(message.text()); });
  const strays = [];
  await page.route('**/*', (route) => {
    const url = route.request().url();
    if (url === `${origin}/`) return route.fulfill({ contentType: 'text/html', body: page_ });
    if (url === `${origin}/grid.glb`) return route.fulfill({ contentType: 'model/gltf-binary', body: glb });
    if (url.startsWith(`${origin}/three/`)) {
      const file = path.join(threeFolder, url.slice(`${origin}/three/`.length));
      if (fs.existsSync(file)) return route.fulfill({ contentType: 'text/javascript', body: fs.readFileSync(file) });
    }
    strays.push(url);
    return route.abort();
  });
  await page.goto(`${origin}/`);
  await page.waitForSelector('body[data-ready="true"]', { timeout: 60000 });
  const seen = await page.evaluate(() => ({ instances: window.instances, cameras: window.cameras, lights: window.lights }));
  // The pictures, as RGB bytes (bottom row first), through base64 to keep the transfer small.
  const picture = async (name) => {
    const got = await page.evaluate((which) => {
      const { width, height, data } = window[which];
      const rgb = new Uint8Array(width * height * 3);
      for (let i = 0, j = 0; i < data.length; i += 4, j += 3) rgb.set(data.subarray(i, i + 3), j);
      let text = '';
      for (let i = 0; i < rgb.length; i += 0x8000) text += String.fromCharCode(...rgb.subarray(i, i + 0x8000));
      return { width, height, base64: btoa(text) };
    }, name);
    return { width: got.width, height: got.height, data: Buffer.from(got.base64, 'base64') };
  };
  seen.orthographic = await picture('orthographic');
  seen.ownCamera = await picture('ownCamera');
  await page.screenshot({ path: path.join(outputDir, 'grid.png') });

  // The instances: one mesh per colour, each instance on its dash, in the grid's order.
  check(seen.instances.length === 2, `three.js finds an instanced mesh per colour (${seen.instances.length})`);
  for (const mesh of seen.instances) {
    const expected = /[ _]2$/.test(mesh.name) ? dashes[2] : dashes[0];  // three.js writes 'lines 2' as lines_2
    check(mesh.ends.length === expected.length, `${mesh.name} has an instance per dash (${mesh.ends.length} of ${expected.length})`);
    let worst = 0;
    mesh.ends.forEach((e, i) => {
      const { c, r, d } = expected[i] ?? { c: NaN, r: NaN, d: [NaN, NaN, NaN] };
      worst = Math.max(worst, Math.hypot(e[0] - c, e[1] - r, e[2]),
        Math.hypot(e[3] - (c + DASH * d[0]), e[4] - (r + DASH * d[1]), e[5] - DASH * d[2]));
    });
    check(worst < 1e-4, `${mesh.name}'s instances stand on their dashes (farthest end off by ${worst.toExponential(2)})`);
  }

  // Pixels: (x, y) in grid units to the read-back row (bottom row first).
  const hue = (p) => {
    const [r, g, b] = p, max = Math.max(r, g, b), min = Math.min(r, g, b);
    if (max - min < 8) return NaN;
    let h = max === r ? (g - b) / (max - min) : max === g ? 2 + (b - r) / (max - min) : 4 + (r - g) / (max - min);
    return ((h * 60) + 360) % 360;
  };
  const hueGap = (a, b) => Math.min(Math.abs(a - b), 360 - Math.abs(a - b));
  const wantedHue = { 0: hue(palette[0].map((v) => v * 255)), 2: hue(palette[2].map((v) => v * 255)) };
  const ortho = seen.orthographic;
  const at = (x, y) => {
    const px = Math.round((x + 1) / (COLUMNS + 1) * ortho.width - 0.5);
    const py = Math.round((y + 1) / (ROWS + 1) * ortho.height - 0.5);
    const k = 3 * (py * ortho.width + px);
    return [...ortho.data.subarray(k, k + 3)];
  };
  const dark = (p) => p[0] + p[1] + p[2] < 30;
  let drawnRight = 0, gapsDark = 0, holeDark = 0, holeCells = 0, whiteDashes = 0;
  for (let c = 0; c < COLUMNS; ++c) {
    for (let r = 0; r < ROWS; ++r) {
      // The gap between four cells, at least 0.2 units clear of every kind of dash drawn
      // as a tube of the writer's radius (0.19 units here).
      const gap = at(c + 0.6, r + 0.6);
      if (inHole(c, r)) {
        holeCells += 1;
        if (dark(at(c, r + DASH / 2)) && dark(gap)) holeDark += 1;
        continue;
      }
      const d = kinds[kindOf(c, r)].direction;
      const p = at(c + d[0] * DASH / 2, r + d[1] * DASH / 2);
      if (!dark(p) && hueGap(hue(p), wantedHue[colourOf(c)]) < 20) drawnRight += 1;
      if (Math.min(p[0], p[1], p[2]) > 240) whiteDashes += 1;
      if (dark(gap)) gapsDark += 1;
    }
  }
  check(drawnRight === total, `every dash's middle is drawn in its colour's hue (${drawnRight} of ${total})`);
  check(whiteDashes === 0, `no dash is washed out to white (${whiteDashes})`);
  check(gapsDark === total, `the gap beside every dash shows the background (${gapsDark} of ${total})`);
  check(holeDark === holeCells, `the hole shows the background (${holeDark} of ${holeCells} cells)`);

  // The file's camera: the model fills its picture, in its hues.
  check(seen.cameras === 1, `the file has its camera (${seen.cameras})`);
  check(seen.lights.length === 0, `the file brings no light (${JSON.stringify(seen.lights)})`);
  const own = seen.ownCamera;
  let covered = 0, white = 0, inHue = 0;
  for (let k = 0; k < own.data.length; k += 3) {
    const p = [own.data[k], own.data[k + 1], own.data[k + 2]];
    if (dark(p)) continue;
    covered += 1;
    if (Math.min(...p) > 240) white += 1;
    const h = hue(p);
    if (hueGap(h, wantedHue[0]) < 20 || hueGap(h, wantedHue[2]) < 20) inHue += 1;
  }
  const pixelsAll = own.data.length / 3;
  console.log(`own camera: ${covered} of ${pixelsAll} pixels drawn, ${white} white, ${inHue} in the palette's hues; lights ${JSON.stringify(seen.lights)}`);
  check(covered > pixelsAll * 0.05, `through the file's camera the model covers the picture (${covered} of ${pixelsAll} pixels)`);
  check(white < covered * 0.01, `through the file's camera the model is not washed white (${white} of ${covered} white)`);
  check(inHue > covered * 0.9, `through the file's camera the model shows its colours (${inHue} of ${covered} in their hues)`);

  check(errors.length === 0, `the page raised nothing ${errors.join('; ')}`);
  check(strays.length === 0, `the page asked for nothing else (${strays.join(', ')})`);
} finally {
  await browser.close();
}
process.exit(failures ? 1 : 0);
