// The oracle: each shape's exact form (fast/src/shapes/: derivation and classification) in
// CGAL::Mpzf, every decision exact; then each output rounded to the nearest double, or float for
// a binary32 answer: from double-word enclosures where their bound decides, else by MPFR.
#include "linequad/exact.hpp"

#include "double_word.hpp"
#include "forms/finish.hpp"
#include "numeric/fp_environment.hpp"
#include "rounding.hpp"
#include "shapes/all.hpp"

#include <CGAL/Gmpq.h>
#include <CGAL/Gmpz.h>
#include <CGAL/Interval_nt.h>
#include <CGAL/Mpzf.h>
#include <CGAL/number_utils.h>
#include <array>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <type_traits>

namespace linequad::exact {

namespace {

// Every value here is dyadic (see rounding.hpp); m 2^e from a canonical rational p / 2^k.
void dyadic_from_mpq(mpq_srcptr q, Dyadic& d) {
    std::size_t k = mpz_sizeinbase(mpq_denref(q), 2) - 1;
    if (mpz_scan1(mpq_denref(q), 0) != k) throw std::logic_error("oracle value is not dyadic");
    mpz_set(d.m, mpq_numref(q));
    d.e = -long(k);
}

void to_dyadic(const CGAL::Gmpq& x, Dyadic& d) {
    dyadic_from_mpq(x.mpq(), d);
}

void to_dyadic(const CGAL::Mpzf& x, Dyadic& d) {
    thread_local struct Q {
        mpq_t q;
        Q() { mpq_init(q); }
        ~Q() { mpq_clear(q); }
    } scratch;
    mpq_set_ui(scratch.q, 0, 1); // export_to_mpq_t requires 0 on entry and writes nothing for 0
    x.export_to_mpq_t(scratch.q);
    dyadic_from_mpq(scratch.q, d);
}

template <class NT>
int sgn(const NT& x) {
    return CGAL::sign(x);
}

// Queues (X + Y sqrt(D)) / Den for rounding, in the form that has no cancellation.
template <class NT>
void queue(SurdRounder& r, const NT& X, const NT& Y, const NT& Den, const NT& D) {
    SurdRounder::Value& v = r.next();
    int sx = sgn(X), sy = CGAL::is_zero(D) ? 0 : sgn(Y);
    to_dyadic(X, v.X);
    to_dyadic(Den, v.Den);
    if (sy == 0) {
        v.form = SurdRounder::Form::rational;
        return;
    }
    to_dyadic(Y, v.Y);
    if (sx * sy >= 0) {
        v.form = SurdRounder::Form::sum;
    } else {
        v.form = SurdRounder::Form::conjugate;
        to_dyadic(NT(X * X - Y * Y * D), v.N2);
    }
}

// One rounder per thread: MPFR and GMP state are costly to create per call.
SurdRounder& rounder() {
    thread_local SurdRounder r;
    return r;
}

// The on-surface interval's ends are rational: num / den.
template <class NT>
Result round_on_surface(const exact_form::Classification<NT>& c, Precision target) {
    Result r;
    r.on_surface = true;
    r.surface_part = c.surface_part;
    SurdRounder& rd = rounder();
    rd.clear();
    // The ends of a disc's chord are (num + S sqrt(D)) / den; every other end is rational.
    bool chord = c.s0.S != 0 || c.s1.S != 0;
    NT D = chord ? c.D : NT(0);
    to_dyadic(D, rd.D());
    if (c.s0.bounded) queue(rd, c.s0.num, NT(c.s0.S), c.s0.den, D);
    if (c.s1.bounded) queue(rd, c.s1.num, NT(c.s1.S), c.s1.den, D);
    rd.run(target);
    r.s0 = c.s0.bounded ? rd.result(0) : -INFINITY;
    r.s1 = c.s1.bounded ? rd.result(c.s0.bounded ? 1 : 0) : INFINITY;
    return r;
}

// The oracle's own filter: the same division-free form and classification in CGAL's interval
// arithmetic (directed rounding, every operation enclosing the exact value), whose sign is
// `undecided` where an interval holds zero. Every sign it decides is the exact sign, so its
// classification is the exact one: a miss needs no exact evaluation at all, and decided hits
// need only the exact values to round (the quadratic, and each root rebuilt from it), not the
// exact classification. A line on the surface and a sign it cannot decide go the exact way. It
// shares with fast/ only the form, as the exact path does, not a solver.
namespace filter {

struct Interval {
    CGAL::Interval_nt<false> x;
    Interval() = default;
    Interval(double d) : x(d) {}
    Interval(int i) : x(double(i)) {}
    Interval(CGAL::Interval_nt<false> v) : x(v) {}
};
inline Interval operator+(const Interval& a, const Interval& b) {
    return a.x + b.x;
}
inline Interval operator-(const Interval& a, const Interval& b) {
    return a.x - b.x;
}
inline Interval operator-(const Interval& a) {
    return -a.x;
}
inline Interval operator*(const Interval& a, const Interval& b) {
    return a.x * b.x;
}
// An interval holding zero (or NaN, from inf - inf) cannot say.
inline int sign(const Interval& a) {
    if (a.x.inf() > 0) return 1;
    if (a.x.sup() < 0) return -1;
    if (a.x.inf() == 0 && a.x.sup() == 0) return 0;
    return exact_form::undecided;
}

// Inputs from 2^-40 to 2^40 (or 0): the form's polynomials (degree at most 12) then stay far
// from overflow, so no interval meets an infinity. Others go straight to the exact path.
inline bool moderate(double x) {
    double a = std::fabs(x);
    return a == 0 || (a >= 0x1p-40 && a <= 0x1p40);
}
inline bool moderate(Vec3 p) {
    return moderate(p.x) && moderate(p.y) && moderate(p.z);
}
template <std::size_t N>
bool moderate(const std::array<double, N>& a) {
    for (double x : a)
        if (!moderate(x)) return false;
    return true;
}

// What the filter decided: nothing, a miss, or the hits (each root's kind, part and form, and
// the orientation, all exact: every sign it decided is the exact sign).
struct Verdict {
    enum class What { undecided, miss, hits } what = What::undecided;
    int orientation = 0;
    exact_form::LineQuadratic<Interval> q;
    exact_form::Classification<Interval> c;
};

// Interval_nt's enclosures need the processor to round upward when asked. One that ignores the
// rounding mode (valgrind does, for SSE) would make them too narrow and the filter's decisions
// wrong, so it is checked once, and without it every case takes the exact path.
// The sum is taken by Interval_nt itself: a plain a + b may be moved out of the protected scope
// by the compiler (the mode switch is no barrier to it), and was.
bool directed_rounding_works() {
    static const bool works = [] {
        CGAL::Protect_FPU_rounding<true> upward;
        volatile double one = 1.0, tiny = 0x1p-60;
        Interval sum = Interval(one) + Interval(tiny);
        return sum.x.sup() > 1.0;
    }();
    return works;
}

template <class ShapeT>
Verdict decide(const ShapeT& shape, const Line& l, Need need) {
    Verdict v;
    bool ok = directed_rounding_works() && moderate(l.L0) && moderate(l.v) &&
              (!l.range.has_t0() || moderate(l.range.t0)) &&
              (!l.range.has_t1() || moderate(l.range.t1));
    detail::for_each_field<ShapeT>([&](const auto& f) { ok = ok && moderate(shape.*f.member); });
    if (!ok) return v;
    CGAL::Protect_FPU_rounding<true> upward; // Interval_nt<false> needs it, and restores it
    using Traits = detail::ShapeTraits<ShapeT>;
    v.orientation = Traits::template exact_orientation<Interval>(shape);
    if (v.orientation == exact_form::undecided) return v;
    v.q = Traits::template exact_quadratic<Interval>(shape, l, v.orientation);
    v.c = exact_form::classify(v.q, exact_form::parameter_range<Interval>(l.range), need);
    if (v.c.outcome == exact_form::Outcome::none) v.what = Verdict::What::miss;
    if (v.c.outcome == exact_form::Outcome::hits) v.what = Verdict::What::hits;
    return v;
}

// The exact classification of decided hits, without classifying again: each root rebuilt
// from the exact quadratic by the form classify() gave it (exact_form::exact_root); D is
// B^2 - A C0, or 0 where A = 0 or D < 0.
template <class NT>
exact_form::Classification<NT> rebuilt(const Verdict& v, const exact_form::LineQuadratic<NT>& q) {
    exact_form::Classification<NT> c;
    c.outcome = exact_form::Outcome::hits;
    c.count = v.c.count;
    c.D = sign(v.q.A) == 0 ? NT(0) : NT(q.B * q.B - q.A * q.C0);
    if (CGAL::sign(c.D) < 0) c.D = NT(0);
    for (int k = 0; k < c.count; ++k)
        c.roots[k] = exact_form::exact_root(q, v.c.roots[k]);
    return c;
}

// The float nearest to x (ties to even), read from x's encoding: exact whatever the rounding
// mode. False where that float would not be normal, or x is not.
inline bool nearest_normal_float(double x, double& out) {
    double a = std::fabs(x);
    if (!(a >= double(FLT_MIN) && a <= double(FLT_MAX))) return false;
    std::uint64_t bits;
    std::memcpy(&bits, &a, sizeof bits);
    // A float's significand is a double's top 23 of 52 bits: drop the low 29, ties to even. A
    // carry out of the significand steps into the next binade, as rounding does.
    constexpr int dropped = 52 - 23;
    constexpr std::uint64_t half = std::uint64_t(1) << (dropped - 1);
    std::uint64_t kept = bits >> dropped, rest = bits & (2 * half - 1);
    kept += rest > half || (rest == half && (kept & 1));
    bits = kept << dropped;
    std::memcpy(&a, &bits, sizeof a);
    if (!(a <= double(FLT_MAX))) return false;
    out = x < 0 ? -a : a;
    return true;
}

// A binary32 case's hits rounded straight from the filter's intervals: t = (N + S sqrt(D)) / Den
// and each coordinate L0 + v t enclosed by interval arithmetic on the enclosures the filter
// decided with. Rounding to nearest is monotonic, so where both ends of a value's enclosure round
// to one float every real between them does, the exact value among them. A usual case's
// enclosures are far narrower than a float's cells (2^-24 of the value), so most binary32 cases
// never form the exact quadratic; they are wider than a double's, whose values take the
// double-word way below. False, with nothing decided, for any value that does not round so.
bool round_to_float(const Verdict& v, const Line& l, bool points, double* rounded) {
    std::size_t per_root = points ? 4 : 1, n = std::size_t(v.c.count) * per_root;
    Interval lo_hi[4 * max_hits];
    {
        CGAL::Protect_FPU_rounding<true> upward; // Interval_nt<false> needs it
        Interval root;                           // sqrt(D), once
        bool rooted = false;
        for (int j = 0; j < v.c.count; ++j) {
            const exact_form::SurdRoot<Interval>& rt = v.c.roots[j];
            Interval num = rt.N;
            if (rt.S != 0) {
                if (!(v.c.D.x.inf() > 0)) return false;
                if (!rooted) root = CGAL::sqrt(v.c.D.x), rooted = true;
                num = rt.S > 0 ? num + root : num - root;
            }
            Interval t = num.x / rt.Den.x;
            Interval* at = lo_hi + std::size_t(j) * per_root;
            at[0] = t;
            for (std::size_t k = 1; k < per_root; ++k)
                at[k] = Interval(l.L0[k - 1]) + Interval(l.v[k - 1]) * t;
        }
    }
    for (std::size_t i = 0; i < n; ++i) {
        std::size_t k = i % per_root;
        if (k > 0 && l.v[k - 1] == 0) { // exactly L0, a float here; zero is +0
            double L0 = l.L0[k - 1];
            rounded[i] = L0 == 0 ? 0.0 : L0;
            continue;
        }
        double lo = lo_hi[i].x.inf(), hi = lo_hi[i].x.sup(), a, b;
        if (lo == 0 && hi == 0) { // exactly zero, which the oracle answers +0
            rounded[i] = 0.0;
            continue;
        }
        if (!(lo > 0 || hi < 0) || !nearest_normal_float(lo, a) || !nearest_normal_float(hi, b) ||
            a != b)
            return false;
        rounded[i] = a;
    }
    return true;
}

// Correct rounding of (X + Y sqrt(D)) / Den from double-word enclosures of its parts
// (double_word.hpp), where their error bound proves it; the SurdRounder (MPFR) takes the rest:
// parts or answers far from double's normal range, zero answers, values the bound leaves too
// near a rounding boundary (ties among them). One per case: sqrt(D) and each root's Den are
// enclosed once for all of the case's values.
class QuickRounder {
  public:
    QuickRounder(const CGAL::Mpzf& D, Precision target) : D_(D), target_(target) {}

