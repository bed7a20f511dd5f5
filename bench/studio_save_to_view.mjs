// Save to view in the studio, measured as a person sees it: `ontogen studio MODEL` on a
// free port, its page in headless Chromium (Debian's, driven by playwright-core); the
// model's file is saved again (its text unchanged but for a trailing comment) and the
// time is taken from the save until the page has drawn the new model (body's
// data-model-version, then the animation frame that draws it). Prints the first load's
// time, each save's, the .glb's size and what the page fetched after the last save.
// A measurement, not a test: nothing here passes or fails.
//
//   NODE_PATH=.tools/node_modules node bench/studio_save_to_view.mjs ONTOGEN MODEL.cell [SAVES] [STUDIO ARGS...]

import { spawn } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { createRequire } from 'node:module';

const [executable, model, savesText = '3', ...studioArgs] = process.argv.slice(2);
const saves = Number(savesText);
const { chromium } = createRequire(import.meta.url)('playwright-core');

const work = fs.mkdtempSync(path.join(os.tmpdir(), 'ontogen-save-to-view-'));
const file = path.join(work, path.basename(model));
const text = fs.readFileSync(model, 'utf8');
fs.writeFileSync(file, text);
for (const entry of fs.readdirSync(path.dirname(model), { withFileTypes: true }))
  if (entry.isDirectory() && entry.name === 'surfaces') fs.cpSync(path.join(path.dirname(model), entry.name), path.join(work, entry.name), { recursive: true });

const child = spawn(executable, ['studio', file, '--port', '0', ...studioArgs],
  { stdio: ['ignore', 'pipe', 'pipe'] });
let errors = '';
child.stderr.on('data', (chunk) => { errors += chunk; });
const url = await new Promise((resolve, reject) => {
  let out = '';
  child.stdout.on('data', (chunk) => {
    out += chunk;
    const match = out.match(/http:\/\/127\.0\.0\.1:(\d+)\//);
    if (match) resolve(match[0]);
  });
  child.on('exit', (code) => reject(new Error(`the studio ended (${code}): ${errors}`)));
});

const browser = await chromium.launch({
  executablePath: '/usr/bin/chromium',
  args: ['--no-sandbox', '--disable-gpu', '--no-first-run', '--enable-unsafe-swiftshader', '--use-angle=swiftshader'],
});
try {
  const page = await browser.newPage({ viewport: { width: 1100, height: 900 } });
  const opened = Date.now();
  // The page sets the version once the model is in its scene; the next animation frame
  // draws it, and reading a pixel of the canvas waits until the drawing is done.
  const drawn = async (version) => {
    await page.waitForSelector(`body[data-model-version="${version}"]`, { timeout: 600000 });
    await page.evaluate(() => new Promise((resolve) => requestAnimationFrame(() => {
      const pixel = document.createElement('canvas');
      pixel.width = pixel.height = 1;
      const context = pixel.getContext('2d');
      context.drawImage(document.getElementById('canvas'), 0, 0, 1, 1);
      resolve(context.getImageData(0, 0, 1, 1).data[0]);
    })));
  };
  await page.goto(url);
  await drawn(1);
  console.log(`first view: ${((Date.now() - opened) / 1000).toFixed(2)} s`);
  const times = [];
  for (let k = 1; k <= saves; ++k) {
    const saved = Date.now();
    const savedInPage = await page.evaluate(() => performance.now());
    fs.writeFileSync(file, `${text}\n// save ${k}\n`);
    await drawn(k + 1);
    times.push((Date.now() - saved) / 1000);
    console.log(`save ${k} to view: ${times.at(-1).toFixed(2)} s (${await page.textContent('#status')})`);
    if (k < saves) continue;
    // Where the last save's time went, as the page saw its requests (ms after the save).
    const fetched = await page.evaluate((from) => performance.getEntriesByType('resource')
      .filter((e) => e.startTime >= from && !e.name.includes('/api/events'))
      .map((e) => `${e.name.replace(/^.*\/(?=[^/]+$)/, '')} asked at ${(e.startTime - from).toFixed(0)}, ` +
        `answered by ${(e.responseEnd - from).toFixed(0)} (${e.encodedBodySize} bytes)`), savedInPage);
    for (const line of fetched) console.log('  ' + line);
  }
  const glb = await page.evaluate(async () => (await (await fetch('/model.glb')).arrayBuffer()).byteLength);
  console.log(`summary: saves ${times.map((t) => t.toFixed(2)).join(' ')} s, .glb ${glb} bytes`);
} finally {
  await browser.close();
  child.kill('SIGINT');
  fs.rmSync(work, { recursive: true, force: true });
}
