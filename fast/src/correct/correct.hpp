// The correct solver: the exact answer, correctly rounded. The classification (how many hits,
// their kinds, the on-surface interval) is the exact one, and t, the hit points and the interval
// ends are each the double nearest the exact value (ties to even), as the oracle gives them.
//
// It follows Ziv's strategy for correctly rounded functions, on the division-free form of each
// shape's derivation (shapes/*.hpp, whose coefficients are polynomials in the inputs):
//  1. Newton (newton_rung.cpp): each root estimated in double, then one Newton step from the
//     estimate with the residual in double-double proves a root's existence, which root it is,
//     and an enclosure about 2^-100 wide; the extent, the range, t and the points are decided
//     on it. Every decision and every rounding must be proven; otherwise
//  2. double-double: the quadratic, its classification and the roots in BoundedDD, which
//     carries a proven error bound. Every sign must be certain and every output's interval must
//     lie inside one rounding cell; otherwise
//  3. exact: the same template in BigFloat (exact dyadic arithmetic, no GMP), every sign exact,
//     and each output rounded by deciding, exactly, on which side of the midpoints between
//     neighbouring doubles it lies.
// Result::rung says which rung answered.
//
// correct32 is the same ladder with a float target (Binary32): the inputs are floats, so every
// quantity above is as exact as for doubles, and only the rounding changes: each output is
// rounded to float directly from its enclosure or exactly (never through the nearest double,
// which would round twice). Its first rung evaluates g in double from the quick line form (the
// hit test's), whose enclosure is loose for a double but some 2^29 times tighter than a float's
// rounding cell; the precise Newton rung, then the others, follow where it cannot prove. On a
// convex shape closed by discs the Newton rung answers from the lateral roots and the discs' t,
// which is rational and rounded directly (newton_rung.cpp); on two solids (a closed two-nappe
// cone) the same, on the scalar ladder.
#pragma once

#include "correct/ladder.hpp"
#include "correct/newton_rung.hpp"
#include "correct/rungs.hpp"
#include "forms/frame.hpp"
#include "numeric/exact_in_double.hpp"
#include "numeric/expansion.hpp"
#include "shapes/all.hpp"
#include "solve/solve.hpp"

#include <cstring>
#include <initializer_list>

