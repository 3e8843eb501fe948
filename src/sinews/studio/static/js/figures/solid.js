// Drawing 3D figures (luxo3d, humanoid3d) from a generation pack (sinews/studio/figure_motion.py
// with header.drawer "solid"): the shapes MuJoCo simulated (sinews/figures/geoms.py), posed
// per frame, lit and shadowed by three.js (vendored, see ../vendor/three/README.md), z up.
//
// The same two calls as planar.js: `view(i, w, h, top)` and `draw(ctx, i, frame, view)`. One
// WebGL renderer serves every cell (a page may hold only so many WebGL contexts): each draw
// poses individual i, renders at the view's size and copies the picture onto the cell's 2D
// canvas. `attach(canvas, view)` lets the user orbit a view's camera (the stage) with the mouse.
import * as THREE from "three";
import { OrbitControls } from "three/addons/controls/OrbitControls.js";

const FLOOR_SIZE = 40;

/** Geometry of one shape in its own frame (MuJoCo's sizes: half-extents, radius, half-length). */
function geometryOf(kind, [a, b, c]) {
  switch (kind) {
    case "sphere": return new THREE.SphereGeometry(a, 24, 16);
    case "ellipsoid": return new THREE.SphereGeometry(1, 24, 16).scale(a, b, c);
    case "capsule": return new THREE.CapsuleGeometry(a, 2 * b, 8, 16).rotateX(Math.PI / 2);
    case "cylinder": return new THREE.CylinderGeometry(a, a, 2 * b, 24).rotateX(Math.PI / 2);
    case "box": return new THREE.BoxGeometry(2 * a, 2 * b, 2 * c);
    default: throw new Error(`cannot draw a ${kind}`);
  }
}

function floor() {
  const plane = new THREE.Mesh(
    new THREE.PlaneGeometry(FLOOR_SIZE, FLOOR_SIZE),
    new THREE.MeshStandardMaterial({ color: 0xe4e4de, roughness: 0.95, polygonOffset: true,
                                     polygonOffsetFactor: 1, polygonOffsetUnits: 1 }),
  );
  plane.receiveShadow = true;
  const grid = new THREE.GridHelper(FLOOR_SIZE, FLOOR_SIZE * 4, 0x8c8c84, 0xb0b0a8);
  grid.rotateX(Math.PI / 2); // three's grid lies in x-z; the floor is x-y
  grid.position.z = 0.001;
  return new THREE.Group().add(plane, grid);
}

export function solidDrawer({ header, arrays }) {
  const [P, T, G] = arrays.positions.shape;
  const s = header.scale, u = 1 / header.quaternion_scale;
  const positions = arrays.positions.data, quaternions = arrays.quaternions.data;
  const scene = new THREE.Scene();
  scene.background = new THREE.Color(0xf5f3ee);
  const sky = new THREE.HemisphereLight(0xffffff, 0x8a8a80, 1.6);
  sky.position.set(0, 0, 1); // z is up
  const sun = new THREE.DirectionalLight(0xffffff, 1.8);
  sun.castShadow = true;
  sun.shadow.mapSize.set(1024, 1024);
  Object.assign(sun.shadow.camera, { left: -3, right: 3, top: 3, bottom: -3 });
  scene.add(sky, sun, sun.target);
  const meshes = header.kinds.map((kind, g) => {
    if (kind === "plane") return null;
    const [r, gr, b, a] = header.colours[g];
    const mesh = new THREE.Mesh(geometryOf(kind, header.sizes[g]), new THREE.MeshStandardMaterial({
      color: new THREE.Color().setRGB(r, gr, b, THREE.SRGBColorSpace),
      roughness: 0.6, transparent: a < 1, opacity: a,
    }));
    mesh.castShadow = mesh.receiveShadow = true;
    scene.add(mesh);
    return mesh;
  });
  if (header.kinds.includes("plane")) scene.add(floor());
  let renderer = null;

  function pose(i, t) {
    for (let g = 0; g < G; g++) {
      const mesh = meshes[g];
      if (!mesh) continue;
      const p = ((i * T + t) * G + g) * 3, q = ((i * T + t) * G + g) * 4;
      mesh.position.set(positions[p] * s, positions[p + 1] * s, positions[p + 2] * s);
      mesh.quaternion.set(quaternions[q + 1] * u, quaternions[q + 2] * u, quaternions[q + 3] * u,
                          quaternions[q] * u).normalize();
    }
  }

  /** A box around individual i over its whole replay and the task's marks, metres. */
  function bounds(i) {
    const box = new THREE.Box3();
    for (let t = 0; t < T; t += Math.max(1, Math.floor(T / 12))) {
      pose(i, t);
      for (const mesh of meshes) if (mesh) box.expandByObject(mesh);
    }
    return box;
  }

  return {
    kind: "solid",
    individuals: P,
    frames: T,
    fps: header.fps,
    /** A camera for individual i seeing all of its replay from the front left, above. */
    view(i, width, height, top = 0) {
      const box = bounds(i);
      const centre = box.getCenter(new THREE.Vector3());
      const camera = new THREE.PerspectiveCamera(35, width / Math.max(1, height - top), 0.05, 100);
      camera.up.set(0, 0, 1);
      const reach = Math.max(0.4, box.getSize(new THREE.Vector3()).length());
      const distance = (0.6 * reach) / Math.tan((camera.fov * Math.PI) / 360);
      camera.position.copy(centre).add(new THREE.Vector3(-0.35, -0.85, 0.4).normalize().multiplyScalar(distance));
      camera.lookAt(centre);
      return { width, height, top, camera, target: centre, controls: null };
    },
    /** Let the mouse orbit ``v``'s camera on ``canvas`` (drag, wheel, right-drag). */
    attach(canvas, v) {
      v.controls = new OrbitControls(v.camera, canvas);
      v.controls.target.copy(v.target);
      v.controls.update();
      return () => v.controls.dispose();
    },
    /** Draw frame t of individual i onto the 2D context ``ctx`` below ``v.top`` pixels. */
    draw(ctx, i, t, v) {
      renderer ??= new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
      renderer.shadowMap.enabled = true;
      const height = v.height - v.top;
      renderer.setSize(v.width, height, false);
      pose(i, t);
      const target = v.controls ? v.controls.target : v.target;
      sun.target.position.copy(target);
      sun.position.copy(target).add(new THREE.Vector3(1.5, -2, 6));
      renderer.render(scene, v.camera);
      ctx.drawImage(renderer.domElement, 0, v.top, v.width, height);
    },
  };
}
