// The 3-D view a World, Scene or Animation shows in a notebook (python/ontogen/display.py):
// the page holds the model's .glb (base64) and its frames' times; the studio's SceneView
// draws it, turned with the mouse, and a time slider and Play poses it when it has more
// than one frame. Bundled with three.js (ontogen_bundle_page) and inlined in the page:
// nothing is fetched.

import { SceneView } from '../studio/web/scene_view.js';

const $ = (id) => document.getElementById(id);

// What a test can read of the page.
const shown = { ready: false, time: 0, times: [], error: '' };
window.ontogenView = shown;

function bytesOf(base64) {
  const text = atob(base64.trim());
  const bytes = new Uint8Array(text.length);
  for (let i = 0; i < text.length; i += 1) bytes[i] = text.charCodeAt(i);
  return bytes.buffer;
}

async function start() {
  const view = new SceneView($('canvas'));
  const times = JSON.parse($('ontogen-times').textContent);
  shown.times = times;
  const slider = $('time');
  const first = times.length ? times[0] : 0;
  const last = times.length ? times[times.length - 1] : 0;
  let playing = false;
  let lastTick = 0;

  const setTime = (t) => {
    shown.time = Math.min(Math.max(t, first), last);
    slider.value = String(shown.time);
    $('time-value').textContent = shown.time.toFixed(2) + ' s';
    view.setTime(shown.time);
  };
  shown.setTime = setTime;
  const stop = () => { playing = false; $('play').textContent = 'Play'; };

  if (times.length > 1) {
    slider.min = String(first);
    slider.max = String(last);
    slider.step = String(Math.max((last - first) / 1000, 1e-6));
    $('time-row').hidden = false;
    slider.addEventListener('input', () => { stop(); setTime(Number(slider.value)); });
    $('play').addEventListener('click', () => {
      if (playing) return stop();
      if (shown.time >= last) setTime(first);
      playing = true;
      lastTick = performance.now();
      $('play').textContent = 'Pause';
    });
  }

  const tick = (now) => {
    requestAnimationFrame(tick);
    if (playing) {
      setTime(shown.time + (now - lastTick) / 1000);
      lastTick = now;
      if (shown.time >= last) stop();
    }
    view.render();
  };

  const gltf = await view.parse(bytesOf($('ontogen-model').textContent));
  view.show(gltf, last);
  setTime(last);
  requestAnimationFrame(tick);
  shown.ready = true;
  document.body.dataset.ready = 'true';
}

start().catch((error) => {
  shown.error = String(error);
  document.body.dataset.error = String(error);
});