    // A value's magnitude as a double-word, and its sign.
    struct Value {
        dw::DoubleWord v;
        int sign = 0;
    };

    // (X + Y sqrt(D)) / Den, for Y a double (as every Y of the oracle's values is: S or v S);
    // false for zero, or beyond the range of the bounds.
    bool value(const CGAL::Mpzf& X, double Y, const CGAL::Mpzf& Den, Value& out) {
        using dw::DoubleWord;
        int sx = sgn(X), sy = CGAL::is_zero(D_) ? 0 : (Y > 0) - (Y < 0), sden = sgn(Den);
        if (sx == 0 && sy == 0) return false;
        if (&Den != den_of_) den_of_ = &Den, den_ok_ = enclose(Den, den_);
        DoubleWord x, v;
        if (!den_ok_ || (sx != 0 && !enclose(X, x))) return false;
        // A form without cancellation:
        //   X / Den;  (X + Y sqrt(D)) / Den for X, Y of one sign, or for one term over twice
        //   the other; otherwise (X^2 - Y^2 D) / (Den (X - Y sqrt(D))), the square exact.
        int sign = sx * sden;
        if (sy != 0) {
            if (!dw::in_range(Y) || !root_ok()) return false;
            DoubleWord ysd = dw::mul({std::fabs(Y), 0}, root_);
            if (!dw::in_range(ysd.hi)) return false;
            if (sx * sy >= 0) {
                DoubleWord sum = sx == 0 ? ysd : dw::add(x, ysd);
                if (!dw::in_range(sum.hi)) return false;
                v = dw::div(sum, den_);
                sign = (sx != 0 ? sx : sy) * sden;
            } else if (bool x_larger = x.hi > ysd.hi; dw::apart(x, ysd)) {
                DoubleWord difference = x_larger ? dw::sub(x, ysd) : dw::sub(ysd, x);
                if (!dw::in_range(difference.hi)) return false;
                v = dw::div(difference, den_);
                sign = (x_larger ? sx : sy) * sden;
            } else {
                CGAL::Mpzf y(Y), N2 = X * X - y * y * D_;
                DoubleWord n2, by = dw::mul(den_, dw::add(x, ysd));
                if (!dw::in_range(by.hi) || CGAL::is_zero(N2) || !enclose(N2, n2)) return false;
                v = dw::div(n2, by);
                sign = sgn(N2) * sden * sx; // X - Y sqrt(D) has the sign of X
            }
        } else {
            v = dw::div(x, den_);
        }
        out = {v, sign};
        return dw::in_range(v.hi);
    }

