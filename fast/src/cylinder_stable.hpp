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
    T r, hh, r2, r2hh, A, inv_vv, dz;
    // From the moved origin.
    T tc, B, Cc, D, zc;
    Vec3T<T> wc;

    CylinderStable(Vec3T<T> C, Vec3T<T> H, Vec3T<T> L0, Vec3T<T> v_, T r_) : v(v_), r(r_) {
        // h = H - C exactly, as hi + lo: for a line nearly along the axis, v x h is a tiny
        // difference that the rounding of H - C alone would swamp.
        hx = difference_exact(H, C);
        h = hx.rounded();
        hh = dot(h, h);
        w = difference_exact(L0, C);
        vh = cross_accurate(v, hx);
        A = dot(vh, vh);
        r2 = r * r;
        r2hh = r2 * hh;
        inv_vv = T(1) / dot(v, v); // tc need not be a rounded quotient: any tc is an exact move
        dz = dot(v, h);
    }

    // C0 at the caller's origin: for lines parallel to the axis, and for Vieta's product.
    T C0_at_origin() const {
        Vec3T<T> wh = cross_accurate(w.rounded(), hx);
        return dot(wh, wh) - r2hh;
    }

    // The origin moved to the line's closest approach to the axis' midpoint: never farther
    // than the caller's origin, so every later product is as small as the geometry allows.
    // Then B, Cc and the discriminant in geometric form. The rounded products of Cc and D are
    // no less accurate than a factored (sqrt - r|h|)(sqrt + r|h|) form would be: their inputs
    // are rounded already.
    void discriminant() {
        using std::fma;
        tc = -dot(v, w.rounded() - T(0.5) * h) * inv_vv;
        wc = moved_origin(w, tc, v);
        Vec3T<T> whc = cross_accurate(wc, hx);
        B = dot2(vh, whc);
        zc = dot(wc, h);
        Cc = dot(whc, whc) - r2hh;
        T det = dot2(vh, wc);
        D = hh * fma(-det, det, r2 * A);
    }

    // z = (P - C) . h at a root: from the moved origin, or from the caller's for a root that
    // came from Vieta's product (near the caller's origin); one fma either way.
    T z_moved(T s) const {
        using std::fma;
        return fma(s, dz, zc);
    }
    T z_at_origin(T t) const {
        using std::fma;
        return fma(t, dz, dot2(w.rounded(), h));
    }
};

} // namespace linequad::detail
