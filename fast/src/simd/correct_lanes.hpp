// The batch correct solver's kernel: the Newton rung (correct/newton_rung.hpp) on a lane of lines
// at a time, through the rung's arithmetic written once over the number type
// (correct/newton_steps.hpp) and each shape's line form in lanes (its line_form<L>, shapes/).
// A lane answers only where the scalar ladder would take the same rung on the same line and
// prove it: a usual line (finite, v nonzero) of moderate size, solved as given, every decision
// and every rounding proven; a hit test (Need::any) on the quick rung, as the scalar solver
// takes it first. The other lanes go back to the scalar ladder. Included only by
// translation units built for L's instruction set.
#pragma once

#include "correct/correct.hpp"
#include "correct/newton_steps.hpp"
#include "simd/batch_kernels.hpp"
#include "simd/lanes.hpp"

namespace linequad::detail {

namespace newton {

// Both roots of one lane's line, as the scalar rung adds them (the smaller first), or the
// proof that there is none. L0 and v: the lane's line as given.
template <int SigmaZ, class L>
void solve_lanes(const LineFormT<L>& f, Mask<L> usable, const Vec3T<L>& L0, const Vec3T<L>& v,
                 Interval range, Query q, CorrectBlock<lane_count<L>>& out) {
    const L one(1.0), zero(0.0); // as given: t and the points need no scaling
    Leading<L> A = leading<SigmaZ>(f);
    usable = usable & (A.e < fabs(A.A)); // not nearly parallel to the axis or a generator
    Estimates<L> est = estimates<SigmaZ>(f, A);
    Mask<L> swap = est.root[1] < est.root[0];
    L lo = select(swap, est.root[1], est.root[0]), hi = select(swap, est.root[0], est.root[1]);
    // The first point is the vertex where the estimates are not real: one evaluation serves both.
    const L c[2] = {select(est.real, lo, est.vertex), hi};
    Local<L> local[2];
    local_at<SigmaZ>(f, c, local);
    Mask<L> no_root = no_root_proven(A, c[0], local[0]);

    Mask<L> failed[2], kept_root[2];
    L t[2], bound[2], p[3][2]; // p[a][j]: coordinate a of root j's point
    for (int j = 0; j < 2; ++j) {
        Enclosure<L> en = root_near(local[j], A, c[j]);
        Kept<L> k = kept(f, range, en);
        Rounded<L> rt = rounded_t(en, one);
        Mask<L> hit_proven = rt.proven;
        t[j] = rt.value;
        bound[j] = half_ulp(rt.value); // mark_certain's bound
#pragma GCC unroll 3
        for (int a = 0; a < 3; ++a) {
            if (!q.points) {
                p[a][j] = zero;
                continue;
            }
            L va = v[a], pa = L0[a];
            Rounded<L> pr = rounded_point(en, pa, va, one);
            Mask<L> along = equal(va, zero); // L0_k + t v_k is L0_k: +0 for a zero
            hit_proven = hit_proven & (along | pr.proven);
            p[a][j] = select(along, pa + zero, pr.value);
        }
        Mask<L> which = j == 0 ? en.smaller : !en.smaller; // the root the scalar rung expects
        Mask<L> decided = k.inside | k.outside;
        failed[j] = (!en.proven) | (!which) | (!decided) | (k.inside & (!hit_proven));
        kept_root[j] = est.real & k.inside;
    }
    // The nearest hit stops at the smaller root when it is kept: the larger one is then never
    // looked at.
    Mask<L> stop = q.need == Need::all ? zero < zero : kept_root[0];
    Mask<L> roots_proven = (!failed[0]) & (stop | (!failed[1]));
    Mask<L> proven = usable & ((est.real & roots_proven) | ((!est.real) & no_root));
    // The first slot takes the smaller root where it is kept, else the larger.
    Mask<L> larger_first = !kept_root[0];
    auto first = [&](const L(&x)[2]) { return select(larger_first, x[1], x[0]); };
    store_rows(first(t), first(p[0]), first(p[1]), first(p[2]), out.tp[0]);
    store_rows(t[1], p[0][1], p[1][1], p[2][1], out.tp[1]);
    store(out.bound[0], first(bound));
    store(out.bound[1], bound[1]);
    out.proven = unsigned(bits(proven));
    out.keep[0] = unsigned(bits(kept_root[0] | (kept_root[1] & !stop)));
    out.keep[1] = unsigned(bits(kept_root[0] & kept_root[1] & !stop));
}

// The hit test (Need::any) of one lane's line, as the scalar quick rung takes it
// (newton_rung.cpp: hit_test): the roots as estimated, in that order; the first proven inside
// the extent and the range is the hit; no hit needs both roots proven outside, or none real.
template <int SigmaZ, class L>
void hit_test_lanes(const LineFormT<L>& f, Mask<L> usable, Interval range,
                    CorrectBlock<lane_count<L>>& out) {
    Leading<L> A = leading<SigmaZ>(f);
    usable = usable & (A.e < fabs(A.A));
    Estimates<L> est = estimates<SigmaZ>(f, A);
    const L c[2] = {select(est.real, est.root[0], est.vertex), est.root[1]};
    Local<L> local[2] = {quick_local_at<SigmaZ>(f, c[0]), quick_local_at<SigmaZ>(f, c[1])};
    Mask<L> no_root = no_root_proven(A, c[0], local[0]);
    Enclosure<L> en[2] = {root_near(local[0], A, c[0]), root_near(local[1], A, c[1])};
    Mask<L> hit[2], outside_smaller = L(0.0) < L(0.0), outside_larger = outside_smaller;
    for (int j = 0; j < 2; ++j) {
        Kept<L> k = kept(f, range, en[j]);
        hit[j] = en[j].proven & k.inside;
        Mask<L> outside = en[j].proven & k.outside;
        outside_smaller = outside_smaller | (outside & en[j].smaller);
        outside_larger = outside_larger | (outside & (!en[j].smaller));
    }
    Mask<L> any_hit = hit[0] | hit[1];
    Mask<L> answered = any_hit | (outside_smaller & outside_larger);
    Mask<L> proven = usable & ((est.real & answered) | ((!est.real) & no_root));
    // t = c + x rounded once: within e + u |t| of the root (the sum's rounding).
    L t = select(hit[0], en[0].c + en[0].x, en[1].c + en[1].x);
    L e = select(hit[0], en[0].e, en[1].e);
    L bound = (e + L(u) * fabs(t)) * L(F::cover(8)) + L(F::denorm_min), zero(0.0);
    for (int j = 0; j < 2; ++j) { // the second slot unused, written all the same
        store_rows(t, zero, zero, zero, out.tp[j]);
        store(out.bound[j], bound);
    }
    out.proven = unsigned(bits(proven));
    out.keep[0] = unsigned(bits(est.real & any_hit));
    out.keep[1] = 0;
}

} // namespace newton

// Lines [i, i + lanes) of the arrays (x, y, z, vx, vy, vz) against the prepared shape: the lanes
// the Newton rung proves, as the scalar ladder would answer them.
template <class L, class S>
void correct_lanes(const Prepared<S>& shape, int orientation, const Real<L>* const soa[6],
                   std::size_t i, Interval range, Query q, CorrectBlock<lane_count<L>>& out) {
    using Traits = ShapeTraits<S>;
    auto src = source(shape);
    Vec3T<L> L0{load(soa[0] + i), load(soa[1] + i), load(soa[2] + i)};
    Vec3T<L> v{load(soa[3] + i), load(soa[4] + i), load(soa[5] + i)};
    // The scalar ladder's first step for a scene of moderate size (correct.hpp: moderate()).
    auto moderate = [](L x) { return (x >= L(0x1p-64)) & (x <= L(0x1p+64)); };
    L extent = maximum(max_abs(L0), L(src.magnitude()));
    auto usable = usual_line(L0, v) & moderate(extent) & moderate(max_abs(v));
    if (q.need == Need::any) { // the quick rung, on the quick line form
        LineFormT<L> f = Traits::template quick_line_form<L>(src, L0, v, orientation);
        return newton::with_sigma_z_of_lanes(f.sigma_z, [&](auto sigma_z) {
            newton::hit_test_lanes<decltype(sigma_z)::value>(f, usable, range, out);
        });
    }
    LineFormT<L> f = Traits::template line_form<L>(src, L0, v, orientation);
    newton::with_sigma_z_of_lanes(f.sigma_z, [&](auto sigma_z) {
        newton::solve_lanes<decltype(sigma_z)::value>(f, usable, L0, v, range, q, out);
    });
}

} // namespace linequad::detail
