import { readFileSync, readdirSync } from 'node:fs';
import { describe, it, expect } from 'vitest';
import {
  SceneError,
  parseScene,
  validateScene,
  validateSettingsOverride,
} from '../../../src/core/scene/validate/validate.ts';
import { DEFAULT_SETTINGS, LIMITS } from '../../../src/core/scene/format/types.ts';
import { utf8Length } from '../../../src/core/scene/validate/validate-helpers.ts';

const scenesDir = new URL('../../../scenes/', import.meta.url);
const sceneFiles = readdirSync(scenesDir).filter((f) => f.endsWith('.json'));

/** A small valid scene as plain JS; each call returns a fresh copy to mutate. */
function base(): any {
  return {
    format: 'pathwise-scene/1',
    name: 'test',
    camera: { position: [0, 0, -4], target: [0, 0, 0], up: [0, 1, 0], fovY: 40 },
    settings: { width: 32, height: 16, maxBounces: 4, spp: 8 },
    materials: {
      red: { type: 'diffuse', albedo: [0.6, 0.1, 0.1] },
      green: { type: 'diffuse', albedo: [0.1, 0.6, 0.1] },
      steel: { type: 'conductor', color: [0.5, 0.5, 0.5], roughness: 0.2 },
      glass: { type: 'dielectric', ior: 1.5 },
    },
    shapes: [
      { type: 'sphere', center: [0, 0, 0], radius: 1, material: 'red' },
      { type: 'quad', corner: [-5, -1, -5], u: [0, 0, 10], v: [10, 0, 0], material: 'green' },
      { type: 'sphere', center: [2, 0, 0], radius: 0.5, material: 'steel' },
      { type: 'sphere', center: [-2, 0, 0], radius: 0.5, material: 'glass' },
    ],
  };
}

/** The SceneError that validating `value` throws (fails the test if none is thrown). */
function errorOf(run: () => unknown): SceneError {
  try {
    run();
  } catch (e) {
    expect(e).toBeInstanceOf(SceneError);
    return e as SceneError;
  }
  throw new Error('expected a SceneError, but the input was accepted');
}

function problemsOf(value: unknown): string[] {
  return errorOf(() => validateScene(value)).problems;
}

/** Asserts that some problem contains `text` (the path and the offending value). */
function expectProblem(value: unknown, text: string): void {
  const problems = problemsOf(value);
  expect(
    problems.some((p) => p.includes(text)),
    problems.join('\n'),
  ).toBe(true);
}

describe('canonical scenes', () => {
  it.each(sceneFiles)('%s loads and gets its defaults filled', (file) => {
    const text = readFileSync(new URL(file, scenesDir), 'utf8');
    const raw = JSON.parse(text);
    const scene = parseScene(text);
    expect(scene.format).toBe('pathwise-scene/1');
    expect(scene.name).toBe(raw.name);
    expect(scene.camera.aperture).toBe(0);
    const [p, t] = [raw.camera.position, raw.camera.target];
    expect(scene.camera.focusDistance).toBeCloseTo(
      Math.hypot(t[0] - p[0], t[1] - p[1], t[2] - p[2]),
      12,
    );
    expect(scene.settings).toEqual(raw.settings);
    if (Array.isArray(raw.environment) || raw.environment === undefined) {
      expect(scene.environment).toEqual(raw.environment ?? [0, 0, 0]);
      expect(scene.environmentMap).toBeNull();
    } else {
      // An environment map: its file is read later (resolveSceneFiles), its defaults now.
      expect(scene.environment).toEqual([0, 0, 0]);
      expect(scene.environmentMap).toMatchObject({ type: 'map', file: raw.environment.file });
    }
    expect(scene.shapes).toHaveLength(raw.shapes.length);
    for (const [name, m] of Object.entries(scene.materials)) {
      expect(m.emission).toEqual(raw.materials[name].emission ?? [0, 0, 0]);
    }
  });

  it('covers at least the six canonical scenes', () => {
    expect(sceneFiles.length).toBeGreaterThanOrEqual(6);
  });
});

