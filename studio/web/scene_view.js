// A model as `ontogen run --format glb` writes it, drawn at a developmental time: the 3-D
// view of the studio's page, and of any other page that shows an ontogen .glb (import
// { SceneView } and bundle with ontogen_bundle_page, studio/CMakeLists.txt). It knows
// nothing of the studio's server.

import * as THREE from 'three';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';

// The union of every frame's geometry: the .glb says it in its scene's extras
// (ontogen_bounds, formats/glb_writer.h), as its parts move and scale over the frames;
// a file without them is measured from its meshes.
function boundsOfAllFrames(root) {
  const b = root.userData.ontogen_bounds;
  if (Array.isArray(b) && b.length === 6) {
    return new THREE.Box3(new THREE.Vector3(b[0], b[1], b[2]), new THREE.Vector3(b[3], b[4], b[5]));
  }
  const box = new THREE.Box3();
  root.traverse((object) => {
    if (!object.geometry) return;
    object.geometry.computeBoundingBox();
    box.union(object.geometry.boundingBox);
  });
  return box;
}

export class SceneView {
  /// Draws into canvas (an HTMLCanvasElement), turned with the mouse.
  constructor(canvas) {
    this.canvas = canvas;
    this.renderer = new THREE.WebGLRenderer({ canvas, antialias: true, preserveDrawingBuffer: true });
    this.renderer.setPixelRatio(window.devicePixelRatio || 1);
    this.scene = new THREE.Scene();
    this.scene.background = new THREE.Color(0x2a2d33);
    this.scene.add(new THREE.HemisphereLight(0xffffff, 0x50505a, 1.6));
    const key = new THREE.DirectionalLight(0xffffff, 2.2);
    key.position.set(1, 2, 1.5);
    this.scene.add(key);
    this.camera = new THREE.PerspectiveCamera(40, 1, 0.01, 1000);
    this.camera.position.set(0, 0, 10);
    this.controls = new OrbitControls(this.camera, canvas);
    this.controls.enableDamping = true;
    this.model = null;   // the loaded glTF scene
    this.mixer = null;   // poses the model at a time
    this.action = null;  // the clip's one action
    this.clipStart = 0;
    this.clipEnd = 0;
    // Each new model is framed (the framing follows the growth) until the user turns or
    // zooms the camera; frameAll() frames it and follows again.
    this.following = true;
    this.controls.addEventListener('start', () => { this.following = false; });
    // Drawn only when something changed (the model, its time, the camera, the canvas'
    // size): a large model takes a software renderer most of a second a frame, which
    // drawn at every animation frame held the page's requests and parsing back for
    // seconds. The controls say when their damping still moves the camera.
    this.stale = true;
    this.controls.addEventListener('change', () => { this.stale = true; });
  }

  /// Parses a .glb's bytes (an ArrayBuffer); resolves to the glTF, not yet shown.
  parse(bytes) {
    return new GLTFLoader().parseAsync(bytes, '');
  }

  /// Shows no model.
  clear() {
    if (this.model) {
      this.scene.remove(this.model);
      this.model.traverse((o) => { if (o.geometry) o.geometry.dispose(); });
    }
    this.model = null;
    this.mixer = null;
    this.action = null;
    this.stale = true;
  }

  /// Shows a parsed glTF in place of the model before, posed at time t.
  show(gltf, t) {
    this.clear();
    this.model = gltf.scene;
    // The file brings no light (docs/LANGUAGE.md, the .glb's camera and light): the
    // page's own lights light it, as any viewer's do; the page test's check that nothing is
    // washed white fails should the file bring one again.
    this.scene.add(this.model);
    this.mixer = null;
    this.action = null;
    this.clipStart = this.clipEnd = 0;
    const clip = gltf.animations[0];
    if (clip) {
      this.mixer = new THREE.AnimationMixer(this.model);
      this.action = this.mixer.clipAction(clip);
      this.action.setLoop(THREE.LoopOnce, 1);
      this.action.clampWhenFinished = true;
      this.action.play();
      this.clipStart = Math.min(...clip.tracks.map((track) => track.times[0]));
      this.clipEnd = clip.duration;
    }
    if (this.following) this.frame();
    this.setTime(t);
  }

  /// Frames the model as a new one is, and frames each model to come until the user
  /// turns the camera again.
  frameAll() {
    this.frame();
    this.following = true;
  }

  /// Turns the camera to see the whole model at every time.
  frame() {
    if (!this.model) return;
    const box = boundsOfAllFrames(this.model);
    if (box.isEmpty()) return;
    const camera = this.camera;
    const centre = box.getCenter(new THREE.Vector3());
    const radius = Math.max(box.getSize(new THREE.Vector3()).length() / 2, 1e-6);
    const distance = radius / Math.sin(THREE.MathUtils.degToRad(camera.fov / 2)) * 1.1;
    camera.near = distance / 1000;
    camera.far = distance * 100;
    camera.position.copy(centre).add(new THREE.Vector3(0.35, 0.45, 1).normalize().multiplyScalar(distance));
    camera.updateProjectionMatrix();
    this.controls.target.copy(centre);
    this.controls.update();
    this.stale = true;
  }

  /// Poses the model at developmental time t (seconds).
  setTime(t) {
    if (!this.mixer) return;
    // The animation's keys are the frames' developmental times less the first's, played
    // faster for a long run (the scene's extras say how); before the first key the first
    // frame shows.
    const extras = this.model.userData;
    const clipTime = typeof extras.ontogen_time_scale === 'number'
      ? (t - extras.ontogen_time_start) * extras.ontogen_time_scale
      : t;
    // The view poses the action itself: once a LoopOnce action reaches its end three.js
    // pauses it (clampWhenFinished), and mixer.setTime() would then leave it at the start
    // for ever after. Unpaused, at the time asked, and updated by nothing, it shows that time.
    this.action.enabled = true;
    this.action.paused = false;
    this.action.time = Math.min(Math.max(clipTime, this.clipStart), this.clipEnd);
    this.mixer.update(0);
    this.stale = true;
  }

  /// Draws a frame when the view changed since the last (call it from
  /// requestAnimationFrame); returns whether it drew.
  render() {
    const { canvas, renderer, camera } = this;
    const { clientWidth: w, clientHeight: h } = canvas;
    const ratio = renderer.getPixelRatio();
    if (canvas.width !== Math.floor(w * ratio) || canvas.height !== Math.floor(h * ratio)) {
      renderer.setSize(w, h, false);
      camera.aspect = w / Math.max(h, 1);
      camera.updateProjectionMatrix();
      this.stale = true;
    }
    this.controls.update();  // dispatches 'change' while the camera still moves
    if (!this.stale) return false;
    this.stale = false;
    renderer.render(this.scene, camera);
    return true;
  }
}
