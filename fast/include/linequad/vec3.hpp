// 3-vectors. Vec3 is the double one; the templates also serve the batch solvers' 4-lane type,
// so that scalar and batch results come from the same code. Accurate products: eft.hpp.
#pragma once

#include <algorithm>
#include <cmath>

// Small helpers inlined always: out of line, a call passes its vectors through memory, which
// costs more than their arithmetic (the batch solvers' 4-lane values, the bounded types).
#if defined(__GNUC__)
#define LINEQUAD_INLINE inline __attribute__((always_inline))
#else
#define LINEQUAD_INLINE inline
#endif

namespace linequad {

template <class T>
struct Vec3T {
    T x{}, y{}, z{};
    T operator[](int i) const { return i == 0 ? x : i == 1 ? y : z; }
};
using Vec3 = Vec3T<double>;

template <class T>
Vec3T<T> operator+(Vec3T<T> a, Vec3T<T> b) {
    return {a.x + b.x, a.y + b.y, a.z + b.z};
}
template <class T>
Vec3T<T> operator-(Vec3T<T> a, Vec3T<T> b) {
    return {a.x - b.x, a.y - b.y, a.z - b.z};
}
template <class T>
Vec3T<T> operator*(T s, Vec3T<T> a) {
    return {s * a.x, s * a.y, s * a.z};
}
inline Vec3 operator*(double s, Vec3 a) {
    return {s * a.x, s * a.y, s * a.z};
}
inline bool operator==(Vec3 a, Vec3 b) {
    return a.x == b.x && a.y == b.y && a.z == b.z;
}
inline bool operator!=(Vec3 a, Vec3 b) {
    return !(a == b);
}
template <class T>
LINEQUAD_INLINE T dot(const Vec3T<T>& a, const Vec3T<T>& b) {
    return a.x * b.x + a.y * b.y + a.z * b.z;
}
template <class T>
LINEQUAD_INLINE Vec3T<T> cross(const Vec3T<T>& a, const Vec3T<T>& b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
template <class T>
T norm(Vec3T<T> a) {
    using std::sqrt;
    return sqrt(dot(a, a));
}
inline double max_abs(Vec3 a) {
    return std::max({std::fabs(a.x), std::fabs(a.y), std::fabs(a.z)});
}
inline bool is_finite(Vec3 a) {
    return std::isfinite(a.x) && std::isfinite(a.y) && std::isfinite(a.z);
}
inline Vec3 ldexp(Vec3 a, int e) {
    return {std::ldexp(a.x, e), std::ldexp(a.y, e), std::ldexp(a.z, e)};
}

} // namespace linequad
