// The correct solver: the exact answer, correctly rounded. The classification (how many hits,
// their kinds, the on-surface interval) is the exact one, and t, the hit points and the interval
// ends are each the double nearest the exact value (ties to even), as the oracle gives them.
//
// It follows Ziv's strategy for correctly rounded functions, on the division-free form of the
// derivations in linequad/line_quadratic.hpp (coefficients are polynomials in the inputs):
//  1. Newton (newton_rung.cpp): each root estimated in double, then one Newton step from the
//     estimate with the residual in double-double proves a root's existence, which root it is,
//     and an enclosure about 2^-100 wide; the extent, the range, t and the points are decided
//     on it. Every decision and every rounding must be proven; otherwise
//  2. double-double: the quadratic, its classification and the roots in BoundedDD, which
//     carries a proven error bound. Every sign must be certain and every output's interval must
//     lie inside one rounding cell; otherwise
//  3. exact: the same template in BigFloat (exact dyadic arithmetic, no GMP), every sign exact,
//     and each output rounded by deciding, exactly, on which side of the midpoints between
//     neighbouring doubles it lies.
// Result::rung says which rung answered.
#include "big_float.hpp"
#include "bounded_dd.hpp"
#include "ladder.hpp"
#include "newton_rung.hpp"
#include "support.hpp"

#include "linequad/cylinder.hpp"
#include "linequad/elliptic_cone.hpp"
#include "linequad/elliptic_cylinder.hpp"
#include "linequad/line_quadratic.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <optional>

