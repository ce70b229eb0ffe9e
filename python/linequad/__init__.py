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
