/**
 * fromThree in whole renders: a three.js scene (Lambert boxes under a transformed group,
 * a RectAreaLight, point, spot and directional lights, a zoomed camera) renders like the
 * same scene written by hand in pathwise-scene/1, where every position, axis, cone and
 * unit was worked out on paper from three's documented conventions; an InstancedMesh
 * like the same boxes as separate meshes. Block tests as in tests/scenes/gltf-features
 * (independent samples, 4×4 blocks, χ² at p = 0.001, no |z| over 5; the two false-alarm
 * rates add to 0.2 % per comparison).
 */
import * as THREE from 'three';
import { describe, expect, it } from 'vitest';
import { fromThree } from '../../src/three/index.ts';
import { sceneWithFiles } from '../helpers/gltf.ts';
import { expectSameImage, renderSampled } from '../helpers/render.ts';

const SIZE = 32;
const SPP = 64;

function render(scene: Awaited<ReturnType<typeof sceneWithFiles>>, seed: number) {
  return renderSampled(scene, {
    spp: SPP,
    seed,
    sampler: 'independent',
    width: SIZE,
    height: SIZE,
    maxBounces: 3,
  });
}

function expectSame(a: ReturnType<typeof render>, b: ReturnType<typeof render>): void {
  expectSameImage(a, b);
}

/** The three.js scene. */
function threeScene(): { scene: THREE.Scene; camera: THREE.PerspectiveCamera } {
  const scene = new THREE.Scene();
  const grey = new THREE.MeshLambertMaterial({ color: new THREE.Color(0.7, 0.7, 0.7) });
  const red = new THREE.MeshLambertMaterial({ color: new THREE.Color(0.8, 0.2, 0.1) });
  // Floor: a 4×4 plane turned from facing +z to facing +y.
  const floor = new THREE.Mesh(new THREE.PlaneGeometry(4, 4), grey);
  floor.rotation.x = -Math.PI / 2;
  scene.add(floor);
  // A box under a group that moves it up by 0.5 and scales x by 2: world x ∈ [−0.5, 0.5]
  // (box width 0.5 × 2), y ∈ [0.25, 0.75], z ∈ [−0.25, 0.25].
  const group = new THREE.Group();
  group.position.set(0, 0.5, 0);
  group.scale.set(2, 1, 1);
  group.add(new THREE.Mesh(new THREE.BoxGeometry(0.5, 0.5, 0.5), red));
  scene.add(group);
  // A 1 × 0.5 area light at y = 2 turned to face down (local −z to −y; local x stays x,
  // local y goes to −z): x ∈ [−0.5, 0.5], z ∈ [−0.25, 0.25].
  const area = new THREE.RectAreaLight(new THREE.Color(1, 0.9, 0.8), 6, 1, 0.5);
  area.position.set(0, 2, 0);
  area.rotation.x = -Math.PI / 2;
  scene.add(area);
  const point = new THREE.PointLight(new THREE.Color(0.2, 0.4, 1), 3);
  point.position.set(1.5, 1, 1);
  scene.add(point);
  const spot = new THREE.SpotLight(new THREE.Color(1, 1, 1), 8, 0, Math.PI / 6, 0.5, 2);
  spot.position.set(-1.5, 2, 0);
  spot.target.position.set(-1, 0, 0);
  scene.add(spot, spot.target);
  const sun = new THREE.DirectionalLight(new THREE.Color(1, 0.5, 0.5), 0.5);
  sun.position.set(1, 3, 2);
  scene.add(sun);
  const camera = new THREE.PerspectiveCamera(50, 1, 0.1, 100);
  camera.zoom = 1.25;
  camera.position.set(0, 2.5, 3.5);
  camera.lookAt(0, 0.3, 0);
  return { scene, camera };
}

