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

#include <limits>

namespace linequad::detail {

namespace newton {

// The lanes of a closed shape's line form as scalar forms, lane by lane: the axial line and the
// discs' planes (with the extent, what the closure reads), the line itself, and g's leading
// coefficient. The closure's branches are per line; the lanes have proven the roots.
template <class L>
struct AxialLanes {
    static constexpr int N = lane_count<L>;
    double A[N], Z0[N], e_Z0[N], dZ[N], e_dZ[N], L0[3][N], v[3][N];
    double plane[6][N]; // the planes' Z0 and dZ: hi, lo, e
    LineForm form;      // the shape's part, set once; the line's set per lane by at()
    AxialLanes(const LineFormT<L>& f, const Leading<L>& lead, const Vec3T<L>& l0,
               const Vec3T<L>& dir) {
        store(A, lead.A), store(Z0, f.Z0), store(e_Z0, f.e_Z0), store(dZ, f.dZ);
        store(e_dZ, f.e_dZ);
        for (int a = 0; a < 3; ++a)
            store(L0[a], l0[a]), store(v[a], dir[a]);
        form.sigma_z = f.sigma_z;
        form.lo = f.lo, form.e_lo = f.e_lo, form.hi = f.hi, form.e_hi = f.e_hi;
        form.lo_bounded = f.lo_bounded, form.hi_bounded = f.hi_bounded;
        form.discs = f.discs;
        if (f.planes) {
            const DiscPlanesT<L>& p = *f.planes;
            const BoundedDDT<L>* z[2] = {&p.Z0, &p.dZ};
            for (int i = 0; i < 2; ++i)
                store(plane[3 * i], z[i]->hi), store(plane[3 * i + 1], z[i]->lo),
                    store(plane[3 * i + 2], z[i]->e);
            form.planes =
                DiscPlanes{{}, {}, p.lo, p.hi, p.at_lo, p.at_hi, p.axis, p.lo_at, p.hi_at};
        }
    }
    // Lane k's form.
    const LineForm& at(int k) {
        form.Z0 = Z0[k], form.e_Z0 = e_Z0[k], form.dZ = dZ[k], form.e_dZ = e_dZ[k];
        if (form.planes) {
            form.planes->Z0 = {plane[0][k], plane[1][k], plane[2][k]};
            form.planes->dZ = {plane[3][k], plane[4][k], plane[5][k]};
        }
        return form;
    }
    Line line(int k, Interval range) const {
        return {{L0[0][k], L0[1][k], L0[2][k]}, {v[0][k], v[1][k], v[2][k]}, range};
    }
};

// Lane k's enclosure of root j.
template <class L>
struct EnclosureLanes {
    static constexpr int N = lane_count<L>;
    double c[N], x[N], e[N];
    unsigned smaller, proven;
    explicit EnclosureLanes(const Enclosure<L>& en)
        : smaller(unsigned(bits(en.smaller))), proven(unsigned(bits(en.proven))) {
        store(c, en.c), store(x, en.x), store(e, en.e);
    }
    Enclosure<double> at(int k) const {
        return {c[k], x[k], e[k], bool((smaller >> k) & 1), bool((proven >> k) & 1)};
    }
};

// A closed shape's slots: every hit a lateral crossing until put_closed_result says otherwise.
template <int N>
void open_closed_slots(CorrectBlock<N>& out) {
    out.closed = true;
    for (int j = 0; j < 2; ++j)
        for (int k = 0; k < N; ++k)
            out.kind[j][k] = HitKind::cross, out.part[j][k] = Part::lateral;
}

// Lane k's result from the scalar closure into the block's slots, as mark_certain() makes it
// (a hit test's bound is its own).
template <int N>
void put_closed_result(const Result& r, int k, bool hit_test, CorrectBlock<N>& out) {
    out.proven |= 1u << k;
    out.keep[0] &= ~(1u << k), out.keep[1] &= ~(1u << k);
    for (int j = 0; j < r.count; ++j) {
        const Hit& h = r.hits[j];
        out.keep[j] |= 1u << k;
        out.tp[j][k][0] = h.t, out.tp[j][k][1] = h.p.x, out.tp[j][k][2] = h.p.y;
        out.tp[j][k][3] = h.p.z;
        out.bound[j][k] = hit_test ? h.bound : Binary64::half_ulp(h.t);
        out.kind[j][k] = h.kind, out.part[j][k] = h.part;
    }
}

// bounded_dd.hpp's a - b (as a + (-b)) and a / b in lanes, a the shape's: the same operations
// in the same order, each branch a select, so the same bits as the scalar rung's plane crossing.
template <class L>
LINEQUAD_INLINE BoundedDDT<L> difference_lanes(const BoundedDD& a, const BoundedDDT<L>& b) {
    const L zero(0.0), ahi(a.hi), alo(a.lo), ae(a.e), bhi = -b.hi, blo = -b.lo;
    TwoTermT<L> s = two_sum(ahi, bhi);
    Mask<L> exact = equal(alo, zero) & equal(blo, zero) & equal(ae, zero) & equal(b.e, zero);
    TwoTermT<L> t = two_sum(alo, blo);
    TwoTermT<L> v = fast_two_sum(s.hi, s.lo + t.hi);
    TwoTermT<L> z = fast_two_sum(v.hi, t.lo + v.lo);
    L e = (ae + b.e + L(4 * u * u) * fabs(z.hi)) * L(F::cover(8)) + L(F::underflow_floor);
    return {select(exact, s.hi, z.hi), select(exact, s.lo, z.lo), select(exact, zero, e)};
}
template <class L>
LINEQUAD_INLINE BoundedDDT<L> quotient_lanes(const BoundedDDT<L>& a, const BoundedDDT<L>& b) {
    const L zero(0.0), size = fabs(b.hi);
    // By a power of two 2^k, |k| < 1000 (moderate_power_of_two): exact, far from underflow.
    Mask<L> by_power = equal(a.e, zero) & equal(b.e, zero) & equal(b.lo, zero) &
                       is_power_of_two(b.hi) & (L(0x1p-999) <= size) & (size <= L(0x1p+999));
    L inv = L(1.0) / b.hi;
    Mask<L> far = (equal(a.hi, zero) | (L(0x1p-900) <= fabs(a.hi * inv))) &
                  (equal(a.lo, zero) | (L(0x1p-1000) <= fabs(a.lo * inv)));
    Mask<L> exact = by_power & far;
    L th = a.hi / b.hi;
    TwoTermT<L> r = two_prod(b.hi, th);
    L rl = fma(b.lo, th, r.lo);
    TwoTermT<L> rr = fast_two_sum(r.hi, rl);
    L d = (a.hi - rr.hi) + (a.lo - rr.lo);
    TwoTermT<L> z = fast_two_sum(th, d / b.hi);
    L gap = size * L(F::shrink(8)) - b.e;
    L q = fabs(z.hi) * L(F::cover(8));
    L e = (a.e + q * b.e) / gap + L(16 * u * u) * q;
    e = select(zero < gap, (e * L(F::cover(8))) * L(F::cover(8)) + L(F::underflow_floor),
               L(F::inf));
    return {select(exact, a.hi * inv, z.hi), select(exact, a.lo * inv, z.lo),
            select(exact, zero, e)};
}

// Where each lane's line crosses the plane Z = end (newton_rung.cpp's plane_crossing), and in
// which lanes that is finite.
template <class L>
struct CrossingLanes {
    Enclosure<L> t;
    Mask<L> finite;
};
template <class L>
LINEQUAD_INLINE CrossingLanes<L> plane_crossing_lanes(const DiscPlanesT<L>& p,
                                                      const BoundedDD& end) {
    BoundedDDT<L> t = quotient_lanes(difference_lanes(end, p.Z0), p.dZ);
    const L largest(std::numeric_limits<double>::max());
    Mask<L> finite = (fabs(t.hi) <= largest) & (fabs(t.e) <= largest);
    return {{t.hi, t.lo, t.e, finite, finite}, finite};
}

// Both roots of one lane's line, as the scalar rung adds them (the smaller first), or the
// proof that there is none. L0 and v: the lane's line as given.
//
// On a convex shape closed by discs with A > 0 the lanes close the line as closed_hits does: each
// root below, within or above the extent (side_of), the piece between them cut to the extent,
// each end of it a root within or the disc beyond which the root lies (its t the plane crossing,
// its coordinate across the plane the plane's own where the plane is perpendicular to an axis).
// The lanes with A < 0 (a line steeper than a cone's generators) are closed one by one by the
// scalar rung's closed_rung. Two solids: only the lanes that miss the quadric.
template <int SigmaZ, class L>
void solve_lanes(const LineFormT<L>& f, Mask<L> usable, const Vec3T<L>& L0, const Vec3T<L>& v,
                 Interval range, Query q, CorrectBlock<lane_count<L>>& out) {
    const L one(1.0), zero(0.0); // as given: t and the points need no scaling
    const Mask<L> none = zero < zero;
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
    Enclosure<L> root[2] = {root_near(local[0], A, c[0]), root_near(local[1], A, c[1])};
    Mask<L> both_proven =
        est.real & root[0].proven & root[0].smaller & root[1].proven & (!root[1].smaller);

    // Slot j's enclosure (a root, or a disc's crossing), what it is, and whether the extent is
    // already decided for it (a closed shape's: then only the range remains).
    Enclosure<L> at[2] = {root[0], root[1]};
    Mask<L> disc[2] = {none, none}, top[2] = {none, none};
    Mask<L> closed_ok = none, missed = none; // lanes the lanes close; lanes that miss the solid
    const bool convex = f.discs == Discs::convex;
    if (convex) {
        Mask<L> below[2], above[2], within[2];
        for (int j = 0; j < 2; ++j) {
            Axial<L> a = axial_at(f, root[j]);
            DifferenceTest<L> dlo = difference_test(a.z, a.e_z, L(f.lo), L(f.e_lo));
            DifferenceTest<L> dhi = difference_test(L(f.hi), L(f.e_hi), a.z, a.e_z);
            below[j] = dlo.d < -dlo.bound;
            above[j] = (!below[j]) & (dhi.d < -dhi.bound);
            within[j] = (dlo.bound < dlo.d) & (dhi.bound < dhi.d);
        }
        Mask<L> sides = (below[0] | above[0] | within[0]) & (below[1] | above[1] | within[1]);
        Mask<L> closing = both_proven & (zero < A.A) & sides;
        missed = closing & ((below[0] & below[1]) | (above[0] & above[1]));
        closed_ok = closing & (!missed);
        const DiscPlanesT<L>& p = *f.planes;
        CrossingLanes<L> cross[2] = {plane_crossing_lanes(p, p.lo), plane_crossing_lanes(p, p.hi)};
        for (int j = 0; j < 2; ++j) {
            disc[j] = !within[j], top[j] = above[j];
            Mask<L> uses_lo = closed_ok & below[j], uses_hi = closed_ok & above[j];
            if (!p.at_lo) closed_ok = closed_ok & (!uses_lo);
            if (!p.at_hi) closed_ok = closed_ok & (!uses_hi);
            closed_ok = closed_ok & ((!uses_lo) | cross[0].finite) & ((!uses_hi) | cross[1].finite);
            auto pick = [&](L Enclosure<L>::*part) {
                return select(below[j], cross[0].t.*part,
                              select(above[j], cross[1].t.*part, root[j].*part));
            };
            at[j].c = pick(&Enclosure<L>::c), at[j].x = pick(&Enclosure<L>::x);
            at[j].e = pick(&Enclosure<L>::e);
        }
    }

    Mask<L> failed[2], kept_root[2];
    L t[2], bound[2], p[3][2]; // p[a][j]: coordinate a of slot j's point
    for (int j = 0; j < 2; ++j) {
        auto range_only = [&] { // a closed shape's extent is decided above
            EnclosedT<L> tj = t_of(at[j]);
            return Kept<L>().range(range, tj.t, tj.e_t);
        };
        Kept<L> k = convex ? range_only() : kept(f, range, at[j]);
        Rounded<L> rt = rounded_t(at[j], one);
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
            Rounded<L> pr = rounded_point(at[j], pa, va, one);
            Mask<L> along = equal(va, zero); // L0_k + t v_k is L0_k: +0 for a zero
            L value = select(along, pa + zero, pr.value);
            Mask<L> exact = along;
            if (convex && a == f.planes->axis) { // a disc's point: the plane's coordinate, +0
                L plane = select(top[j], L(f.planes->hi_at), L(f.planes->lo_at)) + zero;
                value = select(disc[j], plane, value);
                exact = exact | disc[j];
            }
            hit_proven = hit_proven & (exact | pr.proven);
            p[a][j] = value;
        }
        Mask<L> which = j == 0 ? root[j].smaller : !root[j].smaller; // the root the rung expects
        Mask<L> decided = k.inside | k.outside;
        failed[j] = (!root[j].proven) | (!which) | (!decided) | (k.inside & (!hit_proven));
        kept_root[j] = est.real & k.inside & (!missed);
    }
    // The nearest hit stops at the first slot when it is kept: the second is then never looked
    // at.
    Mask<L> stop = q.need == Need::all ? none : kept_root[0];
    Mask<L> roots_proven = (!failed[0]) & (stop | (!failed[1]));
    Mask<L> answered = est.real & roots_proven; // from the roots alone, or closed in the lanes
    if (convex) answered = missed | (closed_ok & roots_proven);
    if (f.discs == Discs::two_solids) answered = none;
    Mask<L> proven = usable & (answered | ((!est.real) & no_root));
    // The first slot takes the smaller root where it is kept, else the larger.
    Mask<L> larger_first = !kept_root[0];
    auto first = [&](const L(&x)[2]) { return select(larger_first, x[1], x[0]); };
    store_rows(first(t), first(p[0]), first(p[1]), first(p[2]), out.tp[0]);
    store_rows(t[1], p[0][1], p[1][1], p[2][1], out.tp[1]);
    store(out.bound[0], first(bound));
    store(out.bound[1], bound[1]);
    out.closed = false;
    out.proven = unsigned(bits(proven));
    out.keep[0] = unsigned(bits(kept_root[0] | (kept_root[1] & !stop)));
    out.keep[1] = unsigned(bits(kept_root[0] & kept_root[1] & !stop));
    if (!convex) return;
    // Each slot's part; the lanes with A < 0, one by one.
    constexpr int N = lane_count<L>;
    out.closed = true;
    unsigned is_disc[2] = {unsigned(bits(disc[0])), unsigned(bits(disc[1]))};
    unsigned is_top[2] = {unsigned(bits(top[0])), unsigned(bits(top[1]))};
    unsigned firsts = unsigned(bits(larger_first));
    for (int k = 0; k < N; ++k)
        for (int j = 0; j < 2; ++j) {
            int slot = j == 0 && ((firsts >> k) & 1) ? 1 : j; // as the rows were stored
            bool d = (is_disc[slot] >> k) & 1, up = (is_top[slot] >> k) & 1;
            out.kind[j][k] = HitKind::cross;
            out.part[j][k] = !d ? Part::lateral : up ? Part::top : Part::base;
        }
    unsigned rest = unsigned(bits(usable & both_proven & (!(zero < A.A))));
    if (rest == 0) return;
    AxialLanes<L> axial(f, A, L0, v);
    EnclosureLanes<L> lanes[2] = {EnclosureLanes<L>(root[0]), EnclosureLanes<L>(root[1])};
    for (int k = 0; k < N; ++k) {
        if (!((rest >> k) & 1)) continue;
        const Enclosure<double> lane[2] = {lanes[0].at(k), lanes[1].at(k)};
        Line l = axial.line(k, range);
        Result r;
        if (closed_rung(axial.at(k), axial.A[k], lane, Unit{1, 1, l}, l, q, r))
            put_closed_result(r, k, false, out);
    }
}

// The hit test (Need::any) of one lane's line, as the scalar quick rung takes it
// (newton_rung.cpp: hit_test): the roots as estimated, in that order; the first proven inside
// the extent and the range is the hit; no hit needs both roots proven outside, or none real.
template <int SigmaZ, class L>
void hit_test_lanes(const LineFormT<L>& f, Mask<L> usable, const Vec3T<L>& L0, const Vec3T<L>& v,
                    Interval range, CorrectBlock<lane_count<L>>& out) {
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
    // On a closed shape, no hit needs closed_hit_test (both roots outside is not enough).
    if (f.discs != Discs::none) answered = any_hit;
    Mask<L> proven = usable & ((est.real & answered) | ((!est.real) & no_root));
    // t = c + x rounded once: within e + u |t| of the root (the sum's rounding).
    L t = select(hit[0], en[0].c + en[0].x, en[1].c + en[1].x);
    L e = select(hit[0], en[0].e, en[1].e);
    L bound = (e + L(u) * fabs(t)) * L(F::cover(8)) + L(F::denorm_min), zero(0.0);
    for (int j = 0; j < 2; ++j) { // the second slot unused, written all the same
        store_rows(t, zero, zero, zero, out.tp[j]);
        store(out.bound[j], bound);
    }
    out.closed = false;
    out.proven = unsigned(bits(proven));
    out.keep[0] = unsigned(bits(est.real & any_hit));
    out.keep[1] = 0;
    if (f.discs == Discs::none) return;
    // The lanes with real roots and no hit proven: closed_hit_test, lane by lane.
    unsigned rest = unsigned(bits(usable & est.real & (!any_hit)));
    if (rest == 0) return;
    constexpr int N = lane_count<L>;
    open_closed_slots(out); // the lanes' own hits: lateral crossings
    AxialLanes<L> axial(f, A, L0, v);
    EnclosureLanes<L> root[2] = {EnclosureLanes<L>(en[0]), EnclosureLanes<L>(en[1])};
    unsigned outside = unsigned(bits(outside_smaller & outside_larger));
    for (int k = 0; k < N; ++k) {
        if (!((rest >> k) & 1)) continue;
        const Enclosure<double> lane[2] = {root[0].at(k), root[1].at(k)};
        Line l = axial.line(k, range);
        Result r;
        if (!closed_hit_test(axial.at(k), axial.A[k], lane, (outside >> k) & 1, Unit{1, 1, l}, r))
            continue;
        put_closed_result(r, k, true, out);
    }
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
            newton::hit_test_lanes<decltype(sigma_z)::value>(f, usable, L0, v, range, out);
        });
    }
    LineFormT<L> f = Traits::template line_form<L>(src, L0, v, orientation);
    newton::with_sigma_z_of_lanes(f.sigma_z, [&](auto sigma_z) {
        newton::solve_lanes<decltype(sigma_z)::value>(f, usable, L0, v, range, q, out);
    });
}

} // namespace linequad::detail
