#!/usr/bin/env python3
"""Renders the independent references of the generated-scene validation.

For every scene file NAME.json in this folder (written by
`node scripts/run-ts.mjs tests/validation/export-references.ts`), two
independent renderers, each in P parts with different seeds:
  - Mitsuba 3 (../shared/tools/mitsuba_ref.py, single precision), with
    --cap-large-spheres so that a ground sphere far larger than the rest of
    the scene is an inscribed mesh cap rather than a float32 sphere;
  - the native anchor (../shared/anchors/native, double precision).
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
    ap.add_argument("names", nargs="*")
    args = ap.parse_args()
    sys.path.insert(0, args.tools)
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
        entry = {"scene": name + ".json"}
        for renderer in ("mitsuba", "native"):
            parts, notes, seconds = [], [], 0.0
            for k in range(args.parts):
                out = os.path.join(tmp, f"{name}.{renderer}.{k}.pfm")
                seed = 1 + k
                t0 = time.time()
                if renderer == "mitsuba":
                    stats = os.path.join(tmp, f"{name}.{k}.stats.json")
                    cmd = [args.python, os.path.join(args.tools, "mitsuba_ref.py"), scene_path,
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
        manifest[name] = entry
        with open(manifest_path, "w") as f:
            json.dump(manifest, f, indent=2, sort_keys=True)
            f.write("\n")
        m, n = entry["mitsuba"]["mean"], entry["native"]["mean"]
        print(f"{name}: mitsuba {m[0]:.5g} {m[1]:.5g} {m[2]:.5g}  native {n[0]:.5g} {n[1]:.5g} "
              f"{n[2]:.5g}  ({entry['mitsuba']['seconds']} s, {entry['native']['seconds']} s)",
              flush=True)


if __name__ == "__main__":
    main()