describe('defaults and output', () => {
  it('fills name, settings, environment, aperture, focusDistance, emission, glass defaults', () => {
    const s = base();
    delete s.name;
    delete s.settings;
    const scene = validateScene(s);
    expect(scene.name).toBe('');
    expect(scene.settings).toEqual(DEFAULT_SETTINGS);
    expect(scene.environment).toEqual([0, 0, 0]);
    expect(scene.camera.aperture).toBe(0);
    expect(scene.camera.focusDistance).toBe(4);
    expect(scene.materials.red.emission).toEqual([0, 0, 0]);
    expect(scene.materials.glass).toEqual({
      type: 'dielectric',
      ior: 1.5,
      color: [1, 1, 1],
      roughness: 0,
      emission: [0, 0, 0],
    });
  });

  it('keeps given optional values and fills missing settings keys from the defaults', () => {
    const s = base();
    s.camera.aperture = 0.1;
    s.camera.focusDistance = 3;
    s.settings = { spp: 16 };
    s.environment = [0.5, 0.5, 0.5];
    const scene = validateScene(s);
    expect(scene.camera.aperture).toBe(0.1);
    expect(scene.camera.focusDistance).toBe(3);
    expect(scene.settings).toEqual({ ...DEFAULT_SETTINGS, spp: 16 });
    expect(scene.environment).toEqual([0.5, 0.5, 0.5]);
  });

  it('returns a fresh object that shares no arrays with the input', () => {
    const s = base();
    const scene = validateScene(s);
    expect(scene.camera.position).not.toBe(s.camera.position);
    expect(scene.shapes).not.toBe(s.shapes);
    s.camera.position[0] = 99;
    s.shapes[0].radius = 7;
    expect(scene.camera.position[0]).toBe(0);
    expect((scene.shapes[0] as { radius: number }).radius).toBe(1);
  });

  it('keeps odd material names as own keys and quotes them in paths', () => {
    const s = base();
    s.materials = JSON.parse('{"__proto__": {"type": "diffuse", "albedo": [0.5, 0.5, 0.5]}}');
    s.shapes = [{ type: 'sphere', center: [0, 0, 0], radius: 1, material: '__proto__' }];
    const scene = validateScene(s);
    expect(Object.hasOwn(scene.materials, '__proto__')).toBe(true);
    expect(scene.materials['__proto__'].type).toBe('diffuse');

    const bad = base();
    bad.materials['my mat'] = { type: 'diffuse', albedo: [2, 0, 0] };
    expectProblem(bad, 'materials["my mat"].albedo[0] must be in [0, 1], got 2');
  });
});

describe('top level', () => {
  it.each([
    [null, 'scene must be an object, got null'],
    [[1, 2], 'scene must be an object, got [1, 2]'],
    ['scene', 'scene must be an object, got the string "scene"'],
    [42, 'scene must be an object, got 42'],
  ])('rejects a non-object scene %j', (value, text) => {
    expect(errorOf(() => validateScene(value)).message).toBe(text);
  });

  it('requires the exact format string, and leads with it', () => {
    const s = base();
    s.format = 'pathwise-scene/2';
    s.shapes[0].radius = -1;
    const problems = problemsOf(s);
    expect(problems[0]).toBe('format must be "pathwise-scene/1", got "pathwise-scene/2"');
    delete s.format;
    expect(problemsOf(s)[0]).toContain('format is required but missing');
  });

  it.each(['camera', 'materials', 'shapes'])('requires %s', (key) => {
    const s = base();
    delete s[key];
    expectProblem(s, `${key} is required but missing`);
  });

  it('rejects an unknown top-level key with a suggestion', () => {
    const s = base();
    s.enviroment = [1, 1, 1];
    expectProblem(s, 'enviroment is not a known key (did you mean environment?)');
  });

  it('rejects a name that is not a string', () => {
    const s = base();
    s.name = 5;
    expectProblem(s, 'name must be a string, got 5');
  });

  it('rejects objects given as arrays or null', () => {
    const s = base();
    s.camera = [0, 0, 0];
    s.materials = null;
    s.settings = [];
    const problems = problemsOf(s);
    expect(problems).toContain('camera must be an object, got [0, 0, 0]');
    expect(problems).toContain('materials must be an object, got null');
    expect(problems).toContain('settings must be an object, got []');
  });
});