    // A point's coordinate L0 + v t from t's value, where that sum has no cancellation: its terms
    // of one sign, or one over twice the other. (The others take their exact numerator.)
    bool point(double L0, double v, const Value& t, double& out) const {
        if (v == 0) { // exactly L0: a double, and a float in a binary32 case; zero is +0
            out = L0 == 0 ? 0.0 : L0;
            return true;
        }
        if (!dw::in_range(v) || (L0 != 0 && !dw::in_range(L0))) return false;
        dw::DoubleWord vt = dw::mul({std::fabs(v), 0}, t.v), a{std::fabs(L0), 0};
        int s_vt = (v > 0 ? 1 : -1) * t.sign, s_a = (L0 > 0) - (L0 < 0);
        if (!dw::in_range(vt.hi)) return false;
        Value p;
        if (s_a == 0 || s_a == s_vt) {
            p = {s_a == 0 ? vt : dw::add(a, vt), s_vt};
        } else if (bool a_larger = a.hi > vt.hi; dw::apart(a, vt)) {
            p = {a_larger ? dw::sub(a, vt) : dw::sub(vt, a), a_larger ? s_a : s_vt};
        } else {
            return false;
        }
        return dw::in_range(p.v.hi) && nearest(p, out);
    }

    bool round(const CGAL::Mpzf& X, double Y, const CGAL::Mpzf& Den, double& out) {
        Value v;
        return value(X, Y, Den, v) && nearest(v, out);
    }

