"""linequad.audit: a Python solver graded against the exact oracle on a campaign's cases."""
import json

from ._linequad import _audit


def audit(fn, families=(), shapes=(), n=100, seed=1, precision="binary64", out=None,
          name="python", answers="all", parametrisation="line", surface="as_posed",
          inside="as_answers", on_surface="as_inside", tangent="hit", tolerance=(0.0, 0.0),
          negative_zero=0.0, contact_as_point=False):
    """Grades fn on the campaign's cases (linequad.cases with these options) against the oracle,
    as the audit grades a plugin: each case posed the way fn declares it takes a line, the exact
    reference solved for what it declares it answers.

    fn(shapes, origins, directions, t0, t1) is called once a chunk of at most 1,024 cases of one
    family and shape: shapes a list of linequad.Shape, origins and directions (M, 3) arrays, t0
    and t1 the range's ends, all float64 (float32 with precision="binary32"). It returns the t of
    each line's hits, an (M,) or (M, K) array, inf or NaN where a slot has no hit (as Open3D's
    t_hit). An exception, or an answer of another shape, is charged to every case of its chunk
    (a refusal the oracle does not make), and the run goes on.

    The declarations are the plugin ABI's (docs/external.md), by their C++ names: answers (all,
    nearest, first_entry, first_exit), parametrisation (line, unit_direction, segment), surface
    (as_posed, closed, infinite), inside (as_answers, no_hit, at_t0, at_zero, undefined),
    on_surface (as_inside, by_direction), tangent (hit, no_hit), tolerance (absolute, relative
    to the scene), negative_zero, contact_as_point.

    Returns {"verdict": the verdict lines, "report": report.json as a dict}; with `out`, the
    report (report.html, report.md, report.json, figures) is written into that directory too.
    """
    absolute, relative = tolerance
    lines, report = _audit(fn, list(families), list(shapes), n, seed, precision, out or "",
                           name, answers, parametrisation, surface, inside, on_surface, tangent,
                           float(absolute), float(relative), float(negative_zero),
                           bool(contact_as_point))
    return {"verdict": list(lines), "report": json.loads(report)}


__all__ = ["audit"]
