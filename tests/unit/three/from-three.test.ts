/**
 * fromThree's mapping, property by property: MeshPhysicalMaterial's layers onto the
 * glTF extensions (the inverse of GLTFLoader's mapping), textures (orientation, colour
 * encoding, transform, sampler), the environment's orientation against three's
 * equirectUv, the camera's depth of field, and one warning for each thing it cannot map.
 */
import * as THREE from 'three';
import { describe, expect, it } from 'vitest';
import { decode as decodePng } from 'fast-png';
import { decodePfm } from '../../../src/core/io/pfm.ts';
import { fromThree } from '../../../src/three/index.ts';
import { io } from '../../helpers/gltf.ts';

function camera(): THREE.PerspectiveCamera {
  const c = new THREE.PerspectiveCamera(40, 1, 0.1, 10);
  c.position.set(0, 0, 3);
  return c;
}

async function gltfJson(scene: THREE.Object3D) {
  const r = await fromThree(scene, camera());
  const { json, resources } = await io().binaryToJSON(r.files.get('three.glb')!);
  return { json: json as any, resources, warnings: r.warnings, result: r };
}

function box(material: THREE.Material): THREE.Scene {
  const s = new THREE.Scene();
  s.add(new THREE.Mesh(new THREE.BoxGeometry(), material));
  return s;
}

/** A 2×2 RGBA8 DataTexture: red, green / blue, white (row 0 first). */
function checker(): THREE.DataTexture {
  const t = new THREE.DataTexture(
    new Uint8Array([255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 255, 255, 255, 255]),
    2,
    2,
  );
  t.needsUpdate = true;
  return t;
}

