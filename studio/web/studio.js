// The studio's page: shows the model the executable grows (the same .glb `ontogen run`
// writes), follows it as the file is saved, scrubs and plays its time, moves its
// #defines, plays its music set with the animation, and breeds variants in a gallery.
// Everything it knows comes from the studio's HTTP routes (studio/studio_server.h); the
// variants and their operators are the executable's, not the page's. The 3-D view is
// scene_view.js.

import { SceneView } from './scene_view.js';

const $ = (id) => document.getElementById(id);

// What a test (or a curious user in the console) can read of the page.
const studio = {
  version: 0,          // of the state last shown
  modelVersion: 0,     // of the model last loaded
  time: 0,             // developmental seconds shown
  playing: false,
  notesPlayed: 0,      // notes the animation passed
  notesSounded: 0,     // of them, those the browser's audio played
  generation: 0,
  galleryEpoch: 0,     // of the generation shown (each reset and breed makes a new one)
  galleryGrown: 0,     // of its variants, those grown when it was shown
  galleryProbed: 0,    // of its probes of what changes the picture, those grown when it was shown
  picked: new Set(),
  lastError: '',
  events: 0,           // states the server pushed
  growing: false,      // a growth is in progress
  draws: 0,            // frames the 3-D view drew (only when it changed)
};
window.studio = studio;

// ---- the 3-D view ----------------------------------------------------------------------
const view = new SceneView($('canvas'));

function setTime(t) {
  const lo = timeSlider.min === '' ? 0 : Number(timeSlider.min);
  const hi = Number(timeSlider.max);
  studio.time = Math.min(Math.max(t, lo), hi);
  timeSlider.value = String(studio.time);
  $('time-value').textContent = studio.time.toFixed(2) + ' s';
  view.setTime(studio.time);
  showPicture();
}

// The image set's pictures, one a frame: the one of the last frame at or before the time.
let pictures = { count: 0, version: 0 };
function showPicture() {
  if (pictures.count === 0) return;
  let frame = 0;
  for (let k = 0; k < Math.min(frameTimes.length, pictures.count); k += 1)
    if (frameTimes[k] <= studio.time + 1e-9 * Math.max(1, Math.abs(frameTimes[k]))) frame = k;
  const source = `/model/picture/${frame}.png?v=${pictures.version}`;
  if ($('picture').getAttribute('src') !== source) $('picture').src = source;
  studio.pictureFrame = frame;
}

// ---- time and music --------------------------------------------------------------------
const timeSlider = $('time');
timeSlider.addEventListener('input', () => { stopPlaying(); setTime(Number(timeSlider.value)); });
let audio = null;
let notes = [];
let lastTick = 0;

function startPlaying() {
  if (!audio && window.AudioContext) audio = new AudioContext();
  if (audio && audio.state === 'suspended') audio.resume();
  if (studio.time >= Number(timeSlider.max)) setTime(Number(timeSlider.min));
  studio.playing = true;
  lastTick = performance.now();
  $('play').textContent = 'Pause';
}
function stopPlaying() {
  studio.playing = false;
  $('play').textContent = 'Play';
}
$('play').addEventListener('click', () => (studio.playing ? stopPlaying() : startPlaying()));
// Rewind: the first frame; Step: the next frame of the model's (its developmental times,
// as the server grew them), the last one at the end.
let frameTimes = [];
$('rewind').addEventListener('click', () => { stopPlaying(); setTime(Number(timeSlider.min)); });
$('step').addEventListener('click', () => {
  stopPlaying();
  const next = frameTimes.find((t) => t > studio.time + 1e-9 * Math.max(1, Math.abs(t)));
  setTime(next === undefined ? Number(timeSlider.max) : next);
});
$('frame-all').addEventListener('click', () => view.frameAll());

// A plain voice per note: a triangle wave with a short attack and release, louder with
// velocity, General MIDI's channel 10 (percussion) as a noise-like click.
function playNote(note, when) {
  if (!audio || !$('music').checked) return;
  const gain = audio.createGain();
  const oscillator = audio.createOscillator();
  oscillator.type = note.channel === 9 ? 'square' : 'triangle';
  oscillator.frequency.value = 440 * Math.pow(2, (note.pitch - 69) / 12);
  const level = 0.15 * (note.velocity / 127);
  const length = Math.max(note.duration, 0.05);
  gain.gain.setValueAtTime(0, when);
  gain.gain.linearRampToValueAtTime(level, when + 0.01);
  gain.gain.setValueAtTime(level, when + length * 0.8);
  gain.gain.linearRampToValueAtTime(0, when + length);
  oscillator.connect(gain).connect(audio.destination);
  oscillator.start(when);
  oscillator.stop(when + length + 0.02);
  studio.notesSounded += 1;
}