namespace linequad {

namespace detail {

std::optional<Unit> unit_scale(const Line& l, double extent,
                               std::initializer_list<Vec3> positions) {
    if (detail::fragile_scene(extent, positions, l.v)) return std::nullopt;
    detail::Prescale ps = detail::prescale_for(extent, l.v);
    double pos_factor = 1 / ps.to_unit, end = ps.to_unit / ps.dir_to_unit;
    if (!(ps.t_factor >= 0x1p-1000 && ps.t_factor <= 0x1p+1000)) return std::nullopt;
    return Unit{pos_factor, ps.t_factor, end, Line{ps.pos(l.L0), ps.dir(l.v), l.range}};
}

} // namespace detail

namespace {

using detail::round_proven;
using detail::Unit;
using detail::unit_scale;
using exact_form::Classification;
using exact_form::LineQuadratic;
using exact_form::Outcome;
using exact_form::SurdRoot;

constexpr double dbl_max = std::numeric_limits<double>::max();

// |t - exact t| <= half an ulp: the bound a correctly rounded value carries.
double half_ulp(double x) {
    if (!std::isfinite(x)) return INFINITY;
    double a = std::fabs(x);
    return (std::nextafter(a, INFINITY) - a) / 2;
}

// Every answer of the ladder is certain, each t within half an ulp; and says which rung gave it.
void mark_certain(Result& r, Rung rung) {
    r.certainty = Certainty::certain;
    r.rung = rung;
    for (int i = 0; i < r.count; ++i) {
        r.hits[i].certain = true;
        r.hits[i].bound = half_ulp(r.hits[i].t);
    }
}

// ---- Rung 2: double-double ----

// t' = (N + S sqrt(D)) / Den without cancellation: when N and S sqrt(D) differ in sign (N = -B,
// Den = A), the other root's form t' = C0 / (N - S sqrt(D)).
BoundedDD root_value(const SurdRoot<BoundedDD>& r, const BoundedDD& sqrt_D,
                     const LineQuadratic<BoundedDD>& q) {
    if (r.S == 0) return r.N / r.Den;
    BoundedDD s = r.S > 0 ? -sqrt_D : sqrt_D; // -S sqrt(D)
    int sn = sign(r.N);
    bool cancels = sn != exact_form::undecided && sn * r.S < 0;
    return cancels ? q.C0 / (r.N + s) : (r.N - s) / r.Den;
}

// The answer in r, or false when the bounds do not settle it (r is then left partly written).
bool double_double_rung(const LineQuadratic<BoundedDD>& q, const Unit& u, Query query, Result& r) {
    Classification<BoundedDD> c =
        exact_form::classify(q, u.line.range, query.need, BoundedDD(u.end));
    switch (c.outcome) {
    case Outcome::undecided:
        return false;
    case Outcome::none:
        return true;
    case Outcome::on_surface: // needs exact zeros of A, B and C0: only BigFloat has them
        return false;
    case Outcome::hits:
        break;
    }
    BoundedDD sqrt_D = c.roots[0].S == 0 ? BoundedDD() : sqrt(c.D);
    for (int i = 0; i < c.count; ++i) {
        BoundedDD t = root_value(c.roots[i], sqrt_D, q);
        std::optional<double> rounded = round_proven(t, u.t_factor);
        if (!rounded) return false;
        Hit& h = r.hits[r.count++];
        h.t = *rounded;
        h.kind = c.roots[i].kind;
        if (!query.points) continue;
        for (int k = 0; k < 3; ++k) {
            BoundedDD p = BoundedDD(u.line.L0[k]) + BoundedDD(u.line.v[k]) * t;
            std::optional<double> pk = round_proven(p, u.pos_factor);
            if (!pk) return false;
            (k == 0 ? h.p.x : k == 1 ? h.p.y : h.p.z) = *pk;
        }
    }
    return true;
}

// ---- Rung 3: exact ----

// Doubles in order, as integers: adjacent doubles have adjacent keys (+0 and -0 share 0).
using Key = std::int64_t;
Key key_of(double x) {
    std::int64_t bits;
    std::memcpy(&bits, &x, sizeof bits);
    return bits >= 0 ? bits : -(bits & std::numeric_limits<std::int64_t>::max());
}
double from_key(Key k) {
    std::int64_t bits = k >= 0 ? k : -k;
    double x;
    std::memcpy(&x, &bits, sizeof x);
    return k >= 0 ? x : -x;
}
const Key key_max = key_of(dbl_max);

// The midpoint between the doubles of keys k and k + 1. Beyond the largest double, the next
// "double" is 2^1024 (IEEE rounds there to infinity): the midpoint is DBL_MAX + 2^970.
BigFloat midpoint_after(Key k) {
    if (k >= key_max) return BigFloat(dbl_max) + BigFloat::pow2(970);
    if (k < -key_max) return -(BigFloat(dbl_max) + BigFloat::pow2(970));
    return (BigFloat(from_key(k)) + BigFloat(from_key(k + 1))).scaled(-1);
}

// A first guess at (X + Y sqrt(D)) / Den from the leading bits, without cancellation: a few
// ulps off at most, so that the exact search below usually needs two comparisons.
struct Approx {
    double m;
    long e; // m 2^e
    static Approx of(const BigFloat& x) {
        BigFloat::Approx a = x.approx();
        return {a.m, a.e};
    }
    Approx operator*(Approx b) const { return {m * b.m, e + b.e}; }
    Approx operator/(Approx b) const { return {m / b.m, e - b.e}; }
    Approx sqrt() const {
        long ee = e;
        double mm = m;
        if (ee % 2 != 0) mm *= 2, ee -= 1;
        return {std::sqrt(mm), ee / 2};
    }
    // For terms of one sign.
    Approx operator+(Approx b) const {
        if (m == 0) return b;
        if (b.m == 0) return *this;
        long d = e - b.e;
        if (d > 2000) return *this;
        if (d < -2000) return b;
        return d >= 0 ? Approx{m + std::ldexp(b.m, int(-d)), e}
                      : Approx{std::ldexp(m, int(d)) + b.m, b.e};
    }
    double value() const {
        if (m == 0) return 0;
        if (e > 2000) return std::copysign(dbl_max, m);
        if (e < -2000) return 0;
        double v = std::ldexp(m, int(e));
        return std::isinf(v) ? std::copysign(dbl_max, m) : v;
    }
};

// (X + Y sqrt(D)) / Den rounded to the nearest double, ties to even; infinite beyond the range,
// +0 for an exact zero (the oracle's conventions).
class ExactRounder {
  public:
    ExactRounder(const BigFloat& X, const BigFloat& Y, const BigFloat& D, const BigFloat& Den)
        : X_(X), Y_(Y), D_(D), Den_(Den), sden_(sign(Den)), sy_(sign(D) == 0 ? 0 : sign(Y)),
          Y2D_(sy_ == 0 ? BigFloat() : Y * Y * D) {}

    double run() const {
        int s = sden_ * exact_form::sign_surd(X_, sy_, Y2D_);
        if (s == 0) return 0.0;
        Key k = search(key_of(guess()));
        if (k > key_max) return INFINITY;
        if (k < -key_max) return -INFINITY;
        double x = from_key(k);
        return x == 0 ? std::copysign(0.0, s) : x;
    }

  private:
    const BigFloat &X_, &Y_, &D_, &Den_;
    int sden_, sy_;
    BigFloat Y2D_; // Y^2 D, the same for every comparison

    // sign(value - midpoint_after(k)): decreasing in k.
    int above_midpoint(Key k) const {
        BigFloat m = midpoint_after(k);
        return sden_ * exact_form::sign_surd(BigFloat(X_ - m * Den_), sy_, Y2D_);
    }

