// Line against a general quadric {q, coincident} (GQ order): every derivation of it, once.
//
// Derivation (checked against the surface equation). P is on the surface iff f(P) = 0 with
//     f(x) = A x^2 + B y^2 + C z^2 + D xy + E yz + F zx + G x + H y + J z + K.
// Substituting P = L0 + t v and expanding term by term (sense/sense_terms.hpp writes out the
// expansion, once for every number type):
//     g(t) = f(L0 + t v) = f2(v) t^2 + (grad f(L0) . v) t + f(L0),
// f2 the quadratic part. In the half-b form every solver takes, multiplied by 2 so that no
// coefficient holds a half:
//     A t^2 + 2 B t + C0 = 0,   A = 2 f2(v),   B = grad f(L0) . v,   C0 = 2 f(L0).
// No extent: every root is on the surface. A = 0 (v along an asymptotic direction, or the surface
// a plane) leaves the linear root; A = B = 0 a line on the surface (C0 = 0) or a miss. Every
// degenerate quadric (a plane pair, a line, a point, nothing) is such a polynomial too, and answers
// as one. `coincident` (the caller's word that L0 is on the surface): C0 = 0 exactly, so the hits
// are t = 0 and -2B / A; g at any other point P of the line is then f(P) - f(L0).
//
// seed: the transport codes' (OpenMC's SurfaceQuadric::distance): a = f2(v),
// k = half the linear coefficient and c = f(L0) as written there, and the roots (-k -+ sqrt(k^2 -
// a c)) / a. Handed over as the textbook a t^2 + b t + c with b = 2k, whose roots round exactly as
// the half-b formula's (every factor of 2 is exact).
//
// stable: the quadric in the prescaled frame (positions times 2^-k: the linear coefficients times
// 2^-k and K times 2^-2k after multiplying through by 2^2k, then all by one power of two towards
// 1), exactly or refused; A, B and C0 at the line's own origin as compensated sums of exact
// products, B and C0 kept to twice the precision, and D = B^2 - A C0 from their two parts (a far
// source's B^2 and A C0 cancel in the last bits of double-double, not of double). The origin is
// not moved: there is no geometric form of D for a general quadric, and a rounded moved origin
// is another line (exact tangencies were lost).
//
// certified: the same quantities in bounded arithmetic (the scaling too: a bounded product covers
// underflow), QuickBounded then Bounded; D = B^2 - A C0 as it is (its bound grows with a far
// source's B^2: uncertain there, never wrong).
//
// exact: A, B and C0 above, term by term in any exact ring type.
//
// correct: no line form of signed squares (a general quadric has none without a division); the
// ladder takes the exact form in double-double on the scene scaled to unit size, then BigFloat.
#pragma once

#include "forms/bounds.hpp"
#include "forms/certified.hpp"
#include "forms/exact_form.hpp"
#include "forms/roots.hpp"
#include "forms/traits.hpp"
#include "numeric/compensated_sum.hpp"
#include "sense/sense_terms.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <type_traits>

