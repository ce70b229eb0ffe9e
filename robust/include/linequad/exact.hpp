// The exact oracle: every case classified exactly, every t and hit point correctly rounded.
//
// Inputs are taken as the exact rationals their doubles denote. Each shape's derivation in its
// exact, division-free form and the classification (fast/'s exact form) run in CGAL::Mpzf (exact
// ring arithmetic on dyadic numbers: no rounding, no gcd), with an interval filter of its own
// ahead of them; roots stay in the form (N + S sqrt(D)) / Den and every decision (discriminant,
// extent, range, order) is the exact sign of such a number. Only the outputs are rounded, each to
// the nearest double (or, for a binary32 answer, float; ties to even): by a double-word
// enclosure with a proven error bound where the bound decides, else by an MPFR enclosure whose
// precision doubles until both ends round to the same value. A binary32 answer needs float
// inputs (else not_binary32).
#pragma once

#include "linequad/cells.hpp"
#include "linequad/scene.hpp"
#include "linequad/solvers.hpp"
#include "linequad/surfaces.hpp"

#include <cstdint>

namespace linequad::exact {

template <class S, if_solvable<S> = 0>
Result intersect(const S& shape, const Line& line, Query query = {},
                 Precision answer = Precision::binary64);
Result intersect(const Shape& shape, const Line& line, Query query = {},
                 Precision answer = Precision::binary64);

// The same derivation and classification in CGAL::Gmpq: a slower,
// independent number type, used to cross-check the oracle.
Result intersect_gmpq(const Shape& shape, const Line& line, Query query = {},
                      Precision answer = Precision::binary64);

// The oracle for a scene: the line against every shape (none culled), each solved exactly, the
// hits in the order of their exact t (equal t: shape order) and tied where their exact t are
// equal on two shapes or more; the answer Scene::intersect (linequad/scene.hpp) defines, which a
// correct scene must give bit for bit. It orders by comparing the exact roots (their surds) in
// CGAL::Mpzf, not by the rounded t, and refuses nothing that double cannot hold. shapes_solved
// counts every shape; exact_comparisons stays 0.
void intersect(const std::vector<Shape>& shapes, const Line& line, Query query, SceneAnswer& out);

// The sense of a point against a plane or a general quadric (linequad/surfaces.hpp), summed
// exactly in CGAL::Mpzf with no filter: what fast/'s sense() must equal.
SenseResult sense(const Plane& s, Vec3 p);
SenseResult sense(const Quadric& s, Vec3 p);
SenseResult sense(const Plane& s, Vec3 p, Vec3 u);
SenseResult sense(const Quadric& s, Vec3 p, Vec3 u);
// And against a model's sphere or axis-aligned cylinder (linequad/cells.hpp).
SenseResult sense(const Sphere& s, Vec3 p);
SenseResult sense(const Cylinder& s, Vec3 p);
SenseResult sense(const Sphere& s, Vec3 p, Vec3 u);
SenseResult sense(const Cylinder& s, Vec3 p, Vec3 u);

// The oracle for a model of cells (linequad/cells.hpp): the exact track Model::track defines,
// from exact senses (above), each surface's crossings solved exactly and ordered by their exact
// roots (a run of equal roots crossed at once, a tie), the distances correctly rounded. What
// fast/'s Model::track must give bit for bit.
Model::Track track(const Model& m, Vec3 p, Vec3 u, int max_steps);

// The oracle as a named solver ("exact") for the CLI and the audit, answering in p.
const Solver& solver(Precision p = Precision::binary64);

// How much precision the rounding needed, counted on this thread since the last reset.
struct RoundingStats {
    // Cases the oracle's interval filter classified (a miss, or its hits) without the exact path.
    std::uint64_t interval_decided = 0;
    // Binary32 values rounded from the interval filter's own enclosures (no exact quadratic).
    std::uint64_t by_intervals = 0;
    // Values rounded by the filter (double-word enclosures), before MPFR sees any.
    std::uint64_t by_filter = 0;
    // The rest, by MPFR:
    std::uint64_t values = 0;       // values rounded
    std::uint64_t by_steps[8] = {}; // values resolved at 64, 128, ... bits (last: more)
    int max_steps = 0;              // most precision levels any value needed (1 = 64 bits)
};
RoundingStats& rounding_stats();

// Rounds (X + Y sqrt(D)) / Den to the nearest double (or float), for integers X, Y, D >= 0,
// Den != 0 given as decimal strings; exposed for the tests of the rounding itself.
double round_surd(const char* X, const char* Y, const char* D, const char* Den,
                  Precision p = Precision::binary64);
// The same by the oracle's rounding filter alone, for Y a double (as Y is in the oracle's own
// values): the value it proves, or NaN where it leaves the value to MPFR; exposed for the tests
// of the filter.
double round_surd_by_filter(const char* X, double Y, const char* D, const char* Den,
                            Precision p = Precision::binary64);

} // namespace linequad::exact
