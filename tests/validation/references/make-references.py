#!/usr/bin/env python3
"""Renders the independent references of the generated-scene validation.

For every scene file NAME.json in this folder (written by
`node scripts/run-ts.mjs tests/validation/export-references.ts`), two
independent renderers, each in P parts with different seeds:
  - Mitsuba 3 (../shared/tools/mitsuba_ref.py, single precision), with
    --cap-large-spheres so that a ground sphere far larger than the rest of
    the scene is an inscribed mesh cap rather than a float32 sphere;
  - the native anchor (../shared/anchors/native, double precision).
Mitsuba renders a similar copy of each scene: moved so that its content is
centred on the origin and scaled to a size of about 10. Radiance is invariant
under a similarity transform of the whole scene (lengths scale, emitted and
reflected radiance do not), and Mitsuba is not scale invariant: it offsets
spawned rays by (1 + max|p|) * RayEpsilon, an absolute ~1e-4 for coordinates
below 1, which at scale 1e-3 moves a grazing light's shadow boundary by a
visible amount (found on gen-grazing-2001 and -2004, see docs/validation.md).
Meshes are moved and scaled by the same similarity, folded into their
`transform` (positions and files stay as they are); mesh and environment-map
files are named by absolute paths in the copy, which lives elsewhere. A mesh
far larger than the rest (a ground sheet 100 times the size of the camera's
surroundings) is left out of the bounds, as a huge sphere is.
The native anchor renders the scene as it is; it renders only spheres and
quads under a constant environment, so a scene with a mesh or an environment
map (the generator's mesh family) has the Mitsuba reference alone.
From the parts it writes, per renderer, the per-pixel mean (NAME.R.pfm) and
the per-pixel variance of that mean, s^2 / P across the parts
(NAME.R-var.pfm), so the test can account for the reference's own noise.
references.json records spp, parts, seeds, timings and Mitsuba's notes.

Tests never run this; it needs Python with numpy and Mitsuba:
  bash ../shared/tools/setup_mitsuba_env.sh   (or a copy of tools/ elsewhere)
  sh ../shared/anchors/native/build.sh         (OUT_DIR=... for elsewhere)
  PY=path/to/.venv/bin/python
  $PY tests/validation/references/make-references.py \\
      --tools ../shared/tools --native /tmp/pathwise-native-anchor/pt [NAME ...]
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))


def needs_mitsuba_only(scene):
    """Whether the scene has a mesh or an environment map: the native anchor has neither."""
    return isinstance(scene.get("environment"), dict) or any(
        sh["type"] not in ("sphere", "quad") for sh in scene["shapes"])


def normalized(scene, huge_ratio, base_dir):
    """The scene moved and scaled so that its content (camera and every shape but
    spheres and meshes huge_ratio times larger than the rest) spans ~10 around the
    origin."""
    pts = [scene["camera"]["position"], scene["camera"]["target"]]
    for sh in scene["shapes"]:
        if sh["type"] == "quad":
            c, u, v = sh["corner"], sh["u"], sh["v"]
            pts += [[c[i] + a * u[i] + b * v[i] for i in range(3)] for a in (0, 1) for b in (0, 1)]
    small = [sh for sh in scene["shapes"] if sh["type"] == "sphere"]
    ext0 = np.ptp(np.array(pts), axis=0).max() if len(pts) > 2 else 0
    for sh in small:
        if sh["radius"] <= huge_ratio * max(ext0, 1e-300):
            pts += [[sh["center"][i] + d * sh["radius"] for i in range(3)] for d in (-1, 1)]
    if any(sh["type"] == "mesh" for sh in scene["shapes"]):
        import mitsuba_ref  # the reference's own mesh loader (transforms applied in float64)
        meshes = mitsuba_ref.scene_meshes(scene, base_dir)
        ext1 = np.ptp(np.array(pts), axis=0).max()
        for m in meshes.values():
            if m.lo is not None and np.max(m.hi - m.lo) <= huge_ratio * max(ext1, 1e-300):
                pts += [list(m.lo), list(m.hi)]
    p = np.array(pts, dtype=np.float64)
    center = (p.min(0) + p.max(0)) / 2
    k = 10.0 / np.ptp(p, axis=0).max()
    out = json.loads(json.dumps(scene))
    pt = lambda x: [float((x[i] - center[i]) * k) for i in range(3)]  # noqa: E731
    vec = lambda x: [float(x[i] * k) for i in range(3)]  # noqa: E731
    cam = out["camera"]
    cam["position"], cam["target"] = pt(cam["position"]), pt(cam["target"])
    for key in ("aperture", "focusDistance"):
        if key in cam:
            cam[key] = float(cam[key] * k)
    # x -> k (x - center), as a row-major 4x4 on the left of each mesh's transform.
    N = np.array([[k, 0, 0, -k * center[0]], [0, k, 0, -k * center[1]],
                  [0, 0, k, -k * center[2]], [0, 0, 0, 1]], dtype=np.float64)
    for sh in out["shapes"]:
        if sh["type"] == "sphere":
            sh["center"], sh["radius"] = pt(sh["center"]), float(sh["radius"] * k)
        elif sh["type"] == "quad":
            sh["corner"], sh["u"], sh["v"] = pt(sh["corner"]), vec(sh["u"]), vec(sh["v"])
        else:
            M = np.array(sh.get("transform", np.eye(4).reshape(-1).tolist()),
                         dtype=np.float64).reshape(4, 4)
            T = N @ M
            T[3] = [0, 0, 0, 1]
            sh["transform"] = [float(x) for x in T.reshape(-1)]
            if "file" in sh:
                sh["file"] = os.path.abspath(os.path.join(base_dir, sh["file"]))
    env = out.get("environment")
    if isinstance(env, dict):
        env["file"] = os.path.abspath(os.path.join(base_dir, env["file"]))
    return out, k, [float(x) for x in center]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--tools", required=True, help="folder of mitsuba_ref.py and pfm.py")
    ap.add_argument("--native", required=True, help="the native anchor's pt binary")
    ap.add_argument("--python", default=sys.executable, help="python with mitsuba")
    ap.add_argument("--parts", type=int, default=8)
    ap.add_argument("--mitsuba-spp", type=int, default=4096, help="per part")
    ap.add_argument("--native-spp", type=int, default=4096, help="per part")
    ap.add_argument("--cap-ratio", type=float, default=100.0)
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--renderers", default="mitsuba,native")
    ap.add_argument("names", nargs="*")
    args = ap.parse_args()
    sys.path.insert(0, os.path.abspath(args.tools))
    from pfm import read_pfm, write_pfm  # noqa: E402

    manifest_path = os.path.join(HERE, "references.json")
    manifest = json.load(open(manifest_path)) if os.path.exists(manifest_path) else {}
    names = args.names or sorted(
        f[:-5] for f in os.listdir(HERE)
        if f.endswith(".json") and f not in ("references.json", "set.json")
    )
    tmp = tempfile.mkdtemp(prefix="pathwise-refs-")
    for name in names:
        scene_path = os.path.join(HERE, name + ".json")
        entry = manifest.get(name, {})
        entry["scene"] = name + ".json"
        scene = json.load(open(scene_path))
        norm, norm_scale, center = normalized(scene, args.cap_ratio, HERE)
        norm_path = os.path.join(tmp, name + ".normalized.json")
        with open(norm_path, "w") as f:
            json.dump(norm, f)
        for renderer in args.renderers.split(","):
            if renderer == "native" and needs_mitsuba_only(scene):
                entry.pop("native", None)
                continue
            parts, notes, seconds = [], [], 0.0
            for k in range(args.parts):
                out = os.path.join(tmp, f"{name}.{renderer}.{k}.pfm")
                seed = 1 + k
                t0 = time.time()
                if renderer == "mitsuba":
                    stats = os.path.join(tmp, f"{name}.{k}.stats.json")
                    cmd = [args.python, os.path.join(args.tools, "mitsuba_ref.py"), norm_path,
                           "--spp", str(args.mitsuba_spp), "--variant", "llvm_ad_rgb",
                           "--threads", str(args.threads), "--seed", str(seed),
                           "--cap-large-spheres", str(args.cap_ratio), "--stats", stats,
                           "--out", out]
                else:
                    cmd = [args.native, scene_path, "--spp", str(args.native_spp), "--threads",
                           str(args.threads), "--seed", str(seed), "--out", out, "--quiet"]
                subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
                seconds += time.time() - t0
                if renderer == "mitsuba" and k == 0:
                    notes = json.load(open(stats)).get("notes", [])
                parts.append(read_pfm(out).astype(np.float64))
            stack = np.stack(parts)
            mean = stack.mean(0)
            var = stack.var(0, ddof=1) / len(parts)
            write_pfm(os.path.join(HERE, f"{name}.{renderer}.pfm"), mean)
            write_pfm(os.path.join(HERE, f"{name}.{renderer}-var.pfm"), var)
            entry[renderer] = {
                "parts": args.parts,
                "sppPerPart": args.mitsuba_spp if renderer == "mitsuba" else args.native_spp,
                "seeds": list(range(1, args.parts + 1)),
                "seconds": round(seconds, 1),
                "mean": [float(x) for x in mean.reshape(-1, 3).mean(0)],
            }
            if renderer == "mitsuba":
                entry[renderer]["variant"] = "llvm_ad_rgb"
                entry[renderer]["capLargeSpheres"] = args.cap_ratio
                entry[renderer]["notes"] = notes
                entry[renderer]["normalized"] = {"scale": norm_scale, "center": center}
        manifest[name] = entry
        with open(manifest_path, "w") as f:
            json.dump(manifest, f, indent=2, sort_keys=True)
            f.write("\n")
        if "mitsuba" in entry and needs_mitsuba_only(scene):
            m = entry["mitsuba"]["mean"]
            print(f"{name}: mitsuba {m[0]:.5g} {m[1]:.5g} {m[2]:.5g}  "
                  f"({entry['mitsuba']['seconds']} s)", flush=True)
        if "mitsuba" not in entry or "native" not in entry:
            continue
        m, n = entry["mitsuba"]["mean"], entry["native"]["mean"]
        print(f"{name}: mitsuba {m[0]:.5g} {m[1]:.5g} {m[2]:.5g}  native {n[0]:.5g} {n[1]:.5g} "
              f"{n[2]:.5g}  ({entry['mitsuba']['seconds']} s, {entry['native']['seconds']} s)",
              flush=True)


if __name__ == "__main__":
    main()