namespace linequad::detail {

// A sum of products kept to about twice the working precision (as numeric/compensated_sum.hpp,
// without its bound, and for float too): each product exact (two_prod), each sum's error carried
// (two_sum), a three-factor product's last low part rounded once.
template <class T>
struct ProductSum {
    T s = T(0), c = T(0);
    void add(T x) {
        TwoTermT<T> t = two_sum(s, x);
        s = t.hi, c = c + t.lo;
    }
    void add(T k, T a) {
        TwoTermT<T> p = two_prod(k, a);
        add(p.hi), c = c + p.lo;
    }
    void add(T k, T a, T b) { // k a b
        TwoTermT<T> p = two_prod(a, b), q = two_prod(k, p.hi);
        add(q.hi), c = c + (q.lo + k * p.lo);
    }
    T value() const { return s + c; }
};

// A = 2 f2(v), B = grad f(w) . v and 2 f(w) (C0 at w) as products k a b of doubles, each handed
// to a sum's add(k), add(k, a) or add(k, a, b) (the factors 2 taken into k, exactly): stable's
// sums (ProductSum) and the correct filter's (QuadricFilterSum) take one list.
template <class T, class Sum>
LINEQUAD_INLINE void curvature_products(const QuadricCoefficients<T>& q, Vec3T<T> v, Sum& A) {
    const T two(2);
    A.add(two * q[0], v.x, v.x), A.add(two * q[1], v.y, v.y), A.add(two * q[2], v.z, v.z);
    A.add(two * q[3], v.x, v.y), A.add(two * q[4], v.y, v.z), A.add(two * q[5], v.z, v.x);
}
template <class T, class Sum>
LINEQUAD_INLINE void slope_products(const QuadricCoefficients<T>& q, Vec3T<T> w, Vec3T<T> v,
                                    Sum& B) {
    const T two(2);
    B.add(two * q[0], w.x, v.x), B.add(q[3], w.y, v.x), B.add(q[5], w.z, v.x), B.add(q[6], v.x);
    B.add(two * q[1], w.y, v.y), B.add(q[3], w.x, v.y), B.add(q[4], w.z, v.y), B.add(q[7], v.y);
    B.add(two * q[2], w.z, v.z), B.add(q[4], w.y, v.z), B.add(q[5], w.x, v.z), B.add(q[8], v.z);
}
template <class T, class Sum>
LINEQUAD_INLINE void value_products(const QuadricCoefficients<T>& q, Vec3T<T> w, Sum& C) {
    const T two(2);
    C.add(two * q[0], w.x, w.x), C.add(two * q[1], w.y, w.y), C.add(two * q[2], w.z, w.z);
    C.add(two * q[3], w.x, w.y), C.add(two * q[4], w.y, w.z), C.add(two * q[5], w.z, w.x);
    C.add(two * q[6], w.x), C.add(two * q[7], w.y), C.add(two * q[8], w.z), C.add(two * q[9]);
}

// The quadric of a shape's positions times 2^-k, multiplied through by 2^2k and then by a power
// of two that brings its largest coefficient near 1: the same surface in the scaled frame, in R.
// None where a nonzero coefficient would leave R's normal range (it would lose bits).
template <class R>
std::optional<QuadricCoefficients<R>> quadric_in_frame(const QuadricCoefficients<double>& q,
                                                       int k) {
    // Each coefficient's shift: 0 for the quadratic part, -k for the linear, -2k for K.
    auto shift_of = [&](int i) { return i < 6 ? 0 : i < 9 ? -k : -2 * k; };
    int top = -(1 << 30);
    for (int i = 0; i < 10; ++i)
        if (q[i] != 0) top = std::max(top, Binary64::exponent(q[i]) + shift_of(i));
    QuadricCoefficients<R> out{};
    for (int i = 0; i < 10; ++i) {
        if (q[i] == 0) continue;
        // A multiply by a power of two (exact where the result is normal; ldexp, a libm call,
        // only beyond R's moderate exponents).
        int shift = shift_of(i) - top;
        R x = std::abs(shift) <= Format<R>::moderate_exponent ? R(q[i]) * Format<R>::pow2(shift)
                                                              : std::ldexp(R(q[i]), shift);
        if (!(std::fabs(x) >= std::numeric_limits<R>::min() &&
              std::fabs(x) <= std::numeric_limits<R>::max()))
            return std::nullopt;
        out[i] = x;
    }
    return out;
}

// The arithmetic of stable's quadric solve, once, for a real type R (double or float).
template <class T>
struct QuadricStable {
    static constexpr bool parallel_is_miss = false; // A = 0: a linear root, or none, or on it
    using Mask = bool;
    QuadricCoefficients<T> q{};
    Vec3T<T> L0, v;
    bool coincident = false, in_frame = false;
    T smallest = T(0); // the smallest nonzero |coefficient| in the frame
    T A = T(0), tc = T(0), B = T(0), C_moved = T(0), D = T(0);

    QuadricStable(const std::optional<QuadricCoefficients<T>>& framed, bool coincident_,
                  Vec3T<T> L0_, Vec3T<T> v_)
        : L0(L0_), v(v_), coincident(coincident_), in_frame(framed.has_value()) {
        if (!in_frame) return;
        q = *framed;
        smallest = Format<T>::inf;
        for (int i = 0; i < 10; ++i)
            if (q[i] != 0) smallest = std::min(smallest, std::fabs(q[i])); // not fmin: a call
        ProductSum<T> a;
        curvature_products(q, v, a);
        A = a.value();
    }
    // The scaling lost bits: the solver refuses (out_of_range, "q").
    Mask smaller_than(T) const { return !in_frame; }
    // A coefficient below the square root of tiny_decisive: its products with two coordinates
    // may underflow, and a zero of A or D be what is left of them.
    Mask zero_may_underflow() const {
        return smallest < T(std::sqrt(double(Guards<T>::tiny_decisive)));
    }
    Mask scalar_only() const { return false; }

