// Vec3T's operations for every number type fast/'s templates run in (lanes, bounded and exact
// numbers); linequad/vec3.hpp has them for Vec3 itself, which overload resolution prefers.
#pragma once

#include "numeric/format.hpp"

#include "linequad/vec3.hpp"

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

inline Vec3 ldexp(Vec3 a, int e) {
    return {std::ldexp(a.x, e), std::ldexp(a.y, e), std::ldexp(a.z, e)};
}

} // namespace linequad
