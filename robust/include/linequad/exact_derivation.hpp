// The three seed derivations in exact arithmetic, over any CGAL kernel whose number type is an
// exact ring (CGAL::Mpzf, CGAL::Gmpq, ...). Nothing here divides, takes a root or rounds: each
// shape becomes one quadratic in the line's parameter with exact coefficients, plus the axial
// coordinate that the extent test needs. src/exact.cpp classifies and rounds it.
//
// The double inputs convert to the number type exactly.
#pragma once

#include "linequad/shapes.hpp"

#include <CGAL/Kernel/global_functions.h>
#include <CGAL/number_utils.h>

namespace linequad::exact {

// A t^2 + 2 B t + C0 = 0 along the line, and Z(t) = Z0 + t dZ with the extent lo <= Z <= hi.
template <class NT>
struct LineQuadratic {
    NT A, B, C0;
    NT Z0, dZ, lo, hi;
    bool lo_bounded = true, hi_bounded = true;
};

template <class K>
typename K::Vector_3 vec(Vec3 p) {
    return typename K::Vector_3(typename K::FT(p.x), typename K::FT(p.y), typename K::FT(p.z));
}

// Seed 001, multiplied through by h.h so that the axis needs no normalisation (erratum 3):
//   |P - C|^2 (h.h) - ((P - C).h)^2 = r^2 (h.h),  0 <= (P - C).h <= h.h,
// with P = L0 + t v, w = L0 - C, h = H - C.
template <class K>
LineQuadratic<typename K::FT> line_quadratic(const Cylinder& s, const Line& l) {
    using FT = typename K::FT;
    auto h = vec<K>(s.H) - vec<K>(s.C), w = vec<K>(l.L0) - vec<K>(s.C), v = vec<K>(l.v);
    FT hh = h * h, vh = v * h, wh = w * h, r(s.r);
    LineQuadratic<FT> q;
    q.A = (v * v) * hh - vh * vh;
    q.B = (v * w) * hh - vh * wh;
    q.C0 = (w * w) * hh - wh * wh - r * r * hh;
    q.Z0 = wh, q.dZ = vh, q.lo = FT(0), q.hi = hh;
    q.lo_bounded = q.hi_bounded = s.finite;
    return q;
}

// M^-1 = adj(M) / det(M), M = [a b c] (erratum 3); the rows of adj(M) are b x c, c x a, a x b.
// The equations below are multiplied through by det^2 (or det), so only adj(M) is needed.
template <class K>
struct AdjugateFrame {
    typename K::Vector_3 nx, ny, nz;
    typename K::FT det;
    AdjugateFrame(const typename K::Vector_3& a, const typename K::Vector_3& b,
                  const typename K::Vector_3& c)
        : nx(CGAL::cross_product(b, c)), ny(CGAL::cross_product(c, a)),
          nz(CGAL::cross_product(a, b)), det(a * nx) {}
    // det * M^-1 u
    typename K::Vector_3 scaled_local(const typename K::Vector_3& u) const {
        return typename K::Vector_3(nx * u, ny * u, nz * u);
    }
};

// Seed 000 in the unit cylinder's frame, w = M^-1 (L0 - C), v' = M^-1 v (a vector, erratum 2):
//   x^2 + y^2 = 1, 0 <= z <= 1; times det^2 with W = det w, V = det v'.
template <class K>
LineQuadratic<typename K::FT> line_quadratic(const EllipticCylinder& s, const Line& l) {
    using FT = typename K::FT;
    AdjugateFrame<K> f(vec<K>(s.a), vec<K>(s.b), vec<K>(s.c));
    auto W = f.scaled_local(vec<K>(l.L0) - vec<K>(s.C)), V = f.scaled_local(vec<K>(l.v));
    LineQuadratic<FT> q;
    q.A = V.x() * V.x() + V.y() * V.y();
    q.B = V.x() * W.x() + V.y() * W.y();
    q.C0 = W.x() * W.x() + W.y() * W.y() - f.det * f.det;
    // z = Z / det in [0, 1]: with the sign of det folded into Z, 0 <= Z <= |det|.
    bool negative = CGAL::is_negative(f.det);
    q.Z0 = negative ? -W.z() : W.z();
    q.dZ = negative ? -V.z() : V.z();
    q.lo = FT(0), q.hi = negative ? -f.det : f.det;
    q.lo_bounded = q.hi_bounded = s.finite;
    return q;
}

// Seed 002 with its own equation (erratum 1): c = H - C (erratum 4), w = M^-1 (L0 - H),
//   x^2 + y^2 = z^2 (homogeneous, so the det^2 factor drops out), -1 <= z <= 0 (erratum 5).
template <class K>
LineQuadratic<typename K::FT> line_quadratic(const EllipticCone& s, const Line& l) {
    using FT = typename K::FT;
    AdjugateFrame<K> f(vec<K>(s.a), vec<K>(s.b), vec<K>(s.H) - vec<K>(s.C));
    auto W = f.scaled_local(vec<K>(l.L0) - vec<K>(s.H)), V = f.scaled_local(vec<K>(l.v));
    LineQuadratic<FT> q;
    q.A = V.x() * V.x() + V.y() * V.y() - V.z() * V.z();
    q.B = V.x() * W.x() + V.y() * W.y() - V.z() * W.z();
    q.C0 = W.x() * W.x() + W.y() * W.y() - W.z() * W.z();
    bool negative = CGAL::is_negative(f.det);
    q.Z0 = negative ? -W.z() : W.z();
    q.dZ = negative ? -V.z() : V.z();
    q.lo = negative ? f.det : -f.det, q.hi = FT(0);
    q.lo_bounded = s.finite;
    q.hi_bounded = true; // the nappe z <= 0
    return q;
}

// det[a b c] of the frame, exactly (zero means the frame is singular).
template <class K>
typename K::FT frame_determinant(const EllipticCylinder& s) {
    return AdjugateFrame<K>(vec<K>(s.a), vec<K>(s.b), vec<K>(s.c)).det;
}
template <class K>
typename K::FT frame_determinant(const EllipticCone& s) {
    return AdjugateFrame<K>(vec<K>(s.a), vec<K>(s.b), vec<K>(s.H) - vec<K>(s.C)).det;
}

} // namespace linequad::exact
