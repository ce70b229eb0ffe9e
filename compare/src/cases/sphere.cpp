// The sphere's cases: the ball-like solids' families (cases/solids.hpp) on round frames.
#include "cases/solids.hpp"

namespace linequad {

template <>
bool CaseMaker<Sphere>::applies(Family f) {
    return solids::ball_applies(f, true);
}

template <>
Case CaseMaker<Sphere>::make(Family f, Rng& r, int k, Frames frames, Precision p) {
    return solids::ball_case(f, r, k, frames, p, true, [](const solids::BallFrame& b) -> Shape {
        return Sphere{b.O, norm(b.a)};
    });
}

} // namespace linequad
