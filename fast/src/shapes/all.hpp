// Every shape's derivations. The list of shapes itself is linequad::Shape (linequad/shapes.hpp);
// LINEQUAD_FOR_EACH_SHAPE names the same list for the explicit instantiations of the solvers,
// which C++17 cannot generate from a type list.
#pragma once

#include "shapes/capsule.hpp"
#include "shapes/cylinder.hpp"
#include "shapes/ellipsoid.hpp"
#include "shapes/elliptic_cone.hpp"
#include "shapes/elliptic_cylinder.hpp"
#include "shapes/frustum.hpp"
#include "shapes/plane.hpp"
#include "shapes/quadric.hpp"
#include "shapes/sphere.hpp"

#include <variant>

#define LINEQUAD_FOR_EACH_SHAPE(X)                                                                 \
    X(Cylinder)                                                                                    \
    X(EllipticCylinder)                                                                            \
    X(EllipticCone) X(Frustum) X(Sphere) X(Ellipsoid) X(Capsule) X(Plane) X(Quadric)
// The shapes that are one quadric, the plane among them (not made of patches: the batch kernels
// take them).
#define LINEQUAD_FOR_EACH_QUADRIC_SHAPE(X)                                                         \
    X(Cylinder)                                                                                    \
    X(EllipticCylinder) X(EllipticCone) X(Frustum) X(Sphere) X(Ellipsoid) X(Plane) X(Quadric)
// The shapes whose quadratic has the Newton rung's form in the batch lanes (line_form_in_lanes).
#define LINEQUAD_FOR_EACH_LINE_FORM_SHAPE(X)                                                       \
    X(Cylinder) X(EllipticCylinder) X(EllipticCone) X(Frustum) X(Sphere) X(Ellipsoid)
// The shapes the correct solver's batch lanes take: those above, and the surfaces with their own
// local quadratic (ShapeTraits::newton_form).
#define LINEQUAD_FOR_EACH_CORRECT_LANES_SHAPE(X)                                                   \
    LINEQUAD_FOR_EACH_LINE_FORM_SHAPE(X) X(Plane) X(Quadric)

namespace linequad::detail {
// Whether the stable batch kernels take the shape: the one-quadric shapes above. (A plane's g is
// linear: its double lanes take the one root; its float lanes go to the scalar solver.)
template <class S>
inline constexpr bool stable_in_lanes = false;
#define LINEQUAD_STABLE_IN_LANES(S)                                                                \
    template <>                                                                                    \
    inline constexpr bool stable_in_lanes<S> = true;
LINEQUAD_FOR_EACH_QUADRIC_SHAPE(LINEQUAD_STABLE_IN_LANES)
#undef LINEQUAD_STABLE_IN_LANES

#define LINEQUAD_COUNT_SHAPE(S) +1
static_assert(std::variant_size_v<Shape> == 0 LINEQUAD_FOR_EACH_SHAPE(LINEQUAD_COUNT_SHAPE),
              "LINEQUAD_FOR_EACH_SHAPE must list every alternative of linequad::Shape");
#undef LINEQUAD_COUNT_SHAPE
} // namespace linequad::detail
