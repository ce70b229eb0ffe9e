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
// correct: no line form of signed squares (a general quadric has none without a division), but
// the Newton rung needs only g's local quadratic at a point c of the line, and a quadric's is its
// own Taylor expansion, exact at any point: g(c + x) = A x^2 + G' x + G with A = f2(v),
// G = f(P), G' = grad f(P) . v at P = L0 + c v (QuadricNewtonForm). P is held as s + w (s the
// rounded sum, w what it dropped), and f(P) = f(s) + grad f(s) . w + f2(w): f(s) in double-double,
// the rest, some 2^-53 of it, in double. Evaluated at the hit rather than at L0, G keeps its
// digits for a far source. Where the rung cannot prove (a tangency, a root at the range's end,
// `coincident`), the ladder takes the exact form in double-double on the scene scaled to unit
// size, then BigFloat.
#pragma once

#include "forms/bounds.hpp"
#include "forms/certified.hpp"
#include "forms/exact_form.hpp"
#include "forms/line_form.hpp"
#include "forms/roots.hpp"
#include "forms/traits.hpp"
#include "numeric/compensated_sum.hpp"
#include "numeric/two_lanes.hpp"
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
    LINEQUAD_INLINE void add(T x) {
        TwoTermT<T> t = two_sum(s, x);
        s = t.hi, c = c + t.lo;
    }
    LINEQUAD_INLINE void add(T k, T a) {
        TwoTermT<T> p = two_prod(k, a);
        add(p.hi), c = c + p.lo;
    }
    LINEQUAD_INLINE void add(T k, T a, T b) { // k a b
        TwoTermT<T> p = two_prod(a, b), q = two_prod(k, p.hi);
        add(q.hi), c = c + (q.lo + k * p.lo);
    }
    LINEQUAD_INLINE T value() const { return s + c; }
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

// quadric_in_frame in lanes of L (the batch kernels'), each lane's 2^-k its `to_unit`: the
// coefficients times 2^-k per degree, then all by the power of two of the largest, as two or three
// products by powers of two, exact while each stays in R's normal range: the same values as
// quadric_in_frame's in the lanes of `ok`, the others the scalar solver's. *smallest: the
// smallest nonzero |coefficient| in the frame.
template <class L>
LINEQUAD_INLINE QuadricCoefficients<L> quadric_in_frame_lanes(const QuadricCoefficients<double>& q,
                                                              L to_unit, MaskOf<L>& ok,
                                                              L& smallest) {
    using R = Real<L>;
    const L lo(std::numeric_limits<R>::min()), hi(std::numeric_limits<R>::max());
    QuadricCoefficients<L> c;
    L largest(R(0));
    ok = !(lo < lo); // every lane
    for (int i = 0; i < 10; ++i) {
        c[i] = L(R(q[i]));
        if (i >= 6) c[i] = c[i] * to_unit;
        if (i == 9) c[i] = c[i] * to_unit;
        if (q[i] == 0) continue;
        ok = ok & (lo <= fabs(c[i])) & (fabs(c[i]) <= hi);
        largest = maximum(largest, fabs(c[i]));
    }
    L inv = power_of_two_inverse(largest); // 2^-E for the largest in [2^E, 2^(E+1))
    smallest = L(std::numeric_limits<R>::infinity());
    for (int i = 0; i < 10; ++i) {
        if (q[i] == 0) continue;
        c[i] = c[i] * inv;
        L size = fabs(c[i]);
        ok = ok & (lo <= size) & (size <= hi);
        smallest = select(size < smallest, size, smallest);
    }
    return c;
}

