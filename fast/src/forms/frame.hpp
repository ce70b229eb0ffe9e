// The affine frame M = [a b c] of the elliptic shapes (P = origin + M (x, y, z)) and its
// inverse, M^-1 = adj(M) / det(M) (erratum 3 of the seeds): the rows of adj(M) are b x c, c x a
// and a x b. Its orientation is decided exactly; the stable solvers keep the rows in
// double-double (DualFrameT); the exact form and the certified solver build them in their own
// number types (AdjugateFrame).
#pragma once

#include "numeric/eft.hpp"
#include "numeric/format.hpp"

#include "linequad/prepared.hpp"

#include <algorithm>
#include <initializer_list>
#include <type_traits>

namespace linequad {

// Exact sign of det[a b c] = a . (b x c).
int det3_sign_exact(Vec3 a, Vec3 b, Vec3 c);
// Exact sign of det[a b H-C], without rounding H - C.
int cone_det_sign_exact(Vec3 a, Vec3 b, Vec3 C, Vec3 H);
// Exact sign of det[a b P-Q-R], without rounding P - Q - R (a point's side of a plane through
// Q + R spanned by a and b).
int det3_sign_exact(Vec3 a, Vec3 b, Vec3 P, Vec3 Q, Vec3 R);

namespace exact_form {

// adj(M) and det(M) in NT; the derivations multiply through by det^2 (or det), so that only
// adj(M) is needed.
template <class NT>
struct AdjugateFrame {
    Vec3T<NT> nx, ny, nz;
    NT det;
    AdjugateFrame(const Vec3T<NT>& a, const Vec3T<NT>& b, const Vec3T<NT>& c)
        : nx(cross(b, c)), ny(cross(c, a)), nz(cross(a, b)), det(dot(a, nx)) {}
    // det * M^-1 u
    Vec3T<NT> scaled_local(const Vec3T<NT>& u) const {
        return {dot(nx, u), dot(ny, u), dot(nz, u)};
    }
};

// adj(M)'s last row alone, a x b: Z = sigma det[a b u] for a vector u, sigma det's sign (the
// orientation the caller decided), so that Z increases along c. What an end's crossing needs,
// without the other two rows.
template <class NT>
struct FrameZ {
    Vec3T<NT> nz;
    bool negative;
    FrameZ(const Vec3T<NT>& a, const Vec3T<NT>& b, int orientation)
        : nz(cross(a, b)), negative(orientation < 0) {}
    NT operator()(const Vec3T<NT>& u) const {
        NT z = dot(nz, u);
        return negative ? -z : z;
    }
};

} // namespace exact_form

namespace detail {

// M^-1 without forming M: the rows of adj(M) over det(M), each row in double-double: for a line
// nearly along the axis, v . (b x c) is a tiny difference that a rounded b x c would swamp. c may
// carry a low part (the cone's c = H - C is not a double).
template <class T>
struct DualFrameT {
    Vec3TwoTermT<T> nx, ny, nz;
    T det;
    DualFrameT(Vec3T<T> a, Vec3T<T> b, const Vec3TwoTermT<T>& c)
        : nx(cross_dd(b, c)), ny(cross_dd(c, a)), nz(cross_dd(a, b)), det(dot2(a, nx)) {}
    // Rows computed at another scale and moved to this one: the rows (products of two) by f2,
    // det (of three) by f3, both powers of two (see prepared_dual_frame).
    DualFrameT(const AdjugateRows& r, T f2, T f3)
        : nx{f2 * r.hi[0], f2 * r.lo[0]}, ny{f2 * r.hi[1], f2 * r.lo[1]}, nz{f2 * r.hi[2],
                                                                             f2 * r.lo[2]},
          det(f3 * r.det) {}
    Vec3T<T> local(Vec3T<T> u) const {
        return {dot2(u, nx) / det, dot2(u, ny) / det, dot2(u, nz) / det};
    }
    // M^-1 u times s det, for s a power of two near 1 / |det| (power_of_two_inverse): for a
    // homogeneous equation, whose roots do not change when every local coordinate is scaled. No
    // division, one rounding per coordinate, and |s det| in [1, 2) keeps the magnitudes of M^-1 u.
    Vec3T<T> scaled_local(Vec3T<T> u, T s) const {
        return {s * dot2(u, nx), s * dot2(u, ny), s * dot2(u, nz)};
    }
    T local_z(Vec3T<T> u) const { return dot2(u, nz) / det; }
    AdjugateRows rows() const { return {{nx.hi, ny.hi, nz.hi}, {nx.lo, ny.lo, nz.lo}, det}; }
};
using DualFrame = DualFrameT<double>;

// The dual frame that prepare() keeps was computed with the shape scaled by 2^-exponent; a line
// may need the scene scaled by 2^-k with k = exponent + delta, delta >= 0 (it lies farther out).
// The rows are products of two inputs and det of three, so every exact intermediate of their
// computation is a multiple of 2^(3 (e - 52)) for e the lowest exponent of a nonzero input;
// scaled down by 2^-delta that stays a multiple of 2^-1074 when e - delta >= -306, and then every
// rounding lands where it would have landed at the other scale (both normal, or both exact): the
// kept rows times 2^-2 delta and det times 2^-3 delta are, bit for bit, what computing them at
// 2^-k gives (and c times 2^-delta). Otherwise the solver computes them.
inline bool dual_frame_rescales(const FrameFacts& f, int delta) {
    return delta == 0 || (delta > 0 && f.lowest_exponent - delta >= -306);
}
inline DualFrame rescaled_dual_frame(const FrameFacts& f, int delta) {
    return DualFrame(f.dual, Binary64::pow2(-2 * delta), Binary64::pow2(-3 * delta));
}
// The lowest exponent of a nonzero coordinate of the given vectors, scaled by `scale`.
inline int lowest_exponent(std::initializer_list<Vec3> inputs, double scale) {
    int e = Binary64::moderate_exponent;
    for (Vec3 u : inputs)
        for (double x : {u.x, u.y, u.z})
            if (x != 0) e = std::min(e, Binary64::exponent(scale * x));
    return e;
}

// 2^-E for |x| in [2^E, 2^(E+1)), exactly; 1 when x is zero or subnormal (no power of two of that
// size is safe to scale by; the solvers' underflow guards then refuse what they cannot decide).
template <class R, std::enable_if_t<std::is_floating_point_v<R>, int> = 0>
R power_of_two_inverse(R x) {
    R p = Format<R>::power_of_two_floor(x);
    return p == 0 ? R(1) : 1 / p;
}

} // namespace detail

} // namespace linequad
