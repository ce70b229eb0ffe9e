// A shape prepared once for many lines: validated, with the work that depends on the shape alone
// done (its frame's orientation, decided exactly; its dual frame; the seed's inverse map; the
// correct solver's frame rows). Every solver takes a prepared shape as well as a plain one and
// returns the same result, bit for bit:
//     auto p = linequad::prepare(cone);
//     for (const Line& l : rays) hits = linequad::correct::intersect(p, l, query);
#pragma once

#include "linequad/result.hpp"
#include "linequad/shapes.hpp"

namespace linequad {

namespace detail {

// What prepare() works out, as plain numbers so that a prepared shape is a value to copy, store
// and share between threads. What each number is, and how the solvers use it, is in each
// shape's derivation (fast/src/shapes/).
struct CommonFacts {
    Error error;
    int orientation = 0;  // sign of det[a b c] of an affine frame, decided exactly
    double magnitude = 0; // the largest |coordinate| of the shape's positions
    double smallest = 0;  // the smallest nonzero one (infinity when there is none)
};

// The rows of adj(M), M = [a b c]: b x c, c x a, a x b, and det M.
struct AdjugateRows {
    Vec3 hi[3]{}, lo[3]{}; // in double-double
    double det = 0;
};

struct FrameFacts : CommonFacts {
    double seed_inverse[16] = {}; // (T R S)^-1 as the seeds build it, column-major
    // The stable solvers' dual frame with the shape scaled by 2^-exponent to unit size, and the
    // smallest exponent of a nonzero coordinate of its inputs there.
    AdjugateRows dual;
    Vec3 c_hi{}, c_lo{}; // c in double-double (the cone's H - C is not a double)
    int exponent = 0, lowest_exponent = 0;
    // The correct solver's rows and determinant: each value, its low part and its error bound.
    double rows[3][3][3] = {}, det[3] = {};
};

// A shape with nothing to keep beyond the common facts (the sphere) needs no specialisation.
template <class S>
struct Facts : CommonFacts {};
// The circular shapes' axis as seed 001 normalises it: h / |h| and |h|.
struct AxisFacts : CommonFacts {
    Vec3 seed_axis{};
    double seed_length = 0;
};

template <>
struct Facts<Cylinder> : AxisFacts {
    Vec3 h_hi{}, h_lo{};          // h = H - C in double-double
    double hh[3] = {}, K[3] = {}; // h.h and r^2 h.h: value, low part, error bound
};
template <>
struct Facts<EllipticCylinder> : FrameFacts {};
template <>
struct Facts<EllipticCone> : FrameFacts {};
template <>
struct Facts<Frustum> : AxisFacts {};
template <>
struct Facts<Ellipsoid> : FrameFacts {};

struct PreparedAccess;

} // namespace detail

template <class S>
class Prepared {
  public:
    using shape_type = S;
    const S& shape() const { return shape_; }
    Error error() const { return facts_.error; }
    bool ok() const { return facts_.error.ok(); }

  private:
    S shape_;
    detail::Facts<S> facts_;
    friend struct detail::PreparedAccess;
};

// Validates the shape (the error is kept: every solve with it then returns it) and does the
// work that depends on the shape alone.
template <class S>
Prepared<S> prepare(const S& shape);

namespace detail {
// std::variant<Prepared<S>...> for std::variant<S...>: a prepared shape of any kind.
template <class Variant>
struct PreparedVariantOf;
template <class... S>
struct PreparedVariantOf<std::variant<S...>> {
    using type = std::variant<Prepared<S>...>;
};
template <class Variant>
using PreparedVariant = typename PreparedVariantOf<Variant>::type;
} // namespace detail

} // namespace linequad
