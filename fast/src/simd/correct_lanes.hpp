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
#include "numeric/bounded_dd_lanes.hpp"
#include "simd/batch_kernels.hpp"
#include "simd/lanes.hpp"

#include <limits>
#include <type_traits>

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

// A closed shape's slots: every hit a lateral crossing until put_hit_test says otherwise.
template <int N>
void open_closed_slots(CorrectBlock<N>& out) {
    out.closed = true;
    for (int j = 0; j < 2; ++j)
        for (int k = 0; k < N; ++k)
            out.kind[j][k] = HitKind::cross, out.part[j][k] = Part::lateral;
}

// Lane k's hit test from the scalar closure into the block's slots (its bound its own).
template <int N>
void put_hit_test(const Result& r, int k, CorrectBlock<N>& out) {
    out.proven |= 1u << k;
    out.keep[0] &= ~(1u << k), out.keep[1] &= ~(1u << k);
    for (int j = 0; j < r.count; ++j) {
        const Hit& h = r.hits[j];
        out.keep[j] |= 1u << k;
        out.tp[j][k][0] = h.t, out.tp[j][k][1] = h.p.x, out.tp[j][k][2] = h.p.y;
        out.tp[j][k][3] = h.p.z;
        out.bound[j][k] = h.bound;
        out.kind[j][k] = h.kind, out.part[j][k] = h.part;
    }
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
    // end - Z0 as bounded_dd.hpp's a - b, a + (-b).
    BoundedDDT<L> t =
        quotient_lanes(sum_lanes(lanes_of<L>(end), {-p.Z0.hi, -p.Z0.lo, p.Z0.e}), p.dZ);
    const L largest(std::numeric_limits<double>::max());
    Mask<L> finite = (fabs(t.hi) <= largest) & (fabs(t.e) <= largest);
    return {{t.hi, t.lo, t.e, finite, finite}, finite};
}

// Slot j's t (with mark_certain's bound) and point, rounded from the root's enclosure on the line
// as given (scale 1); a coordinate along which the line does not move is L0's (+0 for a zero), and
// `fixed(a, value, exact)`, unless it is nullptr, may set coordinate a and the lanes where it is
// exact (a disc's plane). The mask of lanes where every rounding is proven.
template <class L, class Fixed>
LINEQUAD_INLINE Mask<L> round_slot(const Enclosure<L>& en, const Vec3T<L>& L0, const Vec3T<L>& v,
                                   bool points, int j, L (&t)[2], L (&bound)[2], L (&p)[3][2],
                                   Fixed fixed) {
    const L zero(0.0), one(1.0);
    Rounded<L> rt = rounded_t(en, one);
    Mask<L> proven = rt.proven;
    t[j] = rt.value;
    bound[j] = half_ulp(rt.value);
#pragma GCC unroll 3
    for (int a = 0; a < 3; ++a) {
        if (!points) {
            p[a][j] = zero;
            continue;
        }
        Rounded<L> pr = rounded_point(en, L0[a], v[a], one);
        Mask<L> along = equal(v[a], zero); // L0_k + t v_k is L0_k: +0 for a zero
        L value = select(along, L0[a] + zero, pr.value);
        Mask<L> exact = along;
        if constexpr (!std::is_null_pointer_v<Fixed>) fixed(a, value, exact);
        proven = proven & (exact | pr.proven);
        p[a][j] = value;
    }
    return proven;
}

// The block's two slots from the roots' values (t, point, bound of root 0 and root 1): the first
// slot takes the smaller root where it is kept, else the larger; the second the larger where both
// are kept and the lane's search does not `stop` at the first (the nearest hit).
template <class L>
LINEQUAD_INLINE void store_slots(const L (&t)[2], const L (&p)[3][2], const L (&bound)[2],
                                 const Mask<L> (&kept_root)[2], Mask<L> stop, Mask<L> proven,
                                 CorrectBlock<lane_count<L>>& out) {
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
}