// The arithmetic of stable's quadric solve, once, for a real type R (double or float) or lanes of
// one (the batch kernels').
template <class T>
struct QuadricStable {
    static constexpr bool parallel_is_miss = false; // A = 0: a linear root, or none, or on it
    using Mask = MaskOf<T>;
    QuadricCoefficients<T> q{};
    Vec3T<T> L0, v;
    bool coincident = false;
    Mask in_frame{};
    T smallest = T(0); // the smallest nonzero |coefficient| in the frame
    T A = T(0), tc = T(0), B = T(0), C_moved = T(0), D = T(0);
    T A_lo = T(0); // what A, rounded, left out: a far source's A C0 needs it

    QuadricStable(const std::optional<QuadricCoefficients<T>>& framed, bool coincident_,
                  Vec3T<T> L0_, Vec3T<T> v_)
        : L0(L0_), v(v_), coincident(coincident_), in_frame(framed.has_value()) {
        if (!in_frame) return;
        q = *framed;
        smallest = Format<T>::inf;
        for (int i = 0; i < 10; ++i)
            if (q[i] != 0) smallest = std::min(smallest, std::fabs(q[i])); // not fmin: a call
        curvature();
    }
    // Lanes: the frame quadric_in_frame_lanes made, in frame where `ok`.
    QuadricStable(const QuadricCoefficients<T>& framed, Mask ok, T smallest_, bool coincident_,
                  Vec3T<T> L0_, Vec3T<T> v_)
        : q(framed), L0(L0_), v(v_), coincident(coincident_), in_frame(ok), smallest(smallest_) {
        curvature();
    }
    LINEQUAD_INLINE void curvature() {
        ProductSum<T> a;
        curvature_products(q, v, a);
        A = a.value();
        A_lo = (a.s - A) + a.c;
    }
    // The scaling lost bits: the solver refuses (out_of_range, "q").
    Mask smaller_than(T) const { return !in_frame; }
    // A coefficient below the square root of tiny_decisive: its products with two coordinates
    // may underflow, and a zero of A or D be what is left of them.
    Mask zero_may_underflow() const {
        return smallest < T(Real<T>(std::sqrt(double(Guards<Real<T>>::tiny_decisive))));
    }
    Mask scalar_only() const { return Mask{}; } // false; in lanes, no lane