namespace linequad::detail {

// Every answer of the ladder is certain, each t within half an ulp of Target; and says which rung
// gave it.
template <class Target>
void mark_certain(Result& r, Rung rung) {
    r.certainty = Certainty::certain;
    r.rung = rung;
    for (int i = 0; i < r.count; ++i) {
        r.hits[i].certain = true;
        r.hits[i].bound = Target::half_ulp(r.hits[i].t);
    }
}

// A hit test's t is its enclosure's midpoint, not rounded; for a float answer it is rounded to
// the nearest float once, and the bound grows by what that moved it.
inline void hit_test_in(Result&, Binary64) {}
inline void hit_test_in(Result& r, Binary32) {
    for (int i = 0; i < r.count; ++i) {
        Hit& h = r.hits[i];
        double t = float(h.t);
        h.bound = (h.bound + std::fabs(t - h.t)) * Binary64::cover(4);
        h.t = t;
    }
}

// The first input that is not a float, for a float target.
template <class Source>
Error target_error(const Source&, const Line&, Binary64) {
    return {};
}
template <class Source>
Error target_error(const Source& src, const Line& l, Binary32) {
    return binary32_error(src.shape, l);
}

// Sizes of scene and direction at which no quantity the Newton rung forms (products of at most
// twelve inputs) leaves double's normal range: 2^-64 to 2^64. Its bounds hold at any size; this
// only spares such scenes the scaling, which the rung's arithmetic would not need.
inline bool in_moderate_range(double x) {
    return x >= 0x1p-64 && x <= 0x1p+64;
}
inline bool moderate(double extent, const Line& l) {
    return in_moderate_range(extent) && in_moderate_range(max_abs(l.v));
}

// A quadratic's value as a double-double enclosure: a BoundedDD as it is, a BigFloat from its
// leading bits (numeric/big_float.hpp).
inline BoundedDD enclosure(const BoundedDD& x) {
    return x;
}
using linequad::enclosure;
inline BoundedDD enclosure(const ExactDouble& x) { // an exact one only
    return BoundedDD(x.v);
}
inline BoundedDD twice(const BoundedDD& x) {
    return {2 * x.hi, 2 * x.lo, 2 * x.e};
}
inline ExactDouble twice(const ExactDouble& x) {
    return {2 * x.v, x.exact && std::isfinite(2 * x.v)};
}
inline BigFloat twice(const BigFloat& x) {
    return x.scaled(1);
}

// t times `to_rung` (a power of two: a quadratic's parameter, or a coefficient, into the rung's
// units), exactly; no value where a part would leave the normal range or the bound is not finite.
inline std::optional<BoundedDD> in_rung_units(BoundedDD t, double to_rung) {
    if (to_rung != 1) t = BoundedDD(t.hi * to_rung, t.lo * to_rung, t.e * to_rung);
    auto tiny = [](double x) { return x != 0 && std::fabs(x) < 0x1p-960; };
    if (tiny(t.hi) || tiny(t.lo) || tiny(t.e) || !std::isfinite(t.e)) return std::nullopt;
    return t;
}

// The line through its point P = L0 + t v, each coordinate L0_k + t v_k enclosed in bounded
// double-double from an exact product; none where that product may underflow or overflow.
inline std::optional<exact_form::LineThrough<BoundedDD>> line_through(const Line& l, double t) {
    bool exact = true;
    auto at = [&](int k) {
        TwoTerm p = two_prod(t, l.v[k]);
        exact = exact && std::isfinite(p.hi) && dd_detail::product_exact(t, l.v[k], p.hi);
        return BoundedDD(l.L0[k]) + BoundedDD(p.hi, p.lo, 0);
    };
    exact_form::LineThrough<BoundedDD> through{{at(0), at(1), at(2)}, l.v, l.L0};
    if (!exact) return std::nullopt;
    return through;
}

// Where the line crosses one end of q's extent: dZ^2 q(t_E) = (A N + 2 B dZ) N + C0 dZ^2 with
// N = end - Z0 (the exact form's own test of a disc), and t_E = N / dZ enclosed, times
// `to_rung` (a power of two: q's parameter into the rung's). No value where the end is not
// bounded, a sign is not proven (a BoundedDD's bound does not exclude zero) or t_E scaled would
// leave the normal range.
template <class NT>
std::optional<EndCrossing> end_crossing(const exact_form::LineQuadratic<NT>& q, bool top,
                                        double to_rung) {
    if (!(top ? q.hi_bounded : q.lo_bounded)) return std::nullopt;
    NT N = (top ? q.hi : q.lo) - q.Z0;
    EndCrossing c;
    c.q_sign = sign((q.A * N + twice(q.B) * q.dZ) * N + q.C0 * q.dZ * q.dZ);
    c.A_sign = sign(q.A);
    c.dZ_sign = sign(q.dZ);
    for (int s : {c.q_sign, c.A_sign, c.dZ_sign})
        if (s == undecided_sign) return std::nullopt;
    c.open = top ? q.hi_open : q.lo_open;
    std::optional<BoundedDD> t = in_rung_units(enclosure(N) / enclosure(q.dZ), to_rung);
    if (!t) return std::nullopt;
    c.t = *t;
    return c;
}

// Products of doubles are exact in an expansion (a low part and a high one) while they stay
// far from underflow and overflow: every input nonzero component within 2^-480 to 2^480.
inline bool exact_products(std::initializer_list<Vec3> inputs) {
    for (const Vec3& x : inputs)
        for (int k = 0; k < 3; ++k) {
            double a = std::fabs(x[k]);
            if (a != 0 && !(a >= 0x1p-480 && a <= 0x1p+480)) return false;
        }
    return true;
}

// The sign of (a - a') . (b - b'), the differences taken exactly: in double where nothing rounds
// (small integers), else by an expansion; no value where a product could be inexact.
inline std::optional<int> dot_sign(Vec3 a, Vec3 a_, Vec3 b, Vec3 b_) {
    if (std::optional<int> s = dot_sign_in_double(a, a_, b, b_)) return s; // small integers
    if (!exact_products({a, a_, b, b_})) return std::nullopt;
    Expansion<24> e;
    for (int k = 0; k < 3; ++k) {
        e.add_product(a[k], b[k]);
        e.add_product(-a[k], b_[k]);
        e.add_product(-a_[k], b[k]);
        e.add_product(a_[k], b_[k]);
    }
    return e.sign();
}

// Where Z0 lies against the extent, from sgn(Z0 - lo) and sgn(Z0 - hi): -2 below it, -1 in the
// base's plane, 0 strictly within, 1 in the top's plane, 2 above (ExtentEnds::constant_z).
inline int level_of(int against_lo, int against_hi) {
    return against_lo < 0    ? -2
           : against_lo == 0 ? -1
           : against_hi < 0  ? 0
           : against_hi == 0 ? 1
                             : 2;
}

// ExtentEnds::constant_z's answer for a closed shape, from the exact signs of a few products or
// determinants rather than the exact form: no level where dZ != 0 or the line lies in the plane
// of an end without a disc.
struct ConstantZ {
    std::optional<int> level;
};
// From the signs of dZ, Z0 - lo and Z0 - hi; the ends' discs as `discs` has them.
inline ConstantZ constant_z_from(int dZ, int against_lo, int against_hi, Closure discs) {
    if (dZ != 0) return {};
    int level = level_of(against_lo, against_hi);
    if ((level == -1 && !discs.lo) || (level == 1 && !discs.hi)) return {};
    return {level};
}
// A cylinder or a frustum on the axis from C to H: Z = (P - C).h, h = H - C, between 0 and h.h;
// dZ = v.h, Z0 - end = (L0 - C).h or (L0 - H).h, each exactly. No value where a product could be
// inexact.
inline std::optional<ConstantZ> constant_z_on_axis(Vec3 C, Vec3 H, const Line& l, Closure discs) {
    std::optional<int> dZ = dot_sign(l.v, Vec3{}, H, C);
    if (!dZ) return std::nullopt;
    if (*dZ != 0) return ConstantZ{};
    std::optional<int> base = dot_sign(l.L0, C, H, C), top = dot_sign(l.L0, H, H, C);
    if (!base || !top) return std::nullopt;
    return constant_z_from(0, *base, *top, discs);
}
inline std::optional<ConstantZ> constant_z_of_line(const Cylinder& s, const Line& l, int) {
    if (!s.caps) return std::nullopt;
    return constant_z_on_axis(s.C, s.H, l, both_ends(true));
}
inline std::optional<ConstantZ> constant_z_of_line(const Frustum& s, const Line& l, int) {
    if (!s.caps) return std::nullopt; // closed, so finite: Z is u, not the nappe's R
    return constant_z_on_axis(s.C0, s.C1, l, frustum_closure(s));
}
// The elliptic shapes: Z = sigma det[a b P - O] (O the frame's origin, sigma the orientation),
// so dZ = sigma det[a b v] and Z0 - end a determinant of L0 less points, each sign exact.
inline std::optional<ConstantZ> constant_z_of_line(const EllipticCylinder& s, const Line& l,
                                                   int orientation) {
    if (!s.caps) return std::nullopt;
    int sigma = orientation < 0 ? -1 : 1; // 0 <= Z <= |det| = sigma det[a b c]
    return constant_z_from(det3_sign_exact(s.a, s.b, l.v),
                           sigma * det3_sign_exact(s.a, s.b, l.L0, s.C, Vec3{}),
                           sigma * det3_sign_exact(s.a, s.b, l.L0, s.C, s.c), both_ends(true));
}
inline std::optional<ConstantZ> constant_z_of_line(const EllipticCone& s, const Line& l,
                                                   int orientation) {
    if (!s.caps) return std::nullopt; // closed, so finite (validation)
    // Z = sigma det[a b P - H], c = H - C: lo = -|det| (Z0 - lo = sigma det[a b L0 - C]), hi = 0
    // (one nappe) or |det| (two: Z0 - hi = sigma det[a b L0 - H - c]).
    int sigma = orientation < 0 ? -1 : 1;
    int lo = sigma * det3_sign_exact(s.a, s.b, l.L0, s.C, Vec3{}), hi;
    if (s.nappes == 2) {
        Vec3 twice_H = 2 * s.H, minus_C = -1 * s.C; // exact, unless 2 H overflows
        if (!std::isfinite(max_abs(twice_H))) return std::nullopt;
        hi = sigma * det3_sign_exact(s.a, s.b, l.L0, twice_H, minus_C);
    } else {
        hi = sigma * det3_sign_exact(s.a, s.b, l.L0, s.H, Vec3{});
    }
    return constant_z_from(det3_sign_exact(s.a, s.b, l.v), lo, hi, cone_extent(s).caps);
}
template <class S>
std::optional<ConstantZ> constant_z_of_line(const S&, const Line&, int) {
    return std::nullopt;
}

// Whether v x (H - C) = 0 exactly: each component k is det[e_k, v, H - C] = (e_k x v).(H - C),
// e_k x v exact (v's components moved). Where h = H - C is a double exactly and every product is
// exact, v_i h_j - v_j h_i = 0 is two_prod(v_i, h_j) == two_prod(v_j, h_i), a few operations (a
// line along the axis of a frame of small integers, most often); a component that a rounded
// cross product and its error bound show nonzero ends the test. Otherwise its sign by dot_sign's
// expansion, or where a product could be inexact from the frames' orientation test (which scales
// its inputs first).
inline bool cross_is_zero(Vec3 v, Vec3 C, Vec3 H) {
    Vec3TwoTerm h = difference_exact(H, C);
    Vec3 rounded = cross(v, h.hi), size = cross_magnitudes(v, h.hi);
    // Each rounded component is within 3u of its size (two products, h's rounding) and u of
    // itself (the difference) of the exact one, or 2^-1070 where a product underflows.
    for (int k = 0; k < 3; ++k)
        if (std::fabs(rounded[k]) > 8 * Binary64::u * size[k] + Binary64::subnormal_slack)
            return false;
    if (h.lo == Vec3{} && exact_products({v, h.hi})) {
        for (int k = 0; k < 3; ++k) {
            int i = (k + 1) % 3, j = (k + 2) % 3;
            TwoTerm a = two_prod(v[i], h.hi[j]), b = two_prod(v[j], h.hi[i]);
            if (a.hi != b.hi || a.lo != b.lo) return false;
        }
        return true;
    }
    const Vec3 axes[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    const Vec3 moved[3] = {{0, -v.z, v.y}, {v.z, 0, -v.x}, {-v.y, v.x, 0}}; // e_k x v
    for (int k = 0; k < 3; ++k) {
        std::optional<int> s = dot_sign(H, C, moved[k], Vec3{});
        if ((s ? *s : cone_det_sign_exact(axes[k], v, C, H)) != 0) return false;
    }
    return true;
}

// Whether the line runs exactly parallel to a cylinder's axis, which is where A = 0 (and then
// B = 0: g is constant along the line); no value for other shapes, which the exact form answers.
inline std::optional<bool> exactly_parallel(const Cylinder& s, const Line& l) {
    return cross_is_zero(l.v, s.C, s.H);
}
inline std::optional<bool> exactly_parallel(const EllipticCylinder& s, const Line& l) {
    return cross_is_zero(l.v, Vec3{}, s.c);
}
inline std::optional<bool> exactly_parallel(const CapsuleSide& s, const Line& l) {
    return cross_is_zero(l.v, s.C, s.H);
}
template <class S>
std::optional<bool> exactly_parallel(const S&, const Line&) {
    return std::nullopt;
}

// Whether every input (the shape's and the line's) has at most 20 significant bits: a frame and a
// line of small dyadic numbers, where the exact form in double is worth trying (ExactDouble says
// whether it was exact; most other inputs make it round, and the try would be wasted).
struct ShortInputs {
    std::uint64_t low = 0; // the low 33 bits of every significand, or'ed
    LINEQUAD_INLINE void add(double x) {
        std::uint64_t bits;
        std::memcpy(&bits, &x, sizeof bits);
        low |= bits & ((std::uint64_t(1) << 33) - 1);
    }
    LINEQUAD_INLINE void add(const Vec3& a) { add(a.x), add(a.y), add(a.z); }
    template <std::size_t N>
    LINEQUAD_INLINE void add(const std::array<double, N>& a) {
        for (double x : a)
            add(x);
    }
};
template <class S>
bool short_inputs(const S& s, const Line& l) {
    ShortInputs check;
    check.add(l.L0), check.add(l.v);
    for_each_field<S>([&](const auto& f) { check.add(s.*f.member); });
    return check.low == 0;
}

// Whether a shape gives its ends' planes apart from its line form (end_planes), which then does
// not carry them for an open shape.
template <class S, class = void>
inline constexpr bool has_end_planes = false;
template <class S>
inline constexpr bool has_end_planes<S, std::void_t<decltype(ShapeTraits<S>::end_planes(
                                            std::declval<const AsGiven<S>&>(), Vec3{}, Vec3{}))>> =
    true;

// Whether a shape gives the sign of D = B^2 - A C0 from a form of lower degree than the exact
// quadratic's (discriminant_sign), and the side of an end of a tangency (tangency_against_end).
template <class S, class = void>
inline constexpr bool has_discriminant_sign = false;
template <class S>
inline constexpr bool has_discriminant_sign<
    S, std::void_t<decltype(ShapeTraits<S>::template discriminant_sign<BigFloat>(
           std::declval<const S&>(), std::declval<const Line&>(), 0))>> = true;
template <class S, class = void>
inline constexpr bool has_tangency_against_end = false;
template <class S>
inline constexpr bool has_tangency_against_end<
    S, std::void_t<decltype(ShapeTraits<S>::template tangency_against_end<BigFloat>(
           std::declval<const S&>(), std::declval<const Line&>(), true))>> = true;

// Whether a shape's ends belong to other parts (a capsule side's seams: ShapeTraits::ends_open),
// the same for every line; a root there is not the shape's.
template <class S, class = void>
inline constexpr bool ends_open = false;
template <class S>
inline constexpr bool ends_open<S, std::void_t<decltype(ShapeTraits<S>::ends_open)>> =
    ShapeTraits<S>::ends_open;

// Whether a shape gives g's local quadratic at a point by a cheaper form than its exact one
// (local_at: a sphere's, from C0 exact in an expansion).
template <class S, class = void>
inline constexpr bool has_local_at = false;
template <class S>
inline constexpr bool
    has_local_at<S, std::void_t<decltype(ShapeTraits<S>::local_at(
                        std::declval<const S&>(), std::declval<const Line&>(), 0.0))>> = true;

// Whether a shape gives its Z alone (exact_axial), cheaper than its whole exact quadratic.
template <class S, class = void>
inline constexpr bool has_exact_axial = false;
template <class S>
inline constexpr bool
    has_exact_axial<S, std::void_t<decltype(ShapeTraits<S>::template exact_axial<BigFloat>(
                           std::declval<const S&>(), std::declval<const Line&>(), 0))>> = true;

// The scene scaled to unit size (unit_scale): the double-double rung's, and the Newton rung's
// where the scene as given is not of moderate size.
template <class S>
struct UnitScene {
    Unit unit;
    S shape;
};

// What the Newton rung's bounds leave open, answered exactly, each part formed once for the line
// and only when asked. A sign is asked first of the exact form in double, where the inputs are
// small dyadic numbers and nothing rounds; then of the double-double quadratic of the scene
// scaled to unit size (the filter, which the double-double rung takes as it is), whose bounds
// decide all but the exact zeros (a root at a rim, a double root, g or Z constant along the line)
// at a small part of the exact form's cost; where they do not, the double-double rung could not
// answer either, and the exact form in BigFloat does, at once. Z alone (an end's crossing, the
// point there) comes from the shape's exact_axial, a few products; a tangency from the sign of D
// alone, in a form of lower degree (discriminant_sign).
template <class Source>
class ExactForm final : public ExtentEnds {
    using S = typename Source::Shape;

  public:
    ExactForm(const Source& src, const Line& l, int orientation, double extent)
        : src_(src), shape_(src.shape), line_(l), orientation_(orientation), extent_(extent) {}

    // In BigFloat: from the exact form in double where that is exact, else formed in BigFloat.
    const exact_form::LineQuadratic<BigFloat>& quadratic() const {
        if (!q_) {
            if (const exact_form::LineQuadratic<ExactDouble>* d = in_double())
                q_ = lifted(*d);
            else
                q_ =
                    ShapeTraits<S>::template exact_quadratic<BigFloat>(shape_, line_, orientation_);
        }
        return *q_;
    }
    // The exact form in double, once; none where an operation rounded (only a frame and a line of
    // small dyadic numbers have it: most of what meets exact zeros, at a tenth of the filter's
    // cost).
    const exact_form::LineQuadratic<ExactDouble>* in_double() const {
        if (!double_tried_) {
            double_tried_ = true;
            if (!short_inputs(shape_, line_)) return nullptr;
            exact_form::LineQuadratic<ExactDouble> d =
                ShapeTraits<S>::template exact_quadratic<ExactDouble>(shape_, line_, orientation_);
            if (d.A.exact && d.B.exact && d.C0.exact && d.Z0.exact && d.dZ.exact && d.lo.exact &&
                d.hi.exact)
                double_ = d;
        }
        return double_ ? &*double_ : nullptr;
    }
    // Z along the line alone, where that is all the rung asks (an end's crossing, the point
    // there, Z constant): the quadratic's own once it is formed.
    const exact_form::LineAxial<BigFloat>& axial() const {
        if (q_ || in_double()) return quadratic();
        if constexpr (has_exact_axial<S>) {
            if (!axial_)
                axial_ =
                    ShapeTraits<S>::template exact_axial<BigFloat>(shape_, line_, orientation_);
            return *axial_;
        } else {
            return quadratic();
        }
    }
    // D = B^2 - A C0, exactly: for a tangency and for the exact rung.
    const BigFloat& discriminant() const {
        if (!D_) {
            const exact_form::LineQuadratic<BigFloat>& q = quadratic();
            D_ = q.B * q.B - q.A * q.C0;
        }
        return *D_;
    }

    // The scene scaled to unit size, once; none where it cannot be scaled exactly.
    const UnitScene<S>* unit_scene() const {
        if (!unit_tried_) {
            unit_tried_ = true;
            if (std::optional<Unit> u = unit_scale(src_, extent_, line_))
                if (std::optional<S> shape = scaled(shape_, 1 / u->pos_factor))
                    unit_.emplace(UnitScene<S>{*u, *shape});
        }
        return unit_ ? &*unit_ : nullptr;
    }
    // Its quadratic in bounded double-double, once: the filter, and the double-double rung's.
    const exact_form::LineQuadratic<BoundedDD>* filter() const {
        if (!dd_) {
            const UnitScene<S>* scene = unit_scene();
            if (!scene) return nullptr;
            dd_ = ShapeTraits<S>::template exact_quadratic<BoundedDD>(
                scene->shape, scene->unit.line, orientation_);
        }
        return &*dd_;
    }

    std::optional<EndCrossing> at(bool top, double t_factor) const override {
        using Found = std::optional<EndCrossing>;
        if (std::optional<Found> answer =
                ask_filters<Found>(t_factor, [&](const auto& q, double f) {
                    Found c = end_crossing(q, top, f);
                    return c ? std::optional<Found>(c) : std::nullopt;
                }))
            return *answer;
        std::optional<EndCrossing> c = end_crossing(quadratic(), top, 1 / t_factor);
        exact_zero_ = exact_zero_ || (c && c->q_sign == 0); // a root at the end: a rim
        return c;
    }

    // Whether the exact form showed an exact zero (a root at an end, a double root, g or Z
    // constant along the line), where a filter's bounds would most likely not decide.
    bool exact_zero() const { return exact_zero_; }

    // A cylinder's parallel line is shown by a few exact products (cheaper than the filter), and
    // C0's sign by the rung's g(0) or the filter (but on the surface); the exact form answers the
    // rest.
    std::optional<int> constant_sign(double at_0, double e_at_0) const override {
        std::optional<bool> parallel = exactly_parallel(shape_, line_);
        if (parallel && !*parallel) return std::nullopt;
        int rung_sign = std::fabs(at_0) > e_at_0 ? (at_0 > 0 ? 1 : -1) : undecided_sign;
        if (parallel && rung_sign != undecided_sign) return rung_sign;
        using Found = std::optional<int>;
        if (std::optional<Found> answer = ask_filters<Found>(1, [&](const auto& q, double) {
                std::optional<Found> none;
                int A = sign(q.A), B = sign(q.B);
                if ((A != undecided_sign && A != 0) || (B != undecided_sign && B != 0))
                    return std::optional<Found>(Found()); // g is not constant
                int c = rung_sign != undecided_sign ? rung_sign : sign(q.C0);
                if (c == undecided_sign) return none;
                if (parallel) return std::optional<Found>(c);
                if (A != 0 || B != 0) return none;
                exact_zero_ = true; // A and B exactly 0: g is constant
                return std::optional<Found>(c);
            }))
            return *answer;
        const exact_form::LineQuadratic<BigFloat>& q = quadratic();
        if (sign(q.A) != 0 || sign(q.B) != 0) return std::nullopt;
        exact_zero_ = true;
        return sign(q.C0);
    }

    std::optional<int> constant_z() const override {
        if (std::optional<ConstantZ> z = constant_z_of_line(shape_, line_, orientation_))
            return z->level;
        using Found = std::optional<int>;
        if (std::optional<Found> answer = ask_filters<Found>(1, [&](const auto& q, double) {
                int dZ = sign(q.dZ);
                if (dZ == undecided_sign) return std::optional<Found>();
                if (dZ != 0) return std::optional<Found>(Found()); // Z is not constant
                // Z is constant: its level, where the filter's signs decide it
                Found level = level_in(q);
                return level ? std::optional<Found>(level) : std::nullopt;
            }))
            return *answer;
        const exact_form::LineAxial<BigFloat>& z = axial();
        if (sign(z.dZ) != 0) return std::nullopt;
        return level_in(z, [&] { return &quadratic(); }); // in an end's plane: its disc?
    }

    // D's sign: from the exact form in double where that is exact; else, where the shape has a form
    // of lower degree (discriminant_sign), from it in bounded double-double (a near tangency),
    // then exactly (a tangency); else from the filter, then the exact form.
    std::optional<bool> tangency() const override {
        auto found = [&](int D) {
            exact_zero_ = exact_zero_ || D == 0;
            return D == 0;
        };
        if (const exact_form::LineQuadratic<ExactDouble>* d = in_double())
            if (int D = sign(d->B * d->B - d->A * d->C0); D != undecided_sign) return found(D);
        if constexpr (has_discriminant_sign<S>) {
            using Traits = ShapeTraits<S>;
            int D = Traits::template discriminant_sign<BoundedDD>(shape_, line_, orientation_);
            if (D == undecided_sign) {
                D = Traits::template discriminant_sign<BigFloat>(shape_, line_, orientation_);
            }
            return found(D);
        } else {
            if (const exact_form::LineQuadratic<BoundedDD>* dd = filter())
                if (int D = sign(dd->B * dd->B - dd->A * dd->C0); D != undecided_sign)
                    return found(D);
            return found(sign(discriminant()));
        }
    }

    // After tangency(): D = 0 is known, A's sign (the rung's proof of A > 0) too, and the
    // filter's -B/A would be no narrower than the rung's own; the exact form's (lifted from the
    // form in double where that is exact).
    std::optional<BoundedDD> double_root(double t_factor) const override {
        const exact_form::LineQuadratic<BigFloat>& q = quadratic();
        if (sign(q.A) == 0) return std::nullopt;
        return in_rung_units(enclosure(-q.B) / enclosure(q.A), 1 / t_factor);
    }

    std::optional<int> vertex_against(bool top) const override {
        if constexpr (has_tangency_against_end<S>) {
            if (!q_) { // from its form of lower degree, A != 0 shown by a few exact products
                std::optional<bool> parallel = exactly_parallel(shape_, line_);
                if (parallel && *parallel) return std::nullopt; // A = 0
                if (parallel)
                    return ShapeTraits<S>::template tangency_against_end<BigFloat>(shape_, line_,
                                                                                   top);
            }
        }
        const exact_form::LineQuadratic<BigFloat>& q = quadratic();
        if (!(top ? q.hi_bounded : q.lo_bounded) || sign(q.A) == 0) return std::nullopt;
        // Z(-B/A) - end = ((Z0 - end) A - dZ B) / A
        return sign((q.Z0 - (top ? q.hi : q.lo)) * q.A - q.dZ * q.B) * sign(q.A);
    }

    SignsAt signs_at(double near, double half) const override {
        const exact_form::LineQuadratic<BigFloat>& q = quadratic();
        BigFloat m = BigFloat(near) + BigFloat(half), half_slope = q.B + q.A * m;
        return {sign(q.C0 + m * (half_slope + q.B)), sign(half_slope), sign(q.A)};
    }

    // From the shape's type: not the exact form formed for a flag.
    bool end_open(bool /*top*/) const override { return ends_open<S>; }

    std::optional<LinearRoot> linear_root(double t_factor) const override {
        using Found = std::optional<LinearRoot>;
        if (std::optional<Found> answer =
                ask_filters<Found>(t_factor, [&](const auto& q, double f) {
                    int A = sign(q.A), B = sign(q.B);
                    if ((A != undecided_sign && A != 0) || B == 0)
                        return std::optional<Found>(Found());
                    if (A != 0 || B == undecided_sign) return std::optional<Found>();
                    exact_zero_ = true; // A exactly 0: g is linear
                    std::optional<BoundedDD> t =
                        in_rung_units(-enclosure(q.C0) / twice(enclosure(q.B)), f);
                    return t ? std::optional<Found>(LinearRoot{*t, B}) : std::nullopt;
                }))
            return *answer;
        const exact_form::LineQuadratic<BigFloat>& q = quadratic();
        if (sign(q.A) != 0 || sign(q.B) == 0) return std::nullopt;
        exact_zero_ = true;
        std::optional<BoundedDD> t =
            in_rung_units(enclosure(-q.C0) / enclosure(q.B.scaled(1)), 1 / t_factor);
        if (!t) return std::nullopt;
        return LinearRoot{*t, sign(q.B)};
    }

    // At t = c t_factor (the caller's units): G = C0 + t (2B + A t) and G' / 2 = B + A t, exactly
    // or from the shape's cheaper form (where it has one: none otherwise); in the rung's units G'
    // and A carry t_factor and its square.
    std::optional<ExactLocal> local_at(double c, double t_factor, bool exactly) const override {
        double t = c * t_factor;
        if (!std::isfinite(t)) return std::nullopt;
        auto in_rung = [&](const BoundedDD& A_at, const BoundedDD& half_slope,
                           const BoundedDD& G_at) -> std::optional<ExactLocal> {
            std::optional<BoundedDD> A = in_rung_units(A_at, t_factor * t_factor),
                                     Gp = in_rung_units(half_slope, 2 * t_factor),
                                     G0 = in_rung_units(G_at, 1);
            if (!A || !Gp || !G0) return std::nullopt;
            return ExactLocal{{A->hi, bound_of_hi(*A)},
                              {G0->hi, bound_of_hi(*G0), Gp->hi, bound_of_hi(*Gp)}};
        };
        if (!exactly) {
            if constexpr (has_local_at<S>) {
                if (std::optional<exact_form::LocalQuadratic> L =
                        ShapeTraits<S>::local_at(shape_, line_, t))
                    return in_rung(L->A, L->half_slope, L->G);
            }
            // From far away (t v reaching 64 times farther than the shape lies from the world's
            // origin), the quadratic of the line through its point at t: its C0 is G there, its B
            // G' / 2. Nearer, the line's own form cancels no more than that one would; and once
            // the exact form is formed, its local quadratic costs a few products.
            if (!q_ && std::fabs(t) * max_abs(line_.v) >= 64 * src_.magnitude())
                if (std::optional<exact_form::LineQuadratic<BoundedDD>> m = quadratic_through(t))
                    if (int G = sign(m->C0); G == 1 || G == -1) return in_rung(m->A, m->B, m->C0);
            return std::nullopt;
        }
        const exact_form::LineQuadratic<BigFloat>& q = quadratic();
        BigFloat at(t), half_slope = q.B + q.A * at, G = q.C0 + at * (half_slope + q.B);
        return in_rung(enclosure(q.A), enclosure(half_slope), enclosure(G));
    }
    std::optional<BoundedDD> crossing(bool top, double t_factor) const override {
        const exact_form::LineAxial<BigFloat>& q = axial();
        if (!(top ? q.hi_bounded : q.lo_bounded) || sign(q.dZ) == 0) return std::nullopt;
        return in_rung_units(enclosure((top ? q.hi : q.lo) - q.Z0) / enclosure(q.dZ), 1 / t_factor);
    }

    std::optional<BoundedDD> coordinate_at_end(bool top, int k) const override {
        std::optional<BigFloat> p = end_numerator(top, k);
        if (!p) return std::nullopt;
        if (sign(*p) == 0) return BoundedDD(0);
        return enclosure(*p) / enclosure(axial().dZ);
    }
    std::optional<int> coordinate_at_end_against(bool top, int k, double near,
                                                 double half) const override {
        std::optional<BigFloat> p = end_numerator(top, k);
        if (!p) return std::nullopt;
        const BigFloat& dZ = axial().dZ; // P - m = (p - m dZ) / dZ
        return sign(*p - (BigFloat(near) + BigFloat(half)) * dZ) * sign(dZ);
    }

    std::optional<int> coordinate_root_against(int k, int other_side, double near,
                                               double half) const override {
        if (line_.v[k] == 0) return std::nullopt;
        const exact_form::LineQuadratic<BigFloat>& q = quadratic();
        if (sign(q.A) == 0) return std::nullopt;
        // Q(m) = A (m - P) (m - P'): sgn(P - m) = -sgn Q(m) sgn A sgn(m - P').
        BigFloat m = BigFloat(near) + BigFloat(half);
        int Q =
            sign(q.A * m * m + (coordinate_half_slope(k) * m).scaled(1) + at_coordinate_zero(k));
        return -Q * sign(q.A) * other_side;
    }

    bool zero_at_root(int k) const override {
        return line_.v[k] != 0 && sign(at_coordinate_zero(k)) == 0;
    }

    std::optional<std::array<BoundedDD, 2>> coordinate_roots(int k) const override {
        if (line_.v[k] == 0) return std::nullopt;
        const exact_form::LineQuadratic<BigFloat>& q = quadratic();
        if (sign(q.A) == 0 || sign(discriminant()) < 0) return std::nullopt;
        BigFloat half_slope = coordinate_half_slope(k);
        BoundedDD b = enclosure(half_slope);
        BoundedDD root_D = BoundedDD(std::fabs(line_.v[k])) * sqrt(enclosure(discriminant()));
        // The stable pair: m = -(b + sgn(b) sqrt(D')), the roots m / A and c / m.
        BoundedDD m = sign(half_slope) < 0 ? root_D - b : -(b + root_D);
        return std::array<BoundedDD, 2>{enclosure(at_coordinate_zero(k)) / m, m / enclosure(q.A)};
    }

    // The planes of the bounded ends of a shape whose form does not carry them (an open
    // cylinder's, a capsule patch's seam), for the line as given, once.
    const DiscPlanes* end_planes(const Unit& unit) const override {
        if constexpr (has_end_planes<S>) {
            if (unit.pos_factor != 1 || unit.t_factor != 1) return nullptr;
            if (!planes_) planes_ = ShapeTraits<S>::end_planes(src_, line_.L0, line_.v);
            return *planes_ ? &**planes_ : nullptr;
        } else {
            return nullptr;
        }
    }

  private:
    // L0_k dZ + v_k (end - Z0), exactly: coordinate k at the end's crossing times dZ; none where
    // that end is not bounded or dZ = 0.
    std::optional<BigFloat> end_numerator(bool top, int k) const {
        const exact_form::LineAxial<BigFloat>& q = axial();
        if (!(top ? q.hi_bounded : q.lo_bounded) || sign(q.dZ) == 0) return std::nullopt;
        BigFloat N = (top ? q.hi : q.lo) - q.Z0;
        return BigFloat(line_.L0[k]) * q.dZ + BigFloat(line_.v[k]) * N;
    }

    // Half the slope of coordinate k's quadratic: B v_k - A L0_k, exactly.
    BigFloat coordinate_half_slope(int k) const {
        const exact_form::LineQuadratic<BigFloat>& q = quadratic();
        return q.B * BigFloat(line_.v[k]) - q.A * BigFloat(line_.L0[k]);
    }
    // g(-L0_k / v_k) v_k^2 = A L0_k^2 - 2 B L0_k v_k + C0 v_k^2, exactly.
    BigFloat at_coordinate_zero(int k) const {
        const exact_form::LineQuadratic<BigFloat>& q = quadratic();
        BigFloat L(line_.L0[k]), v(line_.v[k]);
        return q.A * L * L - (q.B * L * v).scaled(1) + q.C0 * v * v;
    }

    // The exact form in bounded double-double of the line through its point at t. Its terms are
    // of that point's size, not L0's: where t reaches from a far origin to the shape (a line from
    // far away), its G keeps the digits g(t) in the line's own form would cancel; where the point
    // lies a few ulps from the surface, G is as small as its bound and decides nothing (the exact
    // form's then).
    std::optional<exact_form::LineQuadratic<BoundedDD>> quadratic_through(double t) const {
        std::optional<exact_form::LineThrough<BoundedDD>> through = line_through(line_, t);
        if (!through) return std::nullopt;
        return ShapeTraits<S>::template exact_quadratic<BoundedDD>(shape_, *through, orientation_);
    }

    // The filter's parameter is the caller's over this.
    double filter_t() const { return unit_->unit.t_factor; }

    // A question asked of the cheaper quadratics in turn, the exact form in double (where it is
    // exact) and the filter, each with the factor that takes its parameter into the rung's
    // (`t_factor` is the caller's over the rung's). `answer(q, factor)` returns no value where q's
    // signs leave the question open, else the answer (itself perhaps none); the first answer
    // stands, and none where both leave it open.
    template <class T, class Answer>
    std::optional<T> ask_filters(double t_factor, Answer answer) const {
        if (const exact_form::LineQuadratic<ExactDouble>* d = in_double())
            if (std::optional<T> a = answer(*d, 1 / t_factor)) return a;
        if (const exact_form::LineQuadratic<BoundedDD>* dd = filter())
            if (std::optional<T> a = answer(*dd, filter_t() / t_factor)) return a;
        return std::nullopt;
    }

    // The exact form in BigFloat from an exact one in double.
    static exact_form::LineQuadratic<BigFloat>
    lifted(const exact_form::LineQuadratic<ExactDouble>& d) {
        exact_form::LineQuadratic<BigFloat> q;
        q.A = BigFloat(d.A.v), q.B = BigFloat(d.B.v), q.C0 = BigFloat(d.C0.v);
        q.Z0 = BigFloat(d.Z0.v), q.dZ = BigFloat(d.dZ.v), q.lo = BigFloat(d.lo.v);
        q.hi = BigFloat(d.hi.v);
        q.lo_bounded = d.lo_bounded, q.hi_bounded = d.hi_bounded;
        q.lo_capped = d.lo_capped, q.hi_capped = d.hi_capped, q.two_solids = d.two_solids;
        q.lo_open = d.lo_open, q.hi_open = d.hi_open;
        return q;
    }

    // Z0's level against the extent (ExtentEnds::constant_z) for Z constant along the line, from
    // z's signs; none where one is undecided (a filter's), or where the line lies in the plane of
    // an end without a disc (`capped()`: the quadratic that says which ends have one).
    template <class NT, class Capped>
    std::optional<int> level_in(const exact_form::LineAxial<NT>& z, Capped capped) const {
        int lo = z.lo_bounded ? sign(z.Z0 - z.lo) : 1, hi = z.hi_bounded ? sign(z.Z0 - z.hi) : -1;
        if (lo == undecided_sign || hi == undecided_sign) return std::nullopt;
        exact_zero_ = true;
        int level = level_of(lo, hi);
        if (level != -1 && level != 1) return level;
        const auto* q = capped();
        if ((level == -1 && !q->lo_capped) || (level == 1 && !q->hi_capped)) return std::nullopt;
        return level;
    }
    template <class NT>
    std::optional<int> level_in(const exact_form::LineQuadratic<NT>& q) const {
        return level_in(q, [&] { return &q; });
    }

    const Source& src_;
    const S& shape_;
    const Line& line_;
    int orientation_;
    double extent_;
    mutable bool exact_zero_ = false;
    mutable std::optional<exact_form::LineQuadratic<BigFloat>> q_;
    mutable std::optional<exact_form::LineAxial<BigFloat>> axial_;
    mutable std::optional<BigFloat> D_;
    mutable std::optional<std::optional<DiscPlanes>> planes_; // end_planes', once asked
    mutable bool double_tried_ = false;
    mutable std::optional<exact_form::LineQuadratic<ExactDouble>> double_;
    mutable bool unit_tried_ = false;
    mutable std::optional<UnitScene<S>> unit_;
    mutable std::optional<exact_form::LineQuadratic<BoundedDD>> dd_;
};

template <class Target>
struct CorrectTo {
    static constexpr Certainty says = Certainty::certain;
    static constexpr Rung rung = Rung::newton; // a proof in double with its bounds
    template <class Source>
    static Result solve(const Source& src, const Line& l, Query q) {
        Validity valid = check(src, l);
        if (!valid.error.ok()) return Result::failure(valid.error);
        if (Error e = target_error(src, l, Target{}); !e.ok()) return Result::failure(e);
        double extent = scene_extent(src, l);
        if (q.need == Need::any) q.points = false; // a hit test computes no point
        // The quick rung first, where the scene's products stay in double's normal range.
        using Traits = ShapeTraits<typename Source::Shape>;
        if constexpr (Traits::has_line_form) {
            if (q.need == Need::any && moderate(extent, l)) {
                Result r;
                LineForm form = Traits::quick_line_form(src, l.L0, l.v, valid.orientation);
                if (hit_test_rung(form, Unit{1, 1, l}, r)) {
                    r.certainty = Certainty::certain;
                    r.rung = Rung::newton;
                    hit_test_in(r, Target{});
                    return r;
                }
            }
        }
        return ladder(src, valid.orientation, extent, l, q);
    }

    // The rungs in turn, each only where the one before cannot prove its answer.
    template <class Source>
    static Result ladder(const Source& src, int orientation, double extent, const Line& l,
                         Query q) {
        using S = typename Source::Shape;
        using Traits = ShapeTraits<S>;
        Result r; // the one result, returned in place
        ExactForm<Source> exact(src, l, orientation, extent);
        // A surface without extent (a quadric) has its own local quadratic for the Newton rung.
        if constexpr (has_newton_form<S>) {
            if (moderate(extent, l))
                if (std::optional form = Traits::newton_form(src.shape, l)) {
                    if (surface_newton_rung<Target>(*form, Unit{1, 1, l}, l, q, r, &exact)) {
                        mark_certain<Target>(r, Rung::newton);
                        return r;
                    }
                    r = Result();
                }
        }
        // The Newton rung's bounds hold at any scale (underflow is in them, overflow makes them
        // infinite), so a scene of moderate size is solved as given; others are scaled first,
        // so that tiny or huge scenes are not left to the slower rungs.
        if constexpr (Traits::has_line_form) {
            bool as_given = moderate(extent, l);
            if constexpr (std::is_same_v<Target, Binary32>) {
                if (as_given) {
                    LineForm form = Traits::quick_line_form(src, l.L0, l.v, orientation);
                    if (newton_rung<Target, Residual::quick>(form, Unit{1, 1, l}, l, q, r,
                                                             &exact)) {
                        mark_certain<Target>(r, Rung::newton);
                        return r;
                    }
                    r = Result();
                }
            }
            auto newton = [&](const auto& scene, const Unit& unit) LINEQUAD_INLINE_LAMBDA {
                LineForm form = Traits::line_form(scene, unit.line.L0, unit.line.v, orientation);
                if (newton_rung<Target>(form, unit, l, q, r, &exact)) {
                    mark_certain<Target>(r, Rung::newton);
                    return true;
                }
                r = Result();
                return false;
            };
            if (as_given) {
                if (newton(src, Unit{1, 1, l})) return r;
            } else if (const UnitScene<S>* scene = exact.unit_scene()) {
                if (newton(AsGiven<S>{scene->shape}, scene->unit)) return r;
            }
        }
        if (const exact_form::LineQuadratic<BoundedDD>* dd = exact.filter()) {
            if (double_double_rung<Target>(*dd, exact.unit_scene()->unit, q, r)) {
                mark_certain<Target>(r, Rung::double_double);
                return r;
            }
            r = Result(); // what the rung left
        }
        r = exact_rung<Target>(exact.quadratic(), exact.discriminant(), l, q, !exact.exact_zero());
        mark_certain<Target>(r, Rung::exact);
        return r;
    }
};

using Correct = CorrectTo<Binary64>;
using Correct32 = CorrectTo<Binary32>;

} // namespace linequad::detail