// Both roots of one lane's line, as the scalar rung adds them (the smaller first), or the
// proof that there is none. L0 and v: the lane's line as given.
//
// On a convex shape closed by discs the lanes close the line as closed_hits does, its branches
// as masks: each root below, within or above the extent (side_of), the piece of the line inside
// the quadric cut to the extent, each end of it a root within or a disc (its t the plane
// crossing, its coordinate across the plane the plane's own where the plane is perpendicular to
// an axis). Two solids: only the lanes that miss the quadric.
template <int SigmaZ, bool Convex, class L>
void solve_lanes(const LineFormT<L>& f, Mask<L> usable, const Vec3T<L>& L0, const Vec3T<L>& v,
                 Interval range, Query q, CorrectBlock<lane_count<L>>& out) {
    constexpr bool convex = Convex; // closed by discs around one solid: compiled apart
    const L one(1.0), zero(0.0);    // as given: t and the points need no scaling
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

    // A closed shape's slot j: its enclosure (a root, or a disc's crossing) and what it is; the
    // extent is then decided, and only the range remains. An open shape's slot j is root j.
    [[maybe_unused]] Enclosure<L> root[2], at[2];
    Mask<L> disc[2] = {none, none}, top[2] = {none, none};
    Mask<L> closed_ok = none, missed = none; // lanes the lanes close; lanes that miss the solid
    if constexpr (convex) {
        for (int j = 0; j < 2; ++j)
            at[j] = root[j] = root_near(local[j], A, c[j]);
        // Each root below, within or above the extent (side_of), and for a cone which side of
        // the apex it lies on (root_on_nappe): the solid's nappe is Z <= 0 for the cone, R >= 0
        // (the fourth term's sign) for the frustum.
        Mask<L> below[2], above[2], within[2], on_solid[2], off_solid[2];
        for (int j = 0; j < 2; ++j) {
            Axial<L> a = axial_at(f, root[j]);
            DifferenceTest<L> dlo = difference_test(a.z, a.e_z, L(f.lo), L(f.e_lo));
            DifferenceTest<L> dhi = difference_test(L(f.hi), L(f.e_hi), a.z, a.e_z);
            below[j] = dlo.d < -dlo.bound;
            above[j] = (!below[j]) & (dhi.d < -dhi.bound);
            within[j] = (dlo.bound < dlo.d) & (dhi.bound < dhi.d);
            if constexpr (SigmaZ == four_terms) {
                const FourthTerm<L>& R = *f.fourth;
                a = linear_at(R.U0.hi, bound_of_hi(R.U0), R.U1.hi, bound_of_hi(R.U1), root[j]);
                on_solid[j] = a.e_z < a.z, off_solid[j] = a.z < -a.e_z;
            } else {
                on_solid[j] = a.z < -a.e_z, off_solid[j] = a.e_z < a.z;
            }
        }
        Mask<L> sides = (below[0] | above[0] | within[0]) & (below[1] | above[1] | within[1]);
        Mask<L> both_proven =
            est.real & root[0].proven & root[0].smaller & root[1].proven & (!root[1].smaller);
        Mask<L> closing = both_proven & sides;
        // A > 0: the piece between the roots.
        Mask<L> pos = closing & (zero < A.A);
        Mask<L> pos_missed = pos & ((below[0] & below[1]) | (above[0] & above[1]));
        // A < 0 (a cone's steep line): the ray from the root on the solid's nappe (Z <= 0), i, away
        // from the other root, running towards `away` along Z; from root i to the disc there when
        // root i is within the extent, across both discs (first, then last in t) when it is on
        // the other side, no hit when it is on that side already.
        Mask<L> i0 = on_solid[0] & off_solid[1], i1 = off_solid[0] & on_solid[1];
        if constexpr (SigmaZ == four_terms) {
            // Where the bounds tell neither root's side, R's rate along the line (its proven
            // sign) does, as in root_on_nappe.
            const BoundedDDT<L>& rate = f.fourth->U1;
            Mask<L> by_rate = (!(i0 | i1)) & (bound_of_hi(rate) < fabs(rate.hi));
            i1 = i1 | (by_rate & (zero < rate.hi));
            i0 = i0 | (by_rate & (!(zero < rate.hi)));
        }
        Mask<L> neg = none;
        if constexpr (SigmaZ == -1 || SigmaZ == four_terms)
            neg = closing & (A.A < zero) & (i0 | i1) & (f.e_dZ < fabs(f.dZ));
        Mask<L> rising = zero < f.dZ;
        Mask<L> away_above = (rising & i1) | ((!rising) & i0), away_below = !away_above;
        Mask<L> b_i = (i0 & below[0]) | (i1 & below[1]), a_i = (i0 & above[0]) | (i1 & above[1]);
        Mask<L> w_i = (i0 & within[0]) | (i1 & within[1]);
        Mask<L> neg_missed = neg & ((b_i & away_below) | (a_i & away_above));
        Mask<L> across = neg & (!w_i) & (!neg_missed), from_root = neg & w_i;
        missed = pos_missed | neg_missed;
        Mask<L> use_lo[2] = {(pos & below[0]) | (from_root & i0 & away_below) | (across & rising),
                             (pos & below[1]) | (from_root & i1 & away_below) |
                                 (across & (!rising))};
        Mask<L> use_hi[2] = {(pos & above[0]) | (from_root & i0 & away_above) |
                                 (across & (!rising)),
                             (pos & above[1]) | (from_root & i1 & away_above) | (across & rising)};
        Mask<L> use_root1[2] = {from_root & i1, pos & within[1]}; // else root 0
        closed_ok = (pos | neg) & (!missed);
        const DiscPlanesT<L>& p = *f.planes;
        CrossingLanes<L> cross[2] = {plane_crossing_lanes(p, p.lo), plane_crossing_lanes(p, p.hi)};
        for (int j = 0; j < 2; ++j) {
            disc[j] = use_lo[j] | use_hi[j], top[j] = use_hi[j];
            if (!p.at_lo) closed_ok = closed_ok & (!use_lo[j]);
            if (!p.at_hi) closed_ok = closed_ok & (!use_hi[j]);
            closed_ok =
                closed_ok & ((!use_lo[j]) | cross[0].finite) & ((!use_hi[j]) | cross[1].finite);
            auto pick = [&](L Enclosure<L>::*part) {
                L r = select(use_root1[j], root[1].*part, root[0].*part);
                return select(use_lo[j], cross[0].t.*part, select(use_hi[j], cross[1].t.*part, r));
            };
            at[j].c = pick(&Enclosure<L>::c), at[j].x = pick(&Enclosure<L>::x);
            at[j].e = pick(&Enclosure<L>::e);
        }
    }

    Mask<L> failed[2], kept_root[2];
    L t[2], bound[2], p[3][2]; // p[a][j]: coordinate a of slot j's point
    for (int j = 0; j < 2; ++j) {
        Enclosure<L> en; // slot j's enclosure
        Kept<L> k;
        if constexpr (convex) {
            en = at[j];
            EnclosedT<L> tj = t_of(en);
            k = Kept<L>().range(range, tj.t, tj.e_t);
        } else {
            en = root_near(local[j], A, c[j]);
            k = kept(f, range, en);
        }
        Mask<L> hit_proven;
        if constexpr (convex) {
            auto on_disc = [&](int a, L& value, Mask<L>& exact) {
                if (a == f.planes->axis) { // a disc's point: the plane's coordinate, +0
                    L plane = select(top[j], L(f.planes->hi_at), L(f.planes->lo_at)) + zero;
                    value = select(disc[j], plane, value);
                    exact = exact | disc[j];
                }
            };
            hit_proven = round_slot(en, L0, v, q.points, j, t, bound, p, on_disc);
        } else {
            hit_proven = round_slot(en, L0, v, q.points, j, t, bound, p, nullptr);
        }
        const Enclosure<L>& r = convex ? root[j] : en;   // root j
        Mask<L> which = j == 0 ? r.smaller : !r.smaller; // the root the rung expects
        Mask<L> decided = k.inside | k.outside;
        failed[j] = (!r.proven) | (!which) | (!decided) | (k.inside & (!hit_proven));
        kept_root[j] = est.real & k.inside;
        if constexpr (convex) kept_root[j] = kept_root[j] & (!missed);
    }
    // The nearest hit stops at the first slot when it is kept: the second is then never looked
    // at.
    Mask<L> stop = q.need == Need::all ? none : kept_root[0];
    Mask<L> roots_proven = (!failed[0]) & (stop | (!failed[1]));
    Mask<L> answered = est.real & roots_proven; // from the roots alone, or closed in the lanes
    if constexpr (convex)
        answered = missed | (closed_ok & roots_proven);
    else if (f.discs == Discs::two_solids)
        answered = none;
    Mask<L> proven = usable & (answered | ((!est.real) & no_root));
    store_slots(t, p, bound, kept_root, stop, proven, out);
    if constexpr (!convex) return;
    // Each slot's part.
    constexpr int N = lane_count<L>;
    out.closed = true;
    unsigned is_disc[2] = {unsigned(bits(disc[0])), unsigned(bits(disc[1]))};
    unsigned is_top[2] = {unsigned(bits(top[0])), unsigned(bits(top[1]))};
    unsigned firsts = unsigned(bits(!kept_root[0])); // the larger root in the first slot
    for (int k = 0; k < N; ++k)
        for (int j = 0; j < 2; ++j) {
            int slot = j == 0 && ((firsts >> k) & 1) ? 1 : j; // as the rows were stored
            bool d = (is_disc[slot] >> k) & 1, up = (is_top[slot] >> k) & 1;
            out.kind[j][k] = HitKind::cross;
            out.part[j][k] = !d ? Part::lateral : up ? Part::top : Part::base;
        }
}

