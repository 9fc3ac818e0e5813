/**
 * The parts of a glTF document that pathwise reads little or not at all but
 * that must still be well formed, since a bad index there means a corrupt
 * file (glTF 2.0 §5): skins (§3.7.3), animations (§3.11), samplers
 * (§3.8.4), cameras (§3.10, §5.12–5.14) and materials' alphaMode (§3.9.4).
 * Each check names the JSON path, the problem and the value.
 */
import {
  describeValue,
  fail,
  index,
  indexArray,
  indexValue,
  isObject,
  list,
  positive,
  type Json,
} from './validate-values.ts';

/** The document's arrays, as validate.ts has checked them. */
export interface Arrays {
  accessors: Json[];
  nodes: Json[];
  meshes: Json[];
  cameras: Json[];
}

export function checkSamplers(samplers: Json[]): void {
  samplers.forEach((s, i) => {
    const p = `samplers[${i}]`;
    // §5.26 sampler: the WebGL enums of texParameteri. The schema leaves them open (the
    // validator warns on others). pathwise filters bilinearly whatever the file says, so
    // a filter need only be an integer; a wrap mode it must apply, so it must know it.
    for (const k of ['magFilter', 'minFilter']) {
      if (s[k] !== undefined && !Number.isInteger(s[k]))
        fail(`${p}.${k}`, `must be an integer, got ${describeValue(s[k])}`);
    }
    for (const k of ['wrapS', 'wrapT']) {
      const v = s[k];
      if (v !== undefined && v !== 33071 && v !== 33648 && v !== 10497)
        fail(`${p}.${k}`, `must be one of 33071, 33648, 10497, got ${describeValue(v)}`);
    }
  });
}

/**
 * Morph targets (§3.7.2.2), which pathwise does not apply: each target names at least
 * one attribute, every primitive of a mesh has as many, and mesh.weights has one
 * number per target.
 */
export function checkMorphTargets(mesh: Json, p: string): void {
  const prims = mesh.primitives as Json[];
  const counts = prims.map((pr) => (Array.isArray(pr.targets) ? pr.targets.length : 0));
  prims.forEach((pr, j) => {
    ((pr.targets as Json[] | undefined) ?? []).forEach((t, k) => {
      if (Object.keys(t).length === 0)
        fail(`${p}.primitives[${j}].targets[${k}]`, 'must name at least one attribute');
    });
    if (counts[j] !== counts[0])
      fail(
        `${p}.primitives[${j}].targets`,
        `has ${counts[j]} morph targets, but primitives[0] has ${counts[0]}; a mesh's primitives have as many`,
      );
  });
  const w = mesh.weights;
  if (w === undefined) return;
  if (!Array.isArray(w) || !w.every((x) => typeof x === 'number' && Number.isFinite(x)))
    fail(`${p}.weights`, `must be an array of finite numbers, got ${describeValue(w)}`);
  if (w.length !== counts[0])
    fail(`${p}.weights`, `has ${w.length} weights for ${counts[0]} morph targets`);
}

export function checkSkins(json: Json, a: Arrays): Json[] {
  const skins = list(json, 'skins');
  skins.forEach((s, i) => {
    const p = `skins[${i}]`;
    if (s.joints === undefined) fail(`${p}.joints`, 'is required');
    const joints = indexArray(s, 'joints', p, a.nodes.length, 'nodes');
    if (joints.length === 0) fail(`${p}.joints`, 'must not be empty');
    index(s, 'skeleton', p, a.nodes.length, 'nodes');
    const ibm = index(s, 'inverseBindMatrices', p, a.accessors.length, 'accessors');
    if (ibm !== undefined) {
      const acc = a.accessors[ibm];
      if (acc.type !== 'MAT4' || acc.componentType !== 5126)
        fail(`${p}.inverseBindMatrices`, `accessors[${ibm}] must be MAT4 of FLOAT (§3.7.3.1)`);
      if ((acc.count as number) < joints.length)
        fail(
          `${p}.inverseBindMatrices`,
          `accessors[${ibm}] has ${acc.count as number} matrices for ${joints.length} joints`,
        );
    }
  });
  return skins;
}

export function checkAnimations(json: Json, a: Arrays): void {
  list(json, 'animations').forEach((anim, i) => {
    const p = `animations[${i}]`;
    const samplers = list(anim, 'samplers', `${p}.samplers`);
    const channels = list(anim, 'channels', `${p}.channels`);
    if (samplers.length === 0) fail(`${p}.samplers`, 'is required and must not be empty');
    if (channels.length === 0) fail(`${p}.channels`, 'is required and must not be empty');
    samplers.forEach((s, j) => {
      const sp = `${p}.samplers[${j}]`;
      for (const k of ['input', 'output']) {
        if (s[k] === undefined) fail(`${sp}.${k}`, 'is required');
        indexValue(s[k], `${sp}.${k}`, a.accessors.length, 'accessors');
      }
      const input = a.accessors[s.input as number];
      if (input.type !== 'SCALAR' || input.componentType !== 5126)
        fail(`${sp}.input`, `accessors[${s.input as number}] must be SCALAR of FLOAT (§3.11)`);
      // An open enum, and the animation is not played: a string is enough.
      if (s.interpolation !== undefined && typeof s.interpolation !== 'string')
        fail(`${sp}.interpolation`, `must be a string, got ${describeValue(s.interpolation)}`);
    });
    channels.forEach((c, j) => {
      const cp = `${p}.channels[${j}]`;
      if (c.sampler === undefined) fail(`${cp}.sampler`, 'is required');
      indexValue(c.sampler, `${cp}.sampler`, samplers.length, `${p}.samplers`);
      if (!isObject(c.target))
        fail(`${cp}.target`, `is required, an object; got ${describeValue(c.target)}`);
      index(c.target, 'node', `${cp}.target`, a.nodes.length, 'nodes');
      if (c.target.path === undefined) fail(`${cp}.target.path`, 'is required');
      // An open enum (the core's four paths; extensions add others): the animation is
      // not played, so its path need only be a string.
      if (typeof c.target.path !== 'string')
        fail(`${cp}.target.path`, `must be a string, got ${describeValue(c.target.path)}`);
    });
  });
}