describe('types of values', () => {
  it('rejects a misspelt key and reports the key it should have been', () => {
    const s = base();
    s.camera.fovy = 40;
    delete s.camera.fovY;
    const problems = problemsOf(s);
    expect(problems).toContain('camera.fovy is not a known key (did you mean fovY?)');
    expect(problems.some((p) => p.startsWith('camera.fovY is required but missing'))).toBe(true);
  });

  it('rejects NaN and Infinity given through validateScene', () => {
    const s = base();
    s.camera.fovY = NaN;
    s.shapes[0].center = [0, Infinity, 0];
    const problems = problemsOf(s);
    expect(problems).toContain('camera.fovY must be a finite number, got NaN');
    expect(problems).toContain('shapes[0].center[1] must be a finite number, got Infinity');
  });

  it('rejects numbers given as strings', () => {
    const s = base();
    s.shapes[0].radius = '1';
    s.settings.spp = '512';
    const problems = problemsOf(s);
    expect(problems).toContain(
      'shapes[0].radius must be a finite number, got the string "1" (numbers must not be quoted)',
    );
    expect(
      problems.some((p) => p.startsWith('settings.spp') && p.includes('got the string "512"')),
    ).toBe(true);
  });

  it('requires vectors of exactly 3 numbers', () => {
    const s = base();
    s.camera.up = [0, 1];
    s.shapes[1].u = { x: 1 };
    s.shapes[0].center = [0, 0, 0, 0];
    const problems = problemsOf(s);
    expect(problems).toContain('camera.up must be an array of 3 numbers, got [0, 1]');
    expect(problems).toContain('shapes[1].u must be an array of 3 numbers, got an object');
    expect(problems).toContain('shapes[0].center must be an array of 3 numbers, got [0, 0, 0, 0]');
  });
});

describe('camera', () => {
  it('rejects position equal to target', () => {
    const s = base();
    s.camera.target = [0, 0, -4];
    expectProblem(s, 'camera.target must differ from camera.position, both are [0, 0, -4]');
  });

  it('rejects a zero up vector', () => {
    const s = base();
    s.camera.up = [0, 0, 0];
    expectProblem(s, 'camera.up must be non-zero, got [0, 0, 0]');
  });

  it('rejects up parallel to target - position, whatever their lengths', () => {
    const s = base();
    s.camera.up = [0, 0, -1e-3];
    expectProblem(s, 'camera.up must not be parallel to camera.target - camera.position');
    s.camera.up = [1e-8, 0, 1e6]; // sin(angle) = 1e-14: parallel to within the tolerance
    expectProblem(s, 'got up [1e-8, 0, 1000000]');
    s.camera.up = [1e-3, 0, 1];
    expect(() => validateScene(s)).not.toThrow();
  });

  it('requires 0 < fovY < 180', () => {
    for (const fovY of [0, -10, 180, 200]) {
      const s = base();
      s.camera.fovY = fovY;
      expectProblem(s, `camera.fovY must be in (0, 180) degrees, got ${fovY}`);
    }
    const s = base();
    s.camera.fovY = 179.5;
    expect(validateScene(s).camera.fovY).toBe(179.5);
  });

  it('requires aperture >= 0 and focusDistance > 0', () => {
    const s = base();
    s.camera.aperture = -0.5;
    s.camera.focusDistance = 0;
    const problems = problemsOf(s);
    expect(problems).toContain('camera.aperture must be >= 0, got -0.5');
    expect(problems).toContain('camera.focusDistance must be > 0, got 0');
  });
});

describe('settings', () => {
  it('requires width and height to be positive integers', () => {
    const s = base();
    s.settings.width = 0;
    s.settings.height = 12.5;
    const problems = problemsOf(s);
    expect(problems).toContain('settings.width must be an integer >= 1, got 0');
    expect(problems).toContain('settings.height must be an integer >= 1, got 12.5');
  });

  it('limits width * height to LIMITS.pixels', () => {
    const s = base();
    s.settings.width = 4096;
    s.settings.height = 4097;
    expectProblem(
      s,
      `settings.width * settings.height must be at most ${LIMITS.pixels} pixels, ` +
        'got 4096 * 4097 = 16781312',
    );
    s.settings.height = 4096;
    expect(validateScene(s).settings.height).toBe(4096);
  });

  it('limits spp to [1, LIMITS.spp]', () => {
    for (const spp of [0, LIMITS.spp + 1, 2.5]) {
      const s = base();
      s.settings.spp = spp;
      expectProblem(s, `settings.spp must be an integer in [1, 1048576], got ${spp}`);
    }
    const s = base();
    s.settings.spp = LIMITS.spp;
    expect(validateScene(s).settings.spp).toBe(LIMITS.spp);
  });

  it('limits maxBounces to [0, LIMITS.maxBounces]', () => {
    for (const maxBounces of [-1, LIMITS.maxBounces + 1]) {
      const s = base();
      s.settings.maxBounces = maxBounces;
      expectProblem(s, `settings.maxBounces must be an integer in [0, 64], got ${maxBounces}`);
    }
    for (const maxBounces of [0, LIMITS.maxBounces]) {
      const s = base();
      s.settings.maxBounces = maxBounces;
      expect(validateScene(s).settings.maxBounces).toBe(maxBounces);
    }
  });

  it('rejects unknown settings keys', () => {
    const s = base();
    s.settings.samples = 16;
    expectProblem(s, 'settings.samples is not a known key');
  });
});

