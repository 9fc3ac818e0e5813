/**
 * The default scene of a glTF document flattened into world-space triangle
 * arrays: each node that holds a mesh instances its primitives with the
 * node's world matrix (times the scene shape's own transform). Two passes:
 * the first builds each primitive's triangle list once (shared by all its
 * instances) and counts, the second allocates the output once and fills it.
 *
 * glTF rules applied here (glTF 2.0 §3.7.2 and §3.5):
 * - modes TRIANGLES, TRIANGLE_STRIP and TRIANGLE_FAN become triangles;
 *   POINTS and LINES* are skipped with a warning;
 * - a node whose world matrix has a negative determinant flips the winding
 *   (its front faces are clockwise), so two indices are swapped to keep the
 *   geometric normal on the front side;
 * - normals transform by the inverse transpose, tangents by the matrix, and
 *   a mirroring matrix flips the tangent's handedness w;
 * - a primitive without NORMAL is flat-shaded: its vertices get (0, 0, 0),
 *   which tells the tracer to use the geometric normal.
 * Zero-area triangles are skipped and counted, as for every mesh.
 */
import type { Document, Mesh, Primitive } from '@gltf-transform/core';
import { readFloats } from './accessors.ts';
import { readCamera } from './cameras.ts';
import { nodeLight } from './punctual-lights.ts';
import type { LightDesc } from '../scene/format/types.ts';
import type { GltfCamera } from '../scene/format/gltf-model.ts';
import { triangleList } from './triangles.ts';
import { GltfError } from './errors.ts';
import {
  GM_EMISSIVE,
  GM_STRIDE,
  GM_TEXTURES,
  BINDING_STRIDE,
  B_TEXCOORD,
  TEX_ANISOTROPY,
  TEX_NORMAL,
  hasTexture,
} from '../gltf-material/material-table.ts';
import { usesAnisotropy } from './materials.ts';
import type { GltfGeometry, GltfTriangles, TangentGenerator } from '../scene/format/gltf-model.ts';
import { generatePrimitiveTangents, weldCorners } from './tangents.ts';
import { det3, identity, type Mat4, multiply, nodeMatrix, normalMatrix } from './transforms.ts';
import { GLTF_LIMITS, MODE_TRIANGLE_FAN, MODE_TRIANGLE_STRIP, MODE_TRIANGLES } from './validate.ts';
import { hasGpuInstancing, instanceMatrices } from './gpu-instancing.ts';
import { gatherInstances, splitInstances } from './instance-split.ts';
import {
  areaOverflow,
  checkWorldMatrix,
  collapsed,
  hasLocalArea,
  vertexOverflow,
} from './validate-world.ts';

export type { GltfCamera, GltfGeometry };

type Json = Record<string, unknown>;

interface Plan {
  where: string;
  prim: Primitive;
  material: number;
  /** Triangle corners as source-vertex numbers of the output vertices (`source`). */
  triangles: Uint32Array;
  /** Output vertex → vertex of the primitive's accessors. */
  source: Uint32Array | null;
  vertexCount: number;
  /** MikkTSpace tangents per output vertex (primitive space), when generated. */
  generatedTangents: Float32Array | null;
}

function checkFinite(a: Float32Array, size: number, where: string): void {
  for (let i = 0; i < a.length; i++) {
    if (!Number.isFinite(a[i])) {
      throw new GltfError(`${where}: vertex ${Math.floor(i / size)} has a non-finite value`);
    }
  }
}

