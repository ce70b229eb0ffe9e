// The Newton rung of the correct solver (see newton_rung.hpp for the method). Every bound is
// rigorous at any size of the scene (underflow enters as an absolute floor; overflow makes a bound
// infinite, which proves nothing), and every decision is taken only when a bound proves it.
#include "correct/newton_rung.hpp"

#include "correct/newton_steps.hpp"
#include "shapes/quadric.hpp"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <optional>
#include <type_traits>
#include <utility>

namespace linequad::detail {

namespace {

using namespace newton;

template <int SigmaZ>
Local<double> local_at(const LineForm& f, double c) {
    const double at[1] = {c};
    Local<double> out[1];
    newton::local_at<SigmaZ>(f, at, out);
    return out[0];
}

// The enclosure of the root next to c, when the local quadratic proves one: about x0 (the first
// try, the lanes' too), or about x0 phi(y) (narrower, for the scalar ladder's further tries).
LINEQUAD_INLINE std::optional<Enclosure<double>> root_near(const Local<double>& L,
                                                           const Leading<double>& A, double c) {
    Enclosure<double> en = newton::root_near(L, A, c);
    if (!en.proven) return std::nullopt;
    return en;
}
LINEQUAD_INLINE std::optional<Enclosure<double>>
root_near_tight(const Local<double>& L, const Leading<double>& A, double c) {
    Enclosure<double> en = newton::root_near_tight(L, A, c);
    if (!en.proven) return std::nullopt;
    return en;
}

// No real root, near the vertex c; local_at: the precise expansion or the hit test's quick one.
template <class LocalAt>
bool no_root_proven(const Leading<double>& A, double c, LocalAt local_at) {
    if (!std::isfinite(c)) return false;
    return newton::no_root_proven(A, c, local_at(c));
}

// 1: the root is inside the extent and the range; 0: outside; -1: the bounds cannot tell.
LINEQUAD_INLINE int kept(const LineForm& f, const Unit& unit, const Enclosure<double>& en) {
    Kept<double> k = newton::kept(f, unit.line.range, en);
    return k.outside ? 0 : k.inside ? 1 : -1;
}
// The range's test alone (a disc's crossing, a root already placed against the extent).
LINEQUAD_INLINE Kept<double> in_range(const Unit& unit, const Enclosure<double>& en) {
    auto [t, e_t] = t_of(en);
    return Kept<double>().range(unit.line.range, t, e_t);
}
// The same for tighter()'s enclosures, which may be one of the range's ends exactly (a root
// there, root_from_exact_form's point): in the range, which is closed, where no bound decides it.
LINEQUAD_INLINE bool at_range_end(const Unit& unit, const Enclosure<double>& en) {
    return en.e == 0 && en.x == 0 && (en.c == unit.line.range.t0 || en.c == unit.line.range.t1);
}
LINEQUAD_INLINE int kept_tighter(const LineForm& f, const Unit& unit, const Enclosure<double>& en) {
    if (!at_range_end(unit, en)) return kept(f, unit, en);
    Kept<double> k = newton::kept(f, Range::line, en);
    return k.outside ? 0 : k.inside ? 1 : -1;
}
LINEQUAD_INLINE Kept<double> in_range_tighter(const Unit& unit, const Enclosure<double>& en) {
    return at_range_end(unit, en) ? Kept<double>() : in_range(unit, en);
}

// Root `smaller` (or the larger one) next to c from g's local quadratic q at c: c itself where G is
// exactly 0 there, else the rung's proof at c on q.
LINEQUAD_INLINE std::optional<Enclosure<double>> root_from_local(const ExactLocal& q, double c,
                                                                 bool smaller) {
    if (!(std::fabs(q.A.A) > q.A.e)) return std::nullopt;
    if (q.at.G == 0 && q.at.e_G == 0) { // c is a root exactly (a line starting on the surface)
        // The smaller root where g falls through 0 (G' A < 0), a simple one where G' != 0.
        if (!(std::fabs(q.at.Gp) > q.at.e_Gp) || ((q.at.Gp < 0) == (q.A.A > 0)) != smaller)
            return std::nullopt;
        return Enclosure<double>{c, 0, 0, smaller, true};
    }
    Enclosure<double> en = newton::root_near_tight(q.at, q.A, c);
    if (!en.proven || en.smaller != smaller) return std::nullopt;
    return en;
}
// Root `smaller` (or the larger one) next to c, where the rung's bounds, absolute, are wide
// beside it or beside a coordinate of its point: the same proof at c (a double next to the root)
// on the exact form's local quadratic there (`ends`), whose G is enclosed relatively. Rare, so
// out of line.
[[gnu::noinline]] std::optional<Enclosure<double>> root_from_exact_form(const ExtentEnds& ends,
                                                                        double t_factor, double c,
                                                                        bool smaller,
                                                                        bool* cheaper) {
    // The shape's cheaper local quadratic first (where `cheaper` is set, and left set where it
    // answered), where it has one; where that proves nothing, the exact form's.
    if (cheaper && *cheaper)
        if (std::optional<ExactLocal> q = ends.local_at(c, t_factor, false))
            if (std::optional<Enclosure<double>> en = root_from_local(*q, c, smaller)) return en;
    if (cheaper) *cheaper = false;
    std::optional<ExactLocal> q = ends.local_at(c, t_factor, true);
    return q ? root_from_local(*q, c, smaller) : std::nullopt;
}

// A disc's crossing from the exact form, where the rung's cannot decide or round it (a line
// starting a few ulps from the disc's plane, whose Z0 - end the rung bounds absolutely; dZ's sign
// unproven). Rare, so out of line.
[[gnu::noinline]] std::optional<Enclosure<double>> exact_crossing(const ExtentEnds& ends, bool low,
                                                                  const Unit& unit) {
    std::optional<BoundedDD> exact = ends.crossing(!low, unit.t_factor);
    if (!exact) return std::nullopt;
    return Enclosure<double>{exact->hi, exact->lo, exact->e, true, true};
}

// A coordinate of the hit point known exactly (a disc's plane perpendicular to its axis), or none;
// and the end whose plane's crossing the hit is, exactly (0 the base's, 1 the top's: a disc's
// point, or a root at a rim), or -1. There each coordinate is rational, and where its enclosure
// from t cannot round it (a coordinate a few ulps from zero, or zero), the exact form's can.
struct ExactCoordinate {
    int axis = -1;
    double value = 0;
    int end = -1;
};

// Where x's bound leaves its rounding to Target open because a rounding boundary lies inside it
// (a value at, or a few ulps beside, the midpoint of two Target values): that boundary, near +
// half, between the Target values near and near + 2 half. None where the bound is wide enough
// to hold another boundary too (a quarter of the cell), or near is not a normal Target value.
struct RoundingBoundary {
    double near, half;
};
template <class Target>
std::optional<RoundingBoundary> boundary_within(const BoundedDD& x) {
    double near, beside;
    if constexpr (std::is_same_v<Target, Binary32>) {
        float f = float(x.hi + x.lo);
        near = f;
        if (!(std::fabs(near) >= 0x1p-126 && std::fabs(near) <= 0x1p+127)) return std::nullopt;
        double r = (x.hi - near) + x.lo; // x.hi - near exact: near is within a float's ulp
        if (r == 0) return std::nullopt;
        beside = std::nextafter(f, r > 0 ? INFINITY : -INFINITY);
    } else {
        near = x.hi + x.lo;
        if (!(std::fabs(near) >= 0x1p-960 && std::fabs(near) <= 0x1p+1000)) return std::nullopt;
        double r = (x.hi - near) + x.lo;
        if (r == 0) return std::nullopt;
        beside = std::nextafter(near, r > 0 ? INFINITY : -INFINITY);
    }
    double half = (beside - near) / 2; // exact: adjacent values, far from the subnormals
    double r = (x.hi - near) + x.lo;
    // The value lies within x.e (and r's rounding) of near + r: on this side of the boundary
    // behind near (at least half / 2 away, at a power of two) and short of the one past beside.
    if (!((x.e + F::u * std::fabs(r)) * F::cover(8) < std::fabs(half) / 2)) return std::nullopt;
    return RoundingBoundary{near, half};
}
LINEQUAD_INLINE bool even(double value, Binary64) {
    std::uint64_t bits;
    std::memcpy(&bits, &value, sizeof bits);
    return (bits & 1) == 0;
}
LINEQUAD_INLINE bool even(double value, Binary32) {
    float f = float(value);
    std::uint32_t bits;
    std::memcpy(&bits, &f, sizeof bits);
    return (bits & 1) == 0;
}
// x rounded to Target, where its bound proves it, else by the exact sign of the value against
// the one rounding boundary inside that bound (`against(near, half)`: sgn(value - near - half)):
// beyond it, the Target value past it; short of it, near; on it, the even one.
template <class Target, class Against>
std::optional<double> round_exactly(const BoundedDD& x, Against against) {
    if (std::optional<double> r = round_proven<Target>(x, 1.0)) return r;
    std::optional<RoundingBoundary> b = boundary_within<Target>(x);
    if (!b) return std::nullopt;
    std::optional<int> s = against(b->near, b->half);
    if (!s) return std::nullopt;
    double beside = b->near + 2 * b->half; // exact
    if (*s != 0) return (*s > 0) == (b->half > 0) ? beside : b->near;
    return even(b->near, Target{}) ? b->near : beside;
}

// Coordinate k of the point where the line crosses an end's plane, from the exact form, rounded
// to Target. Rare, so out of line.
template <class Target>
[[gnu::noinline]] std::optional<double> coordinate_at_end(const ExtentEnds& ends, bool top, int k) {
    std::optional<BoundedDD> p = ends.coordinate_at_end(top, k);
    if (!p) return std::nullopt;
    return round_exactly<Target>(*p, [&](double near, double half) {
        return ends.coordinate_at_end_against(top, k, near, half);
    });
}

// (c1 + x1) - (c2 + x2), two values' high and low parts (enclosures' centres): d within `bound`
// of it. c1 - c2 exactly; the two roundings left are each within u of their results (two
// denorm_min for underflow), so the bound is relative to the difference rather than to the
// values: two values an ulp apart are told apart.
struct Difference {
    double d, bound;
};
LINEQUAD_INLINE Difference difference_of(double c1, double x1, double c2, double x2) {
    TwoTerm a = two_sum(c1, -c2);
    double b = x1 - x2, s = a.lo + b, d = a.hi + s;
    return {d, 2 * u * (std::fabs(b) + std::fabs(s) + std::fabs(d)) + 2 * F::denorm_min};
}

// Coordinate k of a lateral root's point where its bound cannot round it: 0 exactly when the line
// crosses that coordinate plane at this root, at t* = -L0_k / v_k: t* inside the root's enclosure
// (which holds one root), and a root (`ends`, exactly). Rare, so out of line.
[[gnu::noinline]] bool zero_coordinate(const Enclosure<double>& en, const Unit& unit, int k,
                                       const ExtentEnds& ends) {
    BoundedDD t = BoundedDD(-unit.line.L0[k]) / BoundedDD(unit.line.v[k]);
    Difference off = difference_of(t.hi, t.lo, en.c, en.x); // t* - (c + x)
    return (std::fabs(off.d) + off.bound + t.e) * F::cover(2) < en.e && ends.zero_at_root(k);
}

// Coordinate k of a lateral root's point where its bound cannot round it and it is not zero (a
// rim point moved a few ulps off a coordinate plane): one of the two roots of its own quadratic
// (ExtentEnds::coordinate_roots), each enclosed relative to itself. This root's coordinate is
// one of them; the other is the one its enclosure, L0_k + t v_k within e, excludes. Rare, so out
// of line.
template <class Target>
[[gnu::noinline]] std::optional<double>
coordinate_at_root(const Enclosure<double>& en, const Unit& unit, int k, const ExtentEnds& ends) {
    std::optional<std::array<BoundedDD, 2>> P = ends.coordinate_roots(k);
    if (!P) return std::nullopt;
    double t = en.c + en.x, v = unit.line.v[k], p = std::fma(t, v, unit.line.L0[k]);
    double e = (std::fabs(v) * (en.e + u * std::fabs(t)) + u * std::fabs(p)) * F::cover(8) +
               F::underflow_floor;
    p *= unit.pos_factor; // the caller's units: a power of two, so within a denormal
    e = e * unit.pos_factor * F::cover(2) + 2 * F::denorm_min;
    // |P - p| >= |P.hi - p| - |P.lo| - P.e - e, and the difference is rounded once.
    auto excluded = [&](const BoundedDD& root) {
        return std::fabs(root.hi - p) * (1 - 2 * u) >
               (std::fabs(root.lo) + root.e + e) * F::cover(2);
    };
    bool out0 = excluded((*P)[0]), out1 = excluded((*P)[1]);
    if (out0 == out1) return std::nullopt;
    const BoundedDD &ours = (*P)[out0 ? 1 : 0], &other = (*P)[out0 ? 0 : 1];
    return round_exactly<Target>(ours, [&](double near, double half) -> std::optional<int> {
        // The other root's side of the boundary: P' - m = (P'.hi - near - half) + P'.lo, three
        // roundings, and P'.e.
        double a = other.hi - near, b = a - half, d = b + other.lo;
        double bound = other.e + u * (std::fabs(a) + std::fabs(b) + std::fabs(d));
        if (!(std::fabs(d) > bound * F::cover(4))) return std::nullopt;
        return ends.coordinate_root_against(k, d > 0 ? -1 : 1, near, half);
    });
}

// t of a lateral root where its bound leaves the rounding open because a rounding boundary m lies
// inside it (a tie, or a few ulps beside one): t - m has the sign of -g(m) g'(m), exactly, where
// no vertex lies between m and the root: g' at m of its sign at a simple root (-A's at the
// smaller, A's at the larger; B's where A = 0). At a double root it holds as well. Rare, so out of
// line.
template <class Target>
[[gnu::noinline]] std::optional<double> t_at_boundary(const Enclosure<double>& en, const Unit& unit,
                                                      const ExtentEnds& ends) {
    double f = unit.t_factor; // a power of two: exact, but for a part that underflows
    TwoTerm c = two_sum(en.c * f, en.x * f);
    BoundedDD t{c.hi, c.lo, en.e * f + 2 * F::denorm_min};
    if (!std::isfinite(t.hi) || !std::isfinite(t.e)) return std::nullopt;
    return round_exactly<Target>(t, [&](double near, double half) -> std::optional<int> {
        SignsAt at = ends.signs_at(near, half);
        if (at.g == 0) return 0;
        if (at.A != 0 && at.slope != (en.smaller ? -at.A : at.A)) return std::nullopt;
        return -at.g * at.slope;
    });
}

// A coordinate its bound leaves unrounded, from the exact form: at an end's crossing, or a
// lateral root's zero; with `dear`, a lateral root's beside zero or at a tie too.
template <class Target>
std::optional<double> exact_coordinate(const Enclosure<double>& en, Part part, const Unit& unit,
                                       int k, ExactCoordinate exact, const ExtentEnds& ends,
                                       bool dear) {
    if (exact.end >= 0) return coordinate_at_end<Target>(ends, exact.end == 1, k);
    if (part != Part::lateral) return std::nullopt;
    if (zero_coordinate(en, unit, k, ends)) return 0.0;
    if (!dear) return std::nullopt;
    return coordinate_at_root<Target>(en, unit, k, ends);
}

// The hit, t and its point correctly rounded to Target in the caller's units; false when a bound
// does not prove a rounding.
// `ends`: where a coordinate is not proven, that coordinate from the exact form where it can
// give it (add_tighter_hit's); `dear`: and t or a coordinate from the exact form's roots, at or
// beside a tie or a coordinate plane, which cost more than a tighter enclosure.
template <class Target>
LINEQUAD_INLINE bool add_rounded_hit(const Enclosure<double>& en, Part part, const Unit& unit,
                                     const Line& caller, Query q, Result& r, ExactCoordinate exact,
                                     const ExtentEnds* ends = nullptr, bool dear = false) {
    if constexpr (std::is_same_v<Target, Binary32>) {
        // A float's rounding cell is 2^29 times a double's: t = c + x and each coordinate
        // fma(t, v_k, L0_k) in double, each with one rounding added to its bound, nearly always
        // prove it.
        double t = en.c + en.x, e_t = en.e + u * std::fabs(t);
        std::optional<double> rounded =
            round_proven<Target>({t, 0, e_t * F::cover(4) + F::denorm_min}, unit.t_factor);
        if (!rounded && dear && part == Part::lateral)
            rounded = t_at_boundary<Target>(en, unit, *ends);
        if (!rounded) return false;
        Hit& h = r.hits[r.count];
        h.t = *rounded, h.kind = HitKind::cross, h.part = part, h.p = {};
        if (q.points) {
            double p[3];
#pragma GCC unroll 3
            for (int k = 0; k < 3; ++k) {
                if (k == exact.axis) { // one rounding of the exact value, +0 for a zero
                    p[k] = double(float(exact.value)) + 0.0;
                    continue;
                }
                if (caller.v[k] == 0) { // an exact zero is +0, as the oracle's
                    p[k] = caller.L0[k] + 0.0;
                    continue;
                }
                double v = unit.line.v[k], pk = std::fma(t, v, unit.line.L0[k]);
                double e =
                    (std::fabs(v) * e_t + u * std::fabs(pk)) * F::cover(8) + F::underflow_floor;
                std::optional<double> rk = round_proven<Target>({pk, 0, e}, unit.pos_factor);
                if (!rk && ends)
                    rk = exact_coordinate<Target>(en, part, unit, k, exact, *ends, dear);
                if (!rk) return false;
                p[k] = *rk;
            }
            h.p = {p[0], p[1], p[2]};
        }
        ++r.count;
        return true;
    } else {
        Rounded<double> t = rounded_t(en, unit.t_factor);
        if (!t.proven) {
            std::optional<double> at = dear && part == Part::lateral
                                           ? t_at_boundary<Target>(en, unit, *ends)
                                           : std::nullopt;
            if (!at) return false;
            t.value = *at;
        }
        Hit& h = r.hits[r.count];
        h.t = t.value;
        h.kind = HitKind::cross;
        h.part = part;
        h.p = {};
        if (q.points) {
            double p[3];
#pragma GCC unroll 3
            for (int k = 0; k < 3; ++k) {
                if (k == exact.axis) { // exact: +0 for a zero, as the oracle's
                    p[k] = exact.value + 0.0;
                    continue;
                }
                // L0_k + t v_k is L0_k exactly when v_k = 0 (an exact zero is +0, as the oracle's).
                if (caller.v[k] == 0) {
                    p[k] = caller.L0[k] + 0.0;
                    continue;
                }
                Rounded<double> pk =
                    rounded_point(en, unit.line.L0[k], unit.line.v[k], unit.pos_factor);
                if (!pk.proven) {
                    std::optional<double> pe;
                    if (ends) pe = exact_coordinate<Target>(en, part, unit, k, exact, *ends, dear);
                    if (!pe) return false;
                    pk.value = *pe;
                }
                p[k] = pk.value;
            }
            h.p = {p[0], p[1], p[2]};
        }
        ++r.count;
        return true;
    }
}

// Where the rung's bounds, absolute, leave a value a few ulps from zero undecided or unrounded
// (t or a coordinate: a line starting beside the surface or a disc's plane, a hit beside a
// coordinate plane): the hit's enclosure once more from the exact form (`ends`), a lateral
// root's from its local quadratic, a disc's crossing exactly; no value where it is not narrower.
// `cheaper` set: a lateral root's from the shape's cheaper local quadratic where it has one, and
// left set where that answered; its wider bounds may still leave the value open, and the caller
// then asks again with it cleared.
LINEQUAD_INLINE std::optional<Enclosure<double>> tighter(const Enclosure<double>& en, Part part,
                                                         const Unit& unit, const ExtentEnds& ends,
                                                         bool* cheaper = nullptr) {
    std::optional<Enclosure<double>> t;
    if (part == Part::lateral) {
        // About the range's end where the root lies beside it, or the line's origin (a line
        // starting on the surface, whatever its range): there the local quadratic shows a root
        // exactly at that point, which no enclosure about another point can.
        auto [at, e_at] = t_of(en);
        double c = at;
        for (double end : {unit.line.range.t0, unit.line.range.t1, 0.0})
            if (std::isfinite(end) && std::fabs(at - end) <= 2 * e_at) c = end;
        t = root_from_exact_form(ends, unit.t_factor, c, en.smaller, cheaper);
    } else {
        t = exact_crossing(ends, part == Part::base, unit);
    }
    if (!t || !(t->e < en.e)) return std::nullopt;
    return t;
}

// tighter() from the shape's cheaper local quadratic first, and where its enclosure does not
// `settle` the value (its wider bounds leave it open), from the exact form's; the last enclosure
// found, or none.
template <class Settles>
LINEQUAD_INLINE std::optional<Enclosure<double>>
tighter_until(const Enclosure<double>& en, Part part, const Unit& unit, const ExtentEnds& ends,
              Settles settles) {
    bool cheaper = true;
    std::optional<Enclosure<double>> t = tighter(en, part, unit, ends, &cheaper);
    if (!t || settles(*t) || !cheaper) return t;
    std::optional<Enclosure<double>> exactly = tighter(*t, part, unit, ends);
    if (!exactly) return t;
    settles(*exactly);
    return exactly;
}

// The same, and where a bound does not prove a rounding: with the coordinates the exact form gives
// (exact_coordinate: a coordinate at or beside zero is what fails most often), then once more
// from a tighter enclosure, and last with what the exact form's roots give (a t or a coordinate
// at or beside a tie, a coordinate beside a plane): dearer than the tighter enclosure, which
// settles most (a line from far away). Only that case out of line.
template <class Target>
[[gnu::noinline]] bool add_tighter_hit(const Enclosure<double>& en, Part part, const Unit& unit,
                                       const Line& caller, Query q, Result& r,
                                       ExactCoordinate exact, const ExtentEnds& ends) {
    if (add_rounded_hit<Target>(en, part, unit, caller, q, r, exact, &ends)) return true;
    bool added = false;
    std::optional<Enclosure<double>> t =
        tighter_until(en, part, unit, ends, [&](const Enclosure<double>& narrower) {
            return added =
                       add_rounded_hit<Target>(narrower, part, unit, caller, q, r, exact, &ends);
        });
    if (added) return true;
    return (t && add_rounded_hit<Target>(*t, part, unit, caller, q, r, exact, &ends, true)) ||
           add_rounded_hit<Target>(en, part, unit, caller, q, r, exact, &ends, true);
}
template <class Target>
LINEQUAD_INLINE bool add_hit(const Enclosure<double>& en, Part part, const Unit& unit,
                             const Line& caller, Query q, Result& r, ExactCoordinate exact = {},
                             const ExtentEnds* ends = nullptr) {
    return add_rounded_hit<Target>(en, part, unit, caller, q, r, exact) ||
           (ends && add_tighter_hit<Target>(en, part, unit, caller, q, r, exact, *ends));
}

// ---- Shapes closed by discs ----

// Where a lateral root lies against the extent: strictly below, within or above it; next to one
// end, where its enclosure cannot tell (near_lo, near_hi); exactly at an end (a rim), which only
// the exact signs of `ends` show; or unknown.
enum class Side { below, at_lo, within, at_hi, above, near_lo, near_hi, unknown };
struct Placement {
    Side side = Side::unknown;
    Enclosure<double> t_end{}; // at_lo, at_hi: the end's crossing, which is the root
    bool open = false;         // and another part owns that end
};

// The crossing t_E of the end root i's bounds leave open, placed against root i by the sign of
// q(t_E): t_E between the roots, beyond root i, or root i itself. That needs t_E proven on root
// i's side of the other root (the roots are proven apart, t_E within a few ulps of root i).
LINEQUAD_INLINE Placement placed_at_end(const std::optional<Enclosure<double>> (&root)[2], int i,
                                        bool top, const ExtentEnds& ends, const Unit& unit) {
    std::optional<EndCrossing> c = ends.at(top, unit.t_factor);
    if (!c || c->dZ_sign == 0 || c->A_sign == 0) return {};
    Enclosure<double> end{c->t.hi, c->t.lo, c->t.e, true, true};
    EnclosedT<double> at_end = t_of(end), other = t_of(*root[1 - i]);
    DifferenceTest<double> apart = i == 0
                                       ? difference_test(other.t, other.e_t, at_end.t, at_end.e_t)
                                       : difference_test(at_end.t, at_end.e_t, other.t, other.e_t);
    if (!(apart.d > apart.bound)) return {};
    // sgn(t_i - t_E), then sgn(Z(t_i) - end) = sgn(dZ) sgn(t_i - t_E).
    bool between = c->q_sign != c->A_sign;
    int after = c->q_sign == 0 ? 0 : (between ? -1 : 1) * (i == 0 ? 1 : -1);
    int z = c->dZ_sign * after;
    if (!top) return {z < 0 ? Side::below : z == 0 ? Side::at_lo : Side::within, end, c->open};
    return {z > 0 ? Side::above : z == 0 ? Side::at_hi : Side::within, end, c->open};
}

// Where the line crosses the disc's plane Z = end: t = (end - Z0) / dZ, rational, in
// double-double; none when dZ's sign is not proven.
LINEQUAD_INLINE std::optional<Enclosure<double>> plane_crossing(const DiscPlanes& p,
                                                                const BoundedDD& end) {
    BoundedDD t = (end - p.Z0) / p.dZ;
    if (!std::isfinite(t.hi) || !std::isfinite(t.e)) return std::nullopt;
    return Enclosure<double>{t.hi, t.lo, t.e, true, true};
}

// A root next to an end, against that end's crossing, both enclosed to about 2^-100 (the ends'
// planes are exact in double-double): a root a few ulps from a rim or a seam. Where the
// enclosures meet (a root at the rim), unknown.
LINEQUAD_INLINE Side beside_plane(const DiscPlanes& p, const Enclosure<double>& root, bool top) {
    if (!(std::fabs(p.dZ.hi) > p.dZ.e)) return Side::unknown;
    std::optional<Enclosure<double>> end = plane_crossing(p, top ? p.hi : p.lo);
    if (!end) return Side::unknown;
    // root - end, bounded relative to itself: a root an ulp of t from the end is placed.
    Difference off = difference_of(root.c, root.x, end->c, end->x);
    double d = off.d;
    if (!(std::fabs(d) > off.bound + root.e + end->e)) return Side::unknown;
    bool later = d > 0, rising = p.dZ.hi > 0; // Z(root) > end iff later == rising
    if (!top) return later == rising ? Side::within : Side::below;
    return later == rising ? Side::above : Side::within;
}

// Where root i lies against the extent (a closed shape's is bounded at both ends; an open one's
// where lo_bounded, hi_bounded say), as its enclosure shows it: next to one end, that end; next
// to both (a tiny extent), unknown.
LINEQUAD_INLINE Side side_of(const LineForm& f, const Enclosure<double>& en) {
    bool closed = f.discs != Discs::none;
    Axial<double> a = axial_at(f, en);
    DifferenceTest<double> lo = difference_test(a.z, a.e_z, f.lo, f.e_lo);
    DifferenceTest<double> hi = difference_test(f.hi, f.e_hi, a.z, a.e_z);
    bool has_lo = closed || f.lo_bounded, has_hi = closed || f.hi_bounded;
    if (has_lo && lo.d < -lo.bound) return Side::below;
    if (has_hi && hi.d < -hi.bound) return Side::above;
    bool lo_clear = !has_lo || lo.bound < lo.d, hi_clear = !has_hi || hi.bound < hi.d;
    if (lo_clear == hi_clear) return lo_clear ? Side::within : Side::unknown;
    return lo_clear ? Side::near_hi : Side::near_lo;
}

// A root next to an end against that end's plane: a closed shape's disc plane, from its form;
// an open shape's end, from `ends`.
LINEQUAD_INLINE Side beside_end(const LineForm& f, const Enclosure<double>& root, bool top,
                                const ExtentEnds& ends, const Unit& unit) {
    const DiscPlanes* planes = f.planes ? &*f.planes : ends.end_planes(unit);
    return planes ? beside_plane(*planes, root, top) : Side::unknown;
}
// Root i, which its enclosure leaves next to one end (`near`: side_of's near_lo or near_hi; the
// scalar ladder's question, the batch lanes hand such a line to it): against that end's crossing
// in double-double, then from the exact signs of `ends`. Rare, so out of line.
[[gnu::noinline]] Placement place_at_end(const LineForm& f,
                                         const std::optional<Enclosure<double>> (&root)[2], int i,
                                         Side near, const ExtentEnds& ends, const Unit& unit) {
    bool top = near == Side::near_hi;
    if (Side s = beside_end(f, *root[i], top, ends, unit); s != Side::unknown) return {s};
    return placed_at_end(root, i, top, ends, unit);
}
LINEQUAD_INLINE bool near_end(Side s) {
    return s == Side::near_lo || s == Side::near_hi;
}

// For A < 0 (a line steeper than a cone's generators, one root on each nappe): the root on the
// solid's nappe, 0 or 1, or -1 where the bounds cannot tell. The cone's nappe is Z <= 0 (the other
// root above the apex, Z > 0); the frustum's is R >= 0, the sign of its fourth term. Where both
// roots lie too near the apex for their signs (a line along the axis, beside the apex), the order
// tells: the roots are apart, on opposite nappes, and Z (R) is linear in t, so the root with the
// smaller Z (the larger R) is the solid's, as the rate's proven sign shows.
LINEQUAD_INLINE int root_on_nappe(const LineForm& f,
                                  const std::optional<Enclosure<double>> (&root)[2]) {
    auto side_of_nappe = [&](const Enclosure<double>& en) { // 1: on the solid's, -1: the other
        Axial<double> a = f.sigma_z == four_terms
                              ? linear_at(f.fourth->U0.hi, bound_of_hi(f.fourth->U0),
                                          f.fourth->U1.hi, bound_of_hi(f.fourth->U1), en)
                              : axial_at(f, en);
        int sign = a.z > a.e_z ? 1 : a.z < -a.e_z ? -1 : 0;
        return f.sigma_z == four_terms ? sign : -sign;
    };
    if (f.sigma_z != -1 && f.sigma_z != four_terms) return -1;
    int s0 = side_of_nappe(*root[0]), s1 = side_of_nappe(*root[1]);
    if (s0 == 1 && s1 == -1) return 0;
    if (s0 == -1 && s1 == 1) return 1;
    if (f.sigma_z == four_terms) {
        const BoundedDD& rate = f.fourth->U1;
        if (!(std::fabs(rate.hi) > bound_of_hi(rate))) return -1;
        return rate.hi > 0 ? 1 : 0;
    }
    if (!(std::fabs(f.dZ) > f.e_dZ)) return -1;
    return f.dZ > 0 ? 0 : 1;
}

// A convex solid closed by discs (a cylinder, a frustum, one nappe), the lateral roots t0 < t1
// proven. The line is inside the quadric on (t0, t1) when A > 0, and on the rays before t0 and
// after t1 when A < 0 (a line steeper than a cone's generators: one ray in each nappe). The solid
// meets it there, cut to the extent (Z is linear in t): each end of that piece is a lateral root
// strictly between the extent's ends, or a disc crossed strictly inside it (the quadric's inside
// at the disc's plane is the disc); a piece beyond one end: no hit. Every hit crosses.
// Two solids (a closed two-nappe cone, each nappe a convex solid): with A > 0 the piece lies in
// one nappe (g < 0 between the roots never reaches the apex) and is found as above over both
// nappes' extent; with A < 0 each ray is one solid's piece, and both count. A side the
// bounds leave open, a disc the form has not (the quick form, the cone's apex end), a rounding not
// proven: the next rungs.
// A root exactly at an end (A > 0) is where the piece meets that end's disc at its rim: the disc
// is that end of the piece (a rim belongs to its disc), and a piece that touches the extent only
// there is one point, a rim the line grazes (tangent).
// piece_hits: the hits from where the roots lie, side[i] for root i (at a rim where rim[i] is
// at_lo or at_hi); `between`: the line is inside the quadric between the roots (A > 0), else
// outside. closed_hits: where each root lies, then piece_hits.
template <class Target>
LINEQUAD_INLINE bool
piece_hits(const LineForm& f, bool between, const std::optional<Enclosure<double>> (&root)[2],
           const Side (&side)[2], const Side (&rim)[2], const Unit& unit, const Line& caller,
           Query query, Result& r, const ExtentEnds* ends) {
    bool at_rim = rim[0] != side[0] || rim[1] != side[1];
    Enclosure<double> at[4]; // four on two solids
    Part part[4];
    ExactCoordinate exact[4];
    // End k of the segment (0: entry, 1: exit; 2 and 3 a second solid's): root i, or the disc
    // beyond which it lies.
    auto end_at = [&](int k, int i, Side s) LINEQUAD_INLINE_LAMBDA {
        if (s == Side::within) {
            at[k] = *root[i], part[k] = Part::lateral;
            return true;
        }
        bool low = s == Side::below;
        if (!f.planes || !(low ? f.planes->at_lo : f.planes->at_hi)) return false;
        std::optional<Enclosure<double>> t =
            plane_crossing(*f.planes, low ? f.planes->lo : f.planes->hi);
        if (!t && ends) t = exact_crossing(*ends, low, unit); // dZ's sign unproven
        if (!t) return false;
        at[k] = *t, part[k] = low ? Part::base : Part::top;
        // In the caller's units (a scaled scene's planes are not): the plane's coordinate.
        if (f.planes->axis >= 0 && unit.pos_factor == 1)
            exact[k] = {f.planes->axis, low ? f.planes->lo_at : f.planes->hi_at};
        exact[k].end = low ? 0 : 1;
        return true;
    };
    int points = 2; // the piece's ends; one where it is a grazed rim
    if (between) {
        if (side[0] == side[1] && side[0] != Side::within) {
            if (!at_rim) return true;
            int i = rim[0] != side[0] ? 0 : 1; // the root at the rim
            if (!end_at(0, i, side[i])) return false;
            points = 1;
        } else if (!end_at(0, 0, side[0]) || !end_at(1, 1, side[1])) {
            return false;
        }
    } else if (f.discs == Discs::two_solids) {
        // One ray in each nappe (distinct roots are never the apex, where g has a double root),
        // each the segment of that nappe's solid: from its root away from the other root, Z
        // running to that nappe's disc (`away`), or nothing where the root lies beyond it. Root
        // 0's ray comes first in t.
        if (at_rim || !(std::fabs(f.dZ) > f.e_dZ)) return false;
        points = 0;
        for (int i = 0; i < 2; ++i) {
            Side away = (f.dZ > 0) == (i == 1) ? Side::above : Side::below;
            if (side[i] == away) continue;
            if (side[i] != Side::within) return false;
            int root_end = i == 0 ? 1 : 0;
            if (!end_at(points + root_end, i, Side::within) ||
                !end_at(points + 1 - root_end, i, away))
                return false;
            points += 2;
        }
    } else {
        if (at_rim) return false;
        // The solid's nappe holds root i and the ray from it away from the other root: before t0
        // (i = 0) or after t1. Along that ray Z runs to one side (`away`, from dZ's sign); the
        // ray meets the extent from root i to the end on that side, or across both ends, or not.
        int i = root_on_nappe(f, root);
        if (i < 0 || !(std::fabs(f.dZ) > f.e_dZ)) return false;
        Side away = (f.dZ > 0) == (i == 1) ? Side::above : Side::below;
        Side first = f.dZ > 0 ? Side::below : Side::above; // the end crossed first in t
        Side last = first == Side::below ? Side::above : Side::below;
        if (side[i] == Side::within) {
            int root_end = i == 0 ? 1 : 0;
            if (!end_at(root_end, i, Side::within) || !end_at(1 - root_end, i, away)) return false;
        } else {
            if (side[i] == away) return true; // the ray runs away from the extent
            if (!end_at(0, i, first) || !end_at(1, i, last)) return false;
        }
    }
    for (int i = 0; i < points; ++i) {
        Kept<double> k = in_range(unit, at[i]);
        if (!k.outside && !k.inside && ends) // t a few ulps from the range's end, 0 most often
            if (std::optional<Enclosure<double>> narrower =
                    tighter_until(at[i], part[i], unit, *ends, [&](const Enclosure<double>& t) {
                        k = in_range_tighter(unit, t);
                        return k.outside || k.inside;
                    }))
                at[i] = *narrower;
        if (k.outside) continue;
        if (!k.inside || !add_hit<Target>(at[i], part[i], unit, caller, query, r, exact[i], ends))
            return false;
        if (query.need != Need::all) break;
    }
    if (points == 1 && r.count == 1) r.hits[0].kind = HitKind::tangent; // a grazed rim
    return true;
}

// t rounded to Target in the caller's units, where its enclosure proves the rounding (add_hit's).
template <class Target>
std::optional<double> rounded_t_to(const Enclosure<double>& en, const Unit& unit) {
    if constexpr (std::is_same_v<Target, Binary32>) {
        double t = en.c + en.x, e_t = en.e + u * std::fabs(t);
        return round_proven<Target>({t, 0, e_t * F::cover(4) + F::denorm_min}, unit.t_factor);
    } else {
        Rounded<double> t = rounded_t(en, unit.t_factor);
        if (!t.proven) return std::nullopt;
        return t.value;
    }
}

// A line in a disc's plane (dZ = 0 and Z0 at that end, exactly, which only `ends` proves) with
// both lateral roots proven and A > 0: the chord between them is the disc's, and the line lies
// on the shape there. The answer is that chord cut to the range, each end the root or the
// range's end beyond it, or nothing where they cross (the exact form's in_disc_plane).
template <class Target>
bool chord_in_disc(const Leading<double>& A, const std::optional<Enclosure<double>> (&root)[2],
                   Part disc, const Unit& unit, const Line& caller, Result& r) {
    if (!(A.A > A.e)) return false;
    const Interval& range = unit.line.range; // in the rung's units; its ends exact
    EnclosedT<double> t[2] = {t_of(*root[0]), t_of(*root[1])};
    // sgn(root i - x) for an exact x, or 0 where the bounds cannot tell.
    auto against = [&](int i, double x) {
        DifferenceTest<double> d = difference_test(t[i].t, t[i].e_t, x, 0.0);
        return d.d > d.bound ? 1 : d.d < -d.bound ? -1 : 0;
    };
    bool from_root = true, to_root = true; // the chord's ends: roots, or the range's
    if (range.has_t0()) {
        int s = against(0, range.t0);
        if (s == 0) return false;
        from_root = s > 0;
    }
    if (range.has_t1()) {
        int s = against(1, range.t1);
        if (s == 0) return false;
        to_root = s < 0;
    }
    // The chord's first end after its last: a chord the range misses.
    int order = from_root && to_root ? -1 // the roots, proven apart
                : from_root          ? against(0, range.t1)
                : to_root            ? -against(1, range.t0)
                                     : -1; // the range's ends, t0 <= t1
    if (order == 0) return false;
    r = Result();
    if (order > 0) return true;
    // A range's end is Target's own value (a float solver refuses others): it is the answer.
    std::optional<double> s0 = from_root ? rounded_t_to<Target>(*root[0], unit) : caller.range.t0;
    std::optional<double> s1 = to_root ? rounded_t_to<Target>(*root[1], unit) : caller.range.t1;
    if (!s0 || !s1) return false;
    r.on_surface = true;
    r.surface_part = disc;
    r.s0 = *s0, r.s1 = *s1;
    return true;
}

// Z constant along the line (dZ = 0 exactly, which only `ends` proves) at Z0's level (`level`,
// ExtentEnds::constant_z's): in a disc's plane, its chord; elsewhere both roots lie on Z0's side
// of the extent. Rare, so out of line.
template <class Target>
[[gnu::noinline]] bool constant_z_hits(const LineForm& f, const Leading<double>& A,
                                       const std::optional<Enclosure<double>> (&root)[2],
                                       const Unit& unit, const Line& caller, Query query, Result& r,
                                       const ExtentEnds& ends, int level) {
    if (level == -1 || level == 1)
        return chord_in_disc<Target>(A, root, level < 0 ? Part::base : Part::top, unit, caller, r);
    Side s = level < 0 ? Side::below : level == 0 ? Side::within : Side::above;
    const Side side[2] = {s, s};
    return piece_hits<Target>(f, A.A > 0, root, side, side, unit, caller, query, r, &ends);
}

template <class Target>
bool closed_hits(const LineForm& f, const Leading<double>& A,
                 const std::optional<Enclosure<double>> (&root)[2], const Unit& unit,
                 const Line& caller, Query query, Result& r, const ExtentEnds* ends) {
    // Where dZ is not proven nonzero, Z may be constant along the line (dZ = 0 exactly): then no
    // crossing of an end places a root next to it, and Z0's level, which a few exact products
    // show, places both (in a disc's plane, the line lies on the disc). Asked once, before any
    // end's crossing.
    bool flat = !(std::fabs(f.dZ) > f.e_dZ), level_asked = false;
    auto at_constant_z = [&]() -> std::optional<bool> {
        if (!ends || !flat || level_asked) return std::nullopt;
        level_asked = true;
        std::optional<int> level = ends->constant_z();
        if (!level) return std::nullopt;
        return constant_z_hits<Target>(f, A, root, unit, caller, query, r, *ends, *level);
    };
    Side side[2], rim[2];
    for (int i = 0; i < 2; ++i) {
        rim[i] = side_of(f, *root[i]);
        if (near_end(rim[i]) || rim[i] == Side::unknown)
            if (std::optional<bool> answered = at_constant_z()) return *answered;
        if (near_end(rim[i]))
            rim[i] = ends ? place_at_end(f, root, i, rim[i], *ends, unit).side : Side::unknown;
        side[i] = rim[i] == Side::at_lo   ? Side::below
                  : rim[i] == Side::at_hi ? Side::above
                                          : rim[i];
        if (side[i] == Side::unknown) return false;
    }
    return piece_hits<Target>(f, A.A > 0, root, side, rim, unit, caller, query, r, ends);
}

// g linear along the line (A = 0 exactly, B != 0: a line parallel to a cone's generator, off
// the cone): it crosses the quadric once, at t* = -C0 / 2B, rational. An open shape meets the
// line there alone, where that point lies inside the extent and the range. A closed one meets
// the piece inside the quadric, the ray from t* on which g < 0: within one nappe (g < 0 never
// reaches the apex), it runs away from it, so the piece from t* to beyond the extent's end it
// runs toward, cut to the extent as two roots' piece is. t* next to an end: the next rungs.
template <class Target>
bool linear_root_hit(const LineForm& f, const Unit& unit, const Line& caller, Query query,
                     Result& r, const ExtentEnds& ends) {
    std::optional<LinearRoot> root = ends.linear_root(unit.t_factor);
    if (!root) return false;
    Enclosure<double> en{root->t.hi, root->t.lo, root->t.e, true, true};
    r = Result();
    if (f.discs == Discs::none) {
        int inside = kept(f, unit, en);
        if (inside < 0) return false;
        return inside == 0 || add_hit<Target>(en, Part::lateral, unit, caller, query, r, {}, &ends);
    }
    Side at = side_of(f, en);
    if (!(std::fabs(f.dZ) > f.e_dZ) || near_end(at) || at == Side::unknown) return false;
    bool later = root->B_sign < 0; // the piece: t > t* (else t < t*)
    Side beyond = (f.dZ > 0) == later ? Side::above : Side::below;
    int i = later ? 0 : 1; // t* is the piece's start (root 0) or its end (root 1)
    std::optional<Enclosure<double>> roots[2];
    Side side[2];
    roots[i] = en, side[i] = at, side[1 - i] = beyond;
    return piece_hits<Target>(f, true, roots, side, side, unit, caller, query, r, &ends);
}

// g constant along the line (A = B = 0 exactly, which only `ends` proves: a line parallel to a
// cylinder's axis, or to a cone's generator in the plane touching the cone along it). Outside the
// quadric (C0 > 0) it meets nothing, and inside (C0 < 0, a cylinder's) it meets no lateral point:
// an open shape nothing, a closed one the two discs, in the order dZ's sign gives (the piece from
// below the extent to above it). On the quadric, or unproven: the next rungs. Rare, so out of line.
template <class Target>
[[gnu::noinline]] bool constant_g_hits(const LineForm& f, const Local<double>& at_0,
                                       const Unit& unit, const Line& caller, Query query, Result& r,
                                       const ExtentEnds& ends) {
    std::optional<int> c0 = ends.constant_sign(at_0.G, at_0.e_G);
    if (!c0) return linear_root_hit<Target>(f, unit, caller, query, r, ends);
    if (*c0 == 0) return false;
    if (*c0 > 0 || f.discs == Discs::none) return true;
    if (f.discs != Discs::convex || !(std::fabs(f.dZ) > f.e_dZ)) return false;
    Side first = f.dZ > 0 ? Side::below : Side::above, last = f.dZ > 0 ? Side::above : Side::below;
    const std::optional<Enclosure<double>> no_roots[2];
    const Side side[2] = {first, last};
    return piece_hits<Target>(f, true, no_roots, side, side, unit, caller, query, r, &ends);
}

} // namespace

namespace {

// G in double-double (the precise line form), or in double from the quick line form: enough for
// a float rounding, which has 29 bits more room.
template <int SigmaZ, Residual R>
Local<double> local_near(const LineForm& f, double c) {
    if constexpr (R == Residual::quick)
        return quick_local_at<SigmaZ>(f, c);
    else
        return local_at<SigmaZ>(f, c);
}

// The root next to the estimate c where the local quadratic there leaves it unproven, or its
// enclosure too wide to round t: an estimate far off in the root's scale (a line from far away,
// whose double estimate lost bits to cancellation) leaves y = 4AG/G'^2 large, and the enclosure
// with it. Up to four more Newton steps, each from the last one's root, each proof tried again;
// the narrowest proven enclosure stands. The scalar ladder's (ends given); rare, so out of line.
template <int SigmaZ, Residual R>
[[gnu::noinline]] std::optional<Enclosure<double>>
stepped_again(const LineForm& f, const Leading<double>& A, const Local<double>& L, double c,
              std::optional<Enclosure<double>> en) {
    if (en) { // proven: a step narrows it only where the step's size, not G's bound, widens it,
              // and the step is more than the ulps by which the next centre, a double, may miss
        double x0 = std::fabs(L.G / L.Gp), y = 4 * std::fabs(A.A) * x0 / std::fabs(L.Gp);
        if (!(x0 * (L.e_Gp + y * std::fabs(L.Gp) * A.e / std::fabs(A.A)) > L.e_G) ||
            !(x0 > 0x1p-51 * std::fabs(c)))
            return en;
    }
    double next = en ? en->c + en->x : c - L.G / L.Gp;
    for (int step = 0; step < 4 && std::isfinite(next); ++step) {
        std::optional<Enclosure<double>> again =
            root_near_tight(local_near<SigmaZ, R>(f, next), A, next);
        if (!again || (en && (again->smaller != en->smaller || !(again->e < en->e)))) break;
        en = again;
        next = en->c + en->x;
    }
    return en;
}
// A tangency its enclosure leaves next to an end (at or beside a rim, a cone's apex): its side of
// that end from the exact form. Beyond it: no hit. Short of it: inside the extent (the other end
// is far), as the range decides. At it: the end's point, kept where the extent is closed there,
// as its disc's where it has one (a rim belongs to its disc); not where another part owns it.
int tangent_at_end(const LineForm& f, const Unit& unit, const Enclosure<double>& en,
                   const ExtentEnds& ends, Part& part, ExactCoordinate& exact) {
    Side near = side_of(f, en);
    if (!near_end(near)) return -1;
    bool top = near == Side::near_hi;
    std::optional<int> against = ends.vertex_against(top);
    if (!against) return -1;
    Kept<double> by_range = in_range(unit, en);
    int in_range = by_range.outside ? 0 : by_range.inside ? 1 : -1;
    if (*against != 0) return (top ? *against > 0 : *against < 0) ? 0 : in_range;
    if (f.discs != Discs::none && !f.planes) return -1; // which ends have discs: not in this form
    if (ends.end_open(top)) return 0;
    if (f.planes && (top ? f.planes->at_hi : f.planes->at_lo)) {
        part = top ? Part::top : Part::base;
        if (f.planes->axis >= 0 && unit.pos_factor == 1)
            exact = {f.planes->axis, top ? f.planes->hi_at : f.planes->lo_at};
    }
    exact.end = top ? 1 : 0;
    return in_range;
}

// A double root's -B/A from the line form in bounded double-double: B = sum sigma_k U0_k U1_k and
// A = sum sigma_k U1_k^2, each product and sum bounded as it goes; none where it is not within
// 2^-95 of itself (B a few ulps from 0: a tangency at the line's origin), which the exact form
// then gives.
inline std::optional<BoundedDD> double_root_of(const LineForm& f) {
    BoundedDD B(0), A(0);
    with_sigma_z(f.sigma_z, [&](auto sigma_z) {
        constexpr int SigmaZ = decltype(sigma_z)::value;
        for (int k = 0; k < used_components<SigmaZ>; ++k) {
            const BoundedDD &u0 = U0_of(f, k), &u1 = U1_of(f, k);
            BoundedDD b = u0 * u1, a = u1 * u1;
            bool minus = sigma<SigmaZ>(k) < 0;
            B = minus ? B - b : B + b;
            A = minus ? A - a : A + a;
        }
    });
    BoundedDD t = -B / A;
    if (!std::isfinite(t.hi) || !std::isfinite(t.e) || !(t.e <= 0x1p-95 * std::fabs(t.hi)))
        return std::nullopt;
    return t;
}

// A tangency (a double root, which only `ends` proves: D = 0 exactly), A > 0: the line touches
// the quadric at t = -B/A, rational, and meets the shape there alone, where that point lies
// inside the extent (a closed solid too, and either of two solids, the apex between them
// included: the quadric's inside is that point) and the range. Unproven: the next rungs. Rare,
// so out of line.
template <class Target>
[[gnu::noinline]] bool tangent_hit(const LineForm& f, const Leading<double>& A, const Unit& unit,
                                   const Line& caller, Query query, Result& r,
                                   const ExtentEnds& ends) {
    if (!(A.A > A.e)) return false;
    std::optional<bool> tangent = ends.tangency();
    if (!tangent || !*tangent) return false;
    std::optional<BoundedDD> t = double_root_of(f);
    if (!t) t = ends.double_root(unit.t_factor);
    if (!t) return false;
    Enclosure<double> en{t->hi, t->lo, t->e, true, true};
    Part part = Part::lateral;
    ExactCoordinate exact;
    int inside = kept(f, unit, en);
    if (inside < 0) inside = tangent_at_end(f, unit, en, ends, part, exact);
    if (inside < 0) return false;
    r = Result();
    if (inside == 0) return true;
    if (!add_hit<Target>(en, part, unit, caller, query, r, exact, &ends)) return false;
    r.hits[0].kind = HitKind::tangent;
    return true;
}

// The local quadratic's own roots x in double, A x^2 + G' x + G = 0 (the stable pair q / A,
// G / q), sorted; false where it shows no two real roots or a root is not finite.
inline bool local_roots(const Local<double>& L, const Leading<double>& A, double (&x)[2]) {
    double D = difference_of_products(L.Gp, L.Gp, 4 * A.A, L.G);
    if (!(D > 0)) return false;
    double q = -0.5 * (L.Gp + std::copysign(std::sqrt(D), L.Gp));
    x[0] = q / A.A, x[1] = L.G / q;
    if (x[1] < x[0]) std::swap(x[0], x[1]);
    return std::isfinite(x[0]) && std::isfinite(x[1]);
}

// Root `smaller` (or the larger one) of g from its local quadratic at c, expanded again about
// c + x_c, x_c that quadratic's own root in double: where no double lies near enough to one root
// for the proof at a double (two roots within a few ulps of each other: a thin shape, a near
// tangency; a root of a line from far away, an ulp from every double). Exactly,
// g(c + x_c + x) = A x^2 + (G' + 2 A x_c) x + (G + x_c (G' + A x_c)); the new coefficients are
// rounded in double, each within the bounds of G, G' and A carried through and its roundings
// (four for the constant term, two for the slope), and the proof is the same. The scalar rung's;
// rare, so out of line.
[[gnu::noinline]] std::optional<Enclosure<double>>
root_beside(const Local<double>& L, const Leading<double>& A, double c, bool smaller) {
    using std::fabs;
    double roots[2];
    if (!local_roots(L, A, roots)) return std::nullopt;
    double x_c = roots[smaller ? 0 : 1];
    double ax = fabs(x_c), Ax = A.A * x_c;
    Local<double> at;
    at.G = L.G + x_c * (L.Gp + Ax);
    at.e_G =
        (L.e_G + ax * L.e_Gp + ax * ax * A.e + 4 * u * (fabs(L.G) + ax * (fabs(L.Gp) + fabs(Ax)))) *
            F::cover(32) +
        F::underflow_floor;
    at.Gp = L.Gp + 2 * Ax;
    at.e_Gp = (L.e_Gp + 2 * ax * A.e + 2 * u * (fabs(L.Gp) + 2 * fabs(Ax))) * F::cover(32) +
              F::underflow_floor;
    Enclosure<double> en = newton::root_near_tight(at, A, c);
    if (!en.proven || en.smaller != smaller) return std::nullopt;
    double x = x_c + en.x; // one rounding more
    en.e = (en.e + u * fabs(x)) * F::cover(4) + F::denorm_min;
    en.x = x;
    return en;
}

// The roots' estimates again, from g's local quadratic at the vertex c = -B/A: g(c + x) =
// A x^2 + G' x + G with G in double-double. Where B^2 and A C0 cancel (a line from far away, a
// thin shape), the estimates from the coefficients' high parts lose their bits, even whether
// the roots are real; the vertex keeps its own to an ulp, and G those that cancel. Sorted; false
// where the local quadratic shows no two real roots. The scalar rung's; rare, so out of line.
[[gnu::noinline]] bool estimates_at_vertex(const Leading<double>& A, const Local<double>& at_vertex,
                                           double vertex, double (&estimate)[2]) {
    double x[2];
    if (!local_roots(at_vertex, A, x)) return false;
    estimate[0] = vertex + x[0], estimate[1] = vertex + x[1]; // sorted still (rounding is monotone)
    return std::isfinite(estimate[0]) && std::isfinite(estimate[1]);
}
template <int SigmaZ, Residual R>
bool estimates_at_vertex(const LineForm& f, const Leading<double>& A, double vertex,
                         double (&estimate)[2]) {
    return std::isfinite(vertex) &&
           estimates_at_vertex(A, local_near<SigmaZ, R>(f, vertex), vertex, estimate);
}

// Unproven, or wider than 2^-64 of the root: far from what rounding t to a double needs. The
// quick residual's enclosures are meant to be wider (a float's rounding needs 2^-24): never.
template <Residual R>
LINEQUAD_INLINE bool too_wide(const std::optional<Enclosure<double>>& en) {
    if constexpr (R == Residual::quick)
        return false;
    else
        return !en || !(en->e <= 0x1p-64 * std::fabs(en->c));
}

// The roots' estimates and their local quadratics (local[i] g's at estimate[i] where fresh[i]),
// and the further tries that narrow a root unproven or too wide to round: the scalar ladder's,
// and only for a root that is needed (one beyond the extent is not). More steps from it; then
// from the estimates from the vertex (once, both roots'); then the local quadratic expanded about
// its own root. Every proven enclosure holds the root, from whichever estimate: the narrowest
// stands.
template <int SigmaZ, Residual R>
struct Roots {
    const LineForm& f;
    const Leading<double>& A;
    double vertex;
    double estimate[2];
    bool recentred; // the estimates taken (or tried) again at the vertex
    Local<double> local[2] = {};
    bool fresh[2] = {false, false};

