// The 3D stage: renderer, camera, orbit controls, lights, render-on-demand and automatic framing.
// World frame "W" is local East-North-Up in metres, so the camera's up is +z.
import {
  AmbientLight,
  Box3,
  Color,
  DirectionalLight,
  GridHelper,
  PerspectiveCamera,
  Scene,
  Vector2,
  Vector3,
  WebGLRenderer,
} from 'three';
import { OrbitControls } from 'three/examples/jsm/controls/OrbitControls.js';

export const BACKGROUND = 0x0d1117;

export class Stage {
  constructor(container) {
    // preserveDrawingBuffer: a screenshot (headless test, the browser's own) must read the last frame even though
    // frames are only drawn on demand.
    this.renderer = new WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
    this.renderer.setPixelRatio(Math.min(window.devicePixelRatio || 1, 2));
    this.renderer.setClearColor(BACKGROUND, 1);
    container.appendChild(this.renderer.domElement);

    this.scene = new Scene();
    this.scene.background = new Color(BACKGROUND);
    this.camera = new PerspectiveCamera(50, 1, 0.1, 1e6);
    this.camera.up.set(0, 0, 1);
    this.camera.position.set(-60, -90, 80);

    // A strong ambient term keeps every building face well above the background's brightness; the directional
    // light gives the faces distinct shades so the city reads as 3D.
    this.scene.add(new AmbientLight(0xffffff, 0.9));
    const sun = new DirectionalLight(0xffffff, 2.4);
    sun.position.set(-0.4, -0.9, 1.3);
    this.scene.add(sun);

    this.grid = new GridHelper(1, 1, 0x262c36, 0x1a1f27);
    this.grid.rotation.x = Math.PI / 2; // GridHelper lies in x-z; the ground here is x-y
    this.grid.visible = false;
    this.scene.add(this.grid);

    this.controls = new OrbitControls(this.camera, this.renderer.domElement);
    this.controls.enableDamping = false; // damping would need a continuous render loop
    this.controls.addEventListener('change', () => this.requestRender());
    // The first user gesture ends automatic framing: the view must never move under the user's hand.
    this.userMoved = false;
    this.controls.addEventListener('start', () => {
      this.userMoved = true;
    });

    this.framed = null; // Box3 the camera currently shows (auto-framing only ever grows it)
    this.resolution = new Vector2(1, 1); // shared by every LineMaterial (fat lines are sized in pixels)
    this.pending = false;
    this.frames = 0;
    this.rightInset = 0;
    this.beforeRender = [];
    window.addEventListener('resize', () => this.resize());
    this.resize();
  }

  resize() {
    const w = window.innerWidth;
    const h = window.innerHeight;
    this.renderer.setSize(w, h);
    this.camera.aspect = w / Math.max(1, h);
    // The side panel covers the right of the window: the projection centre moves left by half its width so that
    // framed content lands in the part that stays visible (narrow windows keep the whole width).
    const panel = document.getElementById('panel');
    this.rightInset = panel && w > 2.5 * panel.offsetWidth ? panel.offsetWidth + 16 : 0;
    if (this.rightInset > 0) this.camera.setViewOffset(w, h, this.rightInset / 2, 0, w, h);
    else this.camera.clearViewOffset();
    this.camera.updateProjectionMatrix();
    this.resolution.set(w, Math.max(1, h)); // CSS pixels: LineMaterial widths are then CSS px at any DPR
    if (this.framed && !this.userMoved) this.placeCamera(this.framed);
    this.requestRender();
  }

  // Rendering only when something changed keeps an idle tab (and software GL in CI) from burning a core.
  requestRender() {
    if (this.pending) return;
    this.pending = true;
    requestAnimationFrame(() => {
      this.pending = false;
      for (const f of this.beforeRender) f();
      this.renderer.render(this.scene, this.camera);
      this.frames += 1;
    });
  }

  // Called with the bounds of everything worth seeing (tiles and trajectories). The frame only widens, and only
  // when content leaves it, with slack: a growing trajectory keeps its on-screen scale most of the time.
  frame(content) {
    if (this.userMoved || content.isEmpty()) return;
    const minSize = 40; // m: a first pose alone must not zoom in to centimetres
    if (this.framed && this.framed.containsBox(content)) return;
    const box = content.clone();
    if (this.framed) box.union(this.framed);
    const size = box.getSize(new Vector3());
    const center = box.getCenter(new Vector3());
    // Slack on every axis: with none on one (height), the framed box would not contain its own content again and
    // every refresh would widen it once more, shrinking the scene away.
    const half = new Vector3(
      Math.max(size.x * 0.6, minSize / 2),
      Math.max(size.y * 0.6, minSize / 2),
      Math.max(size.z * 0.6, 1),
    );
    this.framed = new Box3(center.clone().sub(half), center.clone().add(half));
    this.placeCamera(this.framed);
    this.updateGrid(this.framed);
    this.requestRender();
  }

  placeCamera(box) {
    const center = box.getCenter(new Vector3());
    const size = box.getSize(new Vector3());
    // Fit the ground footprint (x-y) to the narrower of the two view angles, then look down at ~40 degrees from the
    // south-west so building heights show.
    const radius = 0.5 * Math.hypot(size.x, size.y);
    const vfov = (this.camera.fov * Math.PI) / 180;
    const visibleAspect = (window.innerWidth - this.rightInset) / Math.max(1, window.innerHeight);
    const hfov = 2 * Math.atan(Math.tan(vfov / 2) * visibleAspect);
    const distance = (radius / Math.sin(Math.min(vfov, hfov) / 2)) * 0.85;
    const dir = new Vector3(-0.35, -0.75, 0.9).normalize();
    this.camera.position.copy(center).addScaledVector(dir, distance);
    this.camera.near = Math.max(0.05, distance / 1000);
    this.camera.far = distance * 20;
    this.camera.updateProjectionMatrix();
    this.controls.target.copy(center);
    this.controls.update();
  }

  updateGrid(box) {
    const size = box.getSize(new Vector3());
    const extent = Math.max(size.x, size.y) * 2;
    const step = 10 ** Math.floor(Math.log10(Math.max(extent / 10, 1)));
    const divisions = Math.min(400, Math.ceil(extent / step));
    const center = box.getCenter(new Vector3());
    this.scene.remove(this.grid);
    this.grid.geometry.dispose();
    this.grid = new GridHelper(divisions * step, divisions, 0x262c36, 0x1a1f27);
    this.grid.rotation.x = Math.PI / 2;
    this.grid.position.set(Math.round(center.x / step) * step, Math.round(center.y / step) * step, box.min.z - 0.05);
    this.scene.add(this.grid);
  }
}
