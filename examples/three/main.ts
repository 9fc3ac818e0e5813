/**
 * The example app: an ordinary three.js scene with OrbitControls. "Path-trace" puts a
 * <pathwise-view> over three's canvas, gives it the scene and the camera, and stops
 * three's render loop; the controls keep driving the same camera, which the view follows.
 * A page outside this repository imports 'pathwise' and 'three' by name instead.
 */
import * as THREE from 'three';
import { OrbitControls } from 'three/examples/jsm/controls/OrbitControls.js';
import { RectAreaLightUniformsLib } from 'three/examples/jsm/lights/RectAreaLightUniformsLib.js';
import '../../src/widget/register.ts';
import type { PathwiseViewElement } from '../../src/widget/index.ts';

const stage = document.getElementById('stage')!;
const button = document.getElementById('renderer') as HTMLButtonElement;
const status = document.getElementById('status')!;

const renderer = new THREE.WebGLRenderer({ antialias: true });
renderer.setPixelRatio(Math.min(2, devicePixelRatio));
renderer.toneMapping = THREE.ACESFilmicToneMapping;
stage.append(renderer.domElement);
RectAreaLightUniformsLib.init();

const scene = new THREE.Scene();
const camera = new THREE.PerspectiveCamera(40, 4 / 3, 0.1, 100);
camera.position.set(2.5, 2, 4.5);

// A sky: an equirectangular float texture, bright above the horizon, dark below.
const W = 64;
const H = 32;
const sky = new Float32Array(W * H * 4);
for (let y = 0; y < H; y++) {
  const up = Math.cos(((y + 0.5) / H) * Math.PI); // row 0 is the top (flipY below)
  for (let x = 0; x < W; x++) {
    const t = Math.max(0, up);
    sky.set([0.25 + 0.6 * t, 0.3 + 0.7 * t, 0.4 + 0.9 * t, 1], (y * W + x) * 4);
    if (up < 0) sky.set([0.08, 0.07, 0.06, 1], (y * W + x) * 4);
  }
}
const environment = new THREE.DataTexture(sky, W, H, THREE.RGBAFormat, THREE.FloatType);
environment.mapping = THREE.EquirectangularReflectionMapping;
environment.flipY = true;
environment.needsUpdate = true;
scene.environment = environment;
scene.background = environment;

const floor = new THREE.Mesh(
  new THREE.PlaneGeometry(8, 8),
  new THREE.MeshStandardMaterial({ color: 0x9a9a9a, roughness: 0.9 }),
);
floor.rotation.x = -Math.PI / 2;
scene.add(floor);

const coated = new THREE.Mesh(
  new THREE.SphereGeometry(0.6, 48, 24),
  new THREE.MeshPhysicalMaterial({
    color: 0xb01818,
    roughness: 0.5,
    clearcoat: 1,
    clearcoatRoughness: 0.05,
  }),
);
coated.position.set(-1, 0.6, 0);
scene.add(coated);

const glass = new THREE.Mesh(
  new THREE.SphereGeometry(0.5, 48, 24),
  new THREE.MeshPhysicalMaterial({
    color: 0xffffff,
    roughness: 0,
    transmission: 1,
    ior: 1.5,
    thickness: 1,
  }),
);
glass.position.set(0.4, 0.5, 0.8);
scene.add(glass);

const metal = new THREE.Mesh(
  new THREE.TorusKnotGeometry(0.35, 0.12, 128, 16),
  new THREE.MeshStandardMaterial({ color: 0xd4af37, metalness: 1, roughness: 0.25 }),
);
metal.position.set(1.1, 0.6, -0.8);
scene.add(metal);

const lamp = new THREE.RectAreaLight(0xfff4e0, 12, 1.5, 1);
lamp.position.set(0, 3, 0);
lamp.lookAt(0, 0, 0);
scene.add(lamp);

const controls = new OrbitControls(camera, stage);
controls.target.set(0, 0.4, 0);
controls.update();

function resize(): void {
  const { width, height } = stage.getBoundingClientRect();
  renderer.setSize(width, height, false);
  camera.aspect = width / height;
  camera.updateProjectionMatrix();
}
resize();
new ResizeObserver(resize).observe(stage);

let view: PathwiseViewElement | null = null;

function useThree(): void {
  view?.remove();
  view = null;
  renderer.domElement.hidden = false;
  renderer.setAnimationLoop(() => renderer.render(scene, camera));
  button.textContent = 'Path-trace with pathwise';
  status.textContent = 'three.js WebGLRenderer';
}

function usePathwise(): void {
  renderer.setAnimationLoop(null);
  renderer.domElement.hidden = true;
  view = document.createElement('pathwise-view');
  view.threeScene = scene;
  view.threeCamera = camera;
  view.addEventListener('progress', (e) => {
    const p = (e as CustomEvent<{ spp: number }>).detail;
    status.textContent = `pathwise: ${p.spp} samples per pixel`;
  });
  view.addEventListener('warning', (e) => {
    console.warn((e as CustomEvent<{ messages: string[] }>).detail.messages.join('\n'));
  });
  stage.append(view);
  button.textContent = 'Rasterise with three.js';
}

button.addEventListener('click', () => (view ? useThree() : usePathwise()));
useThree();

// For tests (tests/browser/three-example.test.ts).
Object.assign(window, { example: { scene, camera, controls, view: () => view } });