export function flattenGltf(
  doc: Document,
  json: Json,
  sceneIndex: number,
  table: Float64Array,
  defaultMaterial: number,
  shapeTransform: Mat4 | null,
  generateTangents: TangentGenerator | null,
  warn: (message: string) => void,
): GltfGeometry {
  const root = doc.getRoot();
  const meshes = root.listMeshes();
  const materialIndex = new Map(root.listMaterials().map((m, i) => [m, i]));
  const nodes = (json.nodes as Json[] | undefined) ?? [];
  const jsonCameras = (json.cameras as Json[] | undefined) ?? [];
  const cameras: GltfCamera[] = [];
  const lights: LightDesc[] = [];
  const instances: { mesh: number; matrix: Mat4; node: number }[] = [];
  if (sceneIndex >= 0) {
    const scene = (json.scenes as Json[])[sceneIndex];
    const base = shapeTransform ?? identity();
    const stack: { node: number; parent: Mat4 }[] = ((scene.nodes as number[] | undefined) ?? [])
      .map((node) => ({ node, parent: base }))
      .reverse();
    while (stack.length > 0) {
      const { node, parent } = stack.pop()!;
      const n = nodes[node];
      const world = multiply(parent, nodeMatrix(n));
      checkWorldMatrix(world, node);
      if (typeof n.mesh === 'number') {
        const mesh = n.mesh;
        // EXT_mesh_gpu_instancing: the mesh at each instance, never at the node itself.
        if (hasGpuInstancing(n))
          instanceMatrices(doc, json, node, world, (matrix, k) => {
            checkWorldMatrix(matrix, node, k);
            instances.push({ mesh, matrix, node });
          });
        else instances.push({ mesh, matrix: world, node });
      }
      if (typeof n.camera === 'number') {
        const where = `cameras[${n.camera}] (at nodes[${node}])`;
        const cam = readCamera(jsonCameras[n.camera], world);
        if (typeof cam === 'string') warn(`${where}: ${cam}; ignored`);
        else cameras.push(cam);
      }
      // KHR_lights_punctual (punctual-lights.ts).
      const light = nodeLight(json, n, world);
      if (typeof light === 'string')
        warn(`nodes[${node}].extensions.KHR_lights_punctual: ${light}; ignored`);
      else if (light !== null) lights.push(light);
      const children = (n.children as number[] | undefined) ?? [];
      for (let c = children.length - 1; c >= 0; c--)
        stack.push({ node: children[c], parent: world });
    }
  }

  // Pass 1: one plan per primitive (shared by its instances), and the counts.
  const plans = new Map<Mesh, (Plan | null)[]>();
  const planOf = (meshIdx: number): (Plan | null)[] => {
    const mesh = meshes[meshIdx];
    let p = plans.get(mesh);
    if (p !== undefined) return p;
    p = mesh
      .listPrimitives()
      .map((prim, j) => makePlan(prim, `meshes[${meshIdx}].primitives[${j}]`));
    plans.set(mesh, p);
    return p;
  };
  const makePlan = (prim: Primitive, where: string): Plan | null => {
    const mode = prim.getMode();
    if (mode !== MODE_TRIANGLES && mode !== MODE_TRIANGLE_STRIP && mode !== MODE_TRIANGLE_FAN) {
      warn(`${where}: mode ${mode} (points or lines) is not rendered; skipped`);
      return null;
    }
    const pos = prim.getAttribute('POSITION');
    if (pos === null) {
      warn(`${where}: has no POSITION; skipped`);
      return null;
    }
    const mat = prim.getMaterial();
    const material = mat === null ? defaultMaterial : materialIndex.get(mat)!;
    const triangles = triangleList(prim, pos.getCount(), where);
    const plan: Plan = {
      where,
      prim,
      material,
      triangles,
      source: null,
      vertexCount: pos.getCount(),
      generatedTangents: null,
    };
    const normalMapped = hasTexture(table, material, TEX_NORMAL);
    // KHR_materials_anisotropy needs tangents too, normal map or not.
    if (
      (normalMapped || usesAnisotropy(table, material)) &&
      prim.getAttribute('TANGENT') === null
    ) {
      const set =
        table[
          material * GM_STRIDE +
            GM_TEXTURES +
            (normalMapped ? TEX_NORMAL : TEX_ANISOTROPY) * BINDING_STRIDE +
            B_TEXCOORD
        ];
      const uv = prim.getAttribute(`TEXCOORD_${set}`);
      const lost = normalMapped ? 'the normal map is ignored' : 'its anisotropy is isotropic';
      if (uv === null)
        warn(
          `${where}: its material needs tangents (${normalMapped ? 'a normal map' : 'KHR_materials_anisotropy'}) but the primitive has no TEXCOORD_${set}; ${lost} here`,
        );
      else if (generateTangents === null)
        warn(`${where}: no tangent generator was given; ${lost} here`);
      else {
        // MikkTSpace works on unwelded corners; weld the result back.
        const corner = generatePrimitiveTangents(
          prim,
          triangles,
          readFloats(uv),
          generateTangents,
          where,
        );
        const welded = weldCorners(triangles, corner, pos.getCount());
        plan.source = welded.source;
        plan.triangles = welded.triangles;
        plan.vertexCount = welded.source.length;
        plan.generatedTangents = welded.tangents;
      }
    }
    return plan;
  };
  // Which meshes become instances of one object-space copy (instances.ts): those used
  // more than once, unless emissive (a mesh light is sampled by world area).
  const work: { plan: Plan; matrix: Mat4; node: number }[] = [];
  const split = splitInstances(instances, meshes.length, (m) => {
    const p = planOf(m);
    return p.some((plan) => plan !== null && emissiveRow(table, plan.material));
  });
  for (const inst of split.world) {
    for (const plan of planOf(inst.mesh)) {
      if (plan !== null) work.push({ plan, matrix: inst.matrix, node: inst.node });
    }
  }
  // Copies of emissive meshes drawn many times count against the limit of triangles held
  // (validate.ts counted each mesh once): checked before anything is allocated for them.
  let total = 0;
  for (const w of work) total += w.plan.triangles.length / 3;
  for (const m of split.blasMeshes)
    for (const plan of planOf(m)) total += plan === null ? 0 : plan.triangles.length / 3;
  if (total > GLTF_LIMITS.triangles) {
    throw new GltfError(
      `scene: holds ${total} triangles once emissive meshes drawn several times are copied, more than the limit of ${GLTF_LIMITS.triangles}`,
    );
  }
  const geometry = fillWork(work, table);
  const blas = split.blasMeshes.map((m, b) =>
    fillWork(
      planOf(m)
        .filter((plan): plan is Plan => plan !== null)
        .map((plan) => ({ plan, matrix: identity(), node: split.blasNode[b] })),
      table,
    ),
  );
  const gathered = gatherInstances(split, blas, geometry.bounds);
  // Lights only when there are some: a model without lights hashes as before (cli/film-file.ts).
  const extra = lights.length > 0 ? { lights } : {};
  return gathered === null
    ? { ...geometry, cameras, ...extra }
    : { ...geometry, instances: gathered, cameras, ...extra };
}

