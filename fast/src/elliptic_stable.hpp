// The arithmetic of stable's elliptic cylinder and cone solves (derivations: elliptic_cylinder.cpp
// and elliptic_cone.cpp), once, for a lane type T, as cylinder_stable.hpp is for the cylinder.
#pragma once

#include "cylinder_stable.hpp"
#include "frame.hpp"

#include <type_traits>

namespace linequad::detail {

// A s^2 + 2 B s + Cc = 0 where D > 0: the stable pair, smaller first (stable_roots' two roots).
template <class T>
void stable_pair(T A, T B, T Cc, T D, T s[2]) {
    using std::copysign;
    using std::sqrt;
    T q = -(B + copysign(sqrt(D), B));
    T t0 = q / A, t1 = Cc / q;
    s[0] = lane_min(t0, t1), s[1] = lane_max(t0, t1);
}

template <class T>
struct EllipticStable {
    DualFrameT<T> f;
    Vec3TwoTermT<T> w;
    Vec3T<T> c, v, vl;
    T A, tc, B, Cc, D;

    // Prescaled a, b, c, C, L0 and v.
    EllipticStable(Vec3T<T> a, Vec3T<T> b, Vec3T<T> c_, Vec3T<T> C, Vec3T<T> L0, Vec3T<T> v_)
        : f(a, b, {c_, {T(0), T(0), T(0)}}), w(difference_exact(L0, C)), c(c_), v(v_) {
        vl = f.local(v);
        A = vl.x * vl.x + vl.y * vl.y;
    }
    // C0 at the caller's origin: for lines along the axis, and for Vieta's product.
    T C0_at_origin() const {
        Vec3T<T> wl = f.local(w.rounded());
        return squares_difference(wl.x, wl.y, T(1));
    }
    // Origin moved to the closest approach to the axis' midpoint (see cylinder.cpp); then, with
    // u = v'x w'y - v'y w'x = c . (v x w) / det, D = A - u^2 = (sqrt(A) - |u|)(sqrt(A) + |u|).
    void discriminant() {
        using std::fabs;
        using std::sqrt;
        tc = -dot(v, w.rounded() - T(0.5) * c) / dot(v, v); // any tc is an exact move
        Vec3T<T> wc = moved_origin(w, tc, v);
        Vec3T<T> wcl = f.local(wc);
        const T vxy[2] = {vl.x, vl.y}, wxy[2] = {wcl.x, wcl.y};
        B = dot2(vxy, wxy);
        Cc = squares_difference(wcl.x, wcl.y, T(1));
        T u = fabs(dot2(c, cross_dd(v, wc)) / f.det);
        T sA = sqrt(A);
        T gap = sA - u;
        D = select(gap < T(0), T(-1), gap * (sA + u));
    }
    // The local z of a hit point itself, in compensated arithmetic: near the extent's ends,
    // where it decides, a sum of moved-origin terms would cancel.
    T z_at(T t) const { return f.local_z(moved_origin(w, t, v)); }
};

// The cone's equation x^2 + y^2 = z^2 is homogeneous: its roots do not change when every local
// coordinate is scaled by one factor. So the local coordinates here are M^-1 u times sigma =
// s det, s a power of two near 1 / |det| (frame.hpp): A, B and C0 carry sigma^2, D sigma^4, and
// no division by det is needed but in z itself (z_at), which the extent test needs as it is.
template <class T>
struct ConeStable {
    using Mask = decltype(T() < T());
    DualFrameT<T> f;
    Vec3TwoTermT<T> w, c;
    Vec3T<T> a, b, v, vl;
    T s, A, tc, B, Cc, D;
    Mask near_tangent; // D came from the double-double triple products (the scalar solver)

    // Prescaled a, b, H, C, L0 and v; c = H - C exactly (it is not a double).
    ConeStable(Vec3T<T> a_, Vec3T<T> b_, Vec3T<T> H, Vec3T<T> C, Vec3T<T> L0, Vec3T<T> v_)
        : f(a_, b_, difference_exact(H, C)), w(difference_exact(L0, H)), c(difference_exact(H, C)),
          a(a_), b(b_), v(v_) {
        s = power_of_two_inverse(f.det);
        vl = f.scaled_local(v, s);
        A = circle_minus_square(vl.x, vl.y, vl.z);
    }
    T C0_at_origin() const {
        Vec3T<T> wl = f.scaled_local(w.rounded(), s);
        return squares_difference(wl.x, wl.y, wl.z);
    }
    // Origin moved to the line's closest approach to the apex; D = ux^2 + uy^2 - uz^2 with
    // u = v' x w' (sigma^2 u in the scaled coordinates), by Kahan's cross product of the rounded
    // local v' and w'. Its error is a few u of the products u came from, which is small beside D
    // but near tangency: where |D| is at most 1/8 of them, D comes from accurate_discriminant (in
    // the batch: the lane goes to the scalar solver, which does that).
    void discriminant() {
        using std::fabs;
        tc = -dot(v, w.rounded()) / dot(v, v); // any tc is an exact move
        Vec3T<T> wcw = moved_origin(w, tc, v), wc = f.scaled_local(wcw, s);
        const T vm[3] = {vl.x, vl.y, -vl.z}, wm[3] = {wc.x, wc.y, wc.z};
        B = dot2(vm, wm);
        Cc = squares_difference(wc.x, wc.y, wc.z);
        Vec3T<T> u = cross_accurate(vl, wc);
        D = squares_difference(u.x, u.y, u.z);
        T size = fabs(u.x) * (fabs(vl.y * wc.z) + fabs(vl.z * wc.y)) +
                 fabs(u.y) * (fabs(vl.z * wc.x) + fabs(vl.x * wc.z)) +
                 fabs(u.z) * (fabs(vl.x * wc.y) + fabs(vl.y * wc.x));
        near_tangent = fabs(D) <= T(0.125) * size; // and where u, and D with it, came out 0
        if constexpr (std::is_same_v<T, double>)
            if (near_tangent) D = accurate_discriminant(wcw);
    }
    // u = M^T (v x w) / det with each component a double-double triple product, which stays
    // accurate when D nearly vanishes; sigma^2 u = s (s det) M^T (v x w), a product by an exact
    // power-of-two multiple of det.
    T accurate_discriminant(Vec3T<T> wcw) const {
        Vec3TwoTermT<T> vw = cross_dd(v, wcw);
        Vec3T<T> u{dot2(a, vw), dot2(b, vw), dot2(c.hi, vw) + dot(c.lo, vw.hi)};
        u = (s * (s * f.det)) * u;
        return squares_difference(u.x, u.y, u.z);
    }
    T z_at(T t) const { return f.local_z(moved_origin(w, t, v)); }
};

} // namespace linequad::detail
