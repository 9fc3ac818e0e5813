/**
 * KHR_draco_mesh_compression, decoded by the loader itself before glTF-Transform reads
 * the document, with the Draco decoder's glTF build (draco3dgltf, injected:
 * GltfDecoders.draco). For each compressed primitive: the extension's JSON is checked,
 * the stream's declared counts are compared with the accessors' before anything is
 * decoded (draco-header.ts), the decoded counts must then equal the accessors' (the
 * extension's README: the accessors describe the decoded data; glTF-Transform's own
 * class does not compare them, decoders.md §2), and the decoded attributes and indices
 * become plain buffer views of a buffer of their own (decoded-buffer.ts). The triangle
 * limit, counted from the accessors by validate.ts, therefore holds for the decoded
 * mesh too. glTF-Transform and the byte-range checks then see a plain file.
 *
 * Spec: KhronosGroup/glTF extensions/2.0/Khronos/KHR_draco_mesh_compression/README.md.
 */
import type { DracoDecoderModule } from '../scene/format/gltf-model.ts';
import { DecodedBuffer, dropExtensionNames } from './decoded-buffer.ts';
import { peekDracoCounts } from './draco-header.ts';
import { COMPONENT_SIZE, MODE_TRIANGLES, TYPE_SIZE } from './validate.ts';
import { describeValue, fail, index, isObject, list, type Json } from './validate-values.ts';

export const DRACO_EXTENSION = 'KHR_draco_mesh_compression';

/** The parts of Draco's WebIDL Decoder the loader calls (draco_web_decoder.idl). */
interface Decoder {
  GetEncodedGeometryType(buffer: object): number;
  DecodeBufferToMesh(buffer: object, mesh: object): { ok(): boolean; error_msg(): string };
  GetAttributeByUniqueId(mesh: object, id: number): { ptr: number; num_components(): number };
  GetAttributeDataArrayForAllPoints(
    mesh: object,
    attribute: object,
    dataType: number,
    byteLength: number,
    ptr: number,
  ): boolean;
  GetTrianglesUInt32Array(mesh: object, byteLength: number, ptr: number): boolean;
}

type Mesh = InstanceType<DracoDecoderModule['Mesh']>;

/** Whether the file uses KHR_draco_mesh_compression. */
export function usesDraco(json: Json): boolean {
  const used = json.extensionsUsed;
  return Array.isArray(used) && used.includes(DRACO_EXTENSION);
}

/**
 * Decodes every Draco primitive of `json` in place (`data[i]`: the bytes of
 * buffers[i]; `resources`: what glTF-Transform reads). Throws GltfError naming the
 * primitive's extension at the first problem.
 */
