// The audit's input families: where line/quadric code breaks. Every case is a pure function of
// (family, shape, range, seed, index), so any one can be regenerated alone.
#pragma once

#include "linequad/case_io.hpp"

#include <cstdint>
#include <string_view>
#include <vector>

namespace linequad {

enum class Family {
    generic,          // random shapes and lines at moderate scale
    near_tangent,     // 2^-k of the radius from tangency (k = 1..60), both sides; k = 0: exact
    axis_parallel,    // parallel to the axis inside, outside, on the surface; tilted by 2^-k
    apex,             // cone: through the apex, or passing 2^-k from it
    generator,        // cone: parallel to a generator, or 2^-k off it
    degenerate_frame, // nearly singular, very oblique, very thin, very flat frames (2^-k)
    scale,            // shapes of size 2^+-k, small shapes up to 2^50 from the origin
    extent_edge,      // hits exactly at the extent's ends, and 2^-k (k = 40..53) either side
};

constexpr int family_count = 8;
const char* family_name(Family f);
bool parse_family(std::string_view name, Family* f);
bool family_applies(Family f, int shape); // apex and generator are for the cone only

// shape: 0 cylinder, 1 elliptic_cylinder, 2 elliptic_cone.
Case make_case(Family f, int shape, Range range, std::uint64_t seed, std::uint64_t index);

} // namespace linequad