/**
 * A camera (§5.12–5.14): its type, and the numbers the projection divides by, in the
 * ranges the schema gives. pathwise frames with a perspective camera's yfov, which must
 * also be below π (the validator only warns there, CAMERA_YFOV_GEQUAL_PI): a
 * perspective projection of 180° or more has no image plane.
 */
export function checkCameras(cameras: Json[]): void {
  cameras.forEach((c, i) => {
    const p = `cameras[${i}]`;
    if (c.type === undefined) fail(`${p}.type`, 'is required ("perspective" or "orthographic")');
    if (typeof c.type !== 'string')
      fail(`${p}.type`, `must be a string, got ${describeValue(c.type)}`);
    // An open enum in the schema (the validator warns), but glTF-Transform, which parses
    // the document, reads any other type as orthographic and fails on it.
    if (c.type !== 'perspective' && c.type !== 'orthographic')
      fail(
        `${p}.type`,
        `${describeValue(c.type)} is not a camera type pathwise reads ("perspective", "orthographic")`,
      );
    const key = c.type as string;
    const other = key === 'perspective' ? 'orthographic' : 'perspective';
    const proj = c[key];
    if (!isObject(proj))
      fail(`${p}.${key}`, `is required for a camera of type "${key}", got ${describeValue(proj)}`);
    if (c[other] !== undefined)
      fail(`${p}.${other}`, `must be absent: the camera's type is "${key}"`);
    const pp = `${p}.${key}`;
    let znear: number | undefined;
    if (key === 'perspective') {
      if (proj.yfov === undefined) fail(`${pp}.yfov`, 'is required');
      const yfov = positive(proj, 'yfov', pp)!;
      if (yfov >= Math.PI)
        fail(
          `${pp}.yfov`,
          `is out of range: a perspective field of view must be below π (180°), got ${yfov} radians`,
        );
      positive(proj, 'aspectRatio', pp);
      if (proj.znear === undefined) fail(`${pp}.znear`, 'is required');
      znear = positive(proj, 'znear', pp);
    } else {
      for (const k of ['xmag', 'ymag']) {
        const v = proj[k];
        if (typeof v !== 'number' || v === 0 || !Number.isFinite(v))
          fail(`${pp}.${k}`, `must be a finite number other than 0, got ${describeValue(v)}`);
      }
      const zn = proj.znear;
      if (typeof zn !== 'number' || !(zn >= 0) || !Number.isFinite(zn))
        fail(`${pp}.znear`, `must be a finite number of at least 0, got ${describeValue(zn)}`);
      znear = zn;
      if (proj.zfar === undefined) fail(`${pp}.zfar`, 'is required');
    }
    const zfar = positive(proj, 'zfar', pp);
    if (zfar !== undefined && znear !== undefined && !(zfar > znear))
      fail(`${pp}.zfar`, `must be greater than znear (${znear}), got ${zfar}`);
  });
}

/** A node's skin and morph weights need a mesh (node.schema.json "dependencies"). */
export function checkNodeFeatures(n: Json, p: string, a: Arrays, skins: Json[]): void {
  const skin = index(n, 'skin', p, skins.length, 'skins');
  if (skin !== undefined && n.mesh === undefined)
    fail(`${p}.skin`, 'needs a mesh on the same node');
  if (n.weights !== undefined) {
    if (n.mesh === undefined) fail(`${p}.weights`, 'needs a mesh on the same node');
    if (!Array.isArray(n.weights) || !n.weights.every((w) => typeof w === 'number'))
      fail(`${p}.weights`, `must be an array of numbers, got ${describeValue(n.weights)}`);
  }
  // §3.5.2: "a node can have either a matrix or any combination of translation/rotation/scale".
  if (n.matrix !== undefined) {
    const trs = ['translation', 'rotation', 'scale'].filter((k) => n[k] !== undefined);
    if (trs.length > 0)
      fail(p, `has both matrix and ${trs.join(', ')}; a node has one or the other (§3.5.2)`);
  }
}

/**
 * §3.9.4 alpha coverage: "OPAQUE", "MASK" or "BLEND". The schema admits any string (an
 * open enum, for later versions; the validator warns, VALUE_NOT_IN_LIST), so another
 * string is not an error: it is rendered OPAQUE, the default, and the note says so.
 */
export function alphaModeNote(m: Json, p: string): string | undefined {
  const v = m.alphaMode;
  if (v === undefined || v === 'OPAQUE' || v === 'MASK' || v === 'BLEND') return undefined;
  if (typeof v !== 'string') fail(`${p}.alphaMode`, `must be a string, got ${describeValue(v)}`);
  return `${p}.alphaMode: ${describeValue(v)} is not "OPAQUE", "MASK" or "BLEND" (upper case); the material is rendered OPAQUE`;
}