// A closed shape's hit test in the lanes `rest` (real roots, no hit proven): closed_hit_test,
// one lane at a time; `outside`: the lanes with both roots proven outside. Out of line, so that
// the lanes' own path keeps its registers.
template <class L>
[[gnu::noinline]] void close_hit_test_lanes(const LineFormT<L>& f, const Leading<L>& A,
                                            const Enclosure<L> (&en)[2], unsigned rest,
                                            unsigned outside, const Vec3T<L>& L0, const Vec3T<L>& v,
                                            Interval range, CorrectBlock<lane_count<L>>& out) {
    constexpr int N = lane_count<L>;
    open_closed_slots(out); // the lanes' own hits: lateral crossings
    AxialLanes<L> axial(f, A, L0, v);
    EnclosureLanes<L> root[2] = {EnclosureLanes<L>(en[0]), EnclosureLanes<L>(en[1])};
    for (int k = 0; k < N; ++k) {
        if (!((rest >> k) & 1)) continue;
        const Enclosure<double> lane[2] = {root[0].at(k), root[1].at(k)};
        Line l = axial.line(k, range);
        Result r;
        if (closed_hit_test(axial.at(k), axial.A[k], lane, (outside >> k) & 1, Unit{1, 1, l}, r))
            put_hit_test(r, k, out);
    }
}