describe('fromThree materials', () => {
  it('maps MeshPhysicalMaterial onto the glTF extensions as GLTFLoader reads them back', async () => {
    const m = new THREE.MeshPhysicalMaterial({
      color: new THREE.Color(0.5, 0.25, 0.125),
      metalness: 0.3,
      roughness: 0.4,
      opacity: 0.5,
      transparent: true,
      emissive: new THREE.Color(2, 1, 0),
      emissiveIntensity: 3,
      ior: 1.7,
      specularIntensity: 0.6,
      specularColor: new THREE.Color(1, 0.5, 1),
      clearcoat: 0.8,
      clearcoatRoughness: 0.2,
      sheen: 0.5,
      sheenColor: new THREE.Color(1, 0.5, 0),
      sheenRoughness: 0.7,
      transmission: 0.9,
      thickness: 0.1,
      attenuationDistance: 2,
      attenuationColor: new THREE.Color(0.9, 0.8, 0.7),
      iridescence: 1,
      iridescenceIOR: 1.4,
      iridescenceThicknessRange: [200, 500],
      anisotropy: 0.6,
      anisotropyRotation: 0.5,
      dispersion: 0.2,
      side: THREE.DoubleSide,
    });
    const { json, warnings } = await gltfJson(box(m));
    expect(warnings).toEqual([]);
    const g = json.materials[0];
    expect(g.pbrMetallicRoughness.baseColorFactor).toEqual([0.5, 0.25, 0.125, 0.5]);
    expect(g.pbrMetallicRoughness.metallicFactor).toBeCloseTo(0.3, 6);
    expect(g.pbrMetallicRoughness.roughnessFactor).toBeCloseTo(0.4, 6);
    expect(g.alphaMode).toBe('BLEND');
    expect(g.doubleSided).toBe(true);
    // emissive (2, 1, 0) × 3: factor at most 1, the rest in the strength.
    expect(g.emissiveFactor).toEqual([1, 0.5, 0]);
    const x = g.extensions;
    expect(x.KHR_materials_emissive_strength.emissiveStrength).toBe(6);
    expect(x.KHR_materials_ior.ior).toBeCloseTo(1.7, 6);
    expect(x.KHR_materials_specular.specularFactor).toBeCloseTo(0.6, 6);
    expect(x.KHR_materials_specular.specularColorFactor).toEqual([1, 0.5, 1]);
    expect(x.KHR_materials_clearcoat).toMatchObject({
      clearcoatFactor: 0.8,
      clearcoatRoughnessFactor: 0.2,
    });
    // three's sheen weight multiplies sheenColor (GLTFLoader sets sheen = 1).
    expect(x.KHR_materials_sheen.sheenColorFactor).toEqual([0.5, 0.25, 0]);
    expect(x.KHR_materials_sheen.sheenRoughnessFactor).toBeCloseTo(0.7, 6);
    expect(x.KHR_materials_transmission.transmissionFactor).toBeCloseTo(0.9, 6);
    expect(x.KHR_materials_volume.thicknessFactor).toBeCloseTo(0.1, 6);
    expect(x.KHR_materials_volume.attenuationDistance).toBe(2);
    expect(x.KHR_materials_volume.attenuationColor[0]).toBeCloseTo(0.9, 6);
    expect(x.KHR_materials_iridescence).toMatchObject({
      iridescenceFactor: 1,
      iridescenceThicknessMinimum: 200,
      iridescenceThicknessMaximum: 500,
    });
    expect(x.KHR_materials_iridescence.iridescenceIor).toBeCloseTo(1.4, 6);
    expect(x.KHR_materials_anisotropy.anisotropyStrength).toBeCloseTo(0.6, 6);
    expect(x.KHR_materials_anisotropy.anisotropyRotation).toBeCloseTo(0.5, 6);
    expect(x.KHR_materials_dispersion.dispersion).toBeCloseTo(0.2, 6);
  });

  it('maps MeshBasicMaterial to unlit and MeshLambertMaterial to a base without specular', async () => {
    const basic = await gltfJson(box(new THREE.MeshBasicMaterial({ color: 0xffffff })));
    expect(basic.json.materials[0].extensions).toHaveProperty('KHR_materials_unlit');
    const lambert = await gltfJson(box(new THREE.MeshLambertMaterial({ color: 0xffffff })));
    expect(lambert.json.materials[0].extensions.KHR_materials_specular.specularFactor).toBe(0);
    expect(lambert.json.materials[0].pbrMetallicRoughness.metallicFactor).toBe(0);
  });

  it('writes textures in glTF row order and slot encoding, with transform and sampler', async () => {
    const map = checker();
    map.colorSpace = THREE.SRGBColorSpace;
    map.flipY = true; // three draws row 0 at v = 1: glTF's row 0 is three's last
    map.wrapS = THREE.ClampToEdgeWrapping;
    map.wrapT = THREE.MirroredRepeatWrapping;
    map.magFilter = THREE.NearestFilter;
    map.offset.set(0.25, 0.5);
    map.repeat.set(2, 2);
    map.rotation = 0.3;
    map.channel = 1;
    const rough = checker(); // linear data, read as it is
    const m = new THREE.MeshStandardMaterial({ map, roughnessMap: rough, metalnessMap: rough });
    const { json, resources } = await gltfJson(box(m));
    const info = json.materials[0].pbrMetallicRoughness.baseColorTexture;
    expect(info.texCoord).toBe(1);
    expect(info.extensions.KHR_texture_transform).toMatchObject({
      offset: [0.25, 0.5],
      scale: [2, 2],
    });
    expect(info.extensions.KHR_texture_transform.rotation).toBeCloseTo(0.3, 6);
    const sampler = json.samplers[json.textures[info.index].sampler];
    expect(sampler).toMatchObject({ wrapS: 33071, wrapT: 33648, magFilter: 9728 });
    const image = (i: number) => {
      const uri = json.images[json.textures[i].source];
      const view = json.bufferViews[uri.bufferView];
      const bin = Object.values(resources)[0] as Uint8Array;
      return decodePng(
        bin.subarray(view.byteOffset ?? 0, (view.byteOffset ?? 0) + view.byteLength),
      );
    };
    // flipY: the blue/white row comes first.
    expect(Array.from(image(info.index).data.slice(0, 8))).toEqual([
      0, 0, 255, 255, 255, 255, 255, 255,
    ]);
    const mr = json.materials[0].pbrMetallicRoughness.metallicRoughnessTexture;
    expect(Array.from(image(mr.index).data.slice(0, 8))).toEqual([255, 0, 0, 255, 0, 255, 0, 255]);
  });

  it('re-encodes a linear colour texture as sRGB and an sRGB data texture as linear', async () => {
    const grey = new THREE.DataTexture(new Uint8Array([128, 128, 128, 255]), 1, 1);
    grey.needsUpdate = true; // NoColorSpace: three reads 128/255 as linear
    const srgb = new THREE.DataTexture(new Uint8Array([128, 128, 128, 255]), 1, 1);
    srgb.colorSpace = THREE.SRGBColorSpace; // three decodes it: linear 0.2158
    const { json, resources } = await gltfJson(
      box(new THREE.MeshStandardMaterial({ map: grey, roughnessMap: srgb, metalnessMap: srgb })),
    );
    const bin = Object.values(resources)[0] as Uint8Array;
    const pixel = (texture: number) => {
      const view = json.bufferViews[json.images[json.textures[texture].source].bufferView];
      return decodePng(bin.subarray(view.byteOffset ?? 0, (view.byteOffset ?? 0) + view.byteLength))
        .data[0];
    };
    const base = json.materials[0].pbrMetallicRoughness;
    expect(pixel(base.baseColorTexture.index)).toBe(
      Math.round(255 * (1.055 * Math.pow(128 / 255, 1 / 2.4) - 0.055)),
    );
    expect(pixel(base.metallicRoughnessTexture.index)).toBe(
      Math.round(255 * Math.pow((128 / 255 + 0.055) / 1.055, 2.4)),
    );
  });
});

