#include "shapes/seed_frame.hpp"

#include <Eigen/Dense>

namespace linequad::detail {

void seed_inverse_frame(Vec3 origin, Vec3 a, Vec3 b, Vec3 c, double (&inverse)[16]) {
    Eigen::Matrix4d T = Eigen::Matrix4d::Identity(), R = Eigen::Matrix4d::Identity(),
                    S = Eigen::Matrix4d::Identity();
    T.col(3).head<3>() << origin.x, origin.y, origin.z;
    const Vec3 axes[3] = {a, b, c};
    for (int i = 0; i < 3; ++i) {
        double n = norm(axes[i]);
        R.col(i).head<3>() << axes[i].x / n, axes[i].y / n, axes[i].z / n;
        S(i, i) = n;
    }
    // Into a Matrix4d first, as the seeds' solvers always did: Eigen picks its 4x4 inverse by
    // the destination's alignment, and another path would round otherwise.
    Eigen::Matrix4d m = (T * R * S).inverse();
    Eigen::Map<Eigen::Matrix4d> out(inverse);
    out = m;
}

void to_seed_frame(const double (&inverse)[16], const Line& l, Vec3& w, Vec3& v) {
    Eigen::Matrix4d m = Eigen::Map<const Eigen::Matrix4d>(inverse);
    Eigen::Vector4d p = m * Eigen::Vector4d(l.L0.x, l.L0.y, l.L0.z, 1);
    Eigen::Vector4d d = m * Eigen::Vector4d(l.v.x, l.v.y, l.v.z, 0);
    w = {p[0], p[1], p[2]};
    v = {d[0], d[1], d[2]};
}

} // namespace linequad::detail
