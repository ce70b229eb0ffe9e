// The arithmetic of stable's cylinder solve (derivation: cylinder.cpp), once, for a lane type T:
// double for the scalar solver, the 4-lane type for the batch solver. The scalar solver calls
// these steps with its branches; the batch calls them for all lanes and sends the lanes that
// would branch to the scalar solver. Same operations in the same order: the same bits.
#pragma once

#include "linequad/eft.hpp"

#include <algorithm>
#include <cmath>

namespace linequad::detail {

// Selection and ordering with std::min / std::max semantics, for any lane type.
inline double select(bool m, double a, double b) {
    return m ? a : b;
}
template <class T>
T lane_min(T a, T b) {
    return select(b < a, b, a);
}
template <class T>
T lane_max(T a, T b) {
    return select(a < b, b, a);
}

template <class T>
struct CylinderStable {
    // Prescaled inputs and what depends on the shape and the line's direction.
    Vec3TwoTermT<T> hx, w;
    Vec3T<T> h, v, vh;
    T r, hh, hn, rh, A;
    // From the moved origin.
    T tc, B, Cc, D;
    Vec3T<T> wc;

    CylinderStable(Vec3T<T> C, Vec3T<T> H, Vec3T<T> L0, Vec3T<T> v_, T r_) : v(v_), r(r_) {
        using std::sqrt;
        // h = H - C exactly, as hi + lo: for a line nearly along the axis, v x h is a tiny
        // difference that the rounding of H - C alone would swamp.
        hx = difference_exact(H, C);
        h = hx.rounded();
        hh = dot(h, h);
        hn = sqrt(hh);
        w = difference_exact(L0, C);
        vh = cross_dd(v, hx).rounded();
        A = dot(vh, vh);
        rh = r * hn;
    }

    // C0 at the caller's origin: for lines parallel to the axis, and for Vieta's product.
    T C0_at_origin() const {
        T wn = norm(cross_dd(w.rounded(), hx).rounded());
        return (wn - rh) * (wn + rh);
    }

    // The origin moved to the line's closest approach to the axis' midpoint: never farther
    // than the caller's origin, so every later product is as small as the geometry allows.
    // Then B, Cc and the discriminant in geometric form (D = -1 when the line misses).
    void discriminant() {
        using std::fabs;
        using std::sqrt;
        tc = -dot(v, w.rounded() - T(0.5) * h) / dot(v, v); // any tc is an exact move
        wc = moved_origin(w, tc, v);
        Vec3TwoTermT<T> whc = cross_dd(wc, hx);
        B = dot2(vh, whc.rounded());
        T wn = norm(whc.rounded());
        Cc = (wn - rh) * (wn + rh);
        // det = v . (w x h): the line's distance to the axis times |v x h| |h|, a triple
        // product in double-double (moving along the line does not change it).
        T det = fabs(dot2(v, whc));
        T rA = r * sqrt(A);
        T gap = rA - det;
        D = select(gap < T(0), T(-1), hh * gap * (rA + det));
    }

    // z = (P - C) . h at a root: from the moved origin, or from the caller's for a root that
    // came from Vieta's product (near the caller's origin); one fma either way.
    T z_moved(T s) const {
        using std::fma;
        return fma(s, dot2(v, h), dot2(wc, h));
    }
    T z_at_origin(T t) const {
        using std::fma;
        return fma(t, dot2(v, h), dot2(w.rounded(), h));
    }
};

} // namespace linequad::detail
