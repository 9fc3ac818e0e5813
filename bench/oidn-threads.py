#!/usr/bin/env python3
"""Native OIDN (pyoidn) with a set number of threads, for bench/denoise.ts: the RT filter,
HDR, quality high, colour + albedo + normal; one warm-up execute (device, filter and weights
built), then the median wall and process-CPU seconds of REPEAT executes.  Prints one JSON line.
usage: PY bench/oidn-threads.py COLOR ALBEDO NORMAL THREADS REPEAT"""
import json, sys, time

import numpy as np

sys.path.insert(0, "/work/shared/tools")
from pfm import read_pfm  # noqa: E402
import pyoidn  # noqa: E402

color, albedo, normal = (np.ascontiguousarray(read_pfm(p).astype(np.float32)) for p in sys.argv[1:4])
threads, repeat = int(sys.argv[4]), int(sys.argv[5])
out = np.zeros_like(color)
dev = pyoidn.Device()
dev.set_int("numThreads", threads)
dev.commit()
flt = pyoidn.Filter(dev, pyoidn.OIDN_FILTER_TYPE_RT)
for name, img in (("color", color), ("albedo", albedo), ("normal", normal), ("output", out)):
    flt.set_image(name, img, pyoidn.OIDN_FORMAT_FLOAT3)
flt.set_bool("hdr", True)
flt.set_quality(pyoidn.OIDN_QUALITY_HIGH)
flt.commit()
flt.execute()
times, cpu = [], []
for _ in range(repeat):
    t, c = time.perf_counter(), time.process_time()
    flt.execute()
    times.append(time.perf_counter() - t)
    cpu.append(time.process_time() - c)  # all of the process's threads
err = dev.get_error()
print(json.dumps({"threads": threads, "seconds_median": float(np.median(times)), "cpu_seconds_median": float(np.median(cpu)), "error": err}))