    double guess() const {
        int sx = sign(X_), sy = sy_;
        Approx x = Approx::of(X_), y = Approx::of(Y_), d = Approx::of(D_), den = Approx::of(Den_);
        if (sy == 0) return (x / den).value();
        Approx ysd = y * d.sqrt();
        if (sx == 0 || sx == sy) return ((x + ysd) / den).value();
        Approx conj = Approx::of(BigFloat(X_ * X_ - Y2D_)); // X^2 - Y^2 D
        return (conj / (den * (x + Approx{-ysd.m, ysd.e}))).value();
    }

    // b - a for a <= b: keys span more than an int64_t can hold.
    static std::uint64_t distance(Key a, Key b) { return std::uint64_t(b) - std::uint64_t(a); }

    // The key of the rounded value, from the guess g: the smallest k whose midpoint_after(k) is
    // at or above the value (key_max + 1: +infinity), and the even side of a tie.
    Key search(Key g) const {
        const Key first = -key_max - 1, last = key_max;
        g = std::clamp(g, first, last);
        Key lo, hi; // above_midpoint(lo) > 0 >= above_midpoint(hi)
        int fhi;
        if (int fg = above_midpoint(g); fg <= 0) {
            hi = g, fhi = fg;
            for (std::uint64_t step = 1;; step *= 2) {
                if (hi == first) return resolve(first, fhi);
                Key cand = distance(first, hi) > step ? hi - step : first;
                int f = above_midpoint(cand);
                if (f > 0) {
                    lo = cand;
                    break;
                }
                hi = cand, fhi = f;
            }
        } else {
            lo = g;
            for (std::uint64_t step = 1;; step *= 2) {
                if (lo == last) return last + 1; // above every midpoint: +infinity
                Key cand = distance(lo, last) > step ? lo + step : last;
                int f = above_midpoint(cand);
                if (f <= 0) {
                    hi = cand, fhi = f;
                    break;
                }
                lo = cand;
            }
        }
        while (distance(lo, hi) > 1) {
            Key mid = lo + Key(distance(lo, hi) / 2);
            int f = above_midpoint(mid);
            if (f > 0)
                lo = mid;
            else
                hi = mid, fhi = f;
        }
        return resolve(hi, fhi);
    }