function tick(now) {
  requestAnimationFrame(tick);
  if (studio.playing) {
    const before = studio.time;
    const after = before + (now - lastTick) / 1000;
    lastTick = now;
    for (const note of notes) {
      if (note.start >= before && note.start < after) {
        playNote(note, audio ? audio.currentTime : 0);
        studio.notesPlayed += 1;
      }
    }
    setTime(after);
    if (after >= Number(timeSlider.max)) stopPlaying();
  }
  if (view.render()) studio.draws += 1;
}
requestAnimationFrame(tick);

// ---- the state: diagnostics, defines, the source ---------------------------------------
function text(tag, content, className) {
  const element = document.createElement(tag);
  if (content !== undefined) element.textContent = content;
  if (className) element.className = className;
  return element;
}

function showDiagnostics(state) {
  const box = $('diagnostics');
  box.replaceChildren();
  if (state.diagnostics.length === 0) box.append(text('p', 'None.', 'quiet'));
  for (const d of state.diagnostics) box.append(text('pre', d.text, 'diagnostic ' + d.severity));
  // The program with each of its own diagnostics at its line; an imported file's are
  // listed above with their file's name, never marked on the program's line of that number.
  const byLine = new Map();
  for (const d of state.diagnostics)
    if (d.line > 0 && d.file === state.sourceName) byLine.set(d.line, [...(byLine.get(d.line) || []), d]);
  const source = $('source');
  source.replaceChildren();
  state.source.split('\n').forEach((line, i) => {
    const found = byLine.get(i + 1);
    source.append(text('span', line, 'line' + (found ? ' ' + found[0].severity : '')));
    if (found) for (const d of found) source.append(text('span', ' '.repeat(Math.max(d.column - 1, 0)) + '^ ' + d.message, 'note'));
  });
}

// Numbers as a person reads them: whole numbers grouped (1,048,576), others to four
// significant digits (3.6, not 3.5999999999999996).
const count = (n) => Math.round(n).toLocaleString('en-US');
const decimal = (x) => String(Number(x.toPrecision(4)));

function showStatus(state) {
  const status = $('status');
  const growth = state.growth;
  studio.growing = growth.running;
  $('stop').disabled = !growth.running;
  if (growth.running) {
    status.dataset.state = 'growing';
    status.textContent = `growing… ${count(growth.cells)} cells, t = ${decimal(growth.time)}`;
    return;
  }
  const errors = state.diagnostics.filter((d) => d.severity === 'error').length;
  if (state.stopped) {
    status.dataset.state = 'stopped';
    status.textContent = 'stopped; showing the last model that grew';
  } else if (state.ok) {
    status.dataset.state = 'ok';
    status.textContent = `grown in ${state.seconds.toFixed(2)} s: ${count(state.cells)} cells at ${decimal(state.until)} s`;
  } else {
    status.dataset.state = 'error';
    status.textContent = `${errors} error${errors === 1 ? '' : 's'}; showing the last model that grew`;
  }
}

// The interactive limits: the page shows them and may raise them up to the command line's.
function showLimits(limits) {
  const cells = $('max-cells');
  const memory = $('max-memory');
  cells.max = String(limits.ceilingCells);
  memory.max = String(Math.floor(limits.ceilingMemoryBytes / 1048576));
  if (document.activeElement !== cells) cells.value = String(limits.maxCells);
  if (document.activeElement !== memory) memory.value = String(Math.floor(limits.maxMemoryBytes / 1048576));
}

let defineNames = '';
const defineSending = { busy: false, pending: null };

async function sendDefine(name, value) {
  if (defineSending.busy) { defineSending.pending = { name, value }; return; }
  defineSending.busy = true;
  try {
    const response = await post('/api/define', { name, value });
    const answer = await response.json();
    if (!response.ok) studio.lastError = answer.error;
    else await showState(answer);
  } finally {
    defineSending.busy = false;
    const next = defineSending.pending;
    defineSending.pending = null;
    if (next) sendDefine(next.name, next.value);
  }
}

