// The ellipsoid's cases: the ball-like solids' families (cases/solids.hpp) on any frame, and
// thin ones (an axis 2^-k of the others).
#include "cases/solids.hpp"

namespace linequad {

template <>
bool CaseMaker<Ellipsoid>::applies(Family f) {
    return solids::ball_applies(f, false);
}

template <>
Case CaseMaker<Ellipsoid>::make(Family f, Rng& r, int k, Frames frames, Precision p) {
    return solids::ball_case(f, r, k, frames, p, false, [](const solids::BallFrame& b) -> Shape {
        return Ellipsoid{b.O, b.a, b.b, b.c};
    });
}

} // namespace linequad
