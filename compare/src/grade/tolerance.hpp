// A library's declared surface tolerance, graded rigorously: an answer that is wrong for the exact
// solid S is counted within tolerance only when it is the answer, under the library's own
// conventions, for some solid S' with  S shrunk by delta  inside S'  inside  S grown by delta
// (every point it places otherwise than S does lies within delta of S's surface).
//
// The proof, for the closed convex solids: along the line, S' meets it in one interval J (or
// none). Take an outer solid inside S grown by delta and an inner one holding S shrunk by delta
// and lying inside S grown by delta; then for any J with  chord(inner) inside J inside
// chord(outer), the hull of the inner solid and J is such an S' and its chord is J. The brackets
// are exact shapes whose parameters are rounded toward the original (docs/semantics.md,
// "Declared tolerance"); the chords are the oracle's, correctly rounded, and read one ulp
// inward. Anything that is not proved this way stays a mismatch.
#pragma once

#include "linequad/audit_solver.hpp"

#include <optional>
#include <vector>

namespace linequad::audit {

// Whether `got` (after read_conventions), whose classification differs from the exact one, is
// right for some solid within s's tolerance of the posed shape. False where no bracket is built:
// shapes that bound no convex solid (open surfaces, unbounded shapes, two nappes), a tolerance
// below the rounding of the shape's own coordinates, refusals and crashes.
bool within_tolerance(const ExternalSolver& s, const Case& posed, const Result& got);

// The solids that bracket the shape: each pair (outer, inner) has outer inside S grown by delta,
// and inner holding S shrunk by delta and inside S grown by delta (nullopt: S shrunk by delta is
// empty, so anything holds it). None: none can be built. Exposed for the tests, which check it by
// support functions.
struct Bracket {
    Shape outer;
    std::optional<Shape> inner;
};
std::vector<Bracket> brackets(const Shape& s, double delta);

} // namespace linequad::audit
