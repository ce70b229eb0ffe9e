// 3-vectors of doubles. (Inside fast/ the same template holds the other number types its
// derivations run in: lanes, bounded and exact numbers.)
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

namespace linequad {

// A plain value: Vec3{} is zero; a Vec3 left uninitialised is not (a Hit's point is written
// once, by the solver that finds it).
template <class T>
struct Vec3T {
    T x, y, z;
    T operator[](int i) const { return i == 0 ? x : i == 1 ? y : z; }
};
using Vec3 = Vec3T<double>;

inline Vec3 operator+(Vec3 a, Vec3 b) {
    return {a.x + b.x, a.y + b.y, a.z + b.z};
}
inline Vec3 operator-(Vec3 a, Vec3 b) {
    return {a.x - b.x, a.y - b.y, a.z - b.z};
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
inline double dot(Vec3 a, Vec3 b) {
    return a.x * b.x + a.y * b.y + a.z * b.z;
}
inline Vec3 cross(Vec3 a, Vec3 b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline double norm(Vec3 a) {
    return std::sqrt(dot(a, a));
}
inline double max_abs(Vec3 a) {
    return std::max(std::max(std::fabs(a.x), std::fabs(a.y)), std::fabs(a.z));
}
inline bool is_finite(Vec3 a) {
    constexpr double largest = std::numeric_limits<double>::max(); // NaN compares false
    return (std::fabs(a.x) <= largest) & (std::fabs(a.y) <= largest) & (std::fabs(a.z) <= largest);
}

} // namespace linequad
