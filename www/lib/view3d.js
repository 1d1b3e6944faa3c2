// The live mapper's 3D view: the best world's `world.glb` (Mapper.worldGlb, made in the
// chain's worker; the very bytes `ksmcmc floorplan` writes) shown with three.js. The page
// imports this module only when the view is opened, so three.js (www/vendor, copied from npm
// by `make www-vendor`) costs nothing until then. It draws on demand: when the model changes,
// the camera moves or the canvas is resized, never in a loop.
//
// Mouse, pen and touch: drag to orbit, right-drag (or two fingers) to pan, wheel or pinch to
// zoom. Keys on the focused canvas: arrows pan, Shift+arrows orbit, + and - zoom, 0 resets the
// view.

import {
  Box3, Color, DirectionalLight, HemisphereLight, PerspectiveCamera, Scene, SRGBColorSpace, Vector3, WebGLRenderer,
} from 'three';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';

export class View3d {
  /** @param {HTMLCanvasElement} canvas  a canvas of its own (it gets a WebGL context) */
  constructor(canvas) {
    this.canvas = canvas;
    // preserveDrawingBuffer: the picture can be read back (a screenshot, the tests).
    this.renderer = new WebGLRenderer({ canvas, antialias: true, preserveDrawingBuffer: true });
    this.renderer.outputColorSpace = SRGBColorSpace;
    this.renderer.setClearColor(new Color(0xeef1f5), 1);
    this.scene = new Scene();
    this.scene.add(new HemisphereLight(0xffffff, 0x8a8f99, 2.2));
    const sun = new DirectionalLight(0xffffff, 1.6);
    sun.position.set(-0.6, 1, 0.35);
    this.scene.add(sun);
    this.camera = new PerspectiveCamera(45, 1, 0.05, 2000);
    this.controls = new OrbitControls(this.camera, canvas);
    this.controls.listenToKeyEvents(canvas);
    this.controls.maxPolarAngle = Math.PI / 2 - 0.02;
    this.controls.addEventListener('change', () => this.render());
    this.loader = new GLTFLoader();
    this.model = null;
    this.framed = false;
    canvas.addEventListener('keydown', (e) => this.onKey(e));
  }

  /** Shows the model in `bytes` (a .glb) in place of the last one; frames it the first time. */
  async show(bytes) {
    const gltf = await this.loader.parseAsync(bytes.buffer.slice(bytes.byteOffset, bytes.byteOffset + bytes.byteLength), '');
    if (this.model) {
      this.scene.remove(this.model);
      this.model.traverse((o) => {
        o.geometry?.dispose();
        o.material?.dispose?.();
      });
    }
    this.model = gltf.scene;
    this.scene.add(this.model);
    if (!this.framed) this.frame();
    this.render();
    return this.model;
  }

  /**
   * Looks at the whole model from above and to the south, as a plan seen at an angle, from
   * as far as its bounding sphere needs to fit the picture's narrower angle of view.
   */
  frame() {
    if (!this.model) return;
    const box = new Box3().setFromObject(this.model);
    if (box.isEmpty()) return;
    const centre = box.getCenter(new Vector3());
    const radius = Math.max(box.getSize(new Vector3()).length() / 2, 0.5);
    const vertical = (this.camera.fov * Math.PI) / 180;
    const horizontal = 2 * Math.atan(Math.tan(vertical / 2) * this.camera.aspect);
    const distance = radius / Math.sin(Math.min(vertical, horizontal) / 2);
    const direction = new Vector3(0, 1.2, 0.7).normalize();
    this.controls.target.copy(centre);
    this.camera.position.copy(centre).addScaledVector(direction, distance);
    this.camera.far = distance * 10;
    this.camera.updateProjectionMatrix();
    this.controls.update();
    this.framed = true;
  }

  /** Sizes the drawing buffer to the canvas's size on screen. */
  resize() {
    const { clientWidth: w, clientHeight: h } = this.canvas;
    if (!w || !h) return;
    this.renderer.setPixelRatio(Math.min(2, globalThis.devicePixelRatio || 1));
    this.renderer.setSize(w, h, false);
    this.camera.aspect = w / h;
    this.camera.updateProjectionMatrix();
    this.render();
  }

  render() {
    this.renderer.render(this.scene, this.camera);
  }

  onKey(e) {
    if (e.ctrlKey || e.metaKey || e.altKey) return;
    const actions = {
      '+': () => this.controls.dollyIn(1.2),
      '=': () => this.controls.dollyIn(1.2),
      '-': () => this.controls.dollyOut(1.2),
      0: () => this.frame(),
    };
    const action = actions[e.key];
    if (!action) return;
    e.preventDefault();
    e.stopPropagation();
    action();
    this.render();
  }

  /** The names of the model's nodes (walls, lintels, doors, one per room). */
  nodeNames() {
    return this.model ? this.model.children.map((c) => c.name) : [];
  }

  dispose() {
    this.controls.dispose();
    this.renderer.dispose();
  }
}
