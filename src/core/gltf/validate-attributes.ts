/**
 * A primitive's attributes against the table of glTF 2.0 §3.7.2.1 ("Meshes",
 * Overview: the accessor type and component type each attribute semantic
 * allows) and KHR_mesh_quantization (which widens POSITION, NORMAL, TANGENT
 * and TEXCOORD_n to integer types, when the file declares it): the reader
 * takes the accessor's elements at the semantic's width (three floats for
 * POSITION), so a POSITION of VEC2 or UNSIGNED_INT would be read as
 * something else, or as nothing. Also: all attributes of a primitive, and
 * of each of its morph targets (§3.7.2.2), have the same count; names are
 * the spec's semantics or start with "_" (application-specific).
 */
import { describeValue, fail, indexValue, isObject, type Json } from './validate-values.ts';

const FLOAT = 5126;
const BYTE = 5120;
const UBYTE = 5121;
const SHORT = 5122;
const USHORT = 5123;

/** One allowed encoding: a component type, normalised or not. */
type Encoding = readonly [component: number, normalized: boolean];

const F: Encoding = [FLOAT, false];
const UB_N: Encoding = [UBYTE, true];
const US_N: Encoding = [USHORT, true];
/** All eight integer encodings of KHR_mesh_quantization's POSITION and TEXCOORD_n. */
const INTS: Encoding[] = [BYTE, UBYTE, SHORT, USHORT].flatMap((c): Encoding[] => [
  [c, false],
  [c, true],
]);
const SIGNED_N: Encoding[] = [
  [BYTE, true],
  [SHORT, true],
];

interface Rule {
  types: readonly string[];
  core: readonly Encoding[];
  /** Added by KHR_mesh_quantization. */
  quantized: readonly Encoding[];
}

const RULES: Record<string, Rule> = {
  POSITION: { types: ['VEC3'], core: [F], quantized: INTS },
  NORMAL: { types: ['VEC3'], core: [F], quantized: SIGNED_N },
  TANGENT: { types: ['VEC4'], core: [F], quantized: SIGNED_N },
  TEXCOORD: { types: ['VEC2'], core: [F, UB_N, US_N], quantized: INTS },
  COLOR: { types: ['VEC3', 'VEC4'], core: [F, UB_N, US_N], quantized: [] },
  JOINTS: {
    types: ['VEC4'],
    core: [
      [UBYTE, false],
      [USHORT, false],
    ],
    quantized: [],
  },
  WEIGHTS: { types: ['VEC4'], core: [F, UB_N, US_N], quantized: [] },
};

/** Morph targets hold displacements (§3.7.2.2): TANGENT is VEC3 there, and no w. */
const TARGET_RULES: Record<string, Rule> = {
  POSITION: {
    types: ['VEC3'],
    core: [F],
    quantized: [...INTS.filter(([c]) => c !== 5121 && c !== 5123)],
  },
  NORMAL: { types: ['VEC3'], core: [F], quantized: SIGNED_N },
  TANGENT: { types: ['VEC3'], core: [F], quantized: SIGNED_N },
  TEXCOORD: RULES.TEXCOORD,
  COLOR: RULES.COLOR,
};

const COMPONENT_NAMES: Record<number, string> = {
  5120: 'BYTE',
  5121: 'UNSIGNED_BYTE',
  5122: 'SHORT',
  5123: 'UNSIGNED_SHORT',
  5125: 'UNSIGNED_INT',
  5126: 'FLOAT',
};

function encodingName([c, n]: Encoding): string {
  return `${COMPONENT_NAMES[c]}${n ? ' normalized' : ''}`;
}

/** The rule's key of an attribute name (TEXCOORD_3 → TEXCOORD), or null for an unknown name. */
function semantic(name: string): string | null {
  if (name === 'POSITION' || name === 'NORMAL' || name === 'TANGENT') return name;
  // Set indices are decimal without leading zeros (§3.7.2.1: TEXCOORD_n, n = 0, 1, …).
  const m = /^(TEXCOORD|COLOR|JOINTS|WEIGHTS)_(0|[1-9][0-9]*)$/.exec(name);
  return m === null ? null : m[1];
}

function checkOne(
  name: string,
  accessorIndex: number,
  accessors: Json[],
  path: string,
  rule: Rule,
  quantized: boolean,
): void {
  const a = accessors[accessorIndex];
  if (!rule.types.includes(a.type as string)) {
    fail(
      path,
      `accessors[${accessorIndex}] is ${String(a.type)}, but ${name} must be ${rule.types.join(' or ')}`,
    );
  }
  const allowed = quantized ? [...rule.core, ...rule.quantized] : rule.core;
  const enc: Encoding = [a.componentType as number, a.normalized === true];
  if (!allowed.some(([c, n]) => c === enc[0] && n === enc[1])) {
    const hint =
      !quantized && rule.quantized.some(([c, n]) => c === enc[0] && n === enc[1])
        ? ' (allowed only with the extension KHR_mesh_quantization, which the file does not declare)'
        : '';
    fail(
      path,
      `accessors[${accessorIndex}] is ${encodingName(enc)}, but ${name} must be ${allowed.map(encodingName).join(', ')}${hint}`,
    );
  }
}

