"""A textbook ray-cylinder intersection in numpy, audited against linequad's exact oracle:

    PYTHONPATH=build/python /usr/bin/python3 examples/python/textbook_cylinder.py
"""
import numpy as np

import linequad


def textbook(shapes, L0, v, t0, t1):
    """The school formula: project the axis out, solve a t^2 + b t + c = 0, keep the roots between
    the ends (and the caps' crossings inside their discs) and inside the range."""
    t = np.full((len(shapes), 4), np.inf)
    for i, s in enumerate(shapes):
        f = s.fields
        C, H, r = np.array(f["C"]), np.array(f["H"]), f["r"]
        h = np.linalg.norm(H - C)
        n, w = (H - C) / h, L0[i] - C
        a = v[i] @ v[i] - (v[i] @ n) ** 2
        b = 2 * (v[i] @ w - (v[i] @ n) * (w @ n))
        c = w @ w - (w @ n) ** 2 - r * r
        d = b * b - 4 * a * c
        roots = [(-b + sgn * np.sqrt(d)) / (2 * a) for sgn in (-1, 1)] if a != 0 and d >= 0 else []
        finite = f.get("finite", True)
        hits = [x for x in roots if not finite or 0 <= w @ n + x * (v[i] @ n) <= h]
        if f.get("caps", False) and v[i] @ n != 0:
            for end in (0, h):
                x = (end - w @ n) / (v[i] @ n)
                q = w + x * v[i] - end * n
                if q @ q <= r * r:
                    hits.append(x)
        hits = sorted(x for x in hits if t0[i] <= x <= t1[i])[:4]
        t[i, :len(hits)] = hits
    return t


report = linequad.audit(textbook, families=["generic", "near_tangent", "far_origin"],
                        shapes=["cylinder"], n=200)
print("\n".join(report["verdict"]))