    // 2 f(w): C0 at w, unrounded.
    LINEQUAD_INLINE ProductSum<T> twice_value(Vec3T<T> w) const {
        ProductSum<T> c;
        if (!coincident) value_products(q, w, c);
        return c;
    }
    // grad f(w) . v: B at w, unrounded.
    LINEQUAD_INLINE ProductSum<T> slope(Vec3T<T> w) const {
        ProductSum<T> b;
        slope_products(q, w, v, b);
        return b;
    }
    LINEQUAD_INLINE T C0_at_origin() const { return twice_value(L0).value(); }
    // At the line's own origin: A, B and C0 kept to twice the precision, and D = B^2 - A C0
    // formed from their two parts, so that a far source's huge B^2 and A C0 cancel without losing D
    // (and exact inputs give an exact D: a tangency is found, which moving the origin to a
    // rounded point lost).
    LINEQUAD_INLINE void discriminant() {
        tc = T(0);
        ProductSum<T> b = slope(L0), c = twice_value(L0);
        B = b.value(), C_moved = c.value();
        T B_lo = (b.s - B) + b.c, C_lo = (c.s - C_moved) + c.c;
        ProductSum<T> d;
        d.add(B, B), d.add(T(2) * B, B_lo);
        d.add(-A, C_moved), d.add(-A, C_lo), d.add(-A_lo, C_moved);
        D = d.value();
    }
    template <class Roots>
    T z_of(const Roots&, int) const {
        return T(0);
    }
    T z_lanes(T, T, Mask) const { return T(Real<T>(0)); }
    T axial_moved() const { return T(0); }
    T axial_rate() const { return T(0); }
    template <class S>
    ExtentT<T> extent(const S&) const {
        const Real<T> inf = std::numeric_limits<Real<T>>::infinity();
        return {T(-inf), T(inf)};
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

// The Newton rung's view of a quadric (see the derivation above), for a line of the scene as given.
// Bounds: a rounded sum of n products errs by at most gamma_(n+1) of its terms' magnitudes
// (Higham (3.5), one more u for each product's rounding); what is some 2^-53 of G already (w's
// terms, grad f(s)'s rounding times w) is bounded by magnitudes, loosely. Every bound is a dozen
// roundings of nonnegative terms (cover(32)). Products that underflow err by 2^-1074 absolute:
// an absolute floor, times a coefficient where a coefficient multiplies them. Overflow makes a
// value or a bound infinite or NaN, which proves nothing.
template <class R>
class QuadricNewtonFormT {
    using F = Binary64;
    static constexpr double u = F::u;
    using Mask = MaskOf<R>;

  public:
    // The form of the line (L0, v), R = double, or of a lane of lines (R a lane type: the batch
    // correct solver's, simd/correct_lanes.hpp); the shape's coefficients are doubles.
    QuadricNewtonFormT(const QuadricCoefficients<double>& q, const Vec3T<R>& L0, const Vec3T<R>& v)
        : q_(q), L0_(L0), v_(v) {
        for (int i = 0; i < 6; ++i)
            quadratic_size_ += std::fabs(q[i]);
        quadratic_size_ *= F::cover(8);
        linear_size_ = std::fabs(q[6]) + std::fabs(q[7]) + std::fabs(q[8]);
        using std::fabs;
        v_sum_ = fabs(v_.x) + fabs(v_.y) + fabs(v_.z);
        v_max_ = maximum(maximum(fabs(v_.x), fabs(v_.y)), fabs(v_.z));
    }
    // None for `coincident`: g is then f(P) - f(L0), which this form does not carry.
    static std::optional<QuadricNewtonFormT> of(const QuadricCoefficients<double>& q,
                                                bool coincident, const Line& l) {
        if (coincident) return std::nullopt;
        return QuadricNewtonFormT(q, l.L0, l.v);
    }

    // Whether f has no quadratic part (a plane): g is then linear, and A exactly 0.
    bool linear() const { return quadratic_size_ == 0; }

    // A = f2(v): six rounded products q_i (v_a v_b) and five sums (8u covers gamma_7). Exactly 0,
    // with no bound, where f has no quadratic part (a plane): g is then linear.
    newton::Leading<R> leading() const {
        using std::fabs;
        if (linear()) return {R(0.0), R(0.0)};
        const Vec3T<R>& v = v_;
        auto q = [&](int i) { return coefficient(i); };
        R t[6] = {q(0) * (v.x * v.x), q(1) * (v.y * v.y), q(2) * (v.z * v.z),
                  q(3) * (v.x * v.y), q(4) * (v.y * v.z), q(5) * (v.z * v.x)};
        R A(0.0), size(0.0);
        for (R x : t)
            A = A + x, size = size + fabs(x);
        return {A, (R(8 * u) * size + R(quadratic_size_ * 0x1p-1072)) * R(F::cover(32)) +
                       R(F::underflow_floor)};
    }

    // g(c + x) = A x^2 + G' x + G at the point P = L0 + c v; T is R, or D2 for two points of one
    // line at once (the two roots' estimates: numeric/two_lanes.hpp), each lane the bits of R's.
    template <class T = R>
    LINEQUAD_INLINE newton::Local<T> local_at(T c) const {
        using std::fabs;
        // P = s + w + delta exactly: s + (the low parts) is L0 + c v exactly (two_prod, two_sum),
        // w their sum rounded once: |delta_k| <= u |w_k|, or 2^-1074 where c v_k underflows.
        T s[3], w[3];
        for (int k = 0; k < 3; ++k) {
            TwoTermT<T> cv = two_prod(c, T(v_[k])), sum = two_sum(T(L0_[k]), cv.hi);
            s[k] = sum.hi, w[k] = sum.lo + cv.lo;
        }
        // f(s) in double-double: each q_i s_a s_b as q_i times the exact pair s_a s_b.
        CompensatedSumT<T> f;
        constexpr int a_of[6] = {0, 1, 2, 0, 1, 2}, b_of[6] = {0, 1, 2, 1, 2, 0};
        for (int i = 0; i < 6; ++i) {
            TwoTermT<T> p = two_prod(s[a_of[i]], s[b_of[i]]);
            f.add_product(T(q_[i]), p.hi);
            f.add_small(T(q_[i]) * p.lo);
        }
        for (int k = 0; k < 3; ++k)
            f.add_product(T(q_[6 + k]), s[k]);
        f.add_exact(T(q_[9]));
        BoundedDDT<T> fs = f.unnormalized();
        // grad f(s) in double, each component four terms (gamma_4: 5u) no larger than
        // 2 quadratic_size max|s| + linear_size together.
        Vec3T<T> at{s[0], s[1], s[2]}, g = gradient(at);
        T s_max = maximum(maximum(fabs(s[0]), fabs(s[1])), fabs(s[2]));
        T e_g = T(5 * u) * (T(2 * quadratic_size_) * s_max + T(linear_size_)) * T(F::cover(8)) +
                T(F::underflow_floor);
        // G = f(s) + grad f(s) . w + [grad f(s) . delta + f2(w + delta)], the bracket bounded
        // with W = sum |w_k| + slack >= max |w_k + delta_k|.
        T gw = g.x * w[0] + g.y * w[1] + g.z * w[2];
        T aw = fabs(w[0]) + fabs(w[1]) + fabs(w[2]);
        T gw_size = fabs(g.x * w[0]) + fabs(g.y * w[1]) + fabs(g.z * w[2]);
        T g_size = fabs(g.x) + fabs(g.y) + fabs(g.z) + T(3.0) * e_g;
        T W = aw * T(1 + 4 * u) + T(F::subnormal_slack);
        T lo = fs.lo + gw, G = fs.hi + lo;
        // An s_a s_b below the normal range is 2^-1074 off in its pair, times q_i.
        T e_G = (fs.e + e_g * aw + T(6 * u) * gw_size + g_size * T(F::subnormal_slack) +
                 T(quadratic_size_) * (W * W + T(0x1p-1070)) + T(u) * (fabs(lo) + fabs(G))) *
                    T(F::cover(32)) +
                T(2 * F::underflow_floor);
        // G' = grad f(P) . v = grad f(s) . v + d^T H v (d = w + delta, H the Hessian, whose
        // entries' magnitudes sum to 2 quadratic_size).
        Vec3T<T> v{T(v_.x), T(v_.y), T(v_.z)};
        T Gp = g.x * v.x + g.y * v.y + g.z * v.z;
        T gv_size = fabs(g.x * v.x) + fabs(g.y * v.y) + fabs(g.z * v.z);
        T e_Gp = (e_g * T(v_sum_) + T(4 * u) * gv_size + T(2 * quadratic_size_) * W * T(v_max_)) *
                     T(F::cover(32)) +
                 T(F::underflow_floor);
        return {G, e_G, Gp, e_Gp};
    }

    // The roots' estimates in R from g's coefficients at L0 (f(L0) and grad f(L0) . v, each
    // rounded as the seed's), smaller first: the stable pair where the discriminant is positive
    // (`real`), one where g is linear (`real` where its slope is not 0); else the vertex, where
    // the rung proves there is none. Every operation in every lane, for lanes (R's `real` a mask).
    struct Estimates {
        Mask real;
        int count;
        R root[2], vertex;
    };
    Estimates estimates(const newton::Leading<R>& A) const {
        using std::copysign;
        using std::sqrt;
        R b = dot(gradient(L0_), v_), c = value(L0_), zero(0.0);
        if (linear()) return {b != zero, 1, {-c / b, zero}, zero};
        R D = b * b - R(4.0) * A.A * c;
        R vertex = -b / (R(2.0) * A.A);
        if constexpr (std::is_same_v<R, double>) // one line: no root, no division by q
            if (!(D > 0)) return {false, 0, {0, 0}, vertex};
        R q = R(-0.5) * (b + copysign(sqrt(D), b)), r0 = q / A.A, r1 = c / q;
        if constexpr (std::is_same_v<R, double>) {
            if (r1 < r0) std::swap(r0, r1);
            return {true, 2, {r0, r1}, vertex};
        } else {
            Mask swap = r1 < r0;
            return {zero < D, 2, {select(swap, r1, r0), select(swap, r0, r1)}, vertex};
        }
    }

  private:
    R coefficient(int i) const { return R(q_[i]); }
    template <class T>
    Vec3T<T> gradient(const Vec3T<T>& s) const {
        const QuadricCoefficients<double>& q = q_;
        auto c = [&](int i) { return T(q[i]); };
        return {T(2.0) * c(0) * s.x + c(3) * s.y + c(5) * s.z + c(6),
                T(2.0) * c(1) * s.y + c(3) * s.x + c(4) * s.z + c(7),
                T(2.0) * c(2) * s.z + c(4) * s.y + c(5) * s.x + c(8)};
    }
    R value(const Vec3T<R>& p) const {
        auto q = [&](int i) { return coefficient(i); };
        return q(0) * p.x * p.x + q(1) * p.y * p.y + q(2) * p.z * p.z + q(3) * p.x * p.y +
               q(4) * p.y * p.z + q(5) * p.z * p.x + q(6) * p.x + q(7) * p.y + q(8) * p.z + q(9);
    }

    QuadricCoefficients<double> q_;
    Vec3T<R> L0_, v_;
    // Sums of magnitudes, rounded up: |f2(d)| <= quadratic_size max|d_k|^2
    double quadratic_size_ = 0, linear_size_ = 0;
    R v_sum_, v_max_;
};
using QuadricNewtonForm = QuadricNewtonFormT<double>;

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
    double a2 = 0, a1 = 0, a0 = std::fabs(q[9]);
    for (int i = 0; i < 6; ++i)
        a2 = std::max(a2, std::fabs(q[i]));
    for (int i = 6; i < 9; ++i)
        a1 = std::max(a1, std::fabs(q[i]));
    // Each degree's exponent once (a subnormal's costs a call).
    auto e = [](double x) { return x > 0 ? Binary64::exponent(x) : 0; };
    int e2 = e(a2), e1 = e(a1), e0 = e(a0);
    int L = -(1 << 20);
    if (a2 > 0 && a0 > 0) L = std::max(L, (e0 - e2) / 2);
    if (a2 > 0 && a1 > 0) L = std::max(L, e1 - e2);
    if (a1 > 0 && a0 > 0) L = std::max(L, e0 - e1);
    if (L == -(1 << 20)) return 0;
    return Binary64::pow2(std::clamp(L, -Binary64::moderate_exponent, Binary64::moderate_exponent));
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
    static constexpr bool has_line_form = false; // correct: newton_form, then the exact form

    static std::optional<QuadricNewtonForm> newton_form(const S& s, const Line& l) {
        return QuadricNewtonForm::of(Traits::coefficients(s), s.coincident, l);
    }

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
        if constexpr (std::is_floating_point_v<T>) {
            return {quadric_in_frame<T>(Traits::coefficients(s), ps.k), s.coincident, ps.pos(L0),
                    ps.dir(v)};
        } else { // the batch kernels' lanes
            MaskOf<T> ok;
            T smallest;
            QuadricCoefficients<T> q =
                quadric_in_frame_lanes(Traits::coefficients(s), ps.to_unit, ok, smallest);
            return {q, ok, smallest, s.coincident, ps.pos(L0), ps.dir(v)};
        }
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