export function decodeDracoPrimitives(
  json: Json,
  data: Uint8Array[],
  resources: Record<string, Uint8Array>,
  draco: DracoDecoderModule,
): void {
  const views = list(json, 'bufferViews');
  const accessors = list(json, 'accessors');
  const out = new DecodedBuffer(json, '@draco');
  const meshes = new Map<number, { decoder: Decoder; mesh: Mesh }>();
  /** Accessor index → the Draco view and attribute id it was decoded from. */
  const done = new Map<number, string>();
  try {
    list(json, 'meshes').forEach((m, i) => {
      list(m, 'primitives', `meshes[${i}].primitives`).forEach((pr, j) => {
        const ext = isObject(pr.extensions) ? pr.extensions : undefined;
        const e = ext?.[DRACO_EXTENSION];
        if (ext === undefined || e === undefined) return;
        const p = `meshes[${i}].primitives[${j}].extensions.${DRACO_EXTENSION}`;
        if (!isObject(e)) fail(p, `must be an object, got ${describeValue(e)}`);
        const v = index(e, 'bufferView', p, views.length, 'bufferViews');
        if (v === undefined) fail(`${p}.bufferView`, 'is required');
        const sems = e.attributes;
        if (!isObject(sems))
          fail(`${p}.attributes`, `must be an object, got ${describeValue(sems)}`);
        const attributes = pr.attributes as Json;
        for (const [sem, id] of Object.entries(sems)) {
          if (typeof id !== 'number' || !Number.isInteger(id) || id < 0)
            fail(`${p}.attributes.${sem}`, `must be an integer id, got ${describeValue(id)}`);
          if (attributes[sem] === undefined)
            fail(`${p}.attributes.${sem}`, `names an attribute the primitive does not have`);
        }
        if (((pr.mode as number | undefined) ?? MODE_TRIANGLES) !== MODE_TRIANGLES)
          fail(`${p}`, `a Draco primitive must have mode 4 (TRIANGLES), got ${pr.mode as number}`);
        if (pr.indices === undefined) fail(p, 'the primitive has no indices, which Draco decodes');
        const ind = pr.indices as number;
        if (attributes.POSITION === undefined)
          fail(`meshes[${i}].primitives[${j}].attributes`, 'a Draco primitive needs POSITION');
        const indexCount = accessors[ind].count as number;
        const pointCount = accessors[attributes.POSITION as number].count as number;

        let entry = meshes.get(v);
        if (entry === undefined) {
          entry = decodeStream(draco, views[v], v, data, p, indexCount, pointCount);
          meshes.set(v, entry);
        }
        const { decoder, mesh } = entry;
        const faces = mesh.num_faces();
        const points = mesh.num_points();
        if (faces * 3 !== indexCount)
          fail(
            p,
            `decodes to ${faces * 3} indices, but accessors[${ind}] (the indices) has count ${indexCount}`,
          );
        for (const [sem, id] of Object.entries(sems) as [string, number][]) {
          const a = attributes[sem] as number;
          const key = `${v}/${id}`;
          if (done.has(a)) {
            if (done.get(a) !== key)
              fail(
                `${p}.attributes.${sem}`,
                `accessors[${a}] is decoded from two different Draco attributes`,
              );
            continue;
          }
          if ((accessors[a].count as number) !== points)
            fail(
              `${p}.attributes.${sem}`,
              `the stream decodes to ${points} points, but accessors[${a}] has count ${accessors[a].count as number}`,
            );
          const bytes = attributeBytes(
            draco,
            decoder,
            mesh,
            id,
            accessors[a],
            points,
            `${p}.attributes.${sem}`,
          );
          point(json, accessors[a], out, bytes.bytes, bytes.stride);
          done.set(a, key);
        }
        if (done.has(ind) && done.get(ind) !== `${v}/indices`)
          fail(
            `${p}`,
            `accessors[${ind}] (the indices) is decoded from two different Draco streams`,
          );
        if (!done.has(ind)) {
          const bytes = withHeap(
            draco,
            faces * 12,
            (ptr) => decoder.GetTrianglesUInt32Array(mesh, faces * 12, ptr),
            p,
          );
          accessors[ind].componentType = 5125;
          point(json, accessors[ind], out, bytes, undefined);
          done.set(ind, `${v}/indices`);
        }
        delete ext[DRACO_EXTENSION];
        if (Object.keys(ext).length === 0) delete pr.extensions;
      });
    });
  } finally {
    for (const { decoder, mesh } of meshes.values()) {
      draco.destroy(decoder);
      draco.destroy(mesh);
    }
  }
  out.finish(resources, data);
  dropExtensionNames(json, [DRACO_EXTENSION]);
}