/** Whether row m of the material table emits (the compiler's M_EMISSIVE test). */
function emissiveRow(table: Float64Array, m: number): boolean {
  const o = m * GM_STRIDE + GM_EMISSIVE;
  return table[o] > 0 || table[o + 1] > 0 || table[o + 2] > 0;
}

/**
 * The primitives of `work` with their transforms applied, in one set of arrays (the
 * world-space triangles, or one instanced mesh in object space with identity
 * transforms). Two passes: count, then allocate once and fill.
 */
function fillWork(
  work: { plan: Plan; matrix: Mat4; node: number }[],
  table: Float64Array,
): GltfTriangles {
  let vertexTotal = 0;
  let triangleTotal = 0;
  const has = { normal: false, uv0: false, uv1: false, color: false, tangent: false };
  for (const { plan } of work) {
    vertexTotal += plan.vertexCount;
    triangleTotal += plan.triangles.length / 3;
    const p = plan.prim;
    has.normal ||= p.getAttribute('NORMAL') !== null;
    has.uv0 ||= p.getAttribute('TEXCOORD_0') !== null;
    has.uv1 ||= p.getAttribute('TEXCOORD_1') !== null;
    has.color ||= p.getAttribute('COLOR_0') !== null;
    has.tangent ||=
      hasTexture(table, plan.material, TEX_NORMAL) || usesAnisotropy(table, plan.material);
  }

  const positions = new Float64Array(vertexTotal * 3);
  const normals = has.normal ? new Float32Array(vertexTotal * 3) : null;
  const uv0 = has.uv0 ? new Float32Array(vertexTotal * 2) : null;
  const uv1 = has.uv1 ? new Float32Array(vertexTotal * 2) : null;
  const colors = has.color ? new Float32Array(vertexTotal * 4).fill(1) : null;
  const tangents = has.tangent ? new Float32Array(vertexTotal * 4) : null;
  const indices = new Uint32Array(triangleTotal * 3);
  const triangleMaterial = new Uint32Array(triangleTotal);
  const bounds = Float64Array.of(Infinity, Infinity, Infinity, -Infinity, -Infinity, -Infinity);
  let v0 = 0;
  let t = 0;
  let skipped = 0;
  for (const { plan, matrix, node } of work) {
    const { prim, where, source } = plan;
    // A singular node (scale 0 hides objects in some files): all its triangles have no area.
    if (det3(matrix) === 0) {
      skipped += plan.triangles.length / 3;
      continue;
    }
    const n = plan.vertexCount;
    const src = (k: number): number => (source === null ? k : source[k]);
    const pos = readFloats(prim.getAttribute('POSITION')!);
    checkFinite(pos, 3, `${where}.attributes.POSITION`);
    const m = matrix;
    for (let k = 0; k < n; k++) {
      const s = 3 * src(k);
      const x = pos[s],
        y = pos[s + 1],
        z = pos[s + 2];
      const o = 3 * (v0 + k);
      for (let a = 0; a < 3; a++) {
        const w = m[a] * x + m[4 + a] * y + m[8 + a] * z + m[12 + a];
        if (!Number.isFinite(w))
          throw vertexOverflow(node, where, src(k), [
            m[0] * x + m[4] * y + m[8] * z + m[12],
            m[1] * x + m[5] * y + m[9] * z + m[13],
            m[2] * x + m[6] * y + m[10] * z + m[14],
          ]);
        positions[o + a] = w;
        if (w < bounds[a]) bounds[a] = w;
        if (w > bounds[3 + a]) bounds[3 + a] = w;
      }
    }
    const nrmAcc = prim.getAttribute('NORMAL');
    if (normals !== null && nrmAcc !== null) {
      const nrm = readFloats(nrmAcc);
      checkFinite(nrm, 3, `${where}.attributes.NORMAL`);
      const nm = normalMatrix(m);
      for (let k = 0; k < n; k++) {
        const s = 3 * src(k);
        const x = nrm[s],
          y = nrm[s + 1],
          z = nrm[s + 2];
        let wx = nm[0] * x + nm[3] * y + nm[6] * z;
        let wy = nm[1] * x + nm[4] * y + nm[7] * z;
        let wz = nm[2] * x + nm[5] * y + nm[8] * z;
        let l = Math.sqrt(wx * wx + wy * wy + wz * wz);
        if (!(l > 0 && l < Infinity)) {
          // The squares under- or overflowed (a scale of 1e200 on one axis): rescale first.
          const s = Math.max(Math.abs(wx), Math.abs(wy), Math.abs(wz));
          if (s > 0 && s < Infinity) {
            wx /= s;
            wy /= s;
            wz /= s;
            l = Math.sqrt(wx * wx + wy * wy + wz * wz);
          }
        }
        if (!(l > 0) || !Number.isFinite(l)) {
          throw new GltfError(
            `${where}.attributes.NORMAL: vertex ${src(k)} has a zero-length normal`,
          );
        }
        const o = 3 * (v0 + k);
        normals[o] = wx / l;
        normals[o + 1] = wy / l;
        normals[o + 2] = wz / l;
      }
    }
    for (const [name, out] of [
      ['TEXCOORD_0', uv0],
      ['TEXCOORD_1', uv1],
    ] as const) {
      const acc = prim.getAttribute(name);
      if (out === null || acc === null) continue;
      const uv = readFloats(acc);
      checkFinite(uv, 2, `${where}.attributes.${name}`);
      for (let k = 0; k < n; k++) {
        out[2 * (v0 + k)] = uv[2 * src(k)];
        out[2 * (v0 + k) + 1] = uv[2 * src(k) + 1];
      }
    }
    const colAcc = prim.getAttribute('COLOR_0');
    if (colors !== null && colAcc !== null) {
      const col = readFloats(colAcc);
      const size = colAcc.getElementSize();
      checkFinite(col, size, `${where}.attributes.COLOR_0`);
      for (let k = 0; k < n; k++) {
        for (let a = 0; a < size; a++) colors[4 * (v0 + k) + a] = col[size * src(k) + a];
      }
    }
    const flip = det3(m) < 0;
    if (tangents !== null) {
      const tanAcc = prim.getAttribute('TANGENT');
      const tan = plan.generatedTangents ?? (tanAcc === null ? null : readFloats(tanAcc));
      if (tan !== null) {
        if (plan.generatedTangents === null) checkFinite(tan, 4, `${where}.attributes.TANGENT`);
        for (let k = 0; k < n; k++) {
          const s = plan.generatedTangents !== null ? 4 * k : 4 * src(k);
          const x = tan[s],
            y = tan[s + 1],
            z = tan[s + 2];
          const wx = m[0] * x + m[4] * y + m[8] * z;
          const wy = m[1] * x + m[5] * y + m[9] * z;
          const wz = m[2] * x + m[6] * y + m[10] * z;
          const l = Math.sqrt(wx * wx + wy * wy + wz * wz);
          if (!(l > 0)) continue; // degenerate: no normal mapping at this vertex
          const o = 4 * (v0 + k);
          tangents[o] = wx / l;
          tangents[o + 1] = wy / l;
          tangents[o + 2] = wz / l;
          tangents[o + 3] = (tan[s + 3] < 0 ? -1 : 1) * (flip ? -1 : 1);
        }
      }
    }
    const tris = plan.triangles;
    const kept = t;
    for (let k = 0; k < tris.length; k += 3) {
      const a = v0 + tris[k];
      const b = v0 + tris[k + (flip ? 2 : 1)];
      const c = v0 + tris[k + (flip ? 1 : 2)];
      // Zero area in double precision (the scene format's rule): skipped.
      const ex = positions[3 * b] - positions[3 * a];
      const ey = positions[3 * b + 1] - positions[3 * a + 1];
      const ez = positions[3 * b + 2] - positions[3 * a + 2];
      const fx = positions[3 * c] - positions[3 * a];
      const fy = positions[3 * c + 1] - positions[3 * a + 1];
      const fz = positions[3 * c + 2] - positions[3 * a + 2];
      const cx = ey * fz - ez * fy;
      const cy = ez * fx - ex * fz;
      const cz = ex * fy - ey * fx;
      if (cx === 0 && cy === 0 && cz === 0) {
        skipped++;
        continue;
      }
      if (!(Number.isFinite(cx) && Number.isFinite(cy) && Number.isFinite(cz)))
        throw areaOverflow(node, where, k / 3);
      indices[3 * t] = a;
      indices[3 * t + 1] = b;
      indices[3 * t + 2] = c;
      triangleMaterial[t] = plan.material;
      t++;
    }
    if (t === kept && tris.length > 0 && hasLocalArea(pos, tris, source)) {
      const a = tris[0] + v0;
      const at = Math.max(
        Math.abs(positions[3 * a]),
        Math.abs(positions[3 * a + 1]),
        Math.abs(positions[3 * a + 2]),
      );
      throw collapsed(node, where, tris.length / 3, at);
    }
    v0 += n;
  }
  return {
    positions,
    indices: t * 3 === indices.length ? indices : indices.slice(0, 3 * t),
    normals,
    uv0,
    uv1,
    colors,
    tangents,
    triangleMaterial:
      t === triangleMaterial.length ? triangleMaterial : triangleMaterial.slice(0, t),
    skipped,
    bounds,
  };
}
