// The .glb that `ontogen run --format glb` and the studio write, opened in Google's
// <model-viewer> as it comes (its own lighting, tone mapping and camera), in headless
// Chromium (Debian's, driven by playwright-core; model-viewer from .tools/node_modules).
// The file brings no light of its own, so model-viewer's lighting shows it in its
// materials' colours: within the model's silhouette (the picture's opaque pixels) few are
// near white, and most have the hue of one of its materials' base colours.
//
// The measure is checked against a file that does wash out: the same flower with a light
// in lux as Blender wants it (2049, the writer's old sun) added to its scene. A viewer
// that honours the file's lights turns most of that model white; should the writer bring
// such a light back, the flower and Koch checks fail as the control does.
//
//   node model_viewer_test.mjs ONTOGEN_EXECUTABLE MODELS_DIR OUTPUT_DIR
// Exit 0: passed; 1: failed; 77: a checker is missing (a failure when CI=true).

import { spawnSync } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';
import { createRequire } from 'node:module';

const [executable, modelsDir, outputDir] = process.argv.slice(2);
const ci = process.env.CI === 'true';
const chromiumPath = '/usr/bin/chromium';

function missing(what) {
  console.error(`model-viewer test: ${what} is missing (bash .ci/setup --checkers installs it)`);
  process.exit(ci ? 1 : 77);
}
if (!fs.existsSync(chromiumPath)) missing('Chromium (/usr/bin/chromium)');
const require = createRequire(import.meta.url);
let chromium, viewerScript;
try {
  chromium = require('playwright-core').chromium;
} catch {
  missing('playwright-core (NODE_PATH=.tools/node_modules)');
}
try {
  // The UMD build holds three.js and lit: one script, nothing fetched besides.
  viewerScript = fs.readFileSync(
    path.join(path.dirname(require.resolve('@google/model-viewer/package.json')), 'dist/model-viewer-umd.min.js'));
} catch {
  missing('@google/model-viewer (NODE_PATH=.tools/node_modules)');
}

let failures = 0;
function check(condition, message) {
  console.log(`${condition ? 'ok  ' : 'FAIL'} ${message}`);
  if (!condition) failures += 1;
  return condition;
}

// A .glb's JSON chunk, and the file again with the JSON changed (chunks padded to 4 bytes).
function glbJson(glb) {
  return JSON.parse(glb.subarray(20, 20 + glb.readUInt32LE(12)).toString('utf8'));
}
function withJson(glb, json) {
  const rest = glb.subarray(20 + glb.readUInt32LE(12));
  let text = Buffer.from(JSON.stringify(json), 'utf8');
  text = Buffer.concat([text, Buffer.alloc((4 - (text.length % 4)) % 4, 0x20)]);
  const header = Buffer.alloc(20);
  header.writeUInt32LE(0x46546c67, 0);  // glTF
  header.writeUInt32LE(2, 4);
  header.writeUInt32LE(20 + text.length + rest.length, 8);
  header.writeUInt32LE(text.length, 12);
  header.writeUInt32LE(0x4e4f534a, 16);  // JSON
  return Buffer.concat([header, text, rest]);
}
// The control: a directional light of 2049 lux on a node of its own in the scene.
function withBlendersSun(glb) {
  const json = glbJson(glb);
  json.extensionsUsed = [...(json.extensionsUsed ?? []), 'KHR_lights_punctual'];
  json.extensions = { ...(json.extensions ?? {}),
    KHR_lights_punctual: { lights: [{ type: 'directional', intensity: 2049, color: [1, 1, 1] }] } };
  json.nodes.push({ name: 'sun', rotation: [-0.3535534, 0.3535534, 0.1464466, 0.8535534],
    extensions: { KHR_lights_punctual: { light: 0 } } });
  json.scenes[json.scene ?? 0].nodes.push(json.nodes.length - 1);
  return withJson(glb, json);
}

fs.mkdirSync(outputDir, { recursive: true });
const files = {};
for (const name of ['flower', 'koch']) {
  const ran = spawnSync(executable, ['run', path.join(modelsDir, `${name}.cell`), '--format', 'glb', '--out', outputDir],
    { encoding: 'utf8' });
  if (!check(ran.status === 0, `ontogen run ${name}.cell --format glb exits 0 (${ran.status}) ${ran.stderr}`)) process.exit(1);
  files[name] = fs.readFileSync(path.join(outputDir, `${name}.glb`));
}
files.flower_with_sun = withBlendersSun(files.flower);

// sRGB bytes of a linear base colour, and a colour's hue in degrees (NaN for a grey).
const srgb = (linear) => linear.map((c) => 255 * (c <= 0.0031308 ? 12.92 * c : 1.055 * c ** (1 / 2.4) - 0.055));
const hue = ([r, g, b]) => {
  const max = Math.max(r, g, b), min = Math.min(r, g, b);
  if (max - min < 12) return NaN;
  const h = max === r ? (g - b) / (max - min) : max === g ? 2 + (b - r) / (max - min) : 4 + (r - g) / (max - min);
  return (h * 60 + 360) % 360;
};
const hueGap = (a, b) => Math.min(Math.abs(a - b), 360 - Math.abs(a - b));

