// The 3D view: renderer, a Z-up camera with orbit/pan/zoom, lights, and a render loop that draws
// only when something changed, at most at the config's frame rate.
import * as THREE from "three";
import { OrbitControls } from "three/addons/controls/OrbitControls.js";

export class Scene3D {
  constructor(canvas, background, frameRate, stats) {
    this.canvas = canvas;
    this.stats = stats;
    this.minInterval = 1000 / Math.max(1, frameRate) - 2;
    this.renderer = new THREE.WebGLRenderer({ canvas, antialias: true });
    this.renderer.setPixelRatio(Math.min(window.devicePixelRatio || 1, 2));
    this.scene = new THREE.Scene();
    this.scene.background = new THREE.Color().setRGB(background[0] / 255, background[1] / 255, background[2] / 255, THREE.SRGBColorSpace);
    this.camera = new THREE.PerspectiveCamera(60, 1, 0.02, 500);
    this.camera.up.set(0, 0, 1); // ROS frames are Z-up
    this.camera.position.set(-1.7, -2.0, 1.4);
    this.controls = new OrbitControls(this.camera, canvas);
    this.controls.target.set(0, 0, 0);
    this.controls.update();
    this.controls.addEventListener("change", () => this.requestRender());
    this.scene.add(new THREE.HemisphereLight(0xffffff, 0x444444, 1.6));
    const light = new THREE.DirectionalLight(0xffffff, 1.6);
    light.position.set(1, 1, 2);
    this.camera.add(light); // a light that follows the eye, as rviz's does
    this.scene.add(this.camera);
    this.updaters = [];
    this.dirty = true;
    this.lastRender = 0;
    this.frameTimes = [];
    new ResizeObserver(() => this.resize()).observe(canvas);
    this.resize();
    requestAnimationFrame((t) => this.tick(t));
  }

  resize() {
    const width = this.canvas.clientWidth || 1;
    const height = this.canvas.clientHeight || 1;
    this.renderer.setSize(width, height, false);
    this.camera.aspect = width / height;
    this.camera.updateProjectionMatrix();
    this.requestRender();
  }

  requestRender() {
    this.dirty = true;
  }

  // `update()` runs before each frame is drawn (to pose things from TF).
  onFrame(update) {
    this.updaters.push(update);
  }

  render() {
    for (const update of this.updaters) update();
    this.renderer.render(this.scene, this.camera);
    const now = performance.now();
    this.lastRender = now;
    this.dirty = false;
    this.stats.frames += 1;
    this.frameTimes.push(now);
    while (this.frameTimes.length && now - this.frameTimes[0] > 1000) this.frameTimes.shift();
    this.stats.fps = this.frameTimes.length;
  }

  tick(time) {
    requestAnimationFrame((t) => this.tick(t));
    if (this.dirty && time - this.lastRender >= this.minInterval) this.render();
    else if (this.frameTimes.length && time - this.frameTimes[0] > 1000) {
      this.frameTimes.shift();
      this.stats.fps = this.frameTimes.length;
    }
  }

  // Where a point of the world (fixed frame) lands on the canvas, in CSS pixels from its top left.
  project(point) {
    const v = point.clone().project(this.camera);
    return {
      x: ((v.x + 1) / 2) * this.canvas.clientWidth,
      y: ((1 - v.y) / 2) * this.canvas.clientHeight,
      visible: v.z > -1 && v.z < 1,
    };
  }

  // Draw now and read the colours at canvas points (CSS pixels): [[r, g, b], ...].
  sample(points) {
    this.render();
    const gl = this.renderer.getContext();
    const ratio = this.renderer.getPixelRatio();
    const height = gl.drawingBufferHeight;
    const pixel = new Uint8Array(4);
    return points.map(({ x, y }) => {
      gl.readPixels(Math.round(x * ratio), Math.round(height - 1 - y * ratio), 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, pixel);
      return [pixel[0], pixel[1], pixel[2]];
    });
  }
}
