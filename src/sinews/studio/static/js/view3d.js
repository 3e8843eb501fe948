// A 3D figure's replay drawn with three.js (vendored, see vendor/three/README.md): the
// shapes of a pack from sinews/studio/shapes_pack.py, z up as in MuJoCo, an orbit camera
// (drag to turn, wheel to zoom, right-drag to pan) that follows the figure unless the
// user has moved it.
import * as THREE from "three";
import { OrbitControls } from "three/addons/controls/OrbitControls.js";

const FLOOR_SIZE = 40;

/** Geometry of one shape, in its own frame (MuJoCo's sizes: half-extents, radius, half-length). */
function geometryOf(kind, [a, b, c]) {
  switch (kind) {
    case "sphere":
      return new THREE.SphereGeometry(a, 24, 16);
    case "ellipsoid":
      return new THREE.SphereGeometry(1, 24, 16).scale(a, b, c);
    case "capsule":
      return new THREE.CapsuleGeometry(a, 2 * b, 8, 16).rotateX(Math.PI / 2);
    case "cylinder":
      return new THREE.CylinderGeometry(a, a, 2 * b, 24).rotateX(Math.PI / 2);
    case "box":
      return new THREE.BoxGeometry(2 * a, 2 * b, 2 * c);
    default:
      throw new Error(`cannot draw a ${kind}`);
  }
}

function floor() {
  const group = new THREE.Group();
  const plane = new THREE.Mesh(
    new THREE.PlaneGeometry(FLOOR_SIZE, FLOOR_SIZE),
    new THREE.MeshStandardMaterial({ color: 0xe4e4de, roughness: 0.95, polygonOffset: true, polygonOffsetFactor: 1, polygonOffsetUnits: 1 }),
  );
  plane.receiveShadow = true;
  const grid = new THREE.GridHelper(FLOOR_SIZE, FLOOR_SIZE * 4, 0x8c8c84, 0xb0b0a8);
  grid.rotateX(Math.PI / 2);
  grid.position.z = 0.001;
  group.add(plane, grid);
  return group;
}

export class View3D {
  /**
   * @param {HTMLCanvasElement} canvas
   * @param {{header: object, arrays: object}} pack decoded by pack.js's decodePack
   */
  constructor(canvas, { header, arrays }) {
    this.canvas = canvas;
    this.fps = header.fps;
    this.scale = header.scale;
    this.unit = 1 / header.quaternion_scale;
    this.positions = arrays.positions.data; // (T, G, 3) int16 mm
    this.quaternions = arrays.quaternions.data; // (T, G, 4) int16 (w, x, y, z)
    [this.frames, this.count] = arrays.positions.shape;
    this.frame = 0;

    this.renderer = new THREE.WebGLRenderer({ canvas, antialias: true });
    this.renderer.setPixelRatio(window.devicePixelRatio || 1);
    this.renderer.shadowMap.enabled = true;
    this.scene = new THREE.Scene();
    this.scene.background = new THREE.Color(0xeef1f5);
    const sky = new THREE.HemisphereLight(0xffffff, 0x8a8a80, 1.6);
    sky.position.set(0, 0, 1); // z is up
    this.scene.add(sky);
    const sun = new THREE.DirectionalLight(0xffffff, 1.8);
    sun.position.set(1.5, -2, 6);
    sun.castShadow = true;
    sun.shadow.mapSize.set(1024, 1024);
    Object.assign(sun.shadow.camera, { left: -4, right: 4, top: 4, bottom: -4 });
    this.sun = sun;
    this.scene.add(sun, sun.target);

    this.meshes = header.kinds.map((kind, g) => {
      if (kind === "plane") return null;
      const [r, gr, b, a] = header.colours[g];
      const material = new THREE.MeshStandardMaterial({
        color: new THREE.Color().setRGB(r, gr, b, THREE.SRGBColorSpace),
        roughness: 0.6,
        transparent: a < 1,
        opacity: a,
      });
      const mesh = new THREE.Mesh(geometryOf(kind, header.sizes[g]), material);
      mesh.castShadow = mesh.receiveShadow = true;
      this.scene.add(mesh);
      return mesh;
    });
    if (header.kinds.includes("plane")) this.scene.add(floor());
    this.moving = this.#movingShapes();
    this.#pose(0);

    this.camera = new THREE.PerspectiveCamera(40, 1, 0.05, 100);
    this.camera.up.set(0, 0, 1);
    // frame the figure and the task's marks at the start, seen from the front left, above
    const box = new THREE.Box3();
    for (const mesh of this.meshes) if (mesh) box.expandByObject(mesh);
    const centre = box.getCenter(new THREE.Vector3());
    const reach = Math.max(0.5, box.getSize(new THREE.Vector3()).length());
    const distance = (0.75 * reach) / Math.tan((this.camera.fov * Math.PI) / 360);
    this.camera.position.copy(centre).add(new THREE.Vector3(-0.45, -0.8, 0.4).normalize().multiplyScalar(distance));
    this.controls = new OrbitControls(this.camera, canvas);
    this.controls.target.copy(centre);
    this.controls.update();
    this.following = true;
    this.controls.addEventListener("start", () => (this.following = false));
    this.controls.addEventListener("change", () => this.render());
    this.resize();
    this.setFrame(0);
  }

