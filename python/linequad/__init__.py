"""linequad: where a line crosses a surface, exactly and correctly rounded, on numpy arrays.

    import numpy as np, linequad
    cyl = linequad.shape("cylinder", C=(0, 0, 0), H=(0, 0, 10), r=5)
    hits = linequad.intersect(cyl, np.array([[-10.0, 4, 2]]), np.array([[1.0, 0, 0]]))
    hits["t"][0, :hits["count"][0]]   # the correctly rounded t of each hit

docs/python.md in the repository says more.
"""
from ._linequad import (  # noqa: F401
    Shape,
    cases,
    error_codes,
    hit_kinds,
    intersect,
    parts,
    shape,
    solvers,
)
from ._audit import audit  # noqa: F401


def _fields(self):
    """The shape's fields, as the case format names them: numbers and tuples of three."""
    import json

    def value(x):
        if isinstance(x, list):
            return tuple(value(y) for y in x)
        return float.fromhex(x) if isinstance(x, str) else x

    case = json.loads(self._case_text)
    skip = {"id", "shape", "L0", "v", "range", "t0", "t1"}
    return {k: value(v) for k, v in case.items() if k not in skip}


Shape.fields = property(_fields)
