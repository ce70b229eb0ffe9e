// The batch kernels' steps around each shape's stable core (its ShapeTraits<S>::Stable, shapes/),
// written once over the lane type L (D4, F8: lanes_avx2.hpp; D8: lanes_avx512.hpp): the steps
// the scalar solver takes, in lanes: prescaling, the pairing of roots, and finish()'s facts.
// Included only by translation units built for L's instruction set.
#pragma once

#include "shapes/all.hpp"
#include "simd/batch_kernels.hpp"
#include "simd/lanes.hpp"

#include <limits>

namespace linequad::detail {

// A line's lanes: L0 and v as given, and prescale_for()'s powers of two (ScaleLanes).
template <class L>
struct LineLanes {
    Vec3T<L> L0, v;
    ScaleLanes<L> scale;
};

// prescale_for()'s powers of two, per lane, with Prescale's pos, len and dir.
template <class L>
struct LanePrescale {
    L to_unit, dir_to_unit;
    Vec3T<L> pos(Vec3 p) const { return to_unit * Vec3T<L>{L(p.x), L(p.y), L(p.z)}; }
    Vec3T<L> pos(Vec3T<L> p) const { return to_unit * p; }
    L len(double x) const { return to_unit * L(x); }
    Vec3T<L> dir(Vec3T<L> v) const { return dir_to_unit * v; }
};

template <class L>
LineLanes<L> line_lanes(const Real<L>* const soa[6], std::size_t i, double shape_extent) {
    LineLanes<L> ln;
    ln.L0 = {load(soa[0] + i), load(soa[1] + i), load(soa[2] + i)};
    ln.v = {load(soa[3] + i), load(soa[4] + i), load(soa[5] + i)};
    ln.scale = scale_lanes(maximum(max_abs(ln.L0), L(shape_extent)), max_abs(ln.v));
    return ln;
}

// From the moved roots to write_result()'s facts, as shift_back() and assemble() make them for
// one line; e is the extent. The kept roots go to the block's first slots in assemble()'s order
// (the smaller t first, except for a hit test, which takes them as found). A line assemble()
// would refuse (a root's t or z not finite, a hit's point beyond the range) is left to it.
// `linear`: g is linear (A = 0 on every line: a plane), and its one root, -C / 2B as stable_roots
// takes it, is root 0; root 1 is never kept.
template <class L, bool linear = false, class Core>
LINEQUAD_INLINE void finish_lanes(const Core& k, MaskOf<L> generic, const LineLanes<L>& ln,
                                  ExtentT<L> e, Interval range, Query q,
                                  LaneBlock<Real<L>, lane_count<L>>& out) {
    using R = Real<L>;
    L zero(R(0)), sm[2], t[2];
    auto two = k.D >= zero;
    MaskOf<L> from_vieta[2];
    if constexpr (linear) {
        two = k.B != zero;
        sm[0] = sm[1] = -k.C_moved / (L(R(2)) * k.B);
        t[0] = t[1] = sm[0] + k.tc; // shift_back's, for one root
        from_vieta[0] = from_vieta[1] = zero < zero;
    } else {
        stable_pair(k.A, k.B, k.C_moved, k.D, sm);
        // The root of larger magnitude directly, the other from Vieta's product when it
        // cancelled.
        L ta = k.tc + sm[0], tb = k.tc + sm[1];
        auto far_is_a = fabs(ta) >= fabs(tb);
        L t_far = select(far_is_a, ta, tb), t_near = select(far_is_a, tb, ta);
        auto vieta = (t_far != zero) & (fabs(t_near) < L(R(0.5)) * fabs(k.tc)) & two & generic;
        if (bits(vieta)) t_near = select(vieta, (k.C0_at_origin() / k.A) / t_far, t_near);
        t[0] = select(far_is_a, t_far, t_near), t[1] = select(far_is_a, t_near, t_far);
        from_vieta[0] = (!far_is_a) & vieta, from_vieta[1] = far_is_a & vieta;
    }
    L big(std::numeric_limits<R>::max());
    const Vec3T<L>& L0 = ln.L0;
    const Vec3T<L>& v = ln.v;
    L tcall[2], p[3][2]; // p[c][j]: coordinate c of root j's point
    MaskOf<L> in[2], finite[2], bad = zero < zero;
    for (int j = 0; j < 2; ++j) {
        L z = k.z_lanes(t[j], sm[j], from_vieta[j]);
        tcall[j] = t[j] * ln.scale.t_scale;
        in[j] = two & (z >= e.lo) & (z <= e.hi) & (tcall[j] >= L(R(range.t0))) &
                (tcall[j] <= L(R(range.t1)));
        if constexpr (linear)
            if (j == 1) in[j] = zero < zero;
        bad = bad | (!(fabs(tcall[j]) <= big)) | (z != z);
        for (int c = 0; c < 3; ++c)
            p[c][j] = fma(tcall[j], v[c], L0[c]);
        finite[j] = (fabs(p[0][j]) <= big) & (fabs(p[1][j]) <= big) & (fabs(p[2][j]) <= big);
    }
    // assemble()'s order: the second root first where it is smaller (not for a hit test).
    using M = MaskOf<L>;
    auto either = [](M m, M a, M b) { return (m & a) | ((!m) & b); }; // select, on masks
    M no_lane = zero < zero;
    M swap = q.need == Need::any ? no_lane : tcall[1] < tcall[0];
    M first_in = either(swap, in[1], in[0]), second_in = either(swap, in[0], in[1]);
    // The first slot takes the first root kept, the second the other when both are kept and all
    // hits are asked for (the first kept is the nearest).
    M slot[2] = {first_in | second_in, q.need == Need::all ? first_in & second_in : no_lane};
    M root1_in[2] = {either(first_in, swap, !swap), !swap}; // slot j holds root 1
    bool points = q.points && q.need != Need::any;
    M refused = two & bad;
    for (int j = 0; j < 2; ++j) {
        auto pick = [&](const L(&x)[2]) { return select(root1_in[j], x[1], x[0]); };
        if (points) {
            store_rows(pick(tcall), pick(p[0]), pick(p[1]), pick(p[2]), out.tp[j]);
            refused = refused | (slot[j] & !either(root1_in[j], finite[1], finite[0]));
        } else {
            store_rows(pick(tcall), zero, zero, zero, out.tp[j]);
        }
    }
    out.generic = unsigned(bits(generic & !refused));
    out.keep[0] = unsigned(bits(slot[0]));
    out.keep[1] = unsigned(bits(slot[1]));
}

// The lanes the scalar solver would branch on (sizes out of reach, A or D zero or in the
// underflow zone, the scalar-only steps of a core) are not generic: they go back to it.
// A surface whose g is linear (a plane): its lanes where the scalar solver takes the one root
// (StableIn::solve, solve.hpp): B not 0, D clear of the underflow zone, and, since its answer
// rests on A = 0, no fragile scene (fragile_scene and the core's zero_may_underflow, in lanes:
// a surface has no position, so its smallest is infinite). Double lanes only: the guards are
// computed in double, which float lanes would not reproduce.
template <class L, class Core>
MaskOf<L> linear_generic(const Core& k, const LineLanes<L>& ln, double shape_extent) {
    static_assert(std::is_same_v<Real<L>, double>);
    constexpr double min_size = Guards<double>::min_relative_size;
    const L zero(0.0), inf(Binary64::inf);
    auto nonzero = [&](L x) { return select(x != zero, fabs(x), inf); };
    auto lesser = [](L a, L b) { return select(a < b, a, b); }; // fmin, without NaN
    auto min_nonzero = [&](const Vec3T<L>& a) {
        return lesser(nonzero(a.x), lesser(nonzero(a.y), nonzero(a.z)));
    };
    L below = L(min_size) * maximum(max_abs(ln.L0), L(shape_extent));
    auto fragile = (min_nonzero(ln.L0) < below) |
                   (min_nonzero(ln.v) < L(min_size) * max_abs(ln.v)) | k.zero_may_underflow();
    return (k.B != zero) & (fabs(k.D) >= L(Guards<double>::tiny_decisive)) & (!fragile);
}

template <class L, class S>
void stable_lanes(const S& s, double shape_extent, const Real<L>* const soa[6], std::size_t i,
                  Interval range, Query q, LaneBlock<Real<L>, lane_count<L>>& out) {
    using R = Real<L>;
    if constexpr (std::is_same_v<S, Plane> && !std::is_same_v<R, double>) {
        out.generic = out.keep[0] = out.keep[1] = 0; // float lanes: every line the scalar solver's
        return;
    }
    LineLanes<L> ln = line_lanes<L>(soa, i, shape_extent);
    auto k = ShapeTraits<S>::template stable_core<L>(
        AsGiven<S>{s}, LanePrescale<L>{ln.scale.to_unit, ln.scale.dir_to_unit}, ln.L0, ln.v);
    if constexpr (std::is_same_v<S, Plane> && std::is_same_v<R, double>) { // g linear: one root
        k.discriminant();
        auto generic = ln.scale.ok & usual_line(ln.L0, ln.v) &
                       !k.smaller_than(Guards<R>::min_relative_size) &
                       linear_generic(k, ln, shape_extent);
        return finish_lanes<L, true>(k, generic, ln, k.extent(s), range, q, out);
    }
    L tiny(Guards<R>::tiny_decisive);
    auto generic = ln.scale.ok & usual_line(ln.L0, ln.v) &
                   !k.smaller_than(Guards<R>::min_relative_size) & (fabs(k.A) >= tiny);
    k.discriminant();
    generic = generic & !k.scalar_only() & (fabs(k.D) >= tiny);
    finish_lanes(k, generic, ln, k.extent(s), range, q, out);
}

} // namespace linequad::detail