    // The relative error of v against the exact value, to first order: each part within
    // 2^-100 = 64 u^2 (Y exact; D half that through the square root), each operation as
    // double_word.hpp bounds it. Y sqrt(D): 43.4 u^2. The sum form: 67 u^2, then 143 u^2 over
    // Den. The difference of a term and at most half of it: (64 a + 43.4 b) / (a - b) <= 172.3
    // u^2 for a = |X| >= 2b, <= 152 u^2 for b >= 2a, then 8 u^2 more, and 257 u^2 over Den.
    // The conjugate form: 214 u^2. A point's coordinate L0 + v t: v t within 264 u^2, their sum
    // 267 u^2, their difference (264 b) / (a - b) <= 528 u^2 for b = |v t| >= 2a, then 8 u^2
    // more. All under 536 u^2 < 2^-96.9; budgeted: |value - v| <= 2^-94 |v|.
    bool nearest(const Value& x, double& out) const {
        int sign = x.sign;
        dw::DoubleWord w = dw::two_sum(x.v.hi, x.v.lo); // c + r = v exactly, c = RN(v) > 0
        double c = w.hi, r = w.lo;
        // The half gap from x in [2^E, 2^(E+1)) (lead = 2^E) to its neighbour above (up) or
        // below, for a format of `digits` bits; below a power of two the gap is half the one
        // above. Every product here is by a power of two, in range: exact.
        auto half_gap = [](double x, double lead, double half_ulp, bool up) {
            return !up && x == lead ? lead * half_ulp * 0.5 : lead * half_ulp;
        };
        // |value - c| <= |r| + 2^-94 |v| < |r| + 2^(E-92): the value rounds to c when that is
        // under the half gap on r's side (were the value on the other side, it would be within
        // 2^(E-92) of c, under either half gap). The difference is exact.
        if (target_ == Precision::binary64) {
            double lead = dw::binade(c);
            if (!(std::fabs(r) < half_gap(c, lead, 0x1p-53, r >= 0) - lead * 0x1p-92)) return false;
            out = sign > 0 ? c : -c;
            return true;
        }
        // A float f, normal, and s = RN((c - f) + r) (c - f is exact): |value - f| <=
        // |s| (1 + 2^-52) + 2^-94 |v| < |s| + 2^(F-75) where |s| < 2^(F-24) and |v| < 2^(F+1).
        // f is RN(c), or its neighbour towards the value where c lies at a float midpoint
        // (rounding c is then not rounding the value).
        float f = float(c);
        for (int tries = 0;; ++tries) {
            if (std::fpclassify(f) != FP_NORMAL) return false;
            double lead = dw::binade(f), s = (c - double(f)) + r;
            if (std::fabs(s) < half_gap(f, lead, 0x1p-24, s >= 0) - lead * 0x1p-75) break;
            if (tries == 1) return false;
            f = std::nextafter(f, s > 0 ? INFINITY : 0.0f);
        }
        out = sign > 0 ? double(f) : -double(f);
        return true;
    }

  private:
    const CGAL::Mpzf& D_;
    Precision target_;
    const CGAL::Mpzf* den_of_ = nullptr;
    dw::DoubleWord den_, root_;
    bool den_ok_ = false;
    int root_state_ = 0; // 0 not yet enclosed, 1 enclosed, -1 out of range

    bool root_ok() {
        if (root_state_ == 0) {
            dw::DoubleWord d;
            root_state_ = enclose(D_, d) ? 1 : -1;
            if (root_state_ == 1) root_ = dw::sqrt(d);
        }
        return root_state_ == 1;
    }

