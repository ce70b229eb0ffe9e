// The audit's input families: where line/quadric code breaks. Every case is a pure function of
// (family, shape, range, seed, index), so any one can be regenerated alone.
#pragma once

#include "linequad/case_io.hpp"

#include <cstdint>
#include <string>
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
    // Closed shapes (caps on; the cone with one or two nappes):
    rim,          // through a point of a disc's rim exactly (k = 0) or moved k ulps (k = 1..16):
                  // into the solid, across the disc, or grazing the rim
    cap_plane,    // in a disc's plane (across it, grazing its rim, beside it); tilted or lifted
                  // out of the plane by 2^-k
    cap_axis,     // along the axis through the discs' centres; tilted or moved by 2^-k
    inside_start, // from a point inside the solid, on its surface, or 2^-k outside it
    two_nappes,   // cone, two nappes (closed or not): across the apex, 2^-k from it, and lines
                  // through both solids (four hits)
    // Every shape again:
    far_origin, // the line's origin 2^k shape sizes from the shape (k = 10..40; 10..24 in float),
                // aimed through it, near tangency or just past it; the shape at the world origin
                // or itself far out (what a renderer's or a physics engine's long rays meet)
    // The closed solids by definition (sphere, ellipsoid, capsule):
    through_centre, // through the centre (the capsule: a point of its axis), or 2^-k beside it
    thin,           // an ellipsoid's axis, or a capsule's radius or length, 2^-k of the rest
    seam,           // capsule: through a point of a seam circle exactly, or moved k ulps
    poles,          // capsule: along the axis through both poles; tilted or moved by 2^-k
};

constexpr int family_count = 18;

// The frames shapes are built on: any (the elliptic shapes' frames oblique and sheared), circular
// (a, b orthogonal to the axis and of one length: a circular cross-section), axis (circular,
// and the axis along a coordinate axis) or aligned (every vector along a coordinate axis, the
// elliptic shapes' semi-axes of distinct lengths: VecGeom's and Geant4's elliptic solids),
// because most libraries represent only those. The cylinder and the frustum are circular in
// any case.
enum class Frames { any, circular, axis, aligned };
const char* frames_name(Frames f);
bool parse_frames(std::string_view name, Frames* f);
const char* family_name(Family f);
bool parse_family(std::string_view name, Family* f);
// The index in linequad::Shape of the shape named `name` (its case format name), or -1.
int shape_named(std::string_view name);
// Every family's name, and every shape's (in the order of linequad::Shape), as the case format
// and the options write them.
std::vector<std::string> family_names();
std::vector<std::string> shape_names();

// apex and generator: the cone and the frustum; two_nappes: the cone only; the closed solids'
// own families for them alone.
bool family_applies(Family f, int shape);

// shape: its index in linequad::Shape (0 cylinder, 1 elliptic_cylinder, 2 elliptic_cone,
// 3 frustum, 4 sphere). The case's id names all of it, the frames unless they are any, and the
// precision when it is binary32. A binary32 case has every input a float: the family's construction
// with its offsets in float's reach (2^-k for k up to 24, the scale family within float's range,
// the rim's ulps of float), rounded to float.
Case make_case(Family f, int shape, Range range, std::uint64_t seed, std::uint64_t index,
               Frames frames = Frames::any, Precision precision = Precision::binary64);

} // namespace linequad
