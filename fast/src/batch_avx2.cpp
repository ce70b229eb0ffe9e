// The AVX2 batch kernels: the shared solver cores instantiated on four lanes.
#include "batch_kernels.hpp"
#include "cylinder_stable.hpp"
#include "lanes_avx2.hpp"
#include "support.hpp"

#include <limits>

namespace linequad::detail {

void cylinder_stable_x4(const Cylinder& s, double shape_extent, const double* const soa[6],
                        std::size_t i, Range range, LaneResult out[4]) {
    // The power-of-two prescaling of prescale_for(), in lanes: exponents read from the bits,
    // powers of two built from them. Lanes that prescale_for() would send down a slow path (a
    // subnormal extent, exponents beyond +-1000) go back to the scalar solver.
    Vec3T<D4> L0{D4(_mm256_loadu_pd(soa[0] + i)), D4(_mm256_loadu_pd(soa[1] + i)),
                 D4(_mm256_loadu_pd(soa[2] + i))};
    Vec3T<D4> vin{D4(_mm256_loadu_pd(soa[3] + i)), D4(_mm256_loadu_pd(soa[4] + i)),
                  D4(_mm256_loadu_pd(soa[5] + i))};
    auto max_abs4 = [](Vec3T<D4> a) {
        return D4(_mm256_max_pd(_mm256_max_pd(fabs(a.x).v, fabs(a.y).v), fabs(a.z).v));
    };
    D4 extent(_mm256_max_pd(max_abs4(L0).v, _mm256_set1_pd(shape_extent)));
    auto exponent = [](D4 m, __m256i& ok) {
        __m256i biased = _mm256_and_si256(_mm256_srli_epi64(_mm256_castpd_si256(m.v), 52),
                                          _mm256_set1_epi64x(0x7ff));
        __m256i e = _mm256_sub_epi64(biased, _mm256_set1_epi64x(1023));
        __m256i zero_m = _mm256_castpd_si256(_mm256_cmp_pd(m.v, _mm256_setzero_pd(), _CMP_EQ_OQ));
        e = _mm256_andnot_si256(zero_m, e); // m = 0: exponent 0
        __m256i subnormal =
            _mm256_andnot_si256(zero_m, _mm256_cmpeq_epi64(biased, _mm256_setzero_si256()));
        __m256i out = _mm256_or_si256(_mm256_cmpgt_epi64(e, _mm256_set1_epi64x(1000)),
                                      _mm256_cmpgt_epi64(_mm256_set1_epi64x(-1000), e));
        ok = _mm256_andnot_si256(_mm256_or_si256(subnormal, out), ok);
        return e;
    };
    auto pow2 = [](__m256i e) {
        return D4(_mm256_castsi256_pd(
            _mm256_slli_epi64(_mm256_add_epi64(e, _mm256_set1_epi64x(1023)), 52)));
    };
    __m256i ok = _mm256_set1_epi64x(-1);
    __m256i kx = exponent(extent, ok), jx = exponent(max_abs4(vin), ok);
    __m256i kj = _mm256_sub_epi64(kx, jx);
    ok = _mm256_andnot_si256(_mm256_or_si256(_mm256_cmpgt_epi64(kj, _mm256_set1_epi64x(1000)),
                                             _mm256_cmpgt_epi64(_mm256_set1_epi64x(-1000), kj)),
                             ok);
    D4 to_unit = pow2(_mm256_sub_epi64(_mm256_setzero_si256(), kx));
    D4 dir_to_unit = pow2(_mm256_sub_epi64(_mm256_setzero_si256(), jx));
    D4 t_scale = pow2(kj);
    auto pos = [&](Vec3 p) {
        return Vec3T<D4>{to_unit * D4(p.x), to_unit * D4(p.y), to_unit * D4(p.z)};
    };
    CylinderStable<D4> k(pos(s.C), pos(s.H), to_unit * L0, dir_to_unit * vin, to_unit * D4(s.r));
    D4 min_size(min_relative_size), tiny(tiny_decisive), zero(0.0);
    // The lanes the scalar solver would branch on go back to it.
    M4 generic =
        M4{_mm256_castsi256_pd(ok)} & (k.r >= min_size) & (k.hn >= min_size) & (k.A >= tiny);
    k.discriminant();
    generic = generic & (fabs(k.D) >= tiny);
    M4 two = k.D >= zero;
    D4 sm[2];
    k.moved_roots(sm);
    // Back to the caller's origin: the root of larger magnitude directly, the other from
    // Vieta's product when it cancelled (shift_back in roots.hpp).
    D4 ta = k.tc + sm[0], tb = k.tc + sm[1];
    M4 far_is_a = fabs(ta) >= fabs(tb);
    D4 t_far = select(far_is_a, ta, tb), t_near = select(far_is_a, tb, ta);
    M4 vieta = (t_far != zero) & (fabs(t_near) < D4(0.5) * fabs(k.tc)) & two & generic;
    if (bits(vieta)) t_near = select(vieta, (k.C0_at_origin() / k.A) / t_far, t_near);
    D4 t[2] = {select(far_is_a, t_far, t_near), select(far_is_a, t_near, t_far)};
    M4 from_vieta[2] = {(!far_is_a) & vieta, far_is_a & vieta};
    // finish()'s facts for each root, in lanes: t in the caller's units, not finite, inside the
    // extent and the range, and the point fma(t, v, L0) from the caller's own line.
    D4 lo(s.finite ? 0.0 : -inf), hi = s.finite ? k.hh : D4(inf);
    D4 big(std::numeric_limits<double>::max());
    alignas(32) double tt[2][4], px[2][4], py[2][4], pz[2][4];
    int bad[2], keep[2];
    for (int j = 0; j < 2; ++j) {
        D4 z = select(from_vieta[j], k.z_at_origin(t[j]), k.z_moved(sm[j]));
        D4 tcall = t[j] * t_scale;
        M4 in = (z >= lo) & (z <= hi);
        if (range != Range::line) in = in & (tcall >= zero);
        if (range == Range::segment) in = in & (tcall <= D4(1.0));
        bad[j] = bits((!(fabs(tcall) <= big)) | (z != z));
        keep[j] = bits(in);
        _mm256_store_pd(tt[j], tcall.v);
        _mm256_store_pd(px[j], fma(tcall, vin.x, L0.x).v);
        _mm256_store_pd(py[j], fma(tcall, vin.y, L0.y).v);
        _mm256_store_pd(pz[j], fma(tcall, vin.z, L0.z).v);
    }
    int g = bits(generic), tw = bits(two);
    for (int lane = 0; lane < 4; ++lane) {
        LaneResult& o = out[lane];
        o.generic = (g >> lane) & 1;
        o.count = (tw >> lane) & 1 ? 2 : 0;
        for (int j = 0; j < 2; ++j)
            o.root[j] = {tt[j][lane],
                         HitKind::cross,
                         bool((bad[j] >> lane) & 1),
                         bool((keep[j] >> lane) & 1),
                         {px[j][lane], py[j][lane], pz[j][lane]}};
    }
}

} // namespace linequad::detail