const origin = 'http://ontogen.test';
const pageOf = (name) => `<!doctype html><html><body style="margin:0;background:#000">
<script src="${origin}/model-viewer.js"></script>
<model-viewer id="viewer" src="${origin}/${name}.glb" interaction-prompt="none"
  style="width:640px;height:640px;background-color:transparent"></model-viewer>
<script>
const viewer = document.getElementById('viewer');
viewer.addEventListener('error', (event) => { document.body.dataset.error = String(event.detail && event.detail.type); });
viewer.addEventListener('load', async () => {
  await viewer.updateComplete;
  for (let i = 0; i < 10; i += 1) await new Promise((r) => requestAnimationFrame(r));
  // The picture model-viewer makes of what it shows: transparent where the model is not.
  const image = new Image();
  image.src = viewer.toDataURL('image/png');
  await image.decode();
  const canvas = document.createElement('canvas');
  canvas.width = image.naturalWidth;
  canvas.height = image.naturalHeight;
  const context = canvas.getContext('2d');
  context.drawImage(image, 0, 0);
  const { data } = context.getImageData(0, 0, canvas.width, canvas.height);
  const opaque = new Uint8Array(data.length);
  let n = 0;
  for (let i = 0; i < data.length; i += 4)
    if (data[i + 3] > 250) { opaque.set(data.subarray(i, i + 3), n); n += 3; }
  let text = '';
  for (let i = 0; i < n; i += 0x8000) text += String.fromCharCode(...opaque.subarray(i, Math.min(n, i + 0x8000)));
  window.silhouette = { pixels: canvas.width * canvas.height, base64: btoa(text) };
  document.body.dataset.ready = 'true';
});
</script></body></html>`;

const browser = await chromium.launch({
  executablePath: chromiumPath,
  args: ['--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run', '--disable-background-networking',
    '--disable-component-update', '--disable-sync', '--enable-unsafe-swiftshader', '--use-angle=swiftshader'],
});
const measured = {};
try {
  for (const name of Object.keys(files)) {
    const page = await browser.newPage({ viewport: { width: 640, height: 640 } });
    const errors = [];
    page.on('pageerror', (error) => errors.push(String(error)));
    const strays = [];
    await page.route('**/*', (route) => {
      const url = route.request().url();
      if (url === `${origin}/`) return route.fulfill({ contentType: 'text/html', body: pageOf(name) });
      if (url === `${origin}/model-viewer.js`) return route.fulfill({ contentType: 'text/javascript', body: viewerScript });
      if (url === `${origin}/${name}.glb`) return route.fulfill({ contentType: 'model/gltf-binary', body: files[name] });
      strays.push(url);
      return route.abort();
    });
    await page.goto(`${origin}/`);
    await page.waitForFunction(() => document.body.dataset.ready === 'true' || document.body.dataset.error,
      null, { timeout: 120000 });
    const error = await page.evaluate(() => document.body.dataset.error);
    check(!error && errors.length === 0, `model-viewer opens ${name}.glb (${error ?? ''}${errors.join('; ')})`);
    check(strays.length === 0, `model-viewer asked for nothing else for ${name}.glb (${strays.join(', ')})`);
    await page.screenshot({ path: path.join(outputDir, `${name}_model_viewer.png`) });
    const { pixels, base64 } = await page.evaluate(() => window.silhouette);
    const opaque = Buffer.from(base64, 'base64');
    const hues = glbJson(files[name]).materials.map((m) => hue(srgb(m.pbrMetallicRoughness.baseColorFactor.slice(0, 3))));
    let covered = 0, white = 0, inHue = 0;
    for (let k = 0; k < opaque.length; k += 3) {
      const p = [opaque[k], opaque[k + 1], opaque[k + 2]];
      covered += 1;
      if (Math.min(...p) > 235) white += 1;
      const h = hue(p);
      if (hues.some((wanted) => hueGap(h, wanted) < 25)) inHue += 1;
    }
    measured[name] = { covered, white, inHue, pixels };
    console.log(`${name}: ${covered} of ${pixels} pixels in the silhouette, ${white} near white, ${inHue} in its materials' hues`);
    await page.close();
  }
  for (const name of ['flower', 'koch']) {
    const { covered, white, inHue, pixels } = measured[name];
    check(covered > pixels * 0.005, `${name}.glb is drawn (${covered} of ${pixels} pixels)`);
    check(white < covered * 0.02, `${name}.glb is not washed white in model-viewer (${white} of ${covered} near white)`);
    check(inHue > covered * 0.8, `${name}.glb shows its materials' colours (${inHue} of ${covered} pixels in their hues)`);
  }
  const sun = measured.flower_with_sun;
  check(sun.white > sun.covered * 0.25,
    `the measure sees a washed-out model: the flower with a 2049 lux light of its own is white (${sun.white} of ${sun.covered})`);
} finally {
  await browser.close();
}
console.log(failures === 0 ? 'model-viewer test: passed' : `model-viewer test: ${failures} failed`);
process.exit(failures ? 1 : 0);