/**
 * Checks `pr.attributes` and `pr.targets` of the primitive at `path`. `quantized`: the
 * file declares KHR_mesh_quantization in extensionsUsed. Throws GltfError.
 */
export function checkPrimitiveAttributes(
  pr: Json,
  path: string,
  accessors: Json[],
  quantized: boolean,
): void {
  if (!isObject(pr.attributes))
    fail(`${path}.attributes`, `is required, an object; got ${describeValue(pr.attributes)}`);
  const base = new Set<string>();
  for (const [name, v] of Object.entries(pr.attributes)) {
    const p = `${path}.attributes.${name}`;
    const a = indexValue(v, p, accessors.length, 'accessors');
    const sem = semantic(name);
    if (sem === null) {
      if (!name.startsWith('_'))
        fail(
          p,
          'is not a glTF attribute semantic (application-specific names must start with "_", §3.7.2.1)',
        );
    } else {
      checkOne(name, a, accessors, p, RULES[sem], quantized);
    }
    base.add(name);
  }
  if (pr.targets === undefined) return;
  if (!Array.isArray(pr.targets))
    fail(`${path}.targets`, `must be an array, got ${describeValue(pr.targets)}`);
  pr.targets.forEach((t, k) => {
    const tp = `${path}.targets[${k}]`;
    if (!isObject(t)) fail(tp, `must be an object, got ${describeValue(t)}`);
    for (const [name, v] of Object.entries(t)) {
      const p = `${tp}.${name}`;
      const a = indexValue(v, p, accessors.length, 'accessors');
      const sem = semantic(name);
      const rule = sem === null ? undefined : TARGET_RULES[sem];
      if (rule !== undefined) checkOne(name, a, accessors, p, rule, quantized);
      else if (!name.startsWith('_'))
        fail(p, 'is not a morph target attribute (POSITION, NORMAL, TANGENT, TEXCOORD_n, COLOR_n)');
      if (!base.has(name)) fail(p, `the primitive has no ${name} attribute for it to displace`);
    }
  });
}

/**
 * One count per primitive (validator: MESH_PRIMITIVE_UNEQUAL_ACCESSOR_COUNT) and per
 * morph target. Run once the byte ranges are checked (validate-buffers.ts), so that a
 * count that lies about the data is reported as the bytes it would need.
 */
export function checkPrimitiveCounts(json: Json): void {
  const accessors = (json.accessors as Json[] | undefined) ?? [];
  ((json.meshes as Json[] | undefined) ?? []).forEach((mesh, i) => {
    (mesh.primitives as Json[]).forEach((pr, j) => {
      const path = `meshes[${i}].primitives[${j}]`;
      let count = -1;
      let first = '';
      for (const [name, a] of Object.entries(pr.attributes as Json)) {
        const n = accessors[a as number].count as number;
        if (count < 0) {
          count = n;
          first = name;
        } else if (n !== count) {
          fail(
            `${path}.attributes.${name}`,
            `has ${n} elements, but ${first} has ${count}; a primitive's attributes have one count`,
          );
        }
      }
      ((pr.targets as Json[] | undefined) ?? []).forEach((t, k) => {
        for (const [name, a] of Object.entries(t)) {
          const n = accessors[a as number].count as number;
          if (n !== count)
            fail(
              `${path}.targets[${k}].${name}`,
              `has ${n} elements, but the primitive's attributes have ${count}`,
            );
        }
      });
    });
  });
}

/**
 * §3.6.2.1 (buffer views): "When two or more vertex attribute accessors use the same
 * bufferView, its byteStride MUST be defined" (validator:
 * MESH_PRIMITIVE_ACCESSOR_WITHOUT_BYTESTRIDE). Without it, the elements of the two
 * accessors are interleaved in a way no stride describes: the file is corrupt.
 */
export function checkSharedVertexViews(json: Json): void {
  const accessors = (json.accessors as Json[] | undefined) ?? [];
  const views = (json.bufferViews as Json[] | undefined) ?? [];
  const users = new Map<number, number>();
  const use = (a: number, path: string): void => {
    const v = accessors[a].bufferView;
    if (typeof v !== 'number' || views[v].byteStride !== undefined) return;
    const other = users.get(v);
    if (other === undefined) users.set(v, a);
    else if (other !== a)
      fail(
        path,
        `accessors[${a}] and accessors[${other}] both read bufferViews[${v}], which has no byteStride (required when vertex accessors share a view)`,
      );
  };
  ((json.meshes as Json[] | undefined) ?? []).forEach((mesh, i) => {
    (mesh.primitives as Json[]).forEach((pr, j) => {
      const p = `meshes[${i}].primitives[${j}]`;
      for (const [name, a] of Object.entries(pr.attributes as Json))
        use(a as number, `${p}.attributes.${name}`);
      ((pr.targets as Json[] | undefined) ?? []).forEach((t, k) => {
        for (const [name, a] of Object.entries(t)) use(a as number, `${p}.targets[${k}].${name}`);
      });
    });
  });
}
