// The notebook's 3-D view in headless Chromium (Debian's, driven by playwright-core): the
// HTML a World, a Scene and an Animation give as `_repr_html_` (python/ontogen/display.py),
// set as a page's content as a notebook sets an output's, draws its model; the
// animation's time slider poses it at the times asked (fewer pixels at the start of a
// growing model than at its end, the same again when asked again).
//
//   node display_page_test.mjs PYTHON OUTPUT_DIR     (PYTHONPATH: the module's folder)
// Exit 0: passed; 1: failed; 77: a checker is missing (a failure when CI=true).

import { spawnSync } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';
import { createRequire } from 'node:module';

const [python, outputDir] = process.argv.slice(2);
const ci = process.env.CI === 'true';
const chromiumPath = '/usr/bin/chromium';

function missing(what) {
  console.error(`display page test: ${what} is missing (bash .ci/setup --checkers installs it)`);
  process.exit(ci ? 1 : 77);
}
if (!fs.existsSync(chromiumPath)) missing('Chromium (/usr/bin/chromium)');
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

// The views, as a notebook would get them: a branching plant (a World and its Scene), and
// a model that grows one more segment each second (an Animation over 0 to 10 s).
fs.mkdirSync(outputDir, { recursive: true });
const made = spawnSync(python, ['-c', `
import json, sys
import ontogen
out = sys.argv[1]
if ontogen.display.viewer_script() is None:
    sys.exit(3)
plant = ontogen.compile("lsystem plant {\\n  #angle 25.7\\n  axiom F\\n  F -> F [ + F ] F [ - F ] F\\n}\\n").world()
plant.advance(4)
growing = ontogen.compile("lsystem growing {\\n  #angle 30\\n  axiom F A\\n  A -> + F A\\n}\\n").world()
views = {"world": plant._repr_html_(), "scene": plant.scene()._repr_html_(),
         "animation": growing.animation(10, 11)._repr_html_()}
for name, view in views.items():
    with open(f"{out}/{name}.html", "w") as f:
        f.write(view)
`, outputDir], { encoding: 'utf8' });
if (made.status === 3) {
  console.error('display page test: the module was built without its viewer (esbuild and three.js: bash .ci/setup)');
  process.exit(ci ? 1 : 77);
}
if (made.status !== 0) {
  console.error(made.stdout + made.stderr);
  process.exit(1);
}

const browser = await chromium.launch({
  executablePath: chromiumPath,
  args: ['--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run', '--disable-background-networking',
    '--disable-component-update', '--disable-sync', '--enable-unsafe-swiftshader', '--use-angle=swiftshader'],
});

// Pixels of the view's canvas that are not its background (42, 45, 51).
function drawnPixels(frame) {
  return frame.evaluate(() => {
    const source = document.getElementById('canvas');
    const copy = document.createElement('canvas');
    copy.width = source.width;
    copy.height = source.height;
    const context = copy.getContext('2d');
    context.drawImage(source, 0, 0);
    const pixels = context.getImageData(0, 0, copy.width, copy.height).data;
    let drawn = 0;
    for (let i = 0; i < pixels.length; i += 4)
      if (Math.abs(pixels[i] - 42) + Math.abs(pixels[i + 1] - 45) + Math.abs(pixels[i + 2] - 51) > 24) drawn += 1;
    return { drawn, total: pixels.length / 4 };
  });
}
const settle = (frame) => frame.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));

try {
  for (const name of ['world', 'scene', 'animation']) {
    const page = await browser.newPage({ viewport: { width: 900, height: 700 } });
    const requests = [];
    page.on('request', (request) => { if (!request.url().startsWith('about:')) requests.push(request.url()); });
    const errors = [];
    page.on('pageerror', (error) => errors.push(String(error)));
    await page.setContent(fs.readFileSync(path.join(outputDir, `${name}.html`), 'utf8'));
    const frame = page.frames().find((f) => f !== page.mainFrame());
    await frame.waitForSelector('body[data-ready="true"]', { timeout: 30000 });
    await settle(frame);
    const whole = await drawnPixels(frame);
    await page.screenshot({ path: path.join(outputDir, `${name}.png`) });
    check(whole.drawn > whole.total * 0.002, `the ${name}'s view draws its model (${whole.drawn} of ${whole.total} pixels)`);
    const sliderShown = await frame.locator('#time-row').isVisible();
    check(sliderShown === (name === 'animation'), `the ${name}'s view ${sliderShown ? 'has' : 'has no'} time slider`);
    if (name === 'animation') {
      const at = async (t) => {
        await frame.locator('#time').fill(String(t));
        await settle(frame);
        return (await drawnPixels(frame)).drawn;
      };
      const [start, middle, end, again] = [await at(0), await at(5), await at(10), await at(0)];
      check(start < middle && middle < end, `the slider shows the growth: ${start} pixels at 0 s, ${middle} at 5 s, ${end} at 10 s`);
      check(again === start && end === whole.drawn, `the same times show the same pictures (${again} at 0 s again)`);
    }
    check(errors.length === 0, `the ${name}'s page raised nothing ${errors.length ? errors.join('; ') : ''}`);
    check(requests.length === 0, `the ${name}'s page fetched nothing (${requests.join(', ')})`);
    await page.close();
  }
} finally {
  await browser.close();
}
process.exit(failures ? 1 : 0);