/** Decodes the stream of bufferViews[v], once its header's counts fit the accessors. */
function decodeStream(
  draco: DracoDecoderModule,
  view: Json,
  v: number,
  data: Uint8Array[],
  p: string,
  indexCount: number,
  pointCount: number,
): { decoder: Decoder; mesh: Mesh } {
  const b = view.buffer as number;
  const start = (view.byteOffset as number | undefined) ?? 0;
  const end = start + (view.byteLength as number);
  if (end > data[b].length)
    fail(
      `bufferViews[${v}]`,
      `ends at byte ${end}, past the ${data[b].length} bytes of buffers[${b}]`,
    );
  const bytes = data[b].subarray(start, end);
  const head = peekDracoCounts(bytes);
  if (typeof head === 'string') fail(`${p}.bufferView`, `bufferViews[${v}] ${head}`);
  if (head.faces !== null && head.faces * 3 > indexCount)
    fail(
      p,
      `the Draco stream declares ${head.faces} triangles, more than the ${indexCount / 3} of its indices accessor`,
    );
  if (head.points !== null && head.points > pointCount)
    fail(
      p,
      `the Draco stream declares ${head.points} points, more than the ${pointCount} of its POSITION accessor`,
    );
  const decoder = new draco.Decoder() as unknown as Decoder;
  const buffer = new draco.DecoderBuffer();
  const mesh = new draco.Mesh();
  try {
    buffer.Init(bytes, bytes.length);
    if (decoder.GetEncodedGeometryType(buffer) !== draco.TRIANGULAR_MESH)
      fail(`${p}.bufferView`, `bufferViews[${v}] is not a Draco triangle mesh`);
    const status = decoder.DecodeBufferToMesh(buffer, mesh);
    if (!status.ok() || mesh.ptr === 0)
      fail(`${p}.bufferView`, `the Draco stream cannot be decoded (${status.error_msg()})`);
  } catch (e) {
    draco.destroy(decoder);
    draco.destroy(mesh);
    throw e;
  } finally {
    draco.destroy(buffer);
  }
  return { decoder, mesh };
}

/** One attribute's values for all points, in the accessor's component type. */
function attributeBytes(
  draco: DracoDecoderModule,
  decoder: Decoder,
  mesh: Mesh,
  id: number,
  accessor: Json,
  points: number,
  p: string,
): { bytes: Uint8Array; stride: number | undefined } {
  const attribute = decoder.GetAttributeByUniqueId(mesh, id);
  if (attribute.ptr === 0) fail(p, `the Draco stream has no attribute of unique id ${id}`);
  const components = TYPE_SIZE[accessor.type as string];
  if (attribute.num_components() !== components)
    fail(
      p,
      `the Draco attribute has ${attribute.num_components()} components, the accessor's type ${accessor.type as string} ${components}`,
    );
  const ct = accessor.componentType as number;
  const types: Record<number, number> = {
    5120: draco.DT_INT8,
    5121: draco.DT_UINT8,
    5122: draco.DT_INT16,
    5123: draco.DT_UINT16,
    5125: draco.DT_UINT32,
    5126: draco.DT_FLOAT32,
  };
  const element = components * COMPONENT_SIZE[ct];
  const length = points * element;
  const packed = withHeap(
    draco,
    length,
    (ptr) => decoder.GetAttributeDataArrayForAllPoints(mesh, attribute, types[ct], length, ptr),
    p,
  );
  // §3.6.2.4: a vertex attribute's elements start on 4-byte boundaries.
  if (element % 4 === 0) return { bytes: packed, stride: undefined };
  const stride = (element + 3) & ~3;
  const bytes = new Uint8Array(points * stride);
  for (let k = 0; k < points; k++)
    bytes.set(packed.subarray(k * element, (k + 1) * element), k * stride);
  return { bytes, stride };
}

/** Calls `fill(ptr)` on `length` bytes of the decoder's heap and copies them out. */
function withHeap(
  draco: DracoDecoderModule,
  length: number,
  fill: (ptr: number) => boolean,
  p: string,
): Uint8Array {
  const ptr = draco._malloc(length);
  try {
    if (ptr === 0 || !fill(ptr)) fail(p, 'the Draco decoder could not extract the data');
    // Read HEAPU8 after the call: a grown heap replaces the view.
    return draco.HEAPU8.slice(ptr, ptr + length);
  } finally {
    draco._free(ptr);
  }
}

/** Points `accessor` at `bytes`, added to the decoded buffer as a view of its own. */
function point(
  json: Json,
  accessor: Json,
  out: DecodedBuffer,
  bytes: Uint8Array,
  byteStride: number | undefined,
): void {
  const { buffer, byteOffset } = out.add(bytes);
  const views = json.bufferViews as Json[];
  const view: Json = { buffer, byteOffset, byteLength: bytes.length };
  if (byteStride !== undefined) view.byteStride = byteStride;
  accessor.bufferView = views.length;
  views.push(view);
  delete accessor.byteOffset;
}