    // 2 f(w): C0 at w, unrounded.
    ProductSum<T> twice_value(Vec3T<T> w) const {
        ProductSum<T> c;
        if (!coincident) value_products(q, w, c);
        return c;
    }
    // grad f(w) . v: B at w, unrounded.
    ProductSum<T> slope(Vec3T<T> w) const {
        ProductSum<T> b;
        slope_products(q, w, v, b);
        return b;
    }
    T C0_at_origin() const { return twice_value(L0).value(); }
    // At the line's own origin: B and C0 kept to twice the precision, and D = B^2 - A C0 formed
    // from their two parts, so that a far source's huge B^2 and A C0 cancel without losing D
    // (and exact inputs give an exact D: a tangency is found, which moving the origin to a
    // rounded point lost).
    void discriminant() {
        tc = T(0);
        ProductSum<T> b = slope(L0), c = twice_value(L0);
        B = b.value(), C_moved = c.value();
        T B_lo = (b.s - B) + b.c, C_lo = (c.s - C_moved) + c.c;
        ProductSum<T> d;
        d.add(B, B), d.add(T(2) * B, B_lo);
        d.add(-A, C_moved), d.add(-A, C_lo);
        D = d.value();
    }
    template <class Roots>
    T z_of(const Roots&, int) const {
        return T(0);
    }
    T z_lanes(T, T, Mask) const { return T(0); }
    T axial_moved() const { return T(0); }
    T axial_rate() const { return T(0); }
    template <class S>
    ExtentT<T> extent(const S&) const {
        return {T(-Binary64::inf), T(Binary64::inf)};
    }
};

// The certified quantities: the same, each with its bound.
template <class BT>
CertifiedForm<BT> quadric_certified(const QuadricCoefficients<double>& q, bool coincident,
                                    const Prescale& ps, const Line& l) {
    // Positions times 2^-k: multiplied through by 2^2k, the linear coefficients times 2^-k and
    // K times 2^-2k; bounded products (they cover underflow).
    BT to_unit = BT::exact(ps.to_unit);
    QuadricCoefficients<BT> c;
    for (int i = 0; i < 10; ++i) {
        c[i] = BT::exact(q[i]);
        if (i >= 6) c[i] = c[i] * to_unit;
        if (i == 9) c[i] = c[i] * to_unit;
    }
    // At the line's own origin, as stable: exact inputs keep exact zeros (a line on the surface,
    // a tangency), which a moved origin's rounding would blur.
    Vec3 v = ps.dir(l.v), L0 = ps.pos(l.L0);
    BoundedVec3<BT> w = exact<BT>(L0), V = exact<BT>(v);
    const BT two = BT::exact(2);
    auto sum = [](auto terms) {
        BT s = BT::exact(0);
        terms([&](const BT& x) { s = s + x; });
        return s;
    };
    BT A = two * sum([&](auto add) { quadric_curvature_terms(c, V, add); });
    BT B = sum([&](auto add) { quadric_slope_terms(c, w, V, add); });
    BT C = coincident ? BT::exact(0) : two * sum([&](auto add) { quadric_value_terms(c, w, add); });
    return {
        {A, B, C, B * B - A * C}, 0.0, BT::exact(0), BT::exact(0), {-Binary64::inf, Binary64::inf}};
}

// The line's own origin: where a coincident surface's g is 0.
inline Vec3 own_origin(const Line& l) {
    return l.L0;
}
template <class NT>
Vec3 own_origin(const exact_form::LineThrough<NT>& l) {
    return l.line_L0;
}

// The correct ladder's filter: A, B and C0 in bounded double-double at the line's own origin, each
// one compensated sum of exact products with one bound (numeric/compensated_sum.hpp) rather than
// a chain of bounded operations (a third of the instructions). A term of a zero coefficient is
// left out, so that an absent degree is an exact 0 (a plane's A, a coincident C0).
struct QuadricFilterSum {
    CompensatedSum sum;
    bool any = false;
    void add(double k) {
        if (k != 0) sum.add_exact(k), any = true;
    }
    void add(double k, double a) {
        if (k != 0) sum.add_product(k, a), any = true;
    }
    void add(double k, double a, double b) { // k a b: a b exactly, then k times each part
        if (k == 0) return;
        TwoTerm p = two_prod(a, b);
        sum.add_product(k, p.hi), sum.add_small(k * p.lo), any = true;
    }
    BoundedDD result() const { return any ? sum.result() : BoundedDD(0.0); }
};
inline exact_form::LineQuadratic<BoundedDD> quadric_filter(const QuadricCoefficients<double>& q,
                                                           bool coincident, const Line& l) {
    QuadricFilterSum A, B, C;
    curvature_products(q, l.v, A);
    slope_products(q, l.L0, l.v, B);
    if (!coincident) value_products(q, l.L0, C);
    exact_form::LineQuadratic<BoundedDD> out;
    out.A = A.result(), out.B = B.result(), out.C0 = C.result();
    out.Z0 = out.dZ = out.lo = out.hi = BoundedDD(0.0);
    out.lo_bounded = out.hi_bounded = false;
    return out;
}

// A t^2 + 2 B t + C0 in NT, exactly, at the line's origin (or a point of it: LineThrough).
template <class NT, class L>
exact_form::LineQuadratic<NT> quadric_terms(const QuadricCoefficients<double>& q, bool coincident,
                                            const L& l) {
    using exact_form::lift;
    QuadricCoefficients<NT> c;
    for (int i = 0; i < 10; ++i)
        c[i] = NT(q[i]);
    Vec3T<NT> P = exact_form::origin<NT>(l), v = lift<NT>(l.v);
    const NT two(2);
    exact_form::LineQuadratic<NT> out;
    out.A = two * exact_sum<NT>([&](auto add) { quadric_curvature_terms(c, v, add); });
    out.B = exact_sum<NT>([&](auto add) { quadric_slope_terms(c, P, v, add); });
    auto value_at = [&](const Vec3T<NT>& x) {
        return exact_sum<NT>([&](auto add) { quadric_value_terms(c, x, add); });
    };
    if (!coincident)
        out.C0 = two * value_at(P);
    else if constexpr (std::is_same_v<L, Line>)
        out.C0 = NT(0);
    else
        out.C0 = two * (value_at(P) - value_at(lift<NT>(own_origin(l))));
    out.Z0 = out.dZ = out.lo = out.hi = NT(0);
    out.lo_bounded = out.hi_bounded = false;
    return out;
}
// The same, the filter's way in bounded double-double at the line's own origin.
template <class NT, class L>
exact_form::LineQuadratic<NT> quadric_quadratic(const QuadricCoefficients<double>& q,
                                                bool coincident, const L& l) {
    if constexpr (std::is_same_v<NT, BoundedDD> && std::is_same_v<L, Line>)
        return quadric_filter(q, coincident, l);
    else
        return quadric_terms<NT>(q, coincident, l);
}

// The quadric's length scale, a power of two: where its terms of each degree balance
// (a2 L^2 ~ a1 L ~ a0 for the largest coefficient of each degree), for prescaling; 0 when none
// does (a single degree: a cone or a plane through the origin has no size, and the line's origin
// alone sets the scene's).
inline double quadric_length(const QuadricCoefficients<double>& q) {
    double a2 = max_abs(std::array<double, 6>{q[0], q[1], q[2], q[3], q[4], q[5]});
    double a1 = std::max({std::fabs(q[6]), std::fabs(q[7]), std::fabs(q[8])});
    double a0 = std::fabs(q[9]);
    auto e = [](double x) { return Binary64::exponent(x); };
    int L = -(1 << 20);
    if (a2 > 0 && a0 > 0) L = std::max(L, (e(a0) - e(a2)) / 2);
    if (a2 > 0 && a1 > 0) L = std::max(L, e(a1) - e(a2));
    if (a1 > 0 && a0 > 0) L = std::max(L, e(a0) - e(a1));
    if (L == -(1 << 20)) return 0;
    return std::ldexp(1.0,
                      std::clamp(L, -Binary64::moderate_exponent, Binary64::moderate_exponent));
}

// The same surface with every position times f (a power of two): multiplied through by f^2,
// the linear coefficients times f and K times f^2; none where a nonzero one would lose bits.
inline std::optional<QuadricCoefficients<double>> quadric_scaled(QuadricCoefficients<double> q,
                                                                 double f) {
    for (int i = 6; i < 10; ++i) {
        if (q[i] == 0) continue;
        double x = q[i] * f * (i == 9 ? f : 1.0);
        if (!(std::fabs(x) >= std::numeric_limits<double>::min() && std::fabs(x) <= Binary64::max))
            return std::nullopt;
        q[i] = x;
    }
    return q;
}

// What the plane and the quadric share: each is f of degree at most 2, given by its ten GQ
// coefficients (Traits::coefficients) and `coincident`; unbounded; every layer but the seed is the
// quadric's derivation above. A surface's traits derive from AsQuadric<S, their own type>.
template <class S, class Traits>
struct AsQuadric {
    static constexpr bool has_line_form = false; // correct: the exact form's rungs

