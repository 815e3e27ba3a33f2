#!/usr/bin/env python3
"""Benchmarks of the needlekit Python module (figures in BENCHMARKS.md, section "Python module"):
evaluate_many designs per second (random cylinders; cones on a grid of sections; cones with every section
distinct) and the Python call overhead of one `performance_index` call against its cost inside evaluate_many.

    PYTHONPATH=build/python /usr/bin/python3 bench/python_bench.py
"""
import time
import timeit

import numpy as np

import needlekit as nk


def rate(label, count, **arguments):
    """Designs per second of wall time (best of 3) and per second of CPU time summed over the threads (what the
    machine would give without the other jobs that share it: x 2 for two cores)."""
    nk.evaluate_many(**{k: (v[:1000] if isinstance(v, np.ndarray) else v) for k, v in arguments.items()})  # warm-up
    best, cpu = float("inf"), float("inf")
    for _ in range(3):
        start, start_cpu = time.perf_counter(), time.process_time()
        result = nk.evaluate_many(**arguments)
        best = min(best, time.perf_counter() - start)
        cpu = min(cpu, time.process_time() - start_cpu)
    print(f"evaluate_many, {label}: {count / best / 1e6:.2f} M designs/s wall, {count / cpu / 1e6:.2f} M designs "
          f"per CPU-second ({count} designs, {result.distinct_sections} distinct tapered sections)")


rng = np.random.default_rng(1)
count = 1_000_000
d = rng.uniform(30e-6, 300e-6, count)
n = rng.integers(5, 30, count)
w = rng.uniform(5e-3, 1e-2, count)
length = rng.uniform(300e-6, 1000e-6, count)
rate("random solid cylinders", count, shape="cylinder", needles_per_row=n, tip_diameter=d, base_diameter=d,
     length=length, width=w)
d1 = rng.choice(np.arange(30e-6, 151e-6, 10e-6), count)
d2 = rng.choice(np.arange(160e-6, 301e-6, 10e-6), count)
rate("cones on the Fig 6.20 D1 x D2 grid (random n, w, L)", count, shape="cone", needles_per_row=n, tip_diameter=d1,
     base_diameter=d2, length=length, width=w)
few = 20_000
rate("cones, every section distinct", few, shape="cone", needles_per_row=n[:few],
     tip_diameter=rng.uniform(20e-6, 150e-6, few), base_diameter=rng.uniform(160e-6, 300e-6, few),
     length=length[:few], width=w[:few])

design = nk.ArrayDesign(needle=nk.NeedleGeometry(shape="cylinder", tip_diameter="100 um", base_diameter="100 um",
                                                 length="500 um"), material="silicon", width="1 cm")
conditions, options = nk.InsertionConditions(), nk.PerformanceIndexOptions()
calls = 20_000
per_call = min(timeit.repeat(lambda: nk.performance_index(design, conditions, options), number=calls, repeat=5,
                             timer=time.process_time)) / calls
nk.evaluate_many("cylinder", 10, np.full(200_000, 100e-6), 100e-6, 500e-6, 1e-2)  # warm-up
start_cpu = time.process_time()
nk.evaluate_many("cylinder", 10, np.full(200_000, 100e-6), 100e-6, 500e-6, 1e-2)
inside = (time.process_time() - start_cpu) / 200_000
print(f"performance_index from Python: {per_call * 1e6:.2f} us per call; the same design inside evaluate_many "
      f"{inside * 1e6:.3f} us of CPU: Python call overhead about {(per_call - inside) * 1e6:.2f} us per call")
