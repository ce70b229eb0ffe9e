// Vec3T's operations for every number type fast/'s templates run in (lanes, bounded and exact
// numbers); linequad/vec3.hpp has them for Vec3 itself, which overload resolution prefers.
#pragma once

#include "numeric/format.hpp"

#include "linequad/vec3.hpp"

#include <cmath>

namespace linequad {

template <class T>
LINEQUAD_INLINE Vec3T<T> operator+(const Vec3T<T>& a, const Vec3T<T>& b) {
    return {a.x + b.x, a.y + b.y, a.z + b.z};
}
template <class T>
LINEQUAD_INLINE Vec3T<T> operator-(const Vec3T<T>& a, const Vec3T<T>& b) {
    return {a.x - b.x, a.y - b.y, a.z - b.z};
}
template <class T>
LINEQUAD_INLINE Vec3T<T> operator*(const T& s, const Vec3T<T>& a) {
    return {s * a.x, s * a.y, s * a.z};
}
template <class T>
LINEQUAD_INLINE T dot(const Vec3T<T>& a, const Vec3T<T>& b) {
    return a.x * b.x + a.y * b.y + a.z * b.z;
}
template <class T>
LINEQUAD_INLINE Vec3T<T> cross(const Vec3T<T>& a, const Vec3T<T>& b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

// What a comparison of two T gives: bool for double, a lane mask for a lane type.
template <class T>
using MaskOf = decltype(T() < T());

// a in every lane of T (a itself for T = double).
template <class T>
LINEQUAD_INLINE Vec3T<T> lanes_of(const Vec3& a) {
    return {T(a.x), T(a.y), T(a.z)};
}

// Componentwise |a|.
template <class T>
LINEQUAD_INLINE Vec3T<T> magnitudes(const Vec3T<T>& a) {
    using std::fabs;
    return {fabs(a.x), fabs(a.y), fabs(a.z)};
}
// |a_i||b_j| + |a_j||b_i| for each component k of a x b: it bounds |(a x b)_k|, and the
// rounding of computing (a x b)_k is a few u of it.
template <class T>
LINEQUAD_INLINE Vec3T<T> cross_magnitudes(const Vec3T<T>& a, const Vec3T<T>& b) {
    Vec3T<T> p = magnitudes(a), q = magnitudes(b);
    return {p.y * q.z + p.z * q.y, p.z * q.x + p.x * q.z, p.x * q.y + p.y * q.x};
}
// |a| . cross_magnitudes(b, c): the same for the triple product a . (b x c).
template <class T>
LINEQUAD_INLINE T triple_product_magnitude(const Vec3T<T>& a, const Vec3T<T>& b,
                                           const Vec3T<T>& c) {
    return dot(magnitudes(a), cross_magnitudes(b, c));
}

inline Vec3 ldexp(Vec3 a, int e) {
    return {std::ldexp(a.x, e), std::ldexp(a.y, e), std::ldexp(a.z, e)};
}

} // namespace linequad