    std::optional<Enclosure<double>> prove(int i) {
        if (!fresh[i]) local[i] = local_near<SigmaZ, R>(f, estimate[i]), fresh[i] = true;
        return root_near(local[i], A, estimate[i]);
    }
    [[gnu::noinline]] std::optional<Enclosure<double>>
    settled(int i, std::optional<Enclosure<double>> en) {
        auto narrower = [&](const std::optional<Enclosure<double>>& b) {
            if (b && (!en || b->e < en->e)) en = b;
        };
        if (!fresh[i]) narrower(prove(i)); // the other root's settling moved this estimate
        narrower(root_near_tight(local[i], A, estimate[i]));
        if (!too_wide<R>(en)) return en;
        en = stepped_again<SigmaZ, R>(f, A, local[i], estimate[i], en);
        if (too_wide<R>(en) && !recentred) {
            recentred = true;
            double before[2] = {estimate[0], estimate[1]};
            if (estimates_at_vertex<SigmaZ, R>(f, A, vertex, estimate))
                for (int j = 0; j < 2; ++j)
                    fresh[j] = fresh[j] && estimate[j] == before[j];
            if (!fresh[i]) {
                prove(i);
                std::optional<Enclosure<double>> again = root_near_tight(local[i], A, estimate[i]);
                if (too_wide<R>(again))
                    again = stepped_again<SigmaZ, R>(f, A, local[i], estimate[i], again);
                narrower(again);
            }
        }
        if (too_wide<R>(en)) narrower(root_beside(local[i], A, estimate[i], i == 0));
        return en;
    }
};

// An open shape's root i whose bounds leave kept() open, placed against the end's plane, or by
// `ends` once the other root is proven too: outside the extent, not kept; within it or at an end
// (kept unless another part owns that end; `at` becomes the end's crossing, which is the root,
// and `exact` says which), kept where the range proves it. 1, 0, or -1: undecided. Rare, so out
// of line.
template <int SigmaZ, Residual R>
[[gnu::noinline]] int kept_at_end(const LineForm& f, Roots<SigmaZ, R>& roots, int i,
                                  Enclosure<double>& at, ExactCoordinate& exact,
                                  const ExtentEnds& ends, const Unit& unit) {
    Placement p{side_of(f, at)};
    if (near_end(p.side)) {
        bool top = p.side == Side::near_hi;
        p = {beside_end(f, at, top, ends, unit)};
        if (p.side == Side::unknown) {
            std::optional<Enclosure<double>> root[2];
            root[i] = at;
            int j = 1 - i;
            root[j] = roots.prove(j);
            if (!root[j]) root[j] = roots.settled(j, root[j]); // beside a double root (an apex)
            if (!root[j] || root[j]->smaller != (j == 0)) return -1;
            p = placed_at_end(root, i, top, ends, unit);
        }
    }
    switch (p.side) {
    case Side::unknown:
    case Side::near_lo:
    case Side::near_hi:
        return -1;
    case Side::below:
    case Side::above:
        return 0;
    case Side::at_lo:
    case Side::at_hi:
        if (p.open) return 0;
        at = p.t_end;
        exact.end = p.side == Side::at_hi ? 1 : 0;
        break;
    case Side::within:
        break;
    }
    Kept<double> k = in_range(unit, at);
    return k.outside ? 0 : k.inside ? 1 : -1;
}

template <int SigmaZ, class Target, Residual R>
bool solve(const LineForm& f, const Unit& unit, const Line& caller, Query query, Result& r,
           const ExtentEnds* ends) {
    Leading<double> A = leading<SigmaZ>(f);
    if (!(std::fabs(A.A) > A.e)) // nearly parallel to the axis or to a generator
        return ends && constant_g_hits<Target>(f, local_near<SigmaZ, R>(f, 0.0), unit, caller,
                                               query, r, *ends);
    Estimates<double> est = estimates<SigmaZ>(f, A);
    Roots<SigmaZ, R> roots{f, A, est.vertex, {est.root[0], est.root[1]}, false};
    double(&estimate)[2] = roots.estimate;
    Local<double>(&local)[2] = roots.local;
    if (!est.real) {
        bool finite = std::isfinite(est.vertex);
        Local<double> at_vertex{};
        if (finite) {
            at_vertex = local_near<SigmaZ, R>(f, est.vertex);
            if (newton::no_root_proven(A, est.vertex, at_vertex)) return true;
        }
        // The vertex's estimates on the scalar ladder only: the batch lanes decline here.
        if (!ends || !finite || !estimates_at_vertex(A, at_vertex, est.vertex, estimate))
            return ends && tangent_hit<Target>(f, A, unit, caller, query, r, *ends);
        roots.recentred = true;
    }
    if (estimate[1] < estimate[0]) std::swap(estimate[0], estimate[1]);
    // On the scalar ladder (the batch lanes prove what one step proves): unproven, or wider than
    // one step leaves a root whose estimate was near (2^-100 of t): the enclosure about
    // x0 phi(y) first, from the same local quadratic.
    auto unsettled = [&](const std::optional<Enclosure<double>>& en) {
        if constexpr (R == Residual::quick)
            return ends && !en;
        else
            return ends && !(en && en->e <= 0x1p-88 * std::fabs(en->c));
    };
    if (f.discs != Discs::none) {
        // A closed shape: both roots before any hit (closed_hits). Two solids (a closed two-nappe
        // cone) only on the scalar ladder (ends given), the batch lanes' first rung declines them.
        if (f.discs == Discs::two_solids && !ends) return false;
        std::optional<Enclosure<double>> en[2];
        if constexpr (R == Residual::double_double) {
            newton::local_at<SigmaZ>(f, estimate, local);
            roots.fresh[0] = roots.fresh[1] = true;
            for (int i = 0; i < 2; ++i)
                en[i] = root_near(local[i], A, estimate[i]);
        } else {
            for (int i = 0; i < 2; ++i)
                en[i] = roots.prove(i);
        }
        if (unsettled(en[0]) || unsettled(en[1]))
            for (int i = 0; i < 2; ++i) {
                Side s = en[i] ? side_of(f, *en[i]) : Side::unknown;
                if (unsettled(en[i]) && s != Side::below && s != Side::above)
                    en[i] = roots.settled(i, en[i]);
            }
        for (int i = 0; i < 2; ++i) {
            if (!en[i]) return ends && tangent_hit<Target>(f, A, unit, caller, query, r, *ends);
            if (en[i]->smaller != (i == 0)) return false;
        }
        return closed_hits<Target>(f, A, en, unit, caller, query, r, ends);
    }
    // Both roots at once when both are needed; otherwise the second only if the first is not kept.
    bool both = R == Residual::double_double && query.need == Need::all;
    if (both) {
        newton::local_at<SigmaZ>(f, estimate, local);
        roots.fresh[0] = roots.fresh[1] = true;
    }
    for (int i = 0; i < 2; ++i) {
        std::optional<Enclosure<double>> en = roots.prove(i);
        if (!en && ends) en = roots.settled(i, en);
        if (!en) return ends && tangent_hit<Target>(f, A, unit, caller, query, r, *ends);
        if (en->smaller != (i == 0)) return false;
        int inside = kept(f, unit, *en);
        if (inside != 0 && unsettled(en)) { // a hit, or undecided: narrowed first
            en = roots.settled(i, en);      // proven still: at worst as it was
            if (en->smaller != (i == 0)) return false;
            inside = kept(f, unit, *en);
        }
        ExactCoordinate exact;    // set where the root is an end's crossing (a rim)
        if (inside < 0 && ends) { // t a few ulps from the range's end (0 most often), or an end
            Kept<double> by_range = in_range(unit, *en);
            if (!by_range.inside && !by_range.outside)
                if (std::optional<Enclosure<double>> narrower = tighter_until(
                        *en, Part::lateral, unit, *ends, [&](const Enclosure<double>& t) {
                            return (inside = kept_tighter(f, unit, t)) >= 0;
                        }))
                    en = narrower;
            if (inside < 0) inside = kept_at_end<SigmaZ, R>(f, roots, i, *en, exact, *ends, unit);
        }
        if (inside < 0) return false;
        if (inside == 0) continue;
        if (!add_hit<Target>(*en, Part::lateral, unit, caller, query, r, exact, ends)) return false;
        if (query.need != Need::all) break; // the smaller root first: also the nearest
    }
    return true;
}

// ---- The hit test ----

// A convex solid closed by discs whose lateral roots were proven but none inside the extent and
// the range (hit_test): with A > 0, both roots beyond one end is no hit; one below and one above,
// the line crosses both discs, at t = (end - Z0) / dZ, and the first in the range is the hit.
// From the quick form's doubles: with n = end - Z0 and dZ each within their bounds, the quotient
// is within (e_n + |t| e_dZ) / (|dZ| - e_dZ) of n / dZ, and its rounding adds u |t|.
bool closed_hit_test_of(const LineForm& f, const Leading<double>& A,
                        const std::optional<Enclosure<double>> (&root)[2], bool both_outside,
                        const Unit& unit, Result& r) {
    if (f.discs != Discs::convex || !(A.A > 0) || !root[0] || !root[1] ||
        root[0]->smaller == root[1]->smaller)
        return false;
    Side side[2] = {side_of(f, *root[0]), side_of(f, *root[1])};
    if (root[1]->smaller) std::swap(side[0], side[1]);
    auto placed = [](Side s) { return s == Side::below || s == Side::within || s == Side::above; };
    if (!placed(side[0]) || !placed(side[1])) return false;
    // Both beyond one end: no hit; both within: the hits, which the range dropped.
    if (side[0] == side[1]) return side[0] != Side::within || both_outside;
    if (side[0] == Side::within || side[1] == Side::within) return false; // out of the range
    double gap = std::fabs(f.dZ) - f.e_dZ;
    if (!(gap > 0)) return false;
    for (Side s : side) {
        bool low = s == Side::below;
        double n = (low ? f.lo : f.hi) - f.Z0, t = n / f.dZ;
        double e_n = (low ? f.e_lo : f.e_hi) + f.e_Z0 + u * std::fabs(n);
        double e_t = (e_n + std::fabs(t) * F::cover(4) * f.e_dZ) / gap * F::cover(8) +
                     2 * u * std::fabs(t) + F::denorm_min;
        if (!std::isfinite(e_t)) return false;
        Kept<double> k = Kept<double>().range(unit.line.range, t, e_t);
        if (k.outside) continue;
        if (!k.inside) return false;
        r.hits[0] = {t, {}, e_t, HitKind::cross, low ? Part::base : Part::top, true};
        r.count = 1;
        return true;
    }
    return true; // both crossings outside the range
}

// Any root proven inside the extent and the range is a hit, whichever it is: the first one
// found is the answer (on a closed shape too: the lateral surface between the discs is part of
// it). No hit needs none proven real, or, on a shape without discs, both roots proven outside;
// on a convex one closed by discs, closed_hit_test.
template <int SigmaZ>
bool hit_test(const LineForm& f, const Unit& unit, Result& r) {
    Leading<double> A = leading<SigmaZ>(f);
    if (!(std::fabs(A.A) > A.e)) return false;
    auto local = [&](double c) { return quick_local_at<SigmaZ>(f, c); };
    Estimates<double> est = estimates<SigmaZ>(f, A);
    if (!est.real) return no_root_proven(A, est.vertex, local); // r has no hit
    bool outside[2] = {false, false}; // the smaller, the larger root proven outside
    std::optional<Enclosure<double>> root[2];
    for (int i = 0; i < 2; ++i) {
        double c = est.root[i];
        std::optional<Enclosure<double>> en = root[i] = root_near(local(c), A, c);
        if (!en) continue;
        int inside = kept(f, unit, *en);
        if (inside == 1) {
            // t = c + x rounded once: within e + u |t| of the root (the sum's rounding).
            double t = en->c + en->x;
            r.hits[0] = {t,
                         {},
                         (en->e + u * std::fabs(t)) * F::cover(8) + F::denorm_min,
                         HitKind::cross,
                         Part::lateral,
                         true};
            r.count = 1;
            return true;
        }
        if (inside == 0) outside[en->smaller ? 0 : 1] = true;
    }
    if (f.discs == Discs::none) return outside[0] && outside[1];
    return closed_hit_test_of(f, A, root, outside[0] && outside[1], unit, r);
}

} // namespace

bool hit_test_rung(const LineForm& f, const Unit& unit, Result& r) {
    return with_sigma_z(
        f.sigma_z, [&](auto sigma_z) { return hit_test<decltype(sigma_z)::value>(f, unit, r); });
}

bool closed_hit_test(const LineForm& f, double A, const Enclosure<double> (&roots)[2],
                     bool both_outside, const Unit& unit, Result& r) {
    std::optional<Enclosure<double>> en[2];
    for (int i = 0; i < 2; ++i)
        if (roots[i].proven) en[i] = roots[i];
    return closed_hit_test_of(f, {A, 0}, en, both_outside, unit, r);
}

template <class Target, Residual R>
bool newton_rung(const LineForm& f, const Unit& unit, const Line& caller, Query query, Result& r,
                 const ExtentEnds* ends) {
    return with_sigma_z(f.sigma_z, [&](auto sigma_z) {
        return solve<decltype(sigma_z)::value, Target, R>(f, unit, caller, query, r, ends);
    });
}

// ---- A surface without extent ----

// A quadric (QuadricNewtonForm): the same proof from its own local quadratic, without the extent
// and the discs. A tangency, a root at the range's end, or a bound too wide: the next rungs.
//
// Where every hit is asked, two roots go through the steps side by side, a lane each
// (numeric/two_lanes.hpp: every lane the bits of the scalar step), and where every step is
// proven in both lanes (a generic line) the hits are written from the lanes; otherwise the scalar
// steps take the roots in turn from the same local quadratics, with their further tries.
LINEQUAD_INLINE bool both_roots_in_lanes(const Local<D2>& L, const Leading<double>& A, D2 c,
                                         const Unit& unit, const Line& caller, Query query,
                                         Result& r) {
    Enclosure<D2> en = newton::root_near(L, Leading<D2>{A.A, A.e}, c);
    // Proven, the smaller first, and too narrow for the scalar steps to try root_near_tight.
    M2 settled = en.proven & (en.e <= D2(0x1p-88) * fabs(en.c));
    if (!(lane(settled, 0) && lane(settled, 1) && lane(en.smaller, 0) && !lane(en.smaller, 1)))
        return false;
    EnclosedT<D2> t = t_of(en);
    Kept<D2> k = Kept<D2>().range(unit.line.range, t.t, t.e_t);
    bool keep[2];
    for (int i = 0; i < 2; ++i) {
        if (!lane(k.inside, i) && !lane(k.outside, i)) return false;
        keep[i] = lane(k.inside, i);
    }
    Rounded<D2> rt = rounded_t(en, D2(unit.t_factor));
    M2 proven = rt.proven;
    D2 p[3] = {0.0, 0.0, 0.0};
    if (query.points)
        for (int a = 0; a < 3; ++a) {
            // L0_k + t v_k is L0_k exactly when v_k = 0 (an exact zero is +0, as the oracle's).
            if (caller.v[a] == 0) {
                p[a] = D2(caller.L0[a] + 0.0);
                continue;
            }
            Rounded<D2> pa =
                rounded_point(en, D2(unit.line.L0[a]), D2(unit.line.v[a]), D2(unit.pos_factor));
            proven = proven & pa.proven;
            p[a] = pa.value;
        }
    if ((keep[0] && !lane(proven, 0)) || (keep[1] && !lane(proven, 1))) return false;
    for (int i = 0; i < 2; ++i) {
        if (!keep[i]) continue;
        Hit& h = r.hits[r.count++];
        h.t = lane(rt.value, i);
        h.kind = HitKind::cross;
        h.part = Part::lateral;
        h.p = {lane(p[0], i), lane(p[1], i), lane(p[2], i)};
    }
    return true;
}

template <class Target>
bool surface_newton_rung(const QuadricNewtonForm& f, const Unit& unit, const Line& caller,
                         Query query, Result& r, const ExtentEnds* ends) {
    Leading<double> A = f.leading();
    bool linear = f.linear(); // no quadratic part: one root, and A = 0 exactly
    if (!linear && !(std::fabs(A.A) > A.e)) return false;
    QuadricNewtonForm::Estimates est = f.estimates(A);
    if (!est.real) // no root, where g keeps its sign at its vertex
        return !linear && std::isfinite(est.vertex) &&
               newton::no_root_proven(A, est.vertex, f.local_at(est.vertex));
    Local<double> at[2];
    bool evaluated[2] = {false, false};
    // Every hit asked: both roots at once. The nearest or any: the smaller first, alone, which
    // usually answers.
    if (est.count == 2 && query.need == Need::all) {
        D2 c(est.root[0], est.root[1]);
        Local<D2> both = f.local_at(c);
        if constexpr (std::is_same_v<Target, Binary64>)
            if (both_roots_in_lanes(both, A, c, unit, caller, query, r)) return true;
        for (int i = 0; i < 2; ++i) {
            at[i] = {lane(both.G, i), lane(both.e_G, i), lane(both.Gp, i), lane(both.e_Gp, i)};
            evaluated[i] = true;
        }
    }
    for (int i = 0; i < est.count; ++i) {
        double c = est.root[i];
        if (!evaluated[i]) at[i] = f.local_at(c);
        const Local<double>& L = at[i];
        std::optional<Enclosure<double>> en = root_near(L, A, c);
        if (en && !(en->e <= 0x1p-88 * std::fabs(en->c)))
            if (std::optional<Enclosure<double>> tight = root_near_tight(L, A, c))
                if (tight->e < en->e) en = tight;
        if (!en || (!linear && en->smaller != (i == 0))) return false;
        Kept<double> k = in_range(unit, *en);
        if (k.outside) continue;
        if (!k.inside) return false;
        if (!add_hit<Target>(*en, Part::lateral, unit, caller, query, r, {}, ends)) return false;
        if (query.need != Need::all) break; // the smaller root first: also the nearest
    }
    return true;
}

template bool surface_newton_rung<Binary64>(const QuadricNewtonForm&, const Unit&, const Line&,
                                            Query, Result&, const ExtentEnds*);
template bool surface_newton_rung<Binary32>(const QuadricNewtonForm&, const Unit&, const Line&,
                                            Query, Result&, const ExtentEnds*);

template bool newton_rung<Binary64, Residual::double_double>(const LineForm&, const Unit&,
                                                             const Line&, Query, Result&,
                                                             const ExtentEnds*);
template bool newton_rung<Binary32, Residual::double_double>(const LineForm&, const Unit&,
                                                             const Line&, Query, Result&,
                                                             const ExtentEnds*);
template bool newton_rung<Binary32, Residual::quick>(const LineForm&, const Unit&, const Line&,
                                                     Query, Result&, const ExtentEnds*);

} // namespace linequad::detail
