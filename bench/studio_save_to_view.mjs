// Save to view in the studio, measured as a person sees it: `ontogen studio MODEL` on a
// free port, its page in headless Chromium (Debian's, driven by playwright-core); the
// model's file is saved again (its text unchanged but for a trailing comment) and the
// time is taken from the save until the page shows the new model (body's
// data-model-version). Prints the first load's time and each save's.
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
  await page.goto(url);
  await page.waitForSelector('body[data-model-version="1"]', { timeout: 600000 });
  console.log(`first view: ${((Date.now() - opened) / 1000).toFixed(2)} s`);
  for (let k = 1; k <= saves; ++k) {
    const saved = Date.now();
    fs.writeFileSync(file, `${text}\n// save ${k}\n`);
    await page.waitForSelector(`body[data-model-version="${k + 1}"]`, { timeout: 600000 });
    console.log(`save ${k} to view: ${((Date.now() - saved) / 1000).toFixed(2)} s (${await page.textContent('#status')})`);
  }
} finally {
  await browser.close();
  child.kill('SIGINT');
  fs.rmSync(work, { recursive: true, force: true });
}