// The hit test (Need::any) of one lane's line, as the scalar quick rung takes it
// (newton_rung.cpp: hit_test): the roots as estimated, in that order; the first proven inside
// the extent and the range is the hit; no hit needs both roots proven outside, or none real.
template <int SigmaZ, bool Closed, class L>
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
    if constexpr (Closed) answered = any_hit;
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
    if constexpr (!Closed) return;
    // The lanes with real roots and no hit proven: closed_hit_test, lane by lane.
    unsigned rest = unsigned(bits(usable & est.real & (!any_hit)));
    if (rest != 0)
        close_hit_test_lanes(f, A, en, rest, unsigned(bits(outside_smaller & outside_larger)), L0,
                             v, range, out);
}

// A plane's or a quadric's Newton rung (surface_newton_rung, newton_rung.cpp) on a lane of
// lines: the surface's own local quadratic (QuadricNewtonFormT in lanes) at each root's estimate,
// the enclosures, the range and the roundings, every step as the scalar rung takes it. A lane
// answers exactly where the scalar rung proves its line from its enclosures (a miss proven at the
// vertex, or every root it needs proven, placed against the range and rounded); the rest go back
// to the ladder, whose rung may still round a value from the exact form.
template <class L>
void surface_lanes(const QuadricCoefficients<double>& coefficients, Mask<L> usable,
                   const Vec3T<L>& L0, const Vec3T<L>& v, Interval range, Query q,
                   CorrectBlock<lane_count<L>>& out) {
    if (q.need == Need::any) q.points = false; // a hit test computes no point (correct.hpp)
    const L zero(0.0), one(1.0);
    const Mask<L> none = zero < zero, all = zero <= zero;
    QuadricNewtonFormT<L> f(coefficients, L0, v);
    const bool linear = f.linear(); // one root, A = 0 exactly
    Leading<L> A = f.leading();
    if (!linear) usable = usable & (A.e < fabs(A.A));
    auto est = f.estimates(A);
    // Slot 0 at the smaller root's estimate, or at the vertex where there is no real pair: there
    // no_root_proven() looks, as the scalar rung does.
    L c[2] = {linear ? est.root[0] : select(est.real, est.root[0], est.vertex), est.root[1]};
    Local<L> local[2];
    local[0] = f.local_at(c[0]);
    Mask<L> no_root = none;
    if (!linear) {
        local[1] = f.local_at(c[1]);
        no_root = (!est.real) & no_root_proven(A, est.vertex, local[0]);
    }
    Mask<L> failed[2] = {all, all}, kept_root[2] = {none, none};
    L t[2] = {zero, zero}, bound[2] = {zero, zero}, p[3][2] = {};
    for (int j = 0; j < (linear ? 1 : 2); ++j) {
        // The enclosure about x0, or where it is wider than 2^-88 of t the one about x0 phi(y)
        // where that one is narrower, as the scalar rung chooses.
        Enclosure<L> en = root_near(local[j], A, c[j]);
        Enclosure<L> tight = root_near_tight(local[j], A, c[j]);
        Mask<L> wide = !(en.e <= L(0x1p-88) * fabs(en.c));
        Mask<L> narrower = en.proven & wide & tight.proven & (tight.e < en.e);
        en.c = select(narrower, tight.c, en.c), en.x = select(narrower, tight.x, en.x);
        en.e = select(narrower, tight.e, en.e);
        Mask<L> which = linear ? all : j == 0 ? en.smaller : !en.smaller;
        EnclosedT<L> tj = t_of(en);
        Kept<L> k = Kept<L>().range(range, tj.t, tj.e_t);
        Mask<L> hit_proven = round_slot(en, L0, v, q.points, j, t, bound, p, nullptr);
        Mask<L> decided = k.inside | k.outside;
        failed[j] = (!en.proven) | (!which) | (!decided) | (k.inside & (!hit_proven));
        kept_root[j] = est.real & k.inside;
    }
    // The nearest hit stops at the first slot when it is kept: the second is then never looked
    // at; a plane has no second.
    Mask<L> stop = linear ? all : q.need == Need::all ? none : kept_root[0];
    Mask<L> roots_proven = (!failed[0]) & (stop | (!failed[1]));
    Mask<L> proven = usable & ((est.real & roots_proven) | no_root);
    store_slots(t, p, bound, kept_root, stop, proven, out);
}

} // namespace newton

