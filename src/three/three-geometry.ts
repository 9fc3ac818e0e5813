/**
 * A three.js BufferGeometry as glTF primitives: one per group (each with its material,
 * §3.7.2), attributes read through the attribute's own getters so that interleaved,
 * normalized and integer layouts all come out as the float arrays glTF's core allows.
 * Accessors are made once per geometry and shared by every mesh that draws it.
 */
import type { Accessor, Buffer, Document, Mesh, Primitive } from '@gltf-transform/core';
import type { ConvertedMaterial } from './three-material.ts';
import type { ThreeAttribute, ThreeGeometry } from './three-shapes.ts';

/** three's attribute names and their glTF semantics, with the glTF type. */
const ATTRIBUTES: [string, string, 'VEC2' | 'VEC3' | 'VEC4'][] = [
  ['position', 'POSITION', 'VEC3'],
  ['normal', 'NORMAL', 'VEC3'],
  ['uv', 'TEXCOORD_0', 'VEC2'],
  ['uv1', 'TEXCOORD_1', 'VEC2'],
  ['tangent', 'TANGENT', 'VEC4'],
  ['color', 'COLOR_0', 'VEC3'],
];

export class GeometryConverter {
  private readonly accessors = new Map<string, Map<string, Accessor>>();
  private readonly meshes = new Map<string, Mesh>();

  constructor(
    private readonly doc: Document,
    private readonly buffer: Buffer,
    private readonly warn: (m: string) => void,
  ) {}

  /** The glTF mesh of `geometry` drawn with `materials` (one, or one per group). */
  mesh(geometry: ThreeGeometry, materials: ConvertedMaterial[], where: string): Mesh | null {
    const key = `${geometry.uuid}/${materials.map((m) => m.material.getName() + '#' + materialId(m)).join(',')}`;
    const known = this.meshes.get(key);
    if (known !== undefined) return known;
    const position = geometry.attributes.position;
    if (position === undefined || position.count === 0) {
      this.warn(`${where}: the geometry has no positions; skipped`);
      return null;
    }
    if (Object.values(geometry.morphAttributes ?? {}).some((a) => (a?.length ?? 0) > 0)) {
      this.warn(`${where}: morph targets ignored; rendered in the rest shape`);
    }
    const mesh = this.doc.createMesh(where);
    const vertexCount = geometry.index?.count ?? position.count;
    const range = geometry.drawRange ?? { start: 0, count: Infinity };
    const drawStart = Math.max(0, range.start);
    const drawEnd = Math.min(vertexCount, drawStart + range.count);
    const groups =
      materials.length > 1 && geometry.groups.length > 0
        ? geometry.groups
        : [{ start: 0, count: Infinity, materialIndex: 0 }];
    for (const group of groups) {
      const start = Math.max(drawStart, group.start);
      const end = Math.min(drawEnd, group.start + group.count);
      const converted = materials[group.materialIndex ?? 0];
      if (end - start < 3 || converted === undefined) continue;
      mesh.addPrimitive(this.primitive(geometry, converted, start, end, where));
    }
    if (mesh.listPrimitives().length === 0) {
      mesh.dispose();
      return null;
    }
    this.meshes.set(key, mesh);
    return mesh;
  }

  private primitive(
    geometry: ThreeGeometry,
    converted: ConvertedMaterial,
    start: number,
    end: number,
    where: string,
  ): Primitive {
    const prim = this.doc.createPrimitive().setMaterial(converted.material);
    for (const [name, semantic, type] of ATTRIBUTES) {
      const attribute = geometry.attributes[name];
      if (attribute === undefined) continue;
      if (semantic === 'NORMAL' && converted.flat) continue;
      if (semantic === 'COLOR_0' && !converted.vertexColors) continue;
      prim.setAttribute(
        semantic,
        this.accessor(
          geometry,
          name,
          attribute,
          semantic === 'COLOR_0' && attribute.itemSize === 4 ? 'VEC4' : type,
          where,
        ),
      );
    }
    const count = end - start - ((end - start) % 3);
    const index = new Uint32Array(count);
    const source = geometry.index;
    for (let i = 0; i < count; i++) index[i] = source ? source.getX(start + i) : start + i;
    prim.setIndices(
      this.doc.createAccessor().setType('SCALAR').setArray(index).setBuffer(this.buffer),
    );
    return prim;
  }

  private accessor(
    geometry: ThreeGeometry,
    name: string,
    attribute: ThreeAttribute,
    type: 'VEC2' | 'VEC3' | 'VEC4',
    where: string,
  ): Accessor {
    let byName = this.accessors.get(geometry.uuid);
    if (byName === undefined) this.accessors.set(geometry.uuid, (byName = new Map()));
    const known = byName.get(name);
    if (known !== undefined) return known;
    const size = type === 'VEC2' ? 2 : type === 'VEC3' ? 3 : 4;
    if (attribute.itemSize < size && !(name === 'color' && attribute.itemSize === 3)) {
      this.warn(
        `${where}: attribute ${name} has ${attribute.itemSize} components, ${size} expected`,
      );
    }
    const n = attribute.count;
    const out = new Float32Array(n * size);
    for (let i = 0; i < n; i++) {
      // getX etc. undo `normalized` and interleaving (BufferAttribute and its kin).
      out[i * size] = attribute.getX(i);
      out[i * size + 1] = attribute.getY(i);
      if (size > 2) out[i * size + 2] = attribute.getZ(i);
      if (size > 3) out[i * size + 3] = attribute.itemSize > 3 ? attribute.getW(i) : 1;
    }
    const accessor = this.doc
      .createAccessor(name)
      .setType(type)
      .setArray(out)
      .setBuffer(this.buffer);
    byName.set(name, accessor);
    return accessor;
  }
}

const ids = new WeakMap<object, number>();
let nextId = 0;
function materialId(m: ConvertedMaterial): number {
  let id = ids.get(m);
  if (id === undefined) ids.set(m, (id = nextId++));
  return id;
}