function showDefines(state) {
  const names = state.defines.map((d) => `${d.name}:${d.low}:${d.high}`).join(',');
  const box = $('defines');
  if (names !== defineNames) {
    defineNames = names;
    box.replaceChildren();
    if (state.defines.length === 0) box.append(text('p', 'The program has no #define.', 'quiet'));
    for (const d of state.defines) {
      const row = text('div', undefined, 'define');
      const slider = document.createElement('input');
      slider.type = 'range';
      slider.min = String(d.low);
      slider.max = String(d.high);
      slider.step = d.integer ? '1' : String((d.high - d.low) / 200);
      slider.dataset.define = d.name;
      const value = text('output', '');
      value.dataset.defineValue = d.name;
      slider.addEventListener('input', () => {
        value.textContent = slider.value;
        sendDefine(d.name, Number(slider.value));
      });
      // While the slider's value is not the file's, the row says so, with the file's
      // number and one click to write the slider's into the file or to drop it.
      const override = text('div', undefined, 'override');
      override.dataset.override = d.name;
      override.hidden = true;
      const written = text('span', '');
      const write = text('button', 'write to file');
      write.type = 'button';
      write.dataset.write = d.name;
      write.addEventListener('click', () => defineAction('/api/define/write', d.name));
      const drop = text('button', 'drop');
      drop.type = 'button';
      drop.dataset.drop = d.name;
      drop.addEventListener('click', () => defineAction('/api/define/drop', d.name));
      override.append(written, write, drop);
      row.append(text('label', d.name), slider, value, override);
      box.append(row);
    }
  }
  for (const d of state.defines) {
    const slider = box.querySelector(`input[data-define="${d.name}"]`);
    const value = box.querySelector(`output[data-define-value="${d.name}"]`);
    const override = box.querySelector(`div[data-override="${d.name}"]`);
    if (slider && document.activeElement !== slider) slider.value = String(d.value);
    if (value) value.textContent = String(Number(d.value.toPrecision(6)));
    if (override) {
      override.hidden = !d.overridden;
      override.parentElement.classList.toggle('overridden', d.overridden);
      override.firstChild.textContent = `overrides the file's ${Number(d.written.toPrecision(6))}`;
      override.querySelector('button[data-write]').disabled = state.converted;
    }
  }
}

async function defineAction(path, name) {
  const response = await post(path, { name });
  const answer = await response.json();
  if (!response.ok) { studio.lastError = answer.error; $('define-error').textContent = answer.error; return; }
  $('define-error').textContent = '';
  await showState(answer.state);
}

let loadingModel = 0;
// A model that grew: its 3-D view (none for a model of music alone) and its notes. The
// time slider spans the development, and the whole piece when its notes last longer (a
// word read as a piece plays at its own tempo).
async function loadModel(version, hasModel) {
  loadingModel = version;
  // Both asked at once: the notes come while the model is parsed.
  const notesAsked = fetch('/api/notes').then((response) => response.json());
  let gltf = null;
  if (hasModel) {
    const response = await fetch('/model.glb?v=' + version);
    if (response.ok) gltf = await view.parse(await response.arrayBuffer());
  }
  const notesAnswer = await notesAsked;
  if (loadingModel !== version) return;  // a newer model is on its way
  notes = notesAnswer.notes;
  $('note-count').textContent = notes.length ? `(${notes.length} notes)` : '(no music set)';
  pictures = { count: stateShown.pictures || 0, version };
  $('picture').hidden = pictures.count === 0;
  $('no-model').hidden = gltf !== null || pictures.count > 0;
  const grown = studio.time >= Number(timeSlider.max) || studio.modelVersion === 0;
  const end = Math.max(stateShown.until, stateShown.from, ...notes.map((n) => n.start + n.duration));
  timeSlider.min = String(stateShown.from);
  timeSlider.max = String(end);
  timeSlider.step = String(Math.max((end - stateShown.from) / 1000, 1e-6));
  if (grown) studio.time = end;  // a new model shows grown, unless scrubbed
  frameTimes = stateShown.frames || [];
  if (gltf) view.show(gltf, studio.time);
  else view.clear();
  setTime(studio.time);
  studio.modelVersion = version;
  document.body.dataset.modelVersion = String(version);
}

let stateShown = { from: 0, until: 1 };
async function showState(state) {
  showStatus(state);
  showLimits(state.limits);
  showDefines(state);  // a moved slider is marked as overriding the file at once
  if (state.version === studio.version) return;
  studio.version = state.version;
  stateShown = state;
  $('file').textContent = state.file;
  showDiagnostics(state);
  document.body.dataset.version = String(state.version);
  if (state.modelVersion > 0 && state.modelVersion !== studio.modelVersion && state.modelVersion !== loadingModel)
    await loadModel(state.modelVersion, state.hasModel);
}

// The server pushes its state at each change (server-sent events): a growth's start, each
// of its frames, its end. EventSource connects again by itself after an interruption.
const events = new EventSource('/api/events');
let showing = Promise.resolve();
events.onmessage = (message) => {
  studio.events += 1;
  const state = JSON.parse(message.data);
  showing = showing.then(() => showState(state)).catch((error) => { studio.lastError = String(error); });
};
events.onerror = () => {
  $('status').dataset.state = 'error';
  $('status').textContent = 'the studio does not answer (was it stopped?)';
};

// Requests that change something, the only way the page makes one: they carry the token
// the studio wrote into this page for its run, which other sites cannot read, so the
// studio can tell its page's requests from theirs (studio/request_guard.h).
const token = document.querySelector('meta[name="ontogen-token"]').content;
function post(path, body) {
  return fetch(path, {
    method: 'POST',
    headers: { 'Content-Type': 'application/json', 'X-Ontogen-Token': token },
    body: JSON.stringify(body),
  });
}

