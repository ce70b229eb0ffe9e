// Two doubles side by side (D2): a scalar solver's two roots, each at its own point, taken through
// the same steps at once. Every operation is the IEEE one (add, mul, div, sqrt and fma correctly
// rounded), so each lane computes the bits the scalar code computes in double. With FMA (fast/'s
// default build, which implies the 128-bit VEX forms) a lane pair is one SSE register; without it,
// two doubles in turn, so that the portable build computes the same thing.
#pragma once

#include "numeric/format.hpp"
#include "numeric/vector.hpp"

#include <cmath>
#include <cstdint>

#if defined(__FMA__) && defined(__SSE4_1__)
#include <immintrin.h>
#define LINEQUAD_D2_REGISTER 1
#else
#define LINEQUAD_D2_REGISTER 0
#endif

namespace linequad::detail {

// Each form in its own inline namespace: a translation unit built without FMA (a test, or the
// library with LINEQUAD_FMA off beside its AVX2 kernels) links beside one built with it, and the
// two D2 types, and everything instantiated with them, keep distinct names.
#if LINEQUAD_D2_REGISTER
inline namespace d2_register {

struct M2 {
    __m128d m;
};
struct D2 {
    __m128d v;
    D2() = default;
    D2(double x) : v(_mm_set1_pd(x)) {}
    D2(double lane0, double lane1) : v(_mm_setr_pd(lane0, lane1)) {}
    explicit D2(__m128d x) : v(x) {}
    double operator[](int k) const {
        return k == 0 ? _mm_cvtsd_f64(v) : _mm_cvtsd_f64(_mm_unpackhi_pd(v, v));
    }
};
inline D2 operator+(D2 a, D2 b) {
    return D2(_mm_add_pd(a.v, b.v));
}
inline D2 operator-(D2 a, D2 b) {
    return D2(_mm_sub_pd(a.v, b.v));
}
inline D2 operator*(D2 a, D2 b) {
    return D2(_mm_mul_pd(a.v, b.v));
}
inline D2 operator/(D2 a, D2 b) {
    return D2(_mm_div_pd(a.v, b.v));
}
inline D2 operator-(D2 a) {
    return D2(-a.v);
}
inline D2 fma(D2 a, D2 b, D2 c) {
    return D2(_mm_fmadd_pd(a.v, b.v, c.v));
}
inline D2 sqrt(D2 a) {
    return D2(_mm_sqrt_pd(a.v));
}
inline D2 fabs(D2 a) {
    return D2(_mm_andnot_pd(_mm_set1_pd(-0.0), a.v));
}
inline D2 maximum(D2 a, D2 b) {
    return D2(_mm_max_pd(a.v, b.v));
}
// Ordered comparisons are false on NaN, as in C++.
inline M2 operator<(D2 a, D2 b) {
    return {_mm_cmplt_pd(a.v, b.v)};
}
inline M2 operator<=(D2 a, D2 b) {
    return {_mm_cmple_pd(a.v, b.v)};
}
inline M2 operator>=(D2 a, D2 b) {
    return {_mm_cmpge_pd(a.v, b.v)};
}
inline M2 operator!=(D2 a, D2 b) {
    return {_mm_cmpneq_pd(a.v, b.v)};
} // true on NaN, as in C++
inline M2 operator&(M2 a, M2 b) {
    return {_mm_and_pd(a.m, b.m)};
}
inline M2 operator|(M2 a, M2 b) {
    return {_mm_or_pd(a.m, b.m)};
}
inline M2 operator!(M2 a) {
    return {_mm_xor_pd(a.m, _mm_castsi128_pd(_mm_set1_epi64x(-1)))};
}
inline bool lane(M2 m, int k) {
    return (_mm_movemask_pd(m.m) >> k) & 1;
}
inline D2 copysign(D2 mag, D2 sgn) {
    __m128d s = _mm_set1_pd(-0.0);
    return D2(_mm_or_pd(_mm_andnot_pd(s, mag.v), _mm_and_pd(s, sgn.v)));
}
inline D2 select(M2 m, D2 a, D2 b) {
    return D2(_mm_blendv_pd(b.v, a.v, m.m));
}
// Binary64's half_ulp_of_normal and is_power_of_two in each lane: the same bit operations.
inline D2 half_ulp_of_normal(D2 x) {
    __m128i b = _mm_and_si128(_mm_castpd_si128(x.v), _mm_set1_epi64x(0x7ff0000000000000));
    return D2(_mm_castsi128_pd(_mm_sub_epi64(b, _mm_set1_epi64x(std::int64_t(53) << 52))));
}
inline M2 is_power_of_two(D2 x) {
    __m128i b = _mm_and_si128(_mm_castpd_si128(x.v), _mm_set1_epi64x((std::int64_t(1) << 52) - 1));
    return {_mm_castsi128_pd(_mm_cmpeq_epi64(b, _mm_setzero_si128()))};
}

} // namespace d2_register
#else
inline namespace d2_portable {

struct M2 {
    bool m[2];
};
struct D2 {
    double v[2];
    D2() = default;
    D2(double x) : v{x, x} {}
    D2(double lane0, double lane1) : v{lane0, lane1} {}
    double operator[](int k) const { return v[k]; }
};
template <class Op>
inline D2 each(D2 a, D2 b, Op op) {
    return {op(a.v[0], b.v[0]), op(a.v[1], b.v[1])};
}
template <class Op>
inline M2 each_mask(D2 a, D2 b, Op op) {
    return {{op(a.v[0], b.v[0]), op(a.v[1], b.v[1])}};
}
inline D2 operator+(D2 a, D2 b) {
    return each(a, b, [](double x, double y) { return x + y; });
}
inline D2 operator-(D2 a, D2 b) {
    return each(a, b, [](double x, double y) { return x - y; });
}
inline D2 operator*(D2 a, D2 b) {
    return each(a, b, [](double x, double y) { return x * y; });
}
inline D2 operator/(D2 a, D2 b) {
    return each(a, b, [](double x, double y) { return x / y; });
}
inline D2 operator-(D2 a) {
    return {-a.v[0], -a.v[1]};
}
inline D2 fma(D2 a, D2 b, D2 c) {
    return {std::fma(a.v[0], b.v[0], c.v[0]), std::fma(a.v[1], b.v[1], c.v[1])};
}
inline D2 sqrt(D2 a) {
    return {std::sqrt(a.v[0]), std::sqrt(a.v[1])};
}
inline D2 fabs(D2 a) {
    return {std::fabs(a.v[0]), std::fabs(a.v[1])};
}
// maxpd's rule: the second operand where either is NaN or both are zeros.
inline D2 maximum(D2 a, D2 b) {
    return each(a, b, [](double x, double y) { return x > y ? x : y; });
}
inline M2 operator<(D2 a, D2 b) {
    return each_mask(a, b, [](double x, double y) { return x < y; });
}
inline M2 operator<=(D2 a, D2 b) {
    return each_mask(a, b, [](double x, double y) { return x <= y; });
}
inline M2 operator>=(D2 a, D2 b) {
    return each_mask(a, b, [](double x, double y) { return x >= y; });
}
inline M2 operator!=(D2 a, D2 b) {
    return each_mask(a, b, [](double x, double y) { return x != y; });
}
inline M2 operator&(M2 a, M2 b) {
    return {{a.m[0] && b.m[0], a.m[1] && b.m[1]}};
}
inline M2 operator|(M2 a, M2 b) {
    return {{a.m[0] || b.m[0], a.m[1] || b.m[1]}};
}
inline M2 operator!(M2 a) {
    return {{!a.m[0], !a.m[1]}};
}
inline bool lane(M2 m, int k) {
    return m.m[k];
}
inline D2 copysign(D2 mag, D2 sgn) {
    return each(mag, sgn, [](double x, double y) { return std::copysign(x, y); });
}
inline D2 select(M2 m, D2 a, D2 b) {
    return {m.m[0] ? a.v[0] : b.v[0], m.m[1] ? a.v[1] : b.v[1]};
}
inline D2 half_ulp_of_normal(D2 x) {
    return {Binary64::half_ulp_of_normal(x.v[0]), Binary64::half_ulp_of_normal(x.v[1])};
}
inline M2 is_power_of_two(D2 x) {
    return {{Binary64::is_power_of_two(x.v[0]), Binary64::is_power_of_two(x.v[1])}};
}

} // namespace d2_portable
#endif

// maximum() for double, with maxpd's rule, so that a template over both gives the same bits.
inline double maximum(double a, double b) {
    return a > b ? a : b;
}
inline double lane(D2 x, int k) {
    return x[k];
}

} // namespace linequad::detail