describe('fromThree geometry', () => {
  it('makes one primitive per group with its material, for indexed, non-indexed and interleaved geometry', async () => {
    const materials = [0xff0000, 0x00ff00, 0x0000ff, 0xffff00, 0xff00ff, 0x00ffff].map(
      (c) => new THREE.MeshStandardMaterial({ color: c }),
    );
    const indexed = new THREE.BoxGeometry(1, 1, 1);
    const flat = indexed.toNonIndexed();
    // Interleaved positions and normals, as some loaders make them.
    const interleaved = new THREE.BufferGeometry();
    const buffer = new THREE.InterleavedBuffer(
      new Float32Array([0, 0, 0, 0, 0, 1, 1, 0, 0, 0, 0, 1, 0, 1, 0, 0, 0, 1]),
      6,
    );
    interleaved.setAttribute('position', new THREE.InterleavedBufferAttribute(buffer, 3, 0));
    interleaved.setAttribute('normal', new THREE.InterleavedBufferAttribute(buffer, 3, 3));
    const scene = new THREE.Scene();
    scene.add(new THREE.Mesh(indexed, materials), new THREE.Mesh(flat, materials));
    scene.add(new THREE.Mesh(interleaved, new THREE.MeshStandardMaterial()));
    const { json, warnings } = await gltfJson(scene);
    expect(warnings).toEqual([]);
    const [a, b, c] = json.meshes;
    for (const mesh of [a, b]) {
      expect(mesh.primitives.length).toBe(6);
      const colours = mesh.primitives.map((p: any) =>
        json.materials[p.material].pbrMetallicRoughness.baseColorFactor.slice(0, 3),
      );
      expect(colours).toEqual(materials.map((m) => [m.color.r, m.color.g, m.color.b]));
      for (const p of mesh.primitives) expect(json.accessors[p.indices].count).toBe(6);
    }
    const positions = json.accessors[c.primitives[0].attributes.POSITION];
    expect(positions).toMatchObject({ count: 3, max: [1, 1, 0], min: [0, 0, 0] });
  });
});

describe('fromThree environment and camera', () => {
  it.each(['float', 'half'])(
    'orients an equirectangular %s map as three looks it up (equirectUv)',
    async (kind) => {
      // 8×4 texels, each holding its own index; flipY as HDRLoader sets it; half floats as
      // HDRLoader makes them by default.
      const W = 8;
      const H = 4;
      const data = new Float32Array(W * H * 4);
      for (let i = 0; i < W * H; i++) data.set([i, 0, 0, 1], i * 4);
      const env =
        kind === 'float'
          ? new THREE.DataTexture(data, W, H, THREE.RGBAFormat, THREE.FloatType)
          : new THREE.DataTexture(
              Uint16Array.from(data, (v) => THREE.DataUtils.toHalfFloat(v)),
              W,
              H,
              THREE.RGBAFormat,
              THREE.HalfFloatType,
            );
      env.mapping = THREE.EquirectangularReflectionMapping;
      env.flipY = true;
      const scene = new THREE.Scene();
      scene.environment = env;
      scene.environmentRotation.y = 0.4;
      const r = await fromThree(scene, camera());
      expect(r.warnings).toEqual([]);
      const e = r.scene.environment!;
      const pfm = decodePfm(r.files.get(e.file)!);
      for (const d of [
        [1, 0.2, 0.1],
        [-0.3, 0.5, -1],
        [0.1, -0.8, 0.6],
        [-1, -0.1, 0.2],
        [0.4, 0.9, -0.3],
      ]) {
        const n = Math.hypot(d[0], d[1], d[2]);
        const [x, y, z] = d.map((v) => v / n);
        // three: the lookup direction is turned by the negated Euler angles
        // (WebGLBackground / envMapRotation), then equirectUv; with flipY the data's row 0
        // is at v = 1 (the top).
        const a = -0.4;
        const rx = Math.cos(a) * x + Math.sin(a) * z;
        const rz = -Math.sin(a) * x + Math.cos(a) * z;
        const u = Math.atan2(rz, rx) / (2 * Math.PI) + 0.5;
        const v = Math.asin(y) / Math.PI + 0.5;
        const expected =
          Math.min(H - 1, Math.floor((1 - v) * H)) * W + Math.min(W - 1, Math.floor(u * W));
        // pathwise: docs/scene-format.md, Environment maps.
        const t = (e.rotationY * Math.PI) / 180;
        const px = Math.cos(t) * x - Math.sin(t) * z;
        const pz = Math.sin(t) * x + Math.cos(t) * z;
        let pu = Math.atan2(px, -pz) / (2 * Math.PI);
        pu -= Math.floor(pu);
        const pv = Math.acos(y) / Math.PI;
        const texel = Math.min(H - 1, Math.floor(pv * H)) * W + Math.min(W - 1, Math.floor(pu * W));
        expect(pfm.rgb[texel * 3]).toBe(expected);
      }
    },
  );

  it('takes depth of field from a PhysicalCamera-like fStop, bokehSize and focusDistance', async () => {
    const c = Object.assign(camera(), { fStop: 2, bokehSize: 20, focusDistance: 4 });
    const r = await fromThree(new THREE.Scene(), c);
    expect(r.scene.camera.aperture).toBeCloseTo(0.01, 12);
    expect(r.scene.camera.focusDistance).toBe(4);
    expect(r.scene.camera.target).toEqual([0, 0, -1]);
  });

  it('refuses a camera that is not perspective', async () => {
    await expect(fromThree(new THREE.Scene(), new THREE.OrthographicCamera())).rejects.toThrow(
      /PerspectiveCamera/,
    );
  });
});

