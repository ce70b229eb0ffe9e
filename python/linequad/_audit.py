"""linequad.audit: a Python solver graded against the exact oracle on a campaign's cases."""
import json
import math
import os
import tempfile

import numpy as np

from ._linequad import _grade, cases


def _hex(x):
    return float(x).hex()


def audit(fn, families=(), shapes=(), n=100, seed=1, out=None, chunk=4096, name="python"):
    """Grades fn on the campaign's cases (linequad.cases with these options) against the oracle.

    fn(shapes, origins, directions, t0, t1) is called once per chunk of at most `chunk` cases:
    shapes a list of linequad.Shape, origins and directions (M, 3) float64 arrays, t0 and t1 the
    range's ends; it returns the t of each line's hits, an (M,) or (M, K) array, inf or NaN where
    a slot has no hit (as Open3D's t_hit). An exception, or an answer of another shape, is
    charged to every case of its chunk (a refusal the oracle does not make), never the run's end.

    Returns {"verdict": the verdict lines, "report": report.json as a dict}; with `out`, the
    report (report.md, report.json, figures) is written there too.
    """
    c = cases(list(families), list(shapes), n, seed)
    total = len(c["lines"])
    results = []
    for start in range(0, total, chunk):
        stop = min(total, start + chunk)
        try:
            t = np.asarray(fn(c["shapes"][start:stop], c["origins"][start:stop],
                              c["directions"][start:stop], c["t0"][start:stop],
                              c["t1"][start:stop]), dtype=np.float64)
            if t.ndim == 1:
                t = t[:, None]
            if t.ndim != 2 or t.shape[0] != stop - start:
                raise ValueError(f"returned an array of shape {t.shape} for {stop - start} lines")
        except Exception as e:  # the solver's fault, charged to its chunk
            why = f"cases {start} to {stop - 1}: {type(e).__name__}: {e}"
            for i in range(start, stop):
                results.append('{"id":' + c["id"][i] + ',"solver":' + json.dumps(name) +
                               ',"error":' + json.dumps(why) + ',"code":"foreign"}')
            continue
        for i, row in zip(range(start, stop), t):
            hits = sorted(x for x in row if math.isfinite(x))
            results.append('{"id":' + c["id"][i] + ',"solver":' + json.dumps(name) +
                           ',"hits":[' + ",".join('{"t":"' + _hex(x) + '"}' for x in hits) +
                           '],"on_surface":null}')
    with tempfile.TemporaryDirectory() as tmp:
        cases_file, results_file = os.path.join(tmp, "cases.jsonl"), os.path.join(tmp, "results.jsonl")
        with open(cases_file, "w", encoding="utf-8") as f:
            f.write("\n".join(c["lines"]) + "\n")
        with open(results_file, "w", encoding="utf-8") as f:
            f.write("\n".join(results) + "\n")
        lines, report = _grade(cases_file, results_file, out or os.path.join(tmp, "report"))
    return {"verdict": list(lines), "report": json.loads(report)}


__all__ = ["audit"]
