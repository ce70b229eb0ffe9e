#!/usr/bin/env python3
"""Throughput of linequad.intersect on 10^6 rays at one cylinder (generic: sources in a box,
aimed at the cylinder's middle), the median of five runs per solver:

    PYTHONPATH=build/python /usr/bin/python3 bench/python_throughput.py
"""
import time

import numpy as np

import linequad

rng = np.random.default_rng(1)
cyl = linequad.shape("cylinder", C=(0, 0, 0), H=(0, 0, 2), r=1)
n = 10**6
L0 = rng.uniform(-4, 4, (n, 3))
v = rng.uniform(-0.5, 0.5, (n, 3)) + [0, 0, 1] - L0
for solver in ["seed", "stable", "correct"]:
    times = []
    for _ in range(5):
        start = time.perf_counter()
        linequad.intersect(cyl, L0, v, solver=solver)
        times.append(time.perf_counter() - start)
    median = sorted(times)[2]
    print(f"{solver:8s} {median:.3f} s for 10^6 rays: {median / n * 1e9:.0f} ns a ray")