describe('fromThree warnings', () => {
  it('says once what it cannot map, naming the object', async () => {
    const scene = new THREE.Scene();
    scene.background = new THREE.Color(0.2, 0.3, 0.4);
    scene.add(new THREE.AmbientLight(), new THREE.HemisphereLight());
    scene.add(new THREE.Points(new THREE.BufferGeometry(), new THREE.PointsMaterial()));
    const ao = new THREE.MeshStandardMaterial({ aoMap: checker(), bumpMap: checker() });
    const named = new THREE.Mesh(new THREE.BoxGeometry(), ao);
    named.name = 'crate';
    scene.add(named);
    scene.add(new THREE.Mesh(new THREE.BoxGeometry(), new THREE.ShaderMaterial()));
    const point = new THREE.PointLight(0xffffff, 1, 5, 1);
    scene.add(point);
    const cube = new THREE.CubeTexture();
    const withCube = new THREE.Scene();
    withCube.environment = cube;
    const r = await fromThree(scene, camera());
    const text = r.warnings.join('\n');
    expect(r.warnings.length).toBe(new Set(r.warnings).size);
    for (const pattern of [
      /AmbientLight.*left out/,
      /HemisphereLight.*left out/,
      /points, lines and sprites/,
      /"crate".*aoMap ignored/,
      /"crate".*bumpMap ignored/,
      /ShaderMaterial has no glTF counterpart/,
      /PointLight: decay 1/,
      /PointLight: distance 5/,
      /scene.background: a colour/,
    ]) {
      expect(text).toMatch(pattern);
    }
    const rc = await fromThree(withCube, camera());
    expect(rc.warnings.join('\n')).toMatch(/scene.environment: a cube or PMREM texture/);
  });
});

describe('fromThree texture cache', () => {
  it('re-encodes a texture only when its version changes', async () => {
    const map = checker();
    const scene = box(new THREE.MeshStandardMaterial({ map }));
    const texel = async () => {
      const { json, resources } = await gltfJson(scene);
      const view = json.bufferViews[json.images[0].bufferView];
      const bin = Object.values(resources)[0] as Uint8Array;
      return Array.from(
        decodePng(
          bin.subarray(view.byteOffset ?? 0, (view.byteOffset ?? 0) + view.byteLength),
        ).data.slice(0, 4),
      );
    };
    expect(await texel()).toEqual([255, 0, 0, 255]);
    (map.image.data as Uint8Array).set([0, 0, 0, 255], 0);
    expect(await texel()).toEqual([255, 0, 0, 255]); // unchanged version: the cached PNG
    map.needsUpdate = true;
    expect(await texel()).toEqual([0, 0, 0, 255]);
  });
});

describe('fromThree visibility', () => {
  it('leaves out a mesh whose material is hidden, but not its children', async () => {
    const scene = new THREE.Scene();
    const parent = new THREE.Mesh(
      new THREE.BoxGeometry(),
      new THREE.MeshStandardMaterial({ visible: false }),
    );
    parent.add(new THREE.Mesh(new THREE.BoxGeometry(), new THREE.MeshStandardMaterial()));
    scene.add(parent);
    const { json } = await gltfJson(scene);
    expect(json.nodes.length).toBe(1);
  });
});
