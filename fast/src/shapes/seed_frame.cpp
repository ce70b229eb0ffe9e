#include "shapes/seed_frame.hpp"

#include <Eigen/Dense>

namespace linequad::detail {

template <class R>
void seed_inverse_frame(Vec3 origin, Vec3 a, Vec3 b, Vec3 c, R (&inverse)[16]) {
    using Matrix = Eigen::Matrix<R, 4, 4>;
    Matrix T = Matrix::Identity(), Rot = Matrix::Identity(), S = Matrix::Identity();
    T.col(3).template head<3>() << R(origin.x), R(origin.y), R(origin.z);
    const Vec3T<R> axes[3] = {in_real<R>(a), in_real<R>(b), in_real<R>(c)};
    for (int i = 0; i < 3; ++i) {
        R n = std::sqrt(dot(axes[i], axes[i]));
        Rot.col(i).template head<3>() << axes[i].x / n, axes[i].y / n, axes[i].z / n;
        S(i, i) = n;
    }
    // Into a Matrix first, as the seeds' solvers always did: Eigen picks its 4x4 inverse by
    // the destination's alignment, and another path would round otherwise.
    Matrix m = (T * Rot * S).inverse();
    Eigen::Map<Matrix> out(inverse);
    out = m;
}

template <class R>
void to_seed_frame(const R (&inverse)[16], const Line& l, Vec3T<R>& w, Vec3T<R>& v) {
    using Vector = Eigen::Matrix<R, 4, 1>;
    Eigen::Matrix<R, 4, 4> m = Eigen::Map<const Eigen::Matrix<R, 4, 4>>(inverse);
    Vector p = m * Vector(R(l.L0.x), R(l.L0.y), R(l.L0.z), 1);
    Vector d = m * Vector(R(l.v.x), R(l.v.y), R(l.v.z), 0);
    w = {p[0], p[1], p[2]};
    v = {d[0], d[1], d[2]};
}

template void seed_inverse_frame(Vec3, Vec3, Vec3, Vec3, double (&)[16]);
template void seed_inverse_frame(Vec3, Vec3, Vec3, Vec3, float (&)[16]);
template void to_seed_frame(const double (&)[16], const Line&, Vec3&, Vec3&);
template void to_seed_frame(const float (&)[16], const Line&, Vec3T<float>&, Vec3T<float>&);

} // namespace linequad::detail