    // |x| as a double-word within 2^-100 |x| (x != 0): its leading double (to_double, within a
    // few ulps), then the exact remainder's enclosure (to_interval: an enclosure where its ends
    // are normal doubles), the lower end kept, the width bounded.
    static bool enclose(const CGAL::Mpzf& x, dw::DoubleWord& out) {
        double h = CGAL::to_double(x), m = std::fabs(h);
        if (!dw::in_range(h)) return false;
        CGAL::Mpzf rest = x - CGAL::Mpzf(h);
        double lo = 0;
        if (!CGAL::is_zero(rest)) {
            std::pair<double, double> e = CGAL::to_interval(rest);
            if (std::fpclassify(e.first) != FP_NORMAL || std::fpclassify(e.second) != FP_NORMAL ||
                !(e.second - e.first <= m * 0x1p-101) || !(std::fabs(e.first) <= m * 0x1p-40))
                return false;
            lo = h < 0 ? -e.first : e.first;
        }
        out = dw::fast_two_sum(m, lo);
        return true;
    }
};

} // namespace filter

// The oracle's answer: the classified roots' kinds and parts, their values rounded (per root: t,
// then x, y, z where points are asked).
template <class NT>
Result hits_of(const exact_form::Classification<NT>& c, const double* rounded, bool points) {
    std::size_t per_root = points ? 4 : 1;
    Result r;
    for (int j = 0; j < c.count; ++j) {
        Hit& h = r.hits[r.count++];
        h.kind = c.roots[j].kind;
        h.part = c.roots[j].part;
        const double* at = rounded + j * per_root;
        h.t = at[0];
        h.p = points ? Vec3{at[1], at[2], at[3]} : Vec3{};
        h.bound = std::numeric_limits<double>::quiet_NaN(), h.certain = false;
    }
    return r;
}

// One quadric (a shape, or a patch of a composite one). roots, when given, receives the exact
// classification the answer was rounded from.
template <class NT, class ShapeT>
Result solve_quadric(const ShapeT& shape, const Line& l, Query query, Precision target,
                     exact_form::Classification<NT>* roots = nullptr) {
    if (Error e = detail::check_line(l); !e.ok()) return Result::failure(e);
    if (Error e = detail::validity_of(shape).error; !e.ok()) return Result::failure(e);
    if (target == Precision::binary32)
        if (Error e = detail::binary32_error(shape, l); !e.ok()) return Result::failure(e);
    // The filter, on the oracle's own number type only (Gmpq stays unfiltered: the cross-check).
    filter::Verdict verdict;
    if constexpr (std::is_same_v<NT, CGAL::Mpzf>) {
        verdict = filter::decide(shape, l, query.need);
        rounding_stats().interval_decided += verdict.what != filter::Verdict::What::undecided;
        if (verdict.what == filter::Verdict::What::miss) {
            if (roots) *roots = exact_form::Classification<NT>{};
            return Result{};
        }
    }
    bool decided = verdict.what == filter::Verdict::What::hits;
    bool points = query.points && query.need != Need::any; // a hit test computes no point
    constexpr std::size_t most = 4 * max_hits;
    std::size_t per_root = points ? 4 : 1;
    double rounded[most];
    if constexpr (std::is_same_v<NT, CGAL::Mpzf>) {
        if (decided && target == Precision::binary32 && !roots &&
            filter::round_to_float(verdict, l, points, rounded)) {
            rounding_stats().by_intervals += std::size_t(verdict.c.count) * per_root;
            return hits_of(verdict.c, rounded, points);
        }
    }
    // The frame's orientation folds into the extent; the oracle decides it in NT itself (or the
    // filter did).
    using Traits = detail::ShapeTraits<ShapeT>;
    int orientation = decided ? verdict.orientation : Traits::template exact_orientation<NT>(shape);
    exact_form::LineQuadratic<NT> q = Traits::template exact_quadratic<NT>(shape, l, orientation);
    exact_form::Classification<NT> c =
        decided ? filter::rebuilt(verdict, q)
                : exact_form::classify(q, exact_form::parameter_range<NT>(l.range), query.need);
    if (roots) *roots = c;
    if (c.outcome == exact_form::Outcome::on_surface) return round_on_surface(c, target);
    if (c.outcome != exact_form::Outcome::hits) return Result{}; // exact: never undecided

    // Round t and, if asked, each coordinate of L0 + t v = (L0 Den + v N + v S sqrt(D)) / Den:
    // value i (k = i % per_root: t, then x, y, z) is (X + Y sqrt(D)) / Den of its root, Y (S or
    // v S) a double, X formed only where the filter does not round the value from t's.
    std::size_t n = std::size_t(c.count) * per_root;
    auto parts = [&](std::size_t i, NT& X, double& Y) {
        const exact_form::SurdRoot<NT>& rt = c.roots[i / per_root];
        std::size_t k = i % per_root;
        if (k == 0) return void((X = rt.N, Y = rt.S));
        NT L0(l.L0[k - 1]), v(l.v[k - 1]);
        X = NT(L0 * rt.Den + v * rt.N), Y = l.v[k - 1] * rt.S;
    };
    bool quick[most] = {}; // values the filter rounded
    std::size_t left = n;
    if constexpr (std::is_same_v<NT, CGAL::Mpzf>) {
        filter::QuickRounder quick_rounder(c.D, target);
        for (int j = 0; j < c.count; ++j) {
            const exact_form::SurdRoot<NT>& rt = c.roots[j];
            std::size_t first = std::size_t(j) * per_root;
            filter::QuickRounder::Value t;
            bool has_t = quick_rounder.value(rt.N, rt.S, rt.Den, t);
            quick[first] = has_t && quick_rounder.nearest(t, rounded[first]);
            for (std::size_t k = 1; k < per_root; ++k) {
                std::size_t i = first + k;
                if (has_t && quick_rounder.point(l.L0[k - 1], l.v[k - 1], t, rounded[i])) {
                    quick[i] = true;
                    continue;
                }
                NT X;
                double Y;
                parts(i, X, Y);
                quick[i] = quick_rounder.round(X, Y, rt.Den, rounded[i]);
            }
        }
        for (std::size_t i = 0; i < n; ++i)
            left -= quick[i];
        rounding_stats().by_filter += n - left;
    }
    if (left > 0) {
        SurdRounder& rd = rounder();
        rd.clear();
        to_dyadic(c.D, rd.D());
        for (std::size_t i = 0; i < n; ++i) {
            if (quick[i]) continue;
            NT X;
            double Y;
            parts(i, X, Y);
            queue(rd, X, NT(Y), c.roots[i / per_root].Den, c.D);
        }
        rd.run(target);
        for (std::size_t i = 0, slot = 0; i < n; ++i)
            if (!quick[i]) rounded[i] = rd.result(slot++);
    }
    return hits_of(c, rounded, points);
}

// A shape made of patches (the capsule): each patch solved exactly, the hits named by their
// patches' parts and merged in exact order; a line along a patch's surface is the answer.
template <class NT, class ShapeT>
Result solve_patches(const ShapeT& shape, const Line& l, Query query, Precision target) {
    using Traits = detail::ShapeTraits<ShapeT>;
    if (Error e = validate(shape, l); !e.ok()) return Result::failure(e);
    if (target == Precision::binary32)
        if (Error e = detail::binary32_error(shape, l); !e.ok()) return Result::failure(e);
    struct Found {
        Hit hit;
        exact_form::SurdRoot<NT> root;
        NT D;
    };
    std::vector<Found> found;
    Result along;
    int i = 0;
    std::apply(
        [&](const auto&... patch) {
            auto add = [&](const auto& p) {
                Part part = Traits::parts[i++];
                if (along.on_surface || !along.ok()) return;
                exact_form::Classification<NT> c;
                Result r = solve_quadric<NT>(p, l, query, target, &c);
                if (!r.ok() || r.on_surface) {
                    along = r, along.surface_part = part;
                    return;
                }
                for (int k = 0; k < r.count; ++k) {
                    found.push_back({r.hits[k], c.roots[k], c.D});
                    found.back().hit.part = part;
                }
            };
            (add(patch), ...);
        },
        Traits::patches(shape));
    if (along.on_surface || !along.ok()) return along;
    std::stable_sort(found.begin(), found.end(), [](const Found& a, const Found& b) {
        return exact_form::compare_roots<NT>({a.root.N, a.root.S, a.root.Den, a.D},
                                             {b.root.N, b.root.S, b.root.Den, b.D}) < 0;
    });
    Result r;
    std::size_t keep =
        query.need == Need::all ? found.size() : std::min<std::size_t>(found.size(), 1);
    for (std::size_t k = 0; k < keep && r.count < max_hits; ++k)
        r.hits[r.count++] = found[k].hit;
    return r;
}

template <class NT, class ShapeT>
Result solve(const ShapeT& shape, const Line& l, Query query, Precision target) {
    if constexpr (detail::is_composite<ShapeT>)
        return solve_patches<NT>(shape, l, query, target);
    else
        return solve_quadric<NT>(shape, l, query, target);
}

// A scene hit's exact t: (N + S sqrt(D)) / Den, or minus infinity (a line along a surface from
// the start of an unbounded range).
struct ExactT {
    bool minus_infinity = false;
    CGAL::Mpzf N, Den, D;
    int S = 0;
};

// sgn(x - y), the roots compared exactly (exact_form::compare_roots); minus infinity first.
int compare(const ExactT& x, const ExactT& y) {
    if (x.minus_infinity || y.minus_infinity) return int(y.minus_infinity) - int(x.minus_infinity);
    return exact_form::compare_roots<CGAL::Mpzf>({x.N, x.S, x.Den, x.D}, {y.N, y.S, y.Den, y.D});
}

struct ExactHit {
    SceneHit hit;
    ExactT t;
};

constexpr std::uint8_t on_surface_index = 255; // as Scene numbers a line along a surface

// Every hit of one shape on the line (a line along its surface: the interval's first point, as
// a tangent hit), with its exact t.
template <class ShapeT>
void shape_hits(const ShapeT& shape, std::uint32_t index, const Line& l, bool points,
                std::vector<ExactHit>& out, Part part = Part::lateral, int first = 0) {
    if constexpr (detail::is_composite<ShapeT>) {
        // Each patch's hits, named by its part (a scene's order is exact anyway); a line along a
        // patch's surface is the shape's answer, as solve_patches has it.
        if (!validate(shape, l).ok()) return;
        std::vector<ExactHit> mine;
        int i = 0;
        bool along = false;
        std::apply(
            [&](const auto&... patch) {
                auto add = [&](const auto& p) {
                    std::vector<ExactHit> hits;
                    Part named = detail::ShapeTraits<ShapeT>::parts[i];
                    shape_hits(p, index, l, points, hits, named, 2 * i++);
                    bool on = std::any_of(hits.begin(), hits.end(), [](const ExactHit& h) {
                        return h.hit.index == on_surface_index;
                    });
                    if (along) return;
                    if (on) mine.clear(), along = true;
                    mine.insert(mine.end(), hits.begin(), hits.end());
                };
                (add(patch), ...);
            },
            detail::ShapeTraits<ShapeT>::patches(shape));
        out.insert(out.end(), mine.begin(), mine.end());
    } else {
        exact_form::Classification<CGAL::Mpzf> c;
        Result r =
            solve_quadric<CGAL::Mpzf>(shape, l, {Need::all, points}, Precision::binary64, &c);
        constexpr bool patch = !detail::is_alternative<ShapeT, Shape>::value;
        if (patch) {
            for (int k = 0; k < r.count; ++k)
                r.hits[k].part = part;
            r.surface_part = part;
        }
        for (int k = 0; k < r.count; ++k) {
            const exact_form::SurdRoot<CGAL::Mpzf>& root = c.roots[k];
            out.push_back({{r.hits[k], index, std::uint8_t(first + k), false}, {}});
            ExactT& t = out.back().t;
            t.N = root.N, t.Den = root.Den, t.S = root.S, t.D = c.D;
        }
        if (r.on_surface) {
            Hit h{};
            h.t = r.s0;
            h.kind = HitKind::tangent, h.part = r.surface_part;
            h.bound = std::numeric_limits<double>::quiet_NaN();
            // Scene's definition of the point (the interval's end is not a root to round from).
            h.p = points && std::isfinite(r.s0) ? detail::point_at(l, r.s0) : Vec3{};
            out.push_back({{h, index, on_surface_index, false}, {}});
            ExactT& t = out.back().t;
            if (!c.s0.bounded) {
                t.minus_infinity = true;
            } else {
                t.N = c.s0.num, t.Den = c.s0.den, t.S = c.s0.S;
                t.D = c.s0.S != 0 ? c.D : CGAL::Mpzf(0);
            }
        }
    }
}

} // namespace

void intersect(const std::vector<Shape>& shapes, const Line& line, Query query, SceneAnswer& out) {
    numeric::StandardEnvironmentT<true>
        standard; // the caller's rounding mode or FTZ must not reach here
    out.hits.clear();
    out.error = {}, out.error_shape = no_shape, out.exact_comparisons = 0;
    out.shapes_solved = std::uint32_t(shapes.size());
    if (Error e = detail::check_line(line); !e.ok()) return void(out.error = e);
    for (std::uint32_t i = 0; i < shapes.size(); ++i)
        if (Error e = validate(shapes[i], line); !e.ok())
            return void((out.error = e, out.error_shape = i));
    bool points = query.points && query.need != Need::any;
    std::vector<ExactHit> hits;
    for (std::uint32_t i = 0; i < shapes.size(); ++i)
        std::visit([&](const auto& s) { shape_hits(s, i, line, points, hits); }, shapes[i]);
    std::sort(hits.begin(), hits.end(), [](const ExactHit& a, const ExactHit& b) {
        int c = compare(a.t, b.t);
        return c < 0 || (c == 0 &&
                         std::pair(a.hit.shape, a.hit.index) < std::pair(b.hit.shape, b.hit.index));
    });
    // Runs of exactly equal t: tied where they hold two shapes or more.
    std::size_t first_run_end = hits.size();
    for (std::size_t i = 0; i < hits.size();) {
        std::size_t j = i + 1;
        bool shapes_differ = false;
        while (j < hits.size() && compare(hits[j].t, hits[i].t) == 0) {
            shapes_differ = shapes_differ || hits[j].hit.shape != hits[i].hit.shape;
            ++j;
        }
        for (std::size_t k = i; k < j; ++k)
            hits[k].hit.tied = shapes_differ;
        if (i == 0) first_run_end = j;
        i = j;
    }
    std::size_t keep = query.need == Need::all       ? hits.size()
                       : query.need == Need::nearest ? first_run_end
                                                     : std::min<std::size_t>(hits.size(), 1);
    for (std::size_t k = 0; k < keep; ++k) {
        out.hits.push_back(hits[k].hit);
        if (query.need == Need::any) out.hits.back().tied = false;
    }
}

Model::Track track(const Model& m, Vec3 p, Vec3 u, int max_steps) {
    numeric::StandardEnvironmentT<true> standard;
    Model::Track out;
    Line ray{p, u, Interval(0, std::numeric_limits<double>::infinity())};
    if (Error e = detail::check_line(ray); !e.ok()) return out.error = e, out;
    const std::vector<Model::Surface>& surfaces = m.surfaces();
    std::vector<Sense> senses;
    for (const Model::Surface& s : surfaces) {
        SenseResult r = std::visit([&](const auto& x) { return exact::sense(x, p, u); }, s.shape);
        if (!r.ok()) return out.error = r.error, out;
        senses.push_back(r.sense);
    }
    auto holding = [&](std::vector<int>& in, std::vector<int>& undecided) {
        for (std::size_t c = 0; c < m.cells().size(); ++c) {
            std::optional<bool> holds = m.cells()[c].region.contains(senses);
            if (!holds)
                undecided.push_back(int(c));
            else if (*holds)
                in.push_back(int(c));
        }
    };
    holding(out.start, out.start_undecided);
    // Every crossing beyond p (t > 0; a root at p is in its sense already) of every surface the
    // ray does not lie in, in the order of its exact t, and runs of equal exact t crossed at once.
    std::vector<ExactHit> hits;
    for (std::size_t s = 0; s < surfaces.size(); ++s) {
        if (senses[s] == Sense::on) continue;
        std::visit(
            [&](const auto& x) {
                if (Error e = validate(x, ray); !e.ok()) return void(out.error = e);
                shape_hits(x, std::uint32_t(s), ray, false, hits);
            },
            surfaces[s].shape);
        if (!out.error.ok()) return out;
    }
    hits.erase(std::remove_if(hits.begin(), hits.end(),
                              [](const ExactHit& h) {
                                  return !(h.hit.hit.t > 0) || h.hit.hit.kind != HitKind::cross;
                              }),
               hits.end());
    std::sort(hits.begin(), hits.end(), [](const ExactHit& a, const ExactHit& b) {
        int c = compare(a.t, b.t);
        return c < 0 || (c == 0 && a.hit.shape < b.hit.shape);
    });
    std::vector<int> before = out.start, before_undecided = out.start_undecided;
    for (std::size_t i = 0; i < hits.size();) {
        std::size_t j = i;
        std::vector<int> crossed;
        for (; j < hits.size() && compare(hits[j].t, hits[i].t) == 0; ++j) {
            std::size_t s = hits[j].hit.shape;
            senses[s] = senses[s] == Sense::positive ? Sense::negative : Sense::positive;
            crossed.push_back(int(s));
        }
        Model::Step step{hits[i].hit.hit.t, crossed, {}, {}};
        i = j;
        holding(step.cells, step.undecided);
        if (step.cells == before && step.undecided == before_undecided) continue;
        before = step.cells, before_undecided = step.undecided;
        out.steps.push_back(std::move(step));
        if (int(out.steps.size()) >= max_steps) {
            out.truncated = true;
            break;
        }
    }
    return out;
}

template <class S, if_solvable<S>>
Result intersect(const S& shape, const Line& l, Query q, Precision p) {
    numeric::StandardEnvironmentT<true> standard;
    if constexpr (detail::is_prepared<S>::value)
        return solve<CGAL::Mpzf>(shape.shape(), l, q, p);
    else
        return solve<CGAL::Mpzf>(shape, l, q, p);
}
Result intersect(const Shape& s, const Line& l, Query q, Precision p) {
    numeric::StandardEnvironmentT<true> standard;
    return std::visit([&](const auto& shape) { return solve<CGAL::Mpzf>(shape, l, q, p); }, s);
}
Result intersect_gmpq(const Shape& s, const Line& l, Query q, Precision p) {
    numeric::StandardEnvironmentT<true> standard;
    return std::visit([&](const auto& shape) { return solve<CGAL::Gmpq>(shape, l, q, p); }, s);
}

#define LINEQUAD_INSTANTIATE_EXACT(S)                                                              \
    template Result intersect(const S&, const Line&, Query, Precision);                            \
    template Result intersect(const Prepared<S>&, const Line&, Query, Precision);
LINEQUAD_FOR_EACH_SHAPE(LINEQUAD_INSTANTIATE_EXACT)

double round_surd(const char* X, const char* Y, const char* D, const char* Den, Precision p) {
    CGAL::Gmpq x(X), y(Y), d(D), den(Den);
    SurdRounder& rd = rounder();
    rd.clear();
    to_dyadic(d, rd.D());
    queue(rd, x, y, den, d);
    rd.run(p);
    return rd.result(0);
}

double round_surd_by_filter(const char* X, double Y, const char* D, const char* Den, Precision p) {
    // CGAL 5.5's Mpzf(const Gmpz&) drops the sign and misreads zero: built from a nonzero
    // magnitude, then negated.
    auto integer = [](const char* s) {
        CGAL::Gmpz z(s);
        if (CGAL::is_zero(z)) return CGAL::Mpzf(0);
        CGAL::Mpzf m(CGAL::abs(z));
        return CGAL::is_negative(z) ? CGAL::Mpzf(-m) : m;
    };
    CGAL::Mpzf x = integer(X), d = integer(D), den = integer(Den);
    double out;
    return filter::QuickRounder(d, p).round(x, Y, den, out) ? out : NAN;
}

const Solver& solver(Precision p) {
    static const Solver exact_solver = {
        "exact", "exact rational oracle (CGAL kernel over Mpzf), correctly rounded t and points",
        [](const Shape& s, const Line& l, Query q) { return intersect(s, l, q); }};
    static const Solver exact_binary32 = {
        "exact", "exact rational oracle (CGAL kernel over Mpzf), t and points rounded to float",
        [](const Shape& s, const Line& l, Query q) {
            return intersect(s, l, q, Precision::binary32);
        },
        Precision::binary32};
    return p == Precision::binary32 ? exact_binary32 : exact_solver;
}

} // namespace linequad::exact
