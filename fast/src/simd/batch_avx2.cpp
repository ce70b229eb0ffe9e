// The AVX2 batch kernel: each shape's stable core (its ShapeTraits<S>::Stable, shapes/)
// instantiated on four lanes, and the steps around it that the scalar solver takes, in lanes:
// prescaling, the pairing of roots, and finish()'s facts.
#include "shapes/all.hpp"
#include "simd/batch_kernels.hpp"
#include "simd/lanes_avx2.hpp"

#include <limits>

namespace linequad::detail {

namespace {

// A line's lanes: L0 and v as given, and prescale_for()'s powers of two built from their bits.
// `ok` drops the lanes that prescale_for() would take down a slow path (a subnormal extent,
// exponents beyond +-1000): they go back to the scalar solver.
struct LineLanes {
    Vec3T<D4> L0, v;
    D4 to_unit, dir_to_unit, t_scale;
    M4 ok;
};

D4 max_abs4(Vec3T<D4> a) {
    return D4(_mm256_max_pd(_mm256_max_pd(fabs(a.x).v, fabs(a.y).v), fabs(a.z).v));
}

// prescale_for()'s powers of two, per lane, with Prescale's pos, len and dir.
struct LanePrescale {
    D4 to_unit, dir_to_unit;
    Vec3T<D4> pos(Vec3 p) const {
        return {to_unit * D4(p.x), to_unit * D4(p.y), to_unit * D4(p.z)};
    }
    Vec3T<D4> pos(Vec3T<D4> p) const { return to_unit * p; }
    D4 len(double x) const { return to_unit * D4(x); }
    Vec3T<D4> dir(Vec3T<D4> v) const { return dir_to_unit * v; }
};

LineLanes line_lanes(const double* const soa[6], std::size_t i, double shape_extent) {
    LineLanes ln;
    auto load = [&](int a) { return D4(_mm256_loadu_pd(soa[a] + i)); };
    ln.L0 = {load(0), load(1), load(2)};
    ln.v = {load(3), load(4), load(5)};
    __m256i ok = _mm256_set1_epi64x(-1);
    auto exponent = [&ok](D4 m) {
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
    D4 extent(_mm256_max_pd(max_abs4(ln.L0).v, _mm256_set1_pd(shape_extent)));
    __m256i k = exponent(extent), j = exponent(max_abs4(ln.v)), kj = _mm256_sub_epi64(k, j);
    ok = _mm256_andnot_si256(_mm256_or_si256(_mm256_cmpgt_epi64(kj, _mm256_set1_epi64x(1000)),
                                             _mm256_cmpgt_epi64(_mm256_set1_epi64x(-1000), kj)),
                             ok);
    ln.to_unit = pow2(_mm256_sub_epi64(_mm256_setzero_si256(), k));
    ln.dir_to_unit = pow2(_mm256_sub_epi64(_mm256_setzero_si256(), j));
    ln.t_scale = pow2(kj);
    ln.ok = M4{_mm256_castsi256_pd(ok)};
    return ln;
}

// From the moved roots to assemble()'s facts, as shift_back() and finish() do for one line; e is
// the extent.
template <class Core>
void finish_lanes(const Core& k, M4 generic, const LineLanes& ln, ExtentT<D4> e, Interval range,
                  LaneResult out[4]) {
    D4 zero(0.0), sm[2];
    M4 two = k.D >= zero;
    stable_pair(k.A, k.B, k.Cc, k.D, sm);
    // The root of larger magnitude directly, the other from Vieta's product when it cancelled.
    D4 ta = k.tc + sm[0], tb = k.tc + sm[1];
    M4 far_is_a = fabs(ta) >= fabs(tb);
    D4 t_far = select(far_is_a, ta, tb), t_near = select(far_is_a, tb, ta);
    M4 vieta = (t_far != zero) & (fabs(t_near) < D4(0.5) * fabs(k.tc)) & two & generic;
    if (bits(vieta)) t_near = select(vieta, (k.C0_at_origin() / k.A) / t_far, t_near);
    D4 t[2] = {select(far_is_a, t_far, t_near), select(far_is_a, t_near, t_far)};
    M4 from_vieta[2] = {(!far_is_a) & vieta, far_is_a & vieta};
    D4 big(std::numeric_limits<double>::max());
    alignas(32) double tt[2][4], px[2][4], py[2][4], pz[2][4];
    int bad[2], keep[2];
    for (int j = 0; j < 2; ++j) {
        D4 z = k.z_lanes(t[j], sm[j], from_vieta[j]);
        D4 tcall = t[j] * ln.t_scale;
        M4 in = (z >= e.lo) & (z <= e.hi) & (tcall >= D4(range.t0)) & (tcall <= D4(range.t1));
        bad[j] = bits((!(fabs(tcall) <= big)) | (z != z));
        keep[j] = bits(in);
        _mm256_store_pd(tt[j], tcall.v);
        _mm256_store_pd(px[j], fma(tcall, ln.v.x, ln.L0.x).v);
        _mm256_store_pd(py[j], fma(tcall, ln.v.y, ln.L0.y).v);
        _mm256_store_pd(pz[j], fma(tcall, ln.v.z, ln.L0.z).v);
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

} // namespace

// The lanes the scalar solver would branch on (sizes out of reach, A or D zero or in the
// underflow zone, the scalar-only steps of a core) are not generic: they go back to it.
template <class S>
void stable_x4(const S& s, double shape_extent, const double* const soa[6], std::size_t i,
               Interval range, LaneResult out[4]) {
    LineLanes ln = line_lanes(soa, i, shape_extent);
    auto k = ShapeTraits<S>::template stable_core<D4>(
        AsGiven<S>{s}, LanePrescale{ln.to_unit, ln.dir_to_unit}, ln.L0, ln.v);
    D4 tiny(tiny_decisive);
    M4 generic = ln.ok & !k.too_small() & (fabs(k.A) >= tiny);
    k.discriminant();
    generic = generic & !k.scalar_only() & (fabs(k.D) >= tiny);
    finish_lanes(k, generic, ln, k.extent(s), range, out);
}

#define LINEQUAD_INSTANTIATE_KERNEL(S)                                                             \
    template void stable_x4(const S&, double, const double* const[6], std::size_t, Interval,       \
                            LaneResult[4]);
LINEQUAD_FOR_EACH_SHAPE(LINEQUAD_INSTANTIATE_KERNEL)

} // namespace linequad::detail
