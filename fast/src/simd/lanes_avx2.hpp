// Four doubles (D4) or eight floats (F8) in an AVX2 register, with the operations the shared
// solver cores use. Every operation is the IEEE one (add, mul, div, sqrt and fma correctly
// rounded), so a lane computes exactly what the scalar code computes in double or float. Only
// for translation units built with AVX2/FMA.
#pragma once

#include "simd/lanes.hpp"

#include <cstdint>
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

template <>
struct RealOf<D4> {
    using type = double;
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
// GCC's own negation rather than an xor with -0.0: it folds into an fma that takes it
// (vfnmadd, vfmsub), which computes the same correctly rounded value.
inline D4 operator-(D4 a) {
    return D4(-a.v);
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
// Binary64::half_ulp of a finite x in each lane: the distance to the next double away from
// zero, halved (the same operations).
inline D4 half_ulp(D4 x) {
    D4 a = fabs(x);
    D4 next(_mm256_castsi256_pd(_mm256_add_epi64(_mm256_castpd_si256(a.v), _mm256_set1_epi64x(1))));
    return (next - a) * D4(0.5); // x / 2 and x * 0.5 round alike
}
// Binary64's half_ulp_of_normal and is_power_of_two in each lane: the same bit operations.
inline D4 half_ulp_of_normal(D4 x) {
    __m256i b = _mm256_and_si256(_mm256_castpd_si256(x.v), _mm256_set1_epi64x(0x7ff0000000000000));
    return D4(_mm256_castsi256_pd(_mm256_sub_epi64(b, _mm256_set1_epi64x(std::int64_t(53) << 52))));
}
inline M4 is_power_of_two(D4 x) {
    __m256i b =
        _mm256_and_si256(_mm256_castpd_si256(x.v), _mm256_set1_epi64x((std::int64_t(1) << 52) - 1));
    return {_mm256_castsi256_pd(_mm256_cmpeq_epi64(b, _mm256_setzero_si256()))};
}
// power_of_two_inverse (shapes/frame.hpp) in each lane: the same operations, so the same bits.
inline D4 power_of_two_inverse(D4 x) {
    __m256d p = _mm256_and_pd(x.v, _mm256_castsi256_pd(_mm256_set1_epi64x(0x7ff0000000000000)));
    __m256d zero = _mm256_cmp_pd(p, _mm256_setzero_pd(), _CMP_EQ_OQ);
    return D4(_mm256_blendv_pd(_mm256_div_pd(_mm256_set1_pd(1.0), p), _mm256_set1_pd(1.0), zero));
}

// The integer steps of ScaleLanes on W-bit lanes (64 for D4, 32 for F8): the exponent of each
// lane of m (0 for zero), clearing `ok` where it is subnormal or beyond +-limit, and 2^e from e.
template <int W>
struct ExponentLanes {
    static __m256i set(int x) { return W == 64 ? _mm256_set1_epi64x(x) : _mm256_set1_epi32(x); }
    static __m256i add(__m256i a, __m256i b) {
        return W == 64 ? _mm256_add_epi64(a, b) : _mm256_add_epi32(a, b);
    }
    static __m256i sub(__m256i a, __m256i b) {
        return W == 64 ? _mm256_sub_epi64(a, b) : _mm256_sub_epi32(a, b);
    }
    static __m256i greater(__m256i a, __m256i b) {
        return W == 64 ? _mm256_cmpgt_epi64(a, b) : _mm256_cmpgt_epi32(a, b);
    }
    static __m256i equal(__m256i a, __m256i b) {
        return W == 64 ? _mm256_cmpeq_epi64(a, b) : _mm256_cmpeq_epi32(a, b);
    }
    static constexpr int significand = W == 64 ? 52 : 23, bias = W == 64 ? 1023 : 127;
    static __m256i outside(__m256i e, int limit) {
        return _mm256_or_si256(greater(e, set(limit)), greater(set(-limit), e));
    }
    // m's bits, and whether m is zero, in W-bit lanes.
    static __m256i exponent(__m256i m, __m256i is_zero, int limit, __m256i& ok) {
        __m256i shifted =
            W == 64 ? _mm256_srli_epi64(m, significand) : _mm256_srli_epi32(m, significand);
        __m256i biased = _mm256_and_si256(shifted, set(2 * bias + 1));
        __m256i e = _mm256_andnot_si256(is_zero, sub(biased, set(bias))); // m = 0: exponent 0
        __m256i subnormal = _mm256_andnot_si256(is_zero, equal(biased, _mm256_setzero_si256()));
        ok = _mm256_andnot_si256(_mm256_or_si256(subnormal, outside(e, limit)), ok);
        return e;
    }
    static __m256i pow2(__m256i e) {
        __m256i biased = add(e, set(bias));
        return W == 64 ? _mm256_slli_epi64(biased, significand)
                       : _mm256_slli_epi32(biased, significand);
    }
    // The three powers of two from the exponents of extent and max |v| (their bits).
    static void scales(__m256i extent, __m256i extent_zero, __m256i vmax, __m256i vmax_zero,
                       int limit, __m256i out[3], __m256i& ok) {
        ok = set(-1);
        __m256i k = exponent(extent, extent_zero, limit, ok),
                j = exponent(vmax, vmax_zero, limit, ok);
        __m256i kj = sub(k, j);
        ok = _mm256_andnot_si256(outside(kj, limit), ok);
        out[0] = pow2(sub(_mm256_setzero_si256(), k));
        out[1] = pow2(sub(_mm256_setzero_si256(), j));
        out[2] = pow2(kj);
    }
};

inline ScaleLanes<D4> scale_lanes(D4 extent, D4 vmax) {
    auto zero = [](D4 m) {
        return _mm256_castpd_si256(_mm256_cmp_pd(m.v, _mm256_setzero_pd(), _CMP_EQ_OQ));
    };
    __m256i out[3], ok;
    ExponentLanes<64>::scales(_mm256_castpd_si256(extent.v), zero(extent),
                              _mm256_castpd_si256(vmax.v), zero(vmax), Binary64::moderate_exponent,
                              out, ok);
    auto real = [](__m256i x) { return D4(_mm256_castsi256_pd(x)); };
    return {real(out[0]), real(out[1]), real(out[2]), M4{_mm256_castsi256_pd(ok)}};
}

struct M8 {
    __m256 m;
};
struct F8 {
    __m256 v;
    F8() = default;
    F8(float x) : v(_mm256_set1_ps(x)) {}
    explicit F8(__m256 x) : v(x) {}
};
template <>
struct RealOf<F8> {
    using type = float;
};

inline F8 operator+(F8 a, F8 b) {
    return F8(_mm256_add_ps(a.v, b.v));
}
inline F8 operator-(F8 a, F8 b) {
    return F8(_mm256_sub_ps(a.v, b.v));
}
inline F8 operator*(F8 a, F8 b) {
    return F8(_mm256_mul_ps(a.v, b.v));
}
inline F8 operator/(F8 a, F8 b) {
    return F8(_mm256_div_ps(a.v, b.v));
}
// GCC's negation, as D4's.
inline F8 operator-(F8 a) {
    return F8(-a.v);
}
inline F8 fma(F8 a, F8 b, F8 c) {
    return F8(_mm256_fmadd_ps(a.v, b.v, c.v));
}
inline F8 sqrt(F8 a) {
    return F8(_mm256_sqrt_ps(a.v));
}
inline F8 fabs(F8 a) {
    return F8(_mm256_andnot_ps(_mm256_set1_ps(-0.0f), a.v));
}
inline F8 copysign(F8 mag, F8 sgn) {
    __m256 s = _mm256_set1_ps(-0.0f);
    return F8(_mm256_or_ps(_mm256_andnot_ps(s, mag.v), _mm256_and_ps(s, sgn.v)));
}
inline M8 operator<(F8 a, F8 b) {
    return {_mm256_cmp_ps(a.v, b.v, _CMP_LT_OQ)};
}
inline M8 operator>=(F8 a, F8 b) {
    return {_mm256_cmp_ps(a.v, b.v, _CMP_GE_OQ)};
}
inline M8 operator<=(F8 a, F8 b) {
    return {_mm256_cmp_ps(a.v, b.v, _CMP_LE_OQ)};
}
inline M8 operator!=(F8 a, F8 b) {
    return {_mm256_cmp_ps(a.v, b.v, _CMP_NEQ_UQ)};
}
inline M8 operator&(M8 a, M8 b) {
    return {_mm256_and_ps(a.m, b.m)};
}
inline M8 operator|(M8 a, M8 b) {
    return {_mm256_or_ps(a.m, b.m)};
}
inline M8 operator!(M8 a) {
    return {_mm256_xor_ps(a.m, _mm256_castsi256_ps(_mm256_set1_epi32(-1)))};
}
inline F8 select(M8 m, F8 a, F8 b) {
    return F8(_mm256_blendv_ps(b.v, a.v, m.m));
}
inline int bits(M8 m) {
    return _mm256_movemask_ps(m.m);
}
inline F8 power_of_two_inverse(F8 x) {
    __m256 p = _mm256_and_ps(x.v, _mm256_castsi256_ps(_mm256_set1_epi32(0x7f800000)));
    __m256 zero = _mm256_cmp_ps(p, _mm256_setzero_ps(), _CMP_EQ_OQ);
    return F8(_mm256_blendv_ps(_mm256_div_ps(_mm256_set1_ps(1.0f), p), _mm256_set1_ps(1.0f), zero));
}

inline ScaleLanes<F8> scale_lanes(F8 extent, F8 vmax) {
    auto zero = [](F8 m) {
        return _mm256_castps_si256(_mm256_cmp_ps(m.v, _mm256_setzero_ps(), _CMP_EQ_OQ));
    };
    __m256i out[3], ok;
    ExponentLanes<32>::scales(_mm256_castps_si256(extent.v), zero(extent),
                              _mm256_castps_si256(vmax.v), zero(vmax), Binary32::moderate_exponent,
                              out, ok);
    auto real = [](__m256i x) { return F8(_mm256_castsi256_ps(x)); };
    return {real(out[0]), real(out[1]), real(out[2]), M8{_mm256_castsi256_ps(ok)}};
}

// Loads and stores, one lane type's width at a time.
inline D4 load(const double* p) {
    return D4(_mm256_loadu_pd(p));
}
inline F8 load(const float* p) {
    return F8(_mm256_loadu_ps(p));
}
inline void store(double* p, D4 x) {
    _mm256_storeu_pd(p, x.v);
}
inline void store(float* p, F8 x) {
    _mm256_storeu_ps(p, x.v);
}
// Lane k of a, b, c and d as row k: {a_k, b_k, c_k, d_k} (a 4 x 4 transpose), for writers that
// copy a row at once.
inline void store_rows(D4 a, D4 b, D4 c, D4 d, double (*rows)[4]) {
    __m256d ab_lo = _mm256_unpacklo_pd(a.v, b.v), ab_hi = _mm256_unpackhi_pd(a.v, b.v);
    __m256d cd_lo = _mm256_unpacklo_pd(c.v, d.v), cd_hi = _mm256_unpackhi_pd(c.v, d.v);
    _mm256_storeu_pd(rows[0], _mm256_permute2f128_pd(ab_lo, cd_lo, 0x20));
    _mm256_storeu_pd(rows[1], _mm256_permute2f128_pd(ab_hi, cd_hi, 0x20));
    _mm256_storeu_pd(rows[2], _mm256_permute2f128_pd(ab_lo, cd_lo, 0x31));
    _mm256_storeu_pd(rows[3], _mm256_permute2f128_pd(ab_hi, cd_hi, 0x31));
}
inline void store_rows(F8 a, F8 b, F8 c, F8 d, float (*rows)[4]) {
    for (int half = 0; half < 2; ++half) {
        auto part = [half](F8 x) {
            return half == 0 ? _mm256_castps256_ps128(x.v) : _mm256_extractf128_ps(x.v, 1);
        };
        __m128 r0 = part(a), r1 = part(b), r2 = part(c), r3 = part(d);
        _MM_TRANSPOSE4_PS(r0, r1, r2, r3);
        _mm_storeu_ps(rows[4 * half + 0], r0);
        _mm_storeu_ps(rows[4 * half + 1], r1);
        _mm_storeu_ps(rows[4 * half + 2], r2);
        _mm_storeu_ps(rows[4 * half + 3], r3);
    }
}
// The larger of a and b by the max instructions.
inline D4 maximum(D4 a, D4 b) {
    return D4(_mm256_max_pd(a.v, b.v));
}
inline F8 maximum(F8 a, F8 b) {
    return F8(_mm256_max_ps(a.v, b.v));
}

} // namespace linequad::detail
