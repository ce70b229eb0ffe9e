// Four doubles in an AVX2 register, with the operations the shared solver cores use. Every
// operation is the IEEE one (add, mul, div, sqrt and fma correctly rounded), so a lane computes
// exactly what the scalar double code computes. Only for translation units built with AVX2/FMA.
#pragma once

#include <immintrin.h>

namespace linequad::detail {

struct M4 {
    __m256d m;
};
struct D4 {
    __m256d v;
    D4() = default;
    D4(double x) : v(_mm256_set1_pd(x)) {}
    explicit D4(__m256d x) : v(x) {}
};

inline D4 operator+(D4 a, D4 b) {
    return D4(_mm256_add_pd(a.v, b.v));
}
inline D4 operator-(D4 a, D4 b) {
    return D4(_mm256_sub_pd(a.v, b.v));
}
inline D4 operator*(D4 a, D4 b) {
    return D4(_mm256_mul_pd(a.v, b.v));
}
inline D4 operator/(D4 a, D4 b) {
    return D4(_mm256_div_pd(a.v, b.v));
}
inline D4 operator-(D4 a) {
    return D4(_mm256_xor_pd(a.v, _mm256_set1_pd(-0.0)));
}
inline D4 fma(D4 a, D4 b, D4 c) {
    return D4(_mm256_fmadd_pd(a.v, b.v, c.v));
}
inline D4 sqrt(D4 a) {
    return D4(_mm256_sqrt_pd(a.v));
}
inline D4 fabs(D4 a) {
    return D4(_mm256_andnot_pd(_mm256_set1_pd(-0.0), a.v));
}
inline D4 copysign(D4 mag, D4 sgn) {
    __m256d s = _mm256_set1_pd(-0.0);
    return D4(_mm256_or_pd(_mm256_andnot_pd(s, mag.v), _mm256_and_pd(s, sgn.v)));
}
// Ordered comparisons are false on NaN, as in C++; != is true on NaN, as in C++.
inline M4 operator<(D4 a, D4 b) {
    return {_mm256_cmp_pd(a.v, b.v, _CMP_LT_OQ)};
}
inline M4 operator>=(D4 a, D4 b) {
    return {_mm256_cmp_pd(a.v, b.v, _CMP_GE_OQ)};
}
inline M4 operator<=(D4 a, D4 b) {
    return {_mm256_cmp_pd(a.v, b.v, _CMP_LE_OQ)};
}
inline M4 operator!=(D4 a, D4 b) {
    return {_mm256_cmp_pd(a.v, b.v, _CMP_NEQ_UQ)};
}
inline M4 operator&(M4 a, M4 b) {
    return {_mm256_and_pd(a.m, b.m)};
}
inline M4 operator|(M4 a, M4 b) {
    return {_mm256_or_pd(a.m, b.m)};
}
inline M4 operator!(M4 a) {
    return {_mm256_xor_pd(a.m, _mm256_castsi256_pd(_mm256_set1_epi64x(-1)))};
}
inline D4 select(M4 m, D4 a, D4 b) {
    return D4(_mm256_blendv_pd(b.v, a.v, m.m));
}
inline int bits(M4 m) {
    return _mm256_movemask_pd(m.m);
}
// power_of_two_inverse (shapes/frame.hpp) in each lane: the same operations, so the same bits.
inline D4 power_of_two_inverse(D4 x) {
    __m256d p = _mm256_and_pd(x.v, _mm256_castsi256_pd(_mm256_set1_epi64x(0x7ff0000000000000)));
    __m256d zero = _mm256_cmp_pd(p, _mm256_setzero_pd(), _CMP_EQ_OQ);
    return D4(_mm256_blendv_pd(_mm256_div_pd(_mm256_set1_pd(1.0), p), _mm256_set1_pd(1.0), zero));
}

} // namespace linequad::detail