describe('materials', () => {
  it('rejects an unknown material type', () => {
    const s = base();
    s.materials.red.type = 'plastic';
    expectProblem(
      s,
      'materials.red.type must be one of "diffuse", "conductor", "dielectric", got "plastic"',
    );
  });

  it('requires albedo components in [0, 1]', () => {
    const s = base();
    s.materials.red.albedo = [0.5, 1.5, 0];
    expectProblem(s, 'materials.red.albedo[1] must be in [0, 1], got 1.5');
  });

  it('requires conductor color and roughness in [0, 1], roughness present', () => {
    const s = base();
    s.materials.steel.color = [-0.1, 0.5, 0.5];
    s.materials.steel.roughness = 1.2;
    const problems = problemsOf(s);
    expect(problems).toContain('materials.steel.color[0] must be in [0, 1], got -0.1');
    expect(problems).toContain('materials.steel.roughness must be in [0, 1], got 1.2');
    delete s.materials.steel.roughness;
    expectProblem(s, 'materials.steel.roughness is required but missing');
  });

  it('rejects keys of another material type', () => {
    const s = base();
    s.materials.red.roughness = 0.5;
    s.materials.steel.albedo = [1, 1, 1];
    const problems = problemsOf(s);
    expect(problems).toContain('materials.red.roughness is not a known key');
    expect(problems).toContain('materials.steel.albedo is not a known key');
  });

  it('requires ior > 0 and finite', () => {
    for (const [ior, got] of [
      [0, '0'],
      [-1.5, '-1.5'],
      [Infinity, 'Infinity'],
    ] as const) {
      const s = base();
      s.materials.glass.ior = ior;
      expectProblem(
        s,
        `materials.glass.ior must be ${ior === Infinity ? 'a finite number' : '> 0'}, got ${got}`,
      );
    }
  });

  it('requires emission components >= 0 and finite', () => {
    const s = base();
    s.materials.red.emission = [1, -2, 1];
    expectProblem(s, 'materials.red.emission[1] must be >= 0, got -2');
    s.materials.red.emission = [1, 1, NaN];
    expectProblem(s, 'materials.red.emission[2] must be a finite number, got NaN');
  });

  it('rejects rough dielectrics as unsupported', () => {
    const s = base();
    s.materials.frosted = { type: 'dielectric', ior: 1.5, roughness: 0.3 };
    expectProblem(
      s,
      'materials.frosted.roughness: rough dielectric (roughness > 0) is not supported by ' +
        'pathwise; use roughness 0',
    );
  });

  it('rejects a material that is not an object', () => {
    const s = base();
    s.materials.red = 'red';
    expectProblem(s, 'materials.red must be an object, got the string "red"');
  });
});

