// Eight doubles (D8) in an AVX-512 register, with the operations the shared solver cores use, as
// lanes_avx2.hpp gives them for four: every operation the IEEE one, so a lane computes exactly
// what the scalar code computes in double. Masks are the mask registers (K8). Only for
// translation units built with AVX-512F and DQ.
#pragma once

#include "simd/lanes.hpp"

#include <cstdint>
#include <immintrin.h>

namespace linequad::detail {

struct K8 {
    __mmask8 m;
};
struct D8 {
    __m512d v;
    D8() = default;
    D8(double x) : v(_mm512_set1_pd(x)) {}
    explicit D8(__m512d x) : v(x) {}
};

template <>
struct RealOf<D8> {
    using type = double;
};

inline D8 operator+(D8 a, D8 b) {
    return D8(_mm512_add_pd(a.v, b.v));
}
inline D8 operator-(D8 a, D8 b) {
    return D8(_mm512_sub_pd(a.v, b.v));
}
inline D8 operator*(D8 a, D8 b) {
    return D8(_mm512_mul_pd(a.v, b.v));
}
inline D8 operator/(D8 a, D8 b) {
    return D8(_mm512_div_pd(a.v, b.v));
}
// GCC's own negation rather than an xor with -0.0: it folds into an fma that takes it
// (vfnmadd, vfmsub), which computes the same correctly rounded value.
inline D8 operator-(D8 a) {
    return D8(-a.v);
}
inline D8 fma(D8 a, D8 b, D8 c) {
    return D8(_mm512_fmadd_pd(a.v, b.v, c.v));
}
inline D8 sqrt(D8 a) {
    return D8(_mm512_sqrt_pd(a.v));
}
inline D8 fabs(D8 a) {
    return D8(_mm512_andnot_pd(_mm512_set1_pd(-0.0), a.v));
}
inline D8 copysign(D8 mag, D8 sgn) {
    __m512d s = _mm512_set1_pd(-0.0);
    return D8(_mm512_or_pd(_mm512_andnot_pd(s, mag.v), _mm512_and_pd(s, sgn.v)));
}
// Ordered comparisons are false on NaN, as in C++; != is true on NaN, as in C++.
inline K8 operator<(D8 a, D8 b) {
    return {_mm512_cmp_pd_mask(a.v, b.v, _CMP_LT_OQ)};
}
inline K8 operator>=(D8 a, D8 b) {
    return {_mm512_cmp_pd_mask(a.v, b.v, _CMP_GE_OQ)};
}
inline K8 operator<=(D8 a, D8 b) {
    return {_mm512_cmp_pd_mask(a.v, b.v, _CMP_LE_OQ)};
}
inline K8 operator!=(D8 a, D8 b) {
    return {_mm512_cmp_pd_mask(a.v, b.v, _CMP_NEQ_UQ)};
}
inline K8 operator&(K8 a, K8 b) {
    return {__mmask8(a.m & b.m)};
}
inline K8 operator|(K8 a, K8 b) {
    return {__mmask8(a.m | b.m)};
}
inline K8 operator!(K8 a) {
    return {__mmask8(~a.m)};
}
inline D8 select(K8 m, D8 a, D8 b) {
    return D8(_mm512_mask_blend_pd(m.m, b.v, a.v));
}
inline int bits(K8 m) {
    return m.m;
}
// Binary64::half_ulp of a finite x in each lane: the distance to the next double away from
// zero, halved (the same operations).
inline D8 half_ulp(D8 x) {
    D8 a = fabs(x);
    D8 next(_mm512_castsi512_pd(_mm512_add_epi64(_mm512_castpd_si512(a.v), _mm512_set1_epi64(1))));
    return (next - a) * D8(0.5); // x / 2 and x * 0.5 round alike
}
// Binary64's half_ulp_of_normal and is_power_of_two in each lane: the same bit operations.
inline D8 half_ulp_of_normal(D8 x) {
    __m512i b = _mm512_and_si512(_mm512_castpd_si512(x.v), _mm512_set1_epi64(0x7ff0000000000000));
    return D8(_mm512_castsi512_pd(_mm512_sub_epi64(b, _mm512_set1_epi64(std::int64_t(53) << 52))));
}
inline K8 is_power_of_two(D8 x) {
    __m512i b =
        _mm512_and_si512(_mm512_castpd_si512(x.v), _mm512_set1_epi64((std::int64_t(1) << 52) - 1));
    return {_mm512_cmpeq_epi64_mask(b, _mm512_setzero_si512())};
}
// power_of_two_inverse (shapes/frame.hpp) in each lane: the same operations, so the same bits.
inline D8 power_of_two_inverse(D8 x) {
    __m512d p = _mm512_and_pd(x.v, _mm512_castsi512_pd(_mm512_set1_epi64(0x7ff0000000000000)));
    __mmask8 zero = _mm512_cmp_pd_mask(p, _mm512_setzero_pd(), _CMP_EQ_OQ);
    return D8(
        _mm512_mask_blend_pd(zero, _mm512_div_pd(_mm512_set1_pd(1.0), p), _mm512_set1_pd(1.0)));
}

// ScaleLanes (simd/lanes.hpp) from the exponents' bits in 64-bit lanes.

inline ScaleLanes<D8> scale_lanes(D8 extent, D8 vmax) {
    constexpr int significand = 52, bias = 1023, limit = Binary64::moderate_exponent;
    const __m512i lim = _mm512_set1_epi64(limit), neg_lim = _mm512_set1_epi64(-limit);
    auto outside = [&](__m512i e) {
        return __mmask8(_mm512_cmpgt_epi64_mask(e, lim) | _mm512_cmpgt_epi64_mask(neg_lim, e));
    };
    __mmask8 ok = 0xff;
    // The exponent of each lane (0 for zero), clearing `ok` where it is subnormal or out of range.
    auto exponent = [&](D8 m) {
        __mmask8 is_zero = _mm512_cmp_pd_mask(m.v, _mm512_setzero_pd(), _CMP_EQ_OQ);
        __m512i biased = _mm512_and_si512(_mm512_srli_epi64(_mm512_castpd_si512(m.v), significand),
                                          _mm512_set1_epi64(2 * bias + 1));
        __m512i e = _mm512_maskz_sub_epi64(__mmask8(~is_zero), biased, _mm512_set1_epi64(bias));
        __mmask8 subnormal =
            __mmask8(~is_zero & _mm512_cmpeq_epi64_mask(biased, _mm512_setzero_si512()));
        ok = __mmask8(ok & ~(subnormal | outside(e)));
        return e;
    };
    __m512i k = exponent(extent), j = exponent(vmax), kj = _mm512_sub_epi64(k, j);
    ok = __mmask8(ok & ~outside(kj));
    auto pow2 = [&](__m512i e) {
        return D8(_mm512_castsi512_pd(
            _mm512_slli_epi64(_mm512_add_epi64(e, _mm512_set1_epi64(bias)), significand)));
    };
    __m512i zero = _mm512_setzero_si512();
    return {pow2(_mm512_sub_epi64(zero, k)), pow2(_mm512_sub_epi64(zero, j)), pow2(kj), K8{ok}};
}

inline D8 load(const double* p) {
    return D8(_mm512_loadu_pd(p));
}
inline void store(double* p, D8 x) {
    _mm512_storeu_pd(p, x.v);
}
// Lane k of a, b, c and d as row k: {a_k, b_k, c_k, d_k} (an 8 x 4 transpose, as two 4 x 4 ones),
// for writers that copy a row at once.
inline void store_rows(D8 a, D8 b, D8 c, D8 d, double (*rows)[4]) {
    for (int half = 0; half < 2; ++half) {
        auto part = [half](D8 x) {
            return half == 0 ? _mm512_castpd512_pd256(x.v) : _mm512_extractf64x4_pd(x.v, 1);
        };
        __m256d ab_lo = _mm256_unpacklo_pd(part(a), part(b));
        __m256d ab_hi = _mm256_unpackhi_pd(part(a), part(b));
        __m256d cd_lo = _mm256_unpacklo_pd(part(c), part(d));
        __m256d cd_hi = _mm256_unpackhi_pd(part(c), part(d));
        _mm256_storeu_pd(rows[4 * half + 0], _mm256_permute2f128_pd(ab_lo, cd_lo, 0x20));
        _mm256_storeu_pd(rows[4 * half + 1], _mm256_permute2f128_pd(ab_hi, cd_hi, 0x20));
        _mm256_storeu_pd(rows[4 * half + 2], _mm256_permute2f128_pd(ab_lo, cd_lo, 0x31));
        _mm256_storeu_pd(rows[4 * half + 3], _mm256_permute2f128_pd(ab_hi, cd_hi, 0x31));
    }
}
// Through the zero-masked form: GCC 12's _mm512_max_pd reads an undefined register it warns about.
inline D8 maximum(D8 a, D8 b) {
    return D8(_mm512_maskz_max_pd(0xff, a.v, b.v));
}

} // namespace linequad::detail