  /** Seconds the replay lasts. */
  get duration() {
    return this.frames / this.fps;
  }

  /** Shapes that move at some frame (the figure, not the floor's marks). */
  #movingShapes() {
    const stride = this.count * 3;
    const last = (this.frames - 1) * stride;
    const moving = [];
    for (let g = 0; g < this.count; g++) {
      if (!this.meshes[g]) continue;
      for (let t = 0; t <= last; t += stride) {
        const i = t + 3 * g;
        if (this.positions[i] !== this.positions[3 * g] || this.positions[i + 2] !== this.positions[3 * g + 2]) {
          moving.push(g);
          break;
        }
      }
    }
    return moving.length ? moving : this.meshes.flatMap((mesh, g) => (mesh ? [g] : []));
  }

  /** The mean centre of the moving shapes at frame ``t``, m. */
  centreAt(t) {
    const centre = new THREE.Vector3();
    for (const g of this.moving) {
      const i = (t * this.count + g) * 3;
      centre.x += this.positions[i];
      centre.y += this.positions[i + 1];
      centre.z += this.positions[i + 2];
    }
    return centre.multiplyScalar(this.scale / this.moving.length);
  }

  /** Show frame ``t`` (clamped to the replay); the camera follows unless the user moved it. */
  setFrame(t) {
    t = Math.max(0, Math.min(this.frames - 1, Math.floor(t)));
    if (this.following) {
      const shift = this.centreAt(t).sub(this.centreAt(this.frame));
      this.camera.position.add(shift);
      this.controls.target.add(shift);
      this.controls.update();
    }
    this.frame = t;
    this.#pose(t);
    this.sun.target.position.copy(this.controls.target);
    this.sun.position.copy(this.controls.target).add(new THREE.Vector3(1.5, -2, 6));
    this.render();
  }

  /** Place every mesh as at frame ``t``. */
  #pose(t) {
    for (let g = 0; g < this.count; g++) {
      const mesh = this.meshes[g];
      if (!mesh) continue;
      const p = (t * this.count + g) * 3;
      const q = (t * this.count + g) * 4;
      mesh.position.set(this.positions[p], this.positions[p + 1], this.positions[p + 2]).multiplyScalar(this.scale);
      const u = this.unit;
      mesh.quaternion.set(this.quaternions[q + 1] * u, this.quaternions[q + 2] * u, this.quaternions[q + 3] * u, this.quaternions[q] * u).normalize();
    }
  }

  /** Show the frame playing at ``seconds`` (the audio or page clock). */
  setTime(seconds) {
    this.setFrame(seconds * this.fps);
  }

  /** Match the drawing buffer to the canvas's size on the page. */
  resize() {
    const width = Math.max(1, this.canvas.clientWidth);
    const height = Math.max(1, this.canvas.clientHeight);
    this.renderer.setSize(width, height, false);
    this.camera.aspect = width / height;
    this.camera.updateProjectionMatrix();
    this.render();
  }

  render() {
    this.renderer.render(this.scene, this.camera);
  }

  /** Free the GPU resources (the canvas can take another view). */
  dispose() {
    this.controls.dispose();
    this.scene.traverse((node) => {
      node.geometry?.dispose();
      node.material?.dispose();
    });
    this.renderer.dispose();
  }
}