    // ---- Positions: the coefficients are not positions ----

    static double magnitude(const S& s) { return quadric_length(Traits::coefficients(s)); }

    // ---- Bounds (a scene's culling): unbounded ----

    static Box bounds(const S&) { return everything(); }
    static BoundingCapsule bounding_capsule(const S&) { return {{}, {}, Binary64::inf}; }

    static void prepare(const S&, Facts<S>&) {}

    // ---- stable ----

    template <class T>
    using Stable = QuadricStable<T>;
    template <class T, class Source, class Scale>
    static Stable<T> stable_core(const Source& src, const Scale& ps, Vec3T<T> L0, Vec3T<T> v) {
        const S& s = src.shape;
        return {quadric_in_frame<T>(Traits::coefficients(s), ps.k), s.coincident, ps.pos(L0),
                ps.dir(v)};
    }

    // ---- certified ----

    template <class B, class Source>
    static CertifiedForm<B> certified_form(const Source& src, const Prescale& ps, const Line& l) {
        return quadric_certified<B>(Traits::coefficients(src.shape), src.shape.coincident, ps, l);
    }

    // ---- exact ----

    template <class NT>
    static int exact_orientation(const S&) {
        return 0;
    }
    template <class NT, class L>
    static exact_form::LineQuadratic<NT> exact_quadratic(const S& s, const L& l,
                                                         int /*orientation*/) {
        return quadric_quadratic<NT>(Traits::coefficients(s), s.coincident, l);
    }
    template <class NT>
    static int discriminant_sign(const S& s, const Line& l, int /*orientation*/) {
        exact_form::LineQuadratic<NT> g = exact_quadratic<NT>(s, l, 0);
        return sign(g.B * g.B - g.A * g.C0);
    }
};

template <>
struct ShapeTraits<Quadric> : AsQuadric<Quadric, ShapeTraits<Quadric>> {
    static constexpr const char* name = "quadric";
    static constexpr auto fields = std::make_tuple(field("q", &Quadric::q));
    static constexpr const char* scale_fields = "q";
    static constexpr const char* fragile_fields = "v,q";