describe('shapes', () => {
  it('requires shapes to be an array', () => {
    const s = base();
    s.shapes = { 0: s.shapes[0] };
    expectProblem(s, 'shapes must be an array, got an object');
  });

  it(`limits the number of shapes to ${LIMITS.shapes}`, () => {
    const sphere = { type: 'sphere', center: [0, 0, 0], radius: 1, material: 'red' };
    const s = base();
    s.shapes = Array.from({ length: LIMITS.shapes + 1 }, () => ({ ...sphere }));
    expectProblem(s, 'shapes has 100001 entries, more than the limit of 100000');
    s.shapes.pop();
    expect(validateScene(s).shapes).toHaveLength(LIMITS.shapes);
  });

  it('rejects an unknown shape type and a shape that is not an object', () => {
    const s = base();
    s.shapes[0].type = 'cube';
    s.shapes[1] = null;
    const problems = problemsOf(s);
    expect(problems).toContain(
      'shapes[0].type must be one of "sphere", "quad", "mesh", "gltf", got "cube"',
    );
    expect(problems).toContain('shapes[1] must be an object, got null');
  });

  it('requires every key of a shape and rejects unknown ones', () => {
    const s = base();
    delete s.shapes[1].v;
    s.shapes[0].radus = 1;
    const problems = problemsOf(s);
    expect(problems.some((p) => p.startsWith('shapes[1].v is required but missing'))).toBe(true);
    expect(problems).toContain('shapes[0].radus is not a known key (did you mean radius?)');
  });

  it('requires sphere radius > 0', () => {
    const s = base();
    s.shapes[3].radius = -2;
    expect(errorOf(() => validateScene(s)).message).toBe('shapes[3].radius must be > 0, got -2');
  });

  it('rejects a reference to an unknown material, suggesting a close name', () => {
    const s = base();
    s.shapes[1].material = 'gren';
    expectProblem(s, 'shapes[1].material names unknown material "gren" (did you mean "green"?)');
    s.shapes[1].material = 'toString';
    expectProblem(s, 'shapes[1].material names unknown material "toString"');
  });

  it('rejects degenerate quads: parallel or zero edges', () => {
    for (const [u, v] of [
      [
        [1, 0, 0],
        [-3, 0, 0],
      ],
      [
        [0, 0, 0],
        [1, 0, 0],
      ],
    ]) {
      const s = base();
      s.shapes[4] = { type: 'quad', corner: [0, 0, 0], u, v, material: 'red' };
      expectProblem(s, 'shapes[4] is a degenerate quad: u and v are parallel or zero (area 0)');
    }
  });

  it('rejects quads whose area is 0 or not finite in double precision', () => {
    const s = base();
    s.shapes[4] = {
      type: 'quad',
      corner: [0, 0, 0],
      u: [1e-200, 0, 0],
      v: [0, 1e-200, 0],
      material: 'red',
    };
    expectProblem(
      s,
      'shapes[4] is a degenerate quad: its area |u x v| underflows to 0 in double precision',
    );
    s.shapes[4].u = [1e200, 0, 0];
    s.shapes[4].v = [0, 0, 1e200];
    expectProblem(s, 'shapes[4] is too large: its area |u x v| overflows double precision');
  });

  it('accepts tiny, huge and nearly parallel quads whose area is finite and non-zero', () => {
    const s = base();
    s.shapes.push(
      { type: 'quad', corner: [0, 0, 0], u: [1e-9, 0, 0], v: [0, 1e-9, 0], material: 'red' },
      { type: 'quad', corner: [0, 0, 0], u: [1e150, 0, 0], v: [0, 0, 1e150], material: 'red' },
      // sin(angle) = 1e-14, area 1e-2: thin, but a non-zero area in double precision.
      { type: 'quad', corner: [0, 0, 0], u: [1e6, 0, 0], v: [1e6, 1e-8, 0], material: 'red' },
      // |u x v| = 1e-200 underflows nothing once the edges are scaled.
      { type: 'quad', corner: [0, 0, 0], u: [1e-200, 0, 0], v: [0, 1, 0], material: 'red' },
    );
    expect(validateScene(s).shapes).toHaveLength(8);
  });
});

describe('environment', () => {
  it('requires 3 finite numbers >= 0', () => {
    const s = base();
    s.environment = [1, -1, 1];
    expectProblem(s, 'environment[1] must be >= 0, got -1');
    s.environment = [1, 1];
    expectProblem(s, 'environment must be an array of 3 numbers, got [1, 1]');
  });
});

