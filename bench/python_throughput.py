#!/usr/bin/env python3
"""Throughput of linequad.intersect on 10^6 rays at one cylinder (generic: sources in a box,
aimed at the cylinder's middle), and what the binding adds to the C++ batch call on the same
rays (stable and correct, which have one), all timed in turn, seven rounds: medians, and the
median of the rounds' ratios.

  fresh      one intersect() call, a new answer array (160 MB to fault in)
  out=       one call answering into the array of an earlier call
  C++        one correct::intersect(shape, lines, query, out) call, out held for every ray
  chunks     4,096 rays a call, into one reused array (Python) or buffer (C++): in cache

    PYTHONPATH=build/python /usr/bin/python3 bench/python_throughput.py
"""
import statistics
import time

import numpy as np

import linequad
from linequad import _linequad

rng = np.random.default_rng(1)
cyl = linequad.shape("cylinder", C=(0, 0, 0), H=(0, 0, 2), r=1)
n = 10**6
L0 = rng.uniform(-4, 4, (n, 3))
v = rng.uniform(-0.5, 0.5, (n, 3)) + [0, 0, 1] - L0

def timed(call):
    start = time.perf_counter()
    call()
    return time.perf_counter() - start


def ns(seconds):
    return f"{statistics.median(seconds) / n * 1e9:.0f} ns"


def adds(ratios):
    return f"{(statistics.median(ratios) - 1) * 100:+.0f} %"


chunk = 4096


def chunked(solver, rows):
    for at in range(0, n, chunk):
        m = min(chunk, n - at)
        linequad.intersect(cyl, L0[at:at + m], v[at:at + m], solver=solver, out=rows[:m])


print("# PYTHONPATH=build/python /usr/bin/python3 bench/python_throughput.py (10^6 generic rays at "
      "a cylinder, one core)")
print("ns a ray, median of 7; binding adds: Python over C++, median of the rounds' ratios")
print(f"{'solver':8s} {'fresh':>7s} {'out=':>7s} {'C++':>7s} {'adds':>6s} | {'chunks':>7s} "
      f"{'C++':>7s} {'adds':>6s}")
for solver in ["seed", "stable", "correct"]:
    rows = linequad.intersect(cyl, L0, v, solver=solver)
    rows_chunk = linequad.intersect(cyl, L0[:chunk], v[:chunk], solver=solver)
    fresh, reused, cxx, py_chunks, cxx_chunks = [], [], [], [], []
    for _ in range(7):
        fresh.append(timed(lambda: linequad.intersect(cyl, L0, v, solver=solver)))
        reused.append(timed(lambda: linequad.intersect(cyl, L0, v, solver=solver, out=rows)))
        py_chunks.append(timed(lambda: chunked(solver, rows_chunk)))
        if solver != "seed":
            cxx.append(_linequad._batch_seconds(cyl, L0, v, solver, 0))
            cxx_chunks.append(_linequad._batch_seconds(cyl, L0, v, solver, chunk))
    if solver == "seed":
        print(f"{solver:8s} {ns(fresh):>7s} {ns(reused):>7s} {'-':>7s} {'':>6s} | "
              f"{ns(py_chunks):>7s} {'-':>7s}")
        continue
    print(f"{solver:8s} {ns(fresh):>7s} {ns(reused):>7s} {ns(cxx):>7s} "
          f"{adds([r / c for r, c in zip(reused, cxx)]):>6s} | {ns(py_chunks):>7s} "
          f"{ns(cxx_chunks):>7s} {adds([p / c for p, c in zip(py_chunks, cxx_chunks)]):>6s}")