$('stop').addEventListener('click', () => post('/api/stop', {}));
$('limits-apply').addEventListener('click', async () => {
  const response = await post('/api/limits', {
    maxCells: Number($('max-cells').value), maxMemoryMiB: Number($('max-memory').value),
  });
  if (!response.ok) studio.lastError = (await response.json()).error;
});

// ---- evolution -------------------------------------------------------------------------
// A generation is answered before its variants grow (they grow on the studio's gallery
// thread): the page shows it at once and asks again until every variant is pictured.
function showGallery(gallery) {
  if (gallery.epoch !== studio.galleryEpoch) {
    studio.galleryEpoch = gallery.epoch;
    studio.picked.clear();
  }
  studio.generation = gallery.generation;
  studio.galleryGrown = gallery.grown;
  studio.galleryProbed = gallery.probed;
  const progress = gallery.probing
    ? `: finding which #defines change the picture (${gallery.probed} of at most ${gallery.probes} grown)`
    : gallery.growing ? `: ${gallery.grown} of ${gallery.variants.length} grown` : '';
  const held = gallery.held.length && !gallery.warning
    ? ` · held, as they change nothing pictured: ${gallery.held.join(', ')}` : '';
  $('generation').textContent = `generation ${gallery.generation}${progress}` +
    (gallery.warning ? ` (${gallery.warning})` : '') + held;
  $('breed').disabled = studio.picked.size === 0;
  $('gallery-restart').disabled = false;
  document.body.dataset.generation = String(gallery.generation);
  document.body.dataset.galleryGrown = gallery.growing ? '' : String(gallery.generation);
  const box = $('gallery');
  box.replaceChildren();
  for (const variant of gallery.variants) {
    const card = text('div', undefined, 'variant');
    card.dataset.index = String(variant.index);
    card.classList.toggle('picked', studio.picked.has(variant.index));
    if (variant.picture) {
      const image = document.createElement('img');
      image.src = `/gallery/${variant.index}.png?e=${gallery.epoch}`;
      image.alt = `variant ${variant.index}`;
      card.append(image);
    } else if (!variant.grown) {
      card.append(text('div', 'growing…', 'pending'));
    } else {
      card.classList.add('failed');
      const why = text('div', undefined, 'why');
      why.append(text('strong', 'failed'), text('span', variant.error));
      card.append(why);
    }
    const caption = text('div', undefined, 'caption');
    // A value a line, as a person writes it: whole numbers whole, others to 3 digits.
    const values = text('div', undefined, 'values');
    gallery.genes.forEach((gene, i) => {
      const value = variant.values[i];
      const shown = gene.integer ? String(Math.round(value)) : String(Number(value.toPrecision(3)));
      values.append(text('div', `${gene.name} ${shown}`));
    });
    caption.append(values);
    const save = text('button', 'save');
    save.type = 'button';
    save.addEventListener('click', async (event) => {
      event.stopPropagation();
      const answer = await (await post('/api/save', { index: variant.index })).json();
      $('saved').textContent = answer.path ? 'saved ' + answer.path : answer.error;
    });
    caption.append(save);
    card.append(caption);
    card.addEventListener('click', () => {
      if (studio.picked.has(variant.index)) studio.picked.delete(variant.index);
      else studio.picked.add(variant.index);
      card.classList.toggle('picked', studio.picked.has(variant.index));
      $('breed').disabled = studio.picked.size === 0;
    });
    box.append(card);
  }
}

// Asks how far the generation of `epoch` has grown until it has, showing each new
// picture; stops when another generation replaced it (its own request follows that one).
async function followGallery(epoch) {
  for (;;) {
    await new Promise((resolve) => setTimeout(resolve, 250));
    if (studio.galleryEpoch !== epoch) return;
    const response = await fetch('/api/gallery');
    if (!response.ok) return;
    const gallery = await response.json();
    if (gallery.epoch !== epoch) return;
    if (gallery.grown !== studio.galleryGrown || gallery.probed !== studio.galleryProbed || !gallery.growing)
      showGallery(gallery);
    if (!gallery.growing) return;
  }
}

async function galleryRequest(path, body) {
  $('generation').textContent = 'making the variants…';
  const response = await post(path, body);
  const answer = await response.json();
  if (!response.ok) { $('generation').textContent = answer.error; return; }
  showGallery(answer);
  if (answer.growing) followGallery(answer.epoch);
}
$('gallery-open').addEventListener('click', () => galleryRequest('/api/gallery', {}));
$('gallery-restart').addEventListener('click', () => galleryRequest('/api/gallery/restart', {}));
$('breed').addEventListener('click', () => galleryRequest('/api/breed', { picked: [...studio.picked].sort((a, b) => a - b) }));