    static const QuadricCoefficients<double>& coefficients(const Quadric& s) { return s.q; }

    static Validity validate(const Quadric& s) {
        if (max_abs(s.q) == 0) return {{ErrorCode::zero_coefficients, "q"}};
        return {};
    }

    static std::optional<Quadric> scaled_exactly(const Quadric& s, double f) {
        std::optional<QuadricCoefficients<double>> q = quadric_scaled(s.q, f);
        if (!q) return std::nullopt;
        return Quadric{*q, s.coincident};
    }

    // ---- seed: OpenMC's a, k, c as written ----

    template <class R, class Source>
    static SeedFormT<R> seed_form(const Source& src, const Line& l) {
        const Quadric& s = src.shape;
        R A = R(s.q[0]), B = R(s.q[1]), C = R(s.q[2]), D = R(s.q[3]), E = R(s.q[4]), F = R(s.q[5]),
          G = R(s.q[6]), H = R(s.q[7]), J = R(s.q[8]), K = R(s.q[9]);
        R x = R(l.L0.x), y = R(l.L0.y), z = R(l.L0.z), u = R(l.v.x), v = R(l.v.y), w = R(l.v.z);
        R a = A * u * u + B * v * v + C * w * w + D * u * v + E * v * w + F * u * w;
        R k = A * u * x + B * v * y + C * w * z +
              R(0.5) * (D * (u * y + v * x) + E * (v * z + w * y) + F * (w * x + u * z) + G * u +
                        H * v + J * w);
        R c = s.coincident ? R(0)
                           : A * x * x + B * y * y + C * z * z + D * x * y + E * y * z + F * x * z +
                                 G * x + H * y + J * z + K;
        bool usable = std::isfinite(a) && std::isfinite(k) && std::isfinite(c);
        return {a, 2 * k, c, R(0), R(0), Extent{-Binary64::inf, Binary64::inf}, usable};
    }
};

} // namespace linequad::detail
