// The cases of every family for one shape. The shapes with an axis (cylinders, cone, frustum)
// share one construction on a frame and a profile (families.cpp); each closed solid by definition
// has its own file (cases/<shape>.cpp). A shape without its CaseMaker does not link.
#pragma once

#include "linequad/families.hpp"

#include "cases/rng.hpp"

namespace linequad {

template <class S>
struct CaseMaker {
    static bool applies(Family f);
    // The case of family f at difficulty k (families.cpp: difficulty()), from r.
    static Case make(Family f, Rng& r, int k, Frames frames, Precision p);
};

// x moved by k ulps of its format, up or down (0 by k ulps of 1).
double ulps_moved(double x, int k, bool up, Precision p);

} // namespace linequad
