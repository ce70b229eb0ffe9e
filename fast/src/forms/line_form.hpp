// The Newton rung's view of each shape (see newton_rung.hpp): its quadratic written as
//     g(t) = sum_k sigma_k (U0_k + t U1_k)^2 - K,
// with U0, U1 and K in double-double, each a compensated sum with one a-priori bound
// (numeric/compensated_sum.hpp), and the axial coordinate Z(t) = Z0 + t dZ with its extent.
// Each shape's line_form() (shapes/*.hpp) builds one from the pieces here.
#pragma once

#include "numeric/bounded.hpp"
#include "numeric/bounded_dd.hpp"
#include "numeric/compensated_sum.hpp"
#include "numeric/eft.hpp"

#include "linequad/prepared.hpp"

#include <cmath>
#include <optional>
#include <type_traits>

namespace linequad::detail {

// g(t) = sum_k sigma_k (U0_k + t U1_k)^2 - K, and the axial coordinate Z(t) = Z0 + t dZ that the
// extent lo <= Z <= hi bounds (the exact form's Z0, dZ, lo, hi). Every value carries a bound:
// the BoundedDD ones in e, the doubles in the e_ fields.
// T: double, or a lane type for the line's parts (U0, U1, Z0, dZ; the batch correct solver's);
// K, sigma and the extent are the shape's alone.
//
// What closes the extent's ends: nothing (the lateral surface alone), discs around one convex
// solid (a cylinder, one nappe), or discs around two solids that meet at the apex (two nappes).
// The rung answers a convex closed shape from its lateral roots and its discs' t, two solids
// only where the line misses the quadric (newton_rung.cpp).
enum class Discs : unsigned char { none, convex, two_solids };
// Where the discs lie: a disc's t is (end - Z0) / dZ, rational, from Z0, dZ and the extent's ends
// in double-double; at_lo, at_hi: whether that end has a disc (a cone's apex end has none).
template <class T>
struct DiscPlanesT {
    BoundedDDT<T> Z0, dZ; // the line's (a lane type for the batch lanes')
    BoundedDD lo, hi;     // the shape's
    bool at_lo, at_hi;
    // Where both planes are perpendicular to a coordinate axis: its index, and the planes'
    // coordinates on it, exact doubles (a disc point's coordinate there is the plane's, exactly,
    // which no enclosure proves when it is 0); else -1.
    int axis = -1;
    double lo_at = 0, hi_at = 0;
};
using DiscPlanes = DiscPlanesT<double>;
// The coordinate axis a direction runs along (its other two components exactly 0), or -1.
inline int axis_along(Vec3 d) {
    int nonzero = (d.x != 0) + (d.y != 0) + (d.z != 0);
    return nonzero != 1 ? -1 : d.x != 0 ? 0 : d.y != 0 ? 1 : 2;
}
// The coordinate axis a plane spanned by a and b is perpendicular to (a_k = b_k = 0), or -1.
inline int axis_across(Vec3 a, Vec3 b) {
    for (int k = 0; k < 3; ++k)
        if (a[k] == 0 && b[k] == 0) return k;
    return -1;
}
// sigma = (1, 1, sigma_z), or with sigma_z = four_terms (the frustum's) four terms, (1, 1, 1, -1),
// the fourth held apart (set only there: a form is built per line, and what it does not use is
// not initialized).
inline constexpr int four_terms = 2;
template <class T>
struct FourthTerm {
    BoundedDDT<T> U0, U1;
};
template <class T>
struct LineFormT {
    BoundedDDT<T> U0[3], U1[3];
    std::optional<FourthTerm<T>> fourth;
    BoundedDD K;
    int sigma_z;
    T Z0, e_Z0, dZ, e_dZ;
    double lo, e_lo, hi, e_hi;
    bool lo_bounded, hi_bounded;
    Discs discs = Discs::none;            // discs_of(shape), set by every form
    std::optional<DiscPlanesT<T>> planes; // the precise form's, on a shape closed by discs
};
using LineForm = LineFormT<double>;

namespace newton {
// What the Newton rung (correct/newton_rung.hpp) takes of a shape's g near a point c:
// g(c + x) = A x^2 + G' x + G, A within e, G within e_G and G' within e_Gp, each in double. A
// line form gives them (correct/newton_steps.hpp), as does a quadric's own expansion
// (shapes/quadric.hpp).
template <class T>
struct Leading {
    T A, e;
};
template <class T>
struct Local {
    T G, e_G, Gp, e_Gp;
};
} // namespace newton

// Term k's U0 and U1 (k = 3: the fourth term's).
template <class T>
LINEQUAD_INLINE const BoundedDDT<T>& U0_of(const LineFormT<T>& f, int k) {
    return k < 3 ? f.U0[k] : f.fourth->U0;
}
template <class T>
LINEQUAD_INLINE const BoundedDDT<T>& U1_of(const LineFormT<T>& f, int k) {
    return k < 3 ? f.U1[k] : f.fourth->U1;
}

template <class S>
Discs discs_of(const S& s) {
    if (!has_caps(s)) return Discs::none;
    return nappes_of(s) == 2 ? Discs::two_solids : Discs::convex;
}

// Vectors enter as values (Vec3T) or as exact two-term values (Vec3TwoTermT, a difference of two
// points); the low parts only add small terms.
template <class V>
struct IsTwoTerm : std::false_type {};
template <class T>
struct IsTwoTerm<Vec3TwoTermT<T>> : std::true_type {};
template <class V>
constexpr bool has_low_part = IsTwoTerm<V>::value;
template <class T>
Vec3T<T> high(const Vec3T<T>& a) {
    return a;
}
template <class T>
Vec3T<T> high(const Vec3TwoTermT<T>& a) {
    return a.hi;
}
// The number type of a vector's components.
template <class V>
using ComponentOf = std::decay_t<decltype(high(std::declval<V>()).x)>;

// (a x b)_k = a_i b_j - a_j b_i with (i, j) = (k + 1, k + 2) mod 3.
template <class P, class Q, class T = ComponentOf<P>>
LINEQUAD_INLINE BoundedDDT<T> cross_component(const P& a, const Q& b, int k) {
    int i = (k + 1) % 3, j = (k + 2) % 3;
    Vec3T<T> ah = high(a), bh = high(b);
    CompensatedSumT<T> s;
    s.add_product(ah[i], bh[j]);
    s.add_product(-ah[j], bh[i]);
    if constexpr (has_low_part<Q>) {
        s.add_small(ah[i] * b.lo[j]);
        s.add_small(-ah[j] * b.lo[i]);
    }
    if constexpr (has_low_part<P>) {
        s.add_small(a.lo[i] * bh[j]);
        s.add_small(-a.lo[j] * bh[i]);
    }
    if constexpr (has_low_part<P> && has_low_part<Q>) {
        s.add_small(a.lo[i] * b.lo[j]);
        s.add_small(-a.lo[j] * b.lo[i]);
    }
    return s.result();
}

// a . b, in the same way.
template <class P, class Q, class T = ComponentOf<P>>
LINEQUAD_INLINE BoundedDDT<T> dot_dd(const P& a, const Q& b) {
    Vec3T<T> ah = high(a), bh = high(b);
    CompensatedSumT<T> s;
#pragma GCC unroll 3
    for (int k = 0; k < 3; ++k) {
        s.add_product(ah[k], bh[k]);
        if constexpr (has_low_part<Q>) s.add_small(ah[k] * b.lo[k]);
        if constexpr (has_low_part<P>) s.add_small(a.lo[k] * bh[k]);
        if constexpr (has_low_part<P> && has_low_part<Q>) s.add_small(a.lo[k] * b.lo[k]);
    }
    return s.result();
}

// n . w for a row n of bounded values (the shape's, in double): their bounds propagate by |w|.
template <class Q, class T = ComponentOf<Q>>
LINEQUAD_INLINE BoundedDDT<T> dot_row(const BoundedDD (&n)[3], const Q& w) {
    using std::fabs;
    Vec3T<T> wh = high(w);
    CompensatedSumT<T> s;
    T propagated(0.0);
#pragma GCC unroll 3
    for (int k = 0; k < 3; ++k) {
        s.add_product(T(n[k].hi), wh[k]);
        s.add_small(T(n[k].lo) * wh[k]);
        T size = fabs(wh[k]);
        if constexpr (has_low_part<Q>) {
            s.add_small(T(n[k].hi) * w.lo[k]);
            s.add_small(T(n[k].lo) * w.lo[k]);
            size = size + fabs(w.lo[k]);
        }
        propagated = propagated + T(n[k].e) * size;
    }
    return s.result(propagated);
}

// a b, from a and b within their bounds: a'b' - ab = a' eb + b' ea + ea eb.
template <class T>
LINEQUAD_INLINE BoundedDDT<T> product(const BoundedDDT<T>& a, const BoundedDDT<T>& b) {
    using std::fabs;
    CompensatedSumT<T> s;
    s.add_product(a.hi, b.hi);
    s.add_small(a.hi * b.lo);
    s.add_small(a.lo * b.hi);
    s.add_small(a.lo * b.lo);
    T propagated = a.e * (fabs(b.hi) + fabs(b.lo)) + b.e * (fabs(a.hi) + fabs(a.lo)) + a.e * b.e;
    return s.result(propagated);
}

// The rows of adj(M), M = [a b c] (b x c, c x a, a x b), and det M = a . (b x c), each in
// bounded double-double: what the elliptic shapes' forms share, and what prepare() keeps.
// c is a double for the elliptic cylinder, the exact difference H - C for the cone.
struct AdjugateRowsDD {
    BoundedDD n[3][3];
    BoundedDD det;
};
template <class CVec>
AdjugateRowsDD adjugate_rows_dd(Vec3 a, Vec3 b, const CVec& c) {
    AdjugateRowsDD r;
#pragma GCC unroll 3
    for (int k = 0; k < 3; ++k) {
        r.n[0][k] = cross_component(b, c, k);
        r.n[1][k] = cross_component(c, a, k);
        r.n[2][k] = cross_component(a, b, k);
    }
    r.det = dot_row(r.n[0], a);
    return r;
}

// The elliptic shapes: U0 = adj(M) w and U1 = adj(M) v (the exact form's W and V), and
// Z = U_z with det's sign folded in, so that the extent is in units of |det|.
template <class T>
LineFormT<T> elliptic_form(const AdjugateRowsDD& rows, const Vec3TwoTermT<T>& w, Vec3T<T> v,
                           bool negative_det) {
    LineFormT<T> f;
#pragma GCC unroll 3
    for (int k = 0; k < 3; ++k) {
        f.U0[k] = dot_row(rows.n[k], w);
        f.U1[k] = dot_row(rows.n[k], v);
    }
    T sign(negative_det ? -1.0 : 1.0);
    f.Z0 = sign * f.U0[2].hi, f.e_Z0 = bound_of_hi(f.U0[2]);
    f.dZ = sign * f.U1[2].hi, f.e_dZ = bound_of_hi(f.U1[2]);
    return f;
}
// |det| = sign det, exactly.
inline BoundedDD absolute_det(const AdjugateRowsDD& rows, bool negative_det) {
    double sign = negative_det ? -1 : 1;
    return {rows.det.hi * sign, rows.det.lo * sign, rows.det.e};
}

// The quick line form's values (the hit test's, see correct/newton_rung.hpp): values with a
// rigorous bound, computed in QuickBounded, stored with no low part.
template <class T>
LINEQUAD_INLINE BoundedDDT<T> quick(const QuickBoundedT<T>& x) {
    return {x.v, T(0), x.bound()};
}
inline QuickBounded quick(const BoundedDD& x) {
    return {x.hi, bound_of_hi(x)};
}
// The elliptic shapes' quick form, from the precise rows (the same values, prepared or not):
// U0 = adj(M) w, U1 = adj(M) v, Z = U_z with det's sign folded in; abs_det = |det|.
template <class T>
LINEQUAD_INLINE LineFormT<T> quick_elliptic_form(const AdjugateRowsDD& rows,
                                                 const Vec3T<QuickBoundedT<T>>& w, Vec3T<T> v,
                                                 bool negative_det, QuickBounded& abs_det) {
    using Q = QuickBoundedT<T>;
    auto lanes = [](const BoundedDD& x) {
        QuickBounded q = quick(x);
        return Q{T(q.v), T(q.e)};
    };
    Vec3T<Q> n[3], V{Q::exact(v.x), Q::exact(v.y), Q::exact(v.z)};
    for (int i = 0; i < 3; ++i)
        n[i] = {lanes(rows.n[i][0]), lanes(rows.n[i][1]), lanes(rows.n[i][2])};
    QuickBounded det = quick(rows.det);
    abs_det = negative_det ? -det : det;
    LineFormT<T> f;
    for (int k = 0; k < 3; ++k) {
        f.U0[k] = quick(dot(n[k], w));
        f.U1[k] = quick(dot(n[k], V));
    }
    T sign(negative_det ? -1.0 : 1.0);
    f.Z0 = sign * f.U0[2].hi, f.e_Z0 = f.U0[2].e;
    f.dZ = sign * f.U1[2].hi, f.e_dZ = f.U1[2].e;
    return f;
}

// An elliptic shape's line form through the adjugate rows of its frame, whose origin is `origin`
// (the cylinder's C, the cone's apex H): the Newton rung's (precise: U0 and U1 in double-double
// from the exact differences L0 - origin) or the hit test's quick one (doubles with bounds). What
// is the shape's own (sigma, K, the extent, the discs' planes' ends), own(f, |det|, square) sets
// from |det| (a BoundedDD, whose low part is 0 in the quick form), square() giving |det|^2 in the
// form's precision where it needs it (the elliptic cylinder's K).
template <class T, class Own>
LINEQUAD_INLINE LineFormT<T> precise_elliptic_line_form(const AdjugateRowsDD& rows, Vec3T<T> L0,
                                                        Vec3 origin, Vec3T<T> v, bool negative_det,
                                                        Own& own) {
    LineFormT<T> f =
        elliptic_form(rows, difference_exact(L0, lanes_of<T>(origin)), v, negative_det);
    BoundedDD det = absolute_det(rows, negative_det);
    own(f, det, [&] { return product(det, det); });
    if (f.planes) { // Z = U_z with det's sign folded in, as elliptic_form's
        auto signed_z = [&](const BoundedDDT<T>& x) {
            return negative_det ? BoundedDDT<T>(-x.hi, -x.lo, x.e) : x;
        };
        f.planes->Z0 = signed_z(f.U0[2]), f.planes->dZ = signed_z(f.U1[2]);
    }
    return f;
}
template <class T, class Own>
LINEQUAD_INLINE LineFormT<T> quick_elliptic_line_form(const AdjugateRowsDD& rows, Vec3T<T> L0,
                                                      Vec3 origin, Vec3T<T> v, bool negative_det,
                                                      Own& own) {
    QuickBounded d;
    LineFormT<T> f = quick_elliptic_form(
        rows, difference_bounded<QuickBoundedT<T>>(L0, lanes_of<T>(origin)), v, negative_det, d);
    own(f, BoundedDD(d.v, 0, d.bound()), [&] { return quick(d * d); });
    return f;
}
// One named form per function: built in place where it is returned, never copied.
template <bool precise, class T, class Own>
LINEQUAD_INLINE LineFormT<T> elliptic_line_form(const AdjugateRowsDD& rows, Vec3T<T> L0,
                                                Vec3 origin, Vec3T<T> v, int orientation,
                                                Own&& own) {
    if constexpr (precise)
        return precise_elliptic_line_form(rows, L0, origin, v, orientation < 0, own);
    else
        return quick_elliptic_line_form(rows, L0, origin, v, orientation < 0, own);
}

// BoundedDD as prepare() keeps it: value, low part, bound.
inline BoundedDD bounded_dd(const double (&x)[3]) {
    return {x[0], x[1], x[2]};
}
inline void store(const BoundedDD& x, double (&out)[3]) {
    out[0] = x.hi, out[1] = x.lo, out[2] = x.e;
}
inline AdjugateRowsDD adjugate_rows_dd(const FrameFacts& f) {
    AdjugateRowsDD r;
    for (int i = 0; i < 3; ++i)
        for (int k = 0; k < 3; ++k)
            r.n[i][k] = bounded_dd(f.rows[i][k]);
    r.det = bounded_dd(f.det);
    return r;
}
inline void store(const AdjugateRowsDD& r, FrameFacts& f) {
    for (int i = 0; i < 3; ++i)
        for (int k = 0; k < 3; ++k)
            store(r.n[i][k], f.rows[i][k]);
    store(r.det, f.det);
}

} // namespace linequad::detail