describe('SceneError and collecting problems', () => {
  it('reports every problem, leading with a concrete one', () => {
    const s = base();
    s.shapes[0].radius = 0;
    s.materials.red.albedo = [2, 0, 0];
    s.settings.spp = 0;
    const error = errorOf(() => validateScene(s));
    expect(error.name).toBe('SceneError');
    expect(error).toBeInstanceOf(Error);
    expect(error.problems).toHaveLength(3);
    expect(error.problems).toEqual(
      expect.arrayContaining([
        'shapes[0].radius must be > 0, got 0',
        'materials.red.albedo[0] must be in [0, 1], got 2',
        'settings.spp must be an integer in [1, 1048576], got 0',
      ]),
    );
    expect(error.message).toBe(`${error.problems[0]} (and 2 more problems)`);
  });

  it('uses the single problem as the message', () => {
    const s = base();
    s.environment = [0, 0, -1];
    const error = errorOf(() => validateScene(s));
    expect(error.problems).toEqual(['environment[2] must be >= 0, got -1']);
    expect(error.message).toBe('environment[2] must be >= 0, got -1');
  });
});

describe('parseScene', () => {
  it('rejects invalid JSON naming the line and column', () => {
    const text = '{"format": "pathwise-scene/1",\n  }';
    expect(errorOf(() => parseScene(text)).message).toBe(
      `scene file is not valid JSON: line 2, column 3: expected a key in double quotes, got "}"`,
    );
  });

  it('accepts a leading byte-order mark', () => {
    expect(parseScene('\ufeff' + JSON.stringify(base())).name).toBe('test');
  });

  it('rejects text over 16 MiB, counting UTF-8 bytes', () => {
    const json = JSON.stringify(base());
    const exact = json + ' '.repeat(LIMITS.fileBytes - json.length);
    expect(parseScene(exact).name).toBe('test');
    expect(errorOf(() => parseScene(exact + ' ')).message).toBe(
      `scene file must be at most ${LIMITS.fileBytes} bytes (16 MiB), got at least 16777217 bytes`,
    );
    // Fewer UTF-16 code units than the limit, but 3 UTF-8 bytes each: 18 MiB.
    const s = base();
    s.name = '\u20ac'.repeat(6 * 1024 * 1024);
    const wide = JSON.stringify(s);
    expect(wide.length).toBeLessThan(LIMITS.fileBytes);
    expect(errorOf(() => parseScene(wide)).message).toBe(
      `scene file must be at most ${LIMITS.fileBytes} bytes (16 MiB), ` +
        `got ${Buffer.byteLength(wide, 'utf8')} bytes`,
    );
  });

  it('counts UTF-8 bytes as TextEncoder does, surrogates included', () => {
    const text = 'a\u00e9\u20ac\u{1f600}\ud800x\udc00\ud83d';
    expect(utf8Length(text, LIMITS.fileBytes)).toBe(new TextEncoder().encode(text).length);
  });
});

describe('validateSettingsOverride', () => {
  const settings = { width: 64, height: 64, maxBounces: 4, spp: 16 };

  it('applies overrides and ignores undefined ones', () => {
    expect(validateSettingsOverride(settings, { spp: 1024, width: undefined })).toEqual({
      ...settings,
      spp: 1024,
    });
  });

  it('names the command-line option in its messages', () => {
    expect(errorOf(() => validateSettingsOverride(settings, { spp: 0 })).message).toBe(
      '--spp must be an integer in [1, 1048576], got 0',
    );
    expect(
      errorOf(() => validateSettingsOverride(settings, { maxBounces: 100, width: -3 })).problems,
    ).toEqual([
      '--width must be an integer >= 1, got -3',
      '--maxBounces must be an integer in [0, 64], got 100',
    ]);
  });

  it('accepts a prefix or a naming function', () => {
    const kebab = (key: string) => '--' + key.replace(/[A-Z]/g, (c) => '-' + c.toLowerCase());
    expect(
      errorOf(() => validateSettingsOverride(settings, { maxBounces: 65 }, kebab)).message,
    ).toBe('--max-bounces must be an integer in [0, 64], got 65');
    expect(
      errorOf(() => validateSettingsOverride(settings, { spp: NaN }, 'settings.')).message,
    ).toBe('settings.spp must be an integer in [1, 1048576], got NaN');
  });

  it('enforces the pixel limit and rejects unknown keys', () => {
    expect(
      errorOf(() => validateSettingsOverride(settings, { width: 8192, height: 4096 })).message,
    ).toBe('--width * --height must be at most 16777216 pixels, got 8192 * 4096 = 33554432');
    const unknown = { samples: 4 } as unknown as Partial<typeof settings>;
    expect(errorOf(() => validateSettingsOverride(settings, unknown)).message).toBe(
      '--samples is not a known setting',
    );
  });
});