/** The same scene, by hand. */
function handScene() {
  const quad = (corner: number[], u: number[], v: number[], material: string) => ({
    type: 'quad',
    corner,
    u,
    v,
    material,
  });
  // Box faces: x ∈ [−0.5, 0.5], y ∈ [0.25, 0.75], z ∈ [−0.25, 0.25].
  const box = [
    quad([-0.5, 0.25, -0.25], [1, 0, 0], [0, 0.5, 0], 'red'),
    quad([-0.5, 0.25, 0.25], [1, 0, 0], [0, 0.5, 0], 'red'),
    quad([-0.5, 0.25, -0.25], [0, 0, 0.5], [0, 0.5, 0], 'red'),
    quad([0.5, 0.25, -0.25], [0, 0, 0.5], [0, 0.5, 0], 'red'),
    quad([-0.5, 0.25, -0.25], [1, 0, 0], [0, 0, 0.5], 'red'),
    quad([-0.5, 0.75, -0.25], [1, 0, 0], [0, 0, 0.5], 'red'),
  ];
  const spotAngle = 30; // π/6
  return {
    format: 'pathwise-scene/1',
    camera: {
      position: [0, 2.5, 3.5],
      target: [0, 0.3, 0],
      up: [0, 1, 0],
      fovY: (2 * Math.atan(Math.tan((25 * Math.PI) / 180) / 1.25) * 180) / Math.PI,
    },
    materials: {
      grey: { type: 'diffuse', albedo: [0.7, 0.7, 0.7] },
      red: { type: 'diffuse', albedo: [0.8, 0.2, 0.1] },
      lamp: { type: 'diffuse', albedo: [0, 0, 0], emission: [6, 5.4, 4.8] },
    },
    shapes: [
      quad([-2, 0, -2], [4, 0, 0], [0, 0, 4], 'grey'),
      ...box,
      // Facing down: cross(u, v) = (1,0,0) × (0,0,0.5) = (0, −0.5, 0).
      quad([-0.5, 2, -0.25], [1, 0, 0], [0, 0, 0.5], 'lamp'),
    ],
    lights: [
      { type: 'point', position: [1.5, 1, 1], intensity: 3, color: [0.2, 0.4, 1] },
      {
        type: 'spot',
        position: [-1.5, 2, 0],
        direction: [0.5, -2, 0],
        intensity: 8,
        color: [1, 1, 1],
        innerConeAngle: spotAngle * 0.5,
        outerConeAngle: spotAngle,
      },
      { type: 'directional', direction: [-1, -3, -2], intensity: 0.5, color: [1, 0.5, 0.5] },
    ],
  };
}

describe('fromThree renders what three.js describes', () => {
  it('matches the scene written by hand: transforms, zoom, area, point, spot and sun lights', async () => {
    const { scene, camera } = threeScene();
    const converted = await fromThree(scene, camera);
    expect(converted.warnings).toEqual([]);
    const a = await sceneWithFiles(converted.scene, converted.files);
    const b = await sceneWithFiles(handScene(), new Map());
    expectSame(render(a, 1), render(b, 2));
  });

  it('renders an InstancedMesh as the same boxes drawn one by one', async () => {
    const make = (instanced: boolean) => {
      const scene = new THREE.Scene();
      const geometry = new THREE.BoxGeometry(0.4, 0.4, 0.4);
      const material = new THREE.MeshStandardMaterial({ color: 0x88aa44, roughness: 0.6 });
      const floor = new THREE.Mesh(new THREE.PlaneGeometry(4, 4), material);
      floor.rotation.x = -Math.PI / 2;
      scene.add(floor);
      const matrices = [0, 1, 2, 3].map((i) =>
        new THREE.Matrix4().compose(
          new THREE.Vector3(i - 1.5, 0.2 + 0.1 * i, 0),
          new THREE.Quaternion().setFromEuler(new THREE.Euler(0.3 * i, 0.5, 0)),
          new THREE.Vector3(1, 1 + 0.2 * i, 1),
        ),
      );
      if (instanced) {
        const mesh = new THREE.InstancedMesh(geometry, material, 4);
        matrices.forEach((m, i) => mesh.setMatrixAt(i, m));
        scene.add(mesh);
      } else {
        for (const m of matrices) {
          const mesh = new THREE.Mesh(geometry, material);
          mesh.applyMatrix4(m);
          scene.add(mesh);
        }
      }
      const light = new THREE.PointLight(0xffffff, 6);
      light.position.set(0, 2, 1);
      scene.add(light);
      const camera = new THREE.PerspectiveCamera(45, 1, 0.1, 50);
      camera.position.set(0, 2, 4);
      camera.lookAt(0, 0, 0);
      return { scene, camera };
    };
    const one = make(true);
    const many = make(false);
    const a = await fromThree(one.scene, one.camera);
    const b = await fromThree(many.scene, many.camera);
    expect(a.warnings).toEqual([]);
    const ra = render(await sceneWithFiles(a.scene, a.files), 3);
    const rb = render(await sceneWithFiles(b.scene, b.files), 3);
    // Same seed, same geometry in the same world places: equal up to the instance
    // transform's rounding.
    let worst = 0;
    for (let i = 0; i < ra.mean.length; i++) {
      worst = Math.max(
        worst,
        Math.abs(ra.mean[i] - rb.mean[i]) / Math.max(1e-3, Math.abs(rb.mean[i])),
      );
    }
    expect(worst).toBeLessThan(1e-4);
  });
});
