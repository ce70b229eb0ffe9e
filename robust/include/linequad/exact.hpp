// The exact oracle: every case classified exactly, every t and hit point correctly rounded.
//
// Inputs are taken as the exact rationals their doubles denote. Each shape's derivation in its
// exact, division-free form and the classification (fast/'s exact form) run in CGAL::Mpzf (exact
// ring arithmetic on dyadic numbers: no rounding, no gcd); roots stay in the form
// (N + S sqrt(D)) / Den and every decision (discriminant, extent, range, order) is the exact sign
// of such a number. Only the outputs are rounded, each to the nearest double (or, for a binary32
// answer, float; ties to even) by an MPFR enclosure whose precision doubles until both ends
// round to the same value. A binary32 answer needs float inputs (else not_binary32).
#pragma once

#include "linequad/solvers.hpp"

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

// The oracle as a named solver ("exact") for the CLI and the audit, answering in p.
const Solver& solver(Precision p = Precision::binary64);

// How much precision the rounding needed, counted on this thread since the last reset.
struct RoundingStats {
    std::uint64_t values = 0;       // values rounded
    std::uint64_t by_steps[8] = {}; // values resolved at 64, 128, ... bits (last: more)
    int max_steps = 0;              // most precision levels any value needed (1 = 64 bits)
};
RoundingStats& rounding_stats();

// Rounds (X + Y sqrt(D)) / Den to the nearest double (or float), for integers X, Y, D >= 0,
// Den != 0 given as decimal strings; exposed for the tests of the rounding itself.
double round_surd(const char* X, const char* Y, const char* D, const char* Den,
                  Precision p = Precision::binary64);

} // namespace linequad::exact