// Lines [i, i + lanes) of the arrays (x, y, z, vx, vy, vz) against the prepared shape: the lanes
// the Newton rung proves, as the scalar ladder would answer them.
template <class L, class S>
void correct_lanes(const Prepared<S>& shape, int orientation, const Real<L>* const soa[6],
                   std::size_t i, Interval range, Query q, CorrectBlock<lane_count<L>>& out) {
    using Traits = ShapeTraits<S>;
    constexpr bool fourth_term = std::is_same_v<S, Frustum>; // the frustum's four-term form
    auto src = source(shape);
    Vec3T<L> L0{load(soa[0] + i), load(soa[1] + i), load(soa[2] + i)};
    Vec3T<L> v{load(soa[3] + i), load(soa[4] + i), load(soa[5] + i)};
    // The scalar ladder's first step for a scene of moderate size (correct.hpp: moderate()).
    auto moderate = [](L x) { return (x >= L(0x1p-64)) & (x <= L(0x1p+64)); };
    L extent = maximum(max_abs(L0), L(src.magnitude()));
    auto usable = usual_line(L0, v) & moderate(extent) & moderate(max_abs(v));
    if constexpr (has_newton_form<S>) { // a plane or a quadric: its own local quadratic
        if (src.shape.coincident) usable = usable & (!usable); // the ladder's exact form
        return newton::surface_lanes<L>(Traits::coefficients(src.shape), usable, L0, v, range, q,
                                        out);
    } else {
        if (q.need == Need::any) { // the quick rung, on the quick line form
            LineFormT<L> f = Traits::template quick_line_form<L>(src, L0, v, orientation);
            return newton::with_sigma_z_of_lanes<fourth_term>(f.sigma_z, [&](auto sigma_z) {
                constexpr int sz = decltype(sigma_z)::value;
                if (f.discs == Discs::none)
                    newton::hit_test_lanes<sz, false>(f, usable, L0, v, range, out);
                else
                    newton::hit_test_lanes<sz, true>(f, usable, L0, v, range, out);
            });
        }
        LineFormT<L> f = Traits::template line_form<L>(src, L0, v, orientation);
        newton::with_sigma_z_of_lanes<fourth_term>(f.sigma_z, [&](auto sigma_z) {
            constexpr int sz = decltype(sigma_z)::value;
            if (f.discs == Discs::convex)
                newton::solve_lanes<sz, true>(f, usable, L0, v, range, q, out);
            else
                newton::solve_lanes<sz, false>(f, usable, L0, v, range, q, out);
        });
    }
}

} // namespace linequad::detail
