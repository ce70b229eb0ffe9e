// The affine frame M = [a b c] + origin of the elliptic shapes, and its inverse.
#pragma once

#include "linequad/eft.hpp"

#include <Eigen/Dense>

#include <cstdint>
#include <cstring>

namespace linequad::detail {

// Seed 000/002's construction, kept literally for the seed solvers: M = T R S with R built from
// the normalised axes and S from their lengths, inverted as a general 4x4 matrix.
inline Eigen::Matrix4d seed_inverse_frame(Vec3 origin, Vec3 a, Vec3 b, Vec3 c) {
    Eigen::Matrix4d T = Eigen::Matrix4d::Identity(), R = Eigen::Matrix4d::Identity(),
                    S = Eigen::Matrix4d::Identity();
    T.col(3).head<3>() << origin.x, origin.y, origin.z;
    const Vec3 axes[3] = {a, b, c};
    for (int i = 0; i < 3; ++i) {
        double n = norm(axes[i]);
        R.col(i).head<3>() << axes[i].x / n, axes[i].y / n, axes[i].z / n;
        S(i, i) = n;
    }
    return (T * R * S).inverse();
}

inline Vec3 apply_point(const Eigen::Matrix4d& m, Vec3 p) {
    Eigen::Vector4d r = m * Eigen::Vector4d(p.x, p.y, p.z, 1);
    return {r[0], r[1], r[2]};
}
// A direction has homogeneous coordinate 0: no translation (erratum 2).
inline Vec3 apply_vector(const Eigen::Matrix4d& m, Vec3 v) {
    Eigen::Vector4d r = m * Eigen::Vector4d(v.x, v.y, v.z, 0);
    return {r[0], r[1], r[2]};
}

// M^-1 without forming M: its rows are the dual vectors (b x c, c x a, a x b) / det[a b c]
// (adjugate over determinant, erratum 3), each kept in double-double: for a line nearly along
// the axis, v . (b x c) is a tiny difference that a rounded b x c would swamp. c may carry a
// low part (the cone's c = H - C is not a double).
template <class T>
struct DualFrameT {
    Vec3TwoTermT<T> nx, ny, nz;
    T det;
    DualFrameT(Vec3T<T> a, Vec3T<T> b, const Vec3TwoTermT<T>& c)
        : nx(cross_dd(b, c)), ny(cross_dd(c, a)), nz(cross_dd(a, b)), det(dot2(a, nx)) {}
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
};
using DualFrame = DualFrameT<double>;

// 2^-E for |x| in [2^E, 2^(E+1)), exactly; 1 when x is zero or subnormal (no power of two of that
// size is safe to scale by; the solvers' underflow guards then refuse what they cannot decide).
inline double power_of_two_inverse(double x) {
    std::uint64_t bits;
    std::memcpy(&bits, &x, sizeof bits);
    bits &= 0x7ff0000000000000u; // 2^E, or 0
    double p;
    std::memcpy(&p, &bits, sizeof p);
    return p == 0 ? 1.0 : 1 / p;
}

} // namespace linequad::detail