    // The value is at or below midpoint_after(k) and above midpoint_after(k - 1): double k, or
    // on a tie (exactly at the midpoint) the even one of k and k + 1.
    static Key resolve(Key k, int f) {
        if (k == -key_max - 1) return k; // below -DBL_MAX's cell: -infinity
        if (f != 0) return k;
        if (k == key_max) return k + 1; // the midpoint to 2^1024 rounds to infinity
        std::uint64_t bits;
        double x = std::fabs(from_key(k));
        std::memcpy(&bits, &x, sizeof bits);
        return (bits & 1) == 0 ? k : k + 1;
    }
};

double round_exact(const BigFloat& X, const BigFloat& Y, const BigFloat& D, const BigFloat& Den) {
    return ExactRounder(X, Y, D, Den).run();
}

Result exact_rung(const LineQuadratic<BigFloat>& q, const Line& l, Query query) {
    Classification<BigFloat> c = exact_form::classify(q, l.range, query.need);
    Result r;
    if (c.outcome == Outcome::none) return r; // exact: never undecided
    BigFloat zero;
    if (c.outcome == Outcome::on_surface) {
        r.on_surface = true;
        r.s0 = c.s0.bounded ? round_exact(c.s0.num, zero, zero, c.s0.den) : -INFINITY;
        r.s1 = c.s1.bounded ? round_exact(c.s1.num, zero, zero, c.s1.den) : INFINITY;
        return r;
    }
    for (int i = 0; i < c.count; ++i) {
        const SurdRoot<BigFloat>& rt = c.roots[i];
        BigFloat S(rt.S);
        Hit& h = r.hits[r.count++];
        h.kind = rt.kind;
        h.t = round_exact(rt.N, S, c.D, rt.Den);
        if (!query.points) continue;
        // L0 + t v = (L0 Den + v N + v S sqrt(D)) / Den
        for (int k = 0; k < 3; ++k) {
            BigFloat L0(l.L0[k]), v(l.v[k]);
            double pk = round_exact(L0 * rt.Den + v * rt.N, v * S, c.D, rt.Den);
            (k == 0 ? h.p.x : k == 1 ? h.p.y : h.p.z) = pk;
        }
    }
    return r;
}

// ---- The ladder ----

// Sizes of scene and direction at which no quantity the Newton rung forms (products of at most
// twelve inputs) leaves double's normal range: 2^-64 to 2^64. Its bounds hold at any size; this
// only spares such scenes the scaling, which the rung's arithmetic would not need.
bool in_moderate_range(double x) {
    return x >= 0x1p-64 && x <= 0x1p+64;
}

// The ladder for one shape. scaled(s, f): the shape with its positions times f (a power of
// two). form(s, l): its line form for the Newton rung (newton_rung.hpp). quadratic(NT(), s, l):
// the exact form of its derivation in the number type NT.
template <class ShapeT, class Scaled, class Form, class Quadratic>
Result ladder(const ShapeT& s, const Line& l, Query q, double extent,
              std::initializer_list<Vec3> positions, Scaled scaled, Form form,
              Quadratic quadratic) {
    Result r; // the one result, returned in place
    // The Newton rung on the scene as `unit` has it; r is left empty when the rung declines.
    auto newton = [&](const ShapeT& shape, const Unit& unit) {
        if (detail::newton_rung(form(shape, unit.line), unit, l, q, r)) {
            mark_certain(r, Rung::newton);
            return true;
        }
        r = Result();
        return false;
    };
    // The Newton rung's bounds hold at any scale (underflow is in them, overflow makes them
    // infinite), so a scene of moderate size is solved as given; others are scaled first, so
    // that tiny or huge scenes are not left to the slower rungs.
    bool moderate = in_moderate_range(extent) && in_moderate_range(max_abs(l.v));
    if (moderate && newton(s, Unit{1, 1, 1, l})) return r;
    if (std::optional<Unit> u = unit_scale(l, extent, positions)) {
        ShapeT unit = scaled(s, 1 / u->pos_factor);
        if (!moderate && newton(unit, *u)) return r;
        auto dd = quadratic(BoundedDD(), unit, u->line);
        if (double_double_rung(dd, *u, q, r)) {
            mark_certain(r, Rung::double_double);
            return r;
        }
    }
    r = exact_rung(quadratic(BigFloat(), s, l), l, q);
    mark_certain(r, Rung::exact);
    return r;
}

} // namespace

namespace correct {

Result intersect(const Cylinder& s, const Line& l, Query q) {
    if (Error e = validate(s, l); e.code != ErrorCode::none) return Result::failure(e);
    double extent = std::max({max_abs(l.L0), max_abs(s.C), max_abs(s.H), s.r});
    return ladder(
        s, l, q, extent, {s.C, s.H, l.L0, {s.r, 0, 0}},
        [](const Cylinder& x, double f) {
            return Cylinder{f * x.C, f * x.H, f * x.r, x.finite};
        },
        [](const Cylinder& x, const Line& line) { return detail::line_form(x, line); },
        [](auto number, const Cylinder& x, const Line& line) {
            return exact_form::line_quadratic<decltype(number)>(x, line);
        });
}

Result intersect(const EllipticCylinder& s, const Line& l, Query q) {
    detail::ValidFrame valid = detail::validate_frame(s, l);
    if (valid.error.code != ErrorCode::none) return Result::failure(valid.error);
    bool negative = valid.orientation < 0;
    double extent =
        std::max({max_abs(l.L0), max_abs(s.C), max_abs(s.a), max_abs(s.b), max_abs(s.c)});
    return ladder(
        s, l, q, extent, {s.C, s.a, s.b, s.c, l.L0},
        [](const EllipticCylinder& x, double f) {
            return EllipticCylinder{f * x.C, f * x.a, f * x.b, f * x.c, x.finite};
        },
        [&](const EllipticCylinder& x, const Line& line) {
            return detail::line_form(x, line, negative);
        },
        [&](auto number, const EllipticCylinder& x, const Line& line) {
            return exact_form::line_quadratic<decltype(number)>(x, line, negative);
        });
}

Result intersect(const EllipticCone& s, const Line& l, Query q) {
    detail::ValidFrame valid = detail::validate_frame(s, l);
    if (valid.error.code != ErrorCode::none) return Result::failure(valid.error);
    bool negative = valid.orientation < 0;
    double extent =
        std::max({max_abs(l.L0), max_abs(s.C), max_abs(s.H), max_abs(s.a), max_abs(s.b)});
    return ladder(
        s, l, q, extent, {s.C, s.H, s.a, s.b, l.L0},
        [](const EllipticCone& x, double f) {
            return EllipticCone{f * x.C, f * x.H, f * x.a, f * x.b, x.finite};
        },
        [&](const EllipticCone& x, const Line& line) {
            return detail::line_form(x, line, negative);
        },
        [&](auto number, const EllipticCone& x, const Line& line) {
            return exact_form::line_quadratic<decltype(number)>(x, line, negative);
        });
}

} // namespace correct

} // namespace linequad
