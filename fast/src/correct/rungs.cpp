// The correct solver's second and third rungs: the exact form of the derivation in bounded
// double-double (its classification and roots, each rounding proven), and in exact big-float
// arithmetic, each output rounded by deciding exactly on which side of the midpoints between
// neighbouring doubles it lies.
#include "correct/rungs.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>

namespace linequad::detail {

using exact_form::Classification;
using exact_form::LineQuadratic;
using exact_form::Outcome;
using exact_form::SurdRoot;

namespace {

constexpr double dbl_max = std::numeric_limits<double>::max();

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

} // namespace

template <class Target>
bool double_double_rung(const LineQuadratic<BoundedDD>& q, const Unit& u, Query query, Result& r,
                        const BoundedDD* given_D) {
    Classification<BoundedDD> c = exact_form::classify(
        q, exact_form::parameter_range<BoundedDD>(u.line.range), query.need, given_D);
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
    bool surd = false;
    for (int i = 0; i < c.count; ++i)
        surd = surd || c.roots[i].S != 0;
    BoundedDD sqrt_D = surd ? sqrt(c.D) : BoundedDD();
    for (int i = 0; i < c.count; ++i) {
        BoundedDD t = root_value(c.roots[i], sqrt_D, q);
        std::optional<double> rounded = round_proven<Target>(t, u.t_factor);
        if (!rounded) return false;
        Hit& h = r.hits[r.count++];
        h.t = *rounded;
        h.kind = c.roots[i].kind;
        h.part = c.roots[i].part;
        h.p = {};
        if (!query.points) continue;
        for (int k = 0; k < 3; ++k) {
            BoundedDD p = BoundedDD(u.line.L0[k]) + BoundedDD(u.line.v[k]) * t;
            std::optional<double> pk = round_proven<Target>(p, u.pos_factor);
            if (!pk) return false;
            (k == 0 ? h.p.x : k == 1 ? h.p.y : h.p.z) = *pk;
        }
    }
    return true;
}

template bool double_double_rung<Binary64>(const LineQuadratic<BoundedDD>&, const Unit&, Query,
                                           Result&, const BoundedDD*);
template bool double_double_rung<Binary32>(const LineQuadratic<BoundedDD>&, const Unit&, Query,
                                           Result&, const BoundedDD*);

// ---- Rung 3: exact ----

namespace {

// The target's values in order, as integers (Format::ordinal): adjacent values have adjacent
// keys.
using Key = std::int64_t;
template <class Target>
const Key key_max = Target::ordinal(Target::max);
template <class Target>
double value_of(Key k) {
    return double(Target::from_ordinal(typename Target::Ordinal(k)));
}

// The midpoint between the values of keys k and k + 1. Beyond the largest, the next value is
// 2^(emax + 1) (IEEE rounds there to infinity): the midpoint is max + 2^(emax - precision), half
// an ulp of max (2^970 for doubles, 2^103 for floats).
template <class Target>
BigFloat midpoint_after(Key k) {
    if (k >= key_max<Target> || k < -key_max<Target>) {
        BigFloat beyond =
            BigFloat(double(Target::max)) +
            BigFloat::pow2(Binary64::exponent(double(Target::max)) - Target::precision);
        return k > 0 ? beyond : -beyond;
    }
    return (BigFloat(value_of<Target>(k)) + BigFloat(value_of<Target>(k + 1))).scaled(-1);
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

// Den and sqrt(D) in bounded double-double, formed once for all the values of one root: its t
// and its point's coordinates share them.
struct RootBounds {
    std::optional<BoundedDD> den, sqrt_d;
};

// (X + Y sqrt(D)) / Den rounded to the nearest value of Target (double or float), ties to even;
// infinite beyond the range, +0 for an exact zero (the oracle's conventions).
template <class Target>
class ExactRounder {
  public:
    ExactRounder(const BigFloat& X, const BigFloat& Y, const BigFloat& D, const BigFloat& Den,
                 RootBounds& shared)
        : X_(X), Y_(Y), D_(D), Den_(Den), shared_(shared), sden_(sign(Den)),
          sy_(sign(D) == 0 ? 0 : sign(Y)) {}

    // The value in bounded double-double, as proven() formed it (run() forms it first).
    const std::optional<BoundedDD>& enclosed() const { return enclosed_; }

    double run() const {
        // A rounding the bound proves settles the value's sign as well, so the exact sign (a
        // comparison of squares) is formed only for the values it leaves open; a zero from the
        // bound is checked there too (the oracle's +0 is for an exact zero only).
        std::optional<double> quick = proven();
        if (quick && *quick != 0) return *quick;
        int s = sden_ * exact_form::sign_surd(X_, sy_, y2d());
        if (s == 0) return 0.0;
        Key k = search(Target::ordinal(typename Target::Real(guess())));
        if (k > key_max<Target>) return INFINITY;
        if (k < -key_max<Target>) return -INFINITY;
        double x = value_of<Target>(k);
        return x == 0 ? std::copysign(0.0, s) : x;
    }

  private:
    const BigFloat &X_, &Y_, &D_, &Den_;
    RootBounds& shared_;
    int sden_, sy_;
    // Formed when first needed, as most values never need them: Y^2 D, the same for every
    // comparison; and X^2 - Y^2 D where X and Y sqrt(D) differ in sign, where the form without
    // cancellation is conjugate / (Den (X - Y sqrt(D))).
    mutable std::optional<BigFloat> y2d_, conjugate_;
    mutable std::optional<BoundedDD> enclosed_;

    const BigFloat& y2d() const {
        if (!y2d_) y2d_ = sy_ == 0 ? BigFloat() : Y_ * Y_ * D_;
        return *y2d_;
    }
    const BigFloat& conjugate() const {
        if (!conjugate_) conjugate_ = X_ * X_ - y2d();
        return *conjugate_;
    }

    // sign(value - midpoint_after(k)): decreasing in k.
    int above_midpoint(Key k) const {
        BigFloat m = midpoint_after<Target>(k);
        return sden_ * exact_form::sign_surd(BigFloat(X_ - m * Den_), sy_, y2d());
    }

    // The value in bounded double-double, in a form without cancellation, where its bound proves
    // the rounding: the search below is for values near a midpoint (ties among them) and beyond
    // the normal range.
    std::optional<double> proven() const {
        if (!shared_.den) shared_.den = enclosure(Den_);
        BoundedDD x = enclosure(X_), den = *shared_.den, v;
        if (sy_ == 0) {
            v = x / den;
        } else {
            if (!shared_.sqrt_d) shared_.sqrt_d = sqrt(enclosure(D_));
            BoundedDD ysd = enclosure(Y_) * *shared_.sqrt_d;
            int sx = sign(X_);
            v = sx == 0 || sx == sy_ ? (x + ysd) / den : enclosure(conjugate()) / (den * (x - ysd));
        }
        enclosed_ = v;
        return round_proven<Target>(v, 1.0);
    }

    double guess() const {
        int sx = sign(X_), sy = sy_;
        Approx x = Approx::of(X_), y = Approx::of(Y_), d = Approx::of(D_), den = Approx::of(Den_);
        if (sy == 0) return (x / den).value();
        Approx ysd = y * d.sqrt();
        if (sx == 0 || sx == sy) return ((x + ysd) / den).value();
        Approx conj = Approx::of(conjugate());
        return (conj / (den * (x + Approx{-ysd.m, ysd.e}))).value();
    }

    // b - a for a <= b: keys span more than an int64_t can hold.
    static std::uint64_t distance(Key a, Key b) { return std::uint64_t(b) - std::uint64_t(a); }

    // The key of the rounded value, from the guess g: the smallest k whose midpoint_after(k) is
    // at or above the value (key_max + 1: +infinity), and the even side of a tie.
    Key search(Key g) const {
        const Key first = -key_max<Target> - 1, last = key_max<Target>;
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
        if (k == -key_max<Target> - 1) return k; // below -max's cell: -infinity
        if (f != 0) return k;
        if (k == key_max<Target>) return k + 1; // the midpoint beyond max rounds to infinity
        auto x = Target::from_ordinal(typename Target::Ordinal(k));
        return (Target::bits(x) & 1) == 0 ? k : k + 1;
    }
};

} // namespace

template <class Target>
double round_exact(const BigFloat& X, const BigFloat& Y, const BigFloat& D, const BigFloat& Den) {
    RootBounds own;
    return ExactRounder<Target>(X, Y, D, Den, own).run();
}
template double round_exact<Binary64>(const BigFloat&, const BigFloat&, const BigFloat&,
                                      const BigFloat&);
template double round_exact<Binary32>(const BigFloat&, const BigFloat&, const BigFloat&,
                                      const BigFloat&);

namespace {

// Each of q's values enclosed from its exact one (numeric/big_float.hpp's enclosure).
LineQuadratic<BoundedDD> enclosed(const LineQuadratic<BigFloat>& q) {
    LineQuadratic<BoundedDD> e;
    e.A = enclosure(q.A), e.B = enclosure(q.B), e.C0 = enclosure(q.C0);
    e.Z0 = enclosure(q.Z0), e.dZ = enclosure(q.dZ), e.lo = enclosure(q.lo);
    e.hi = enclosure(q.hi);
    e.lo_bounded = q.lo_bounded, e.hi_bounded = q.hi_bounded;
    e.lo_capped = q.lo_capped, e.hi_capped = q.hi_capped, e.two_solids = q.two_solids;
    e.lo_open = q.lo_open, e.hi_open = q.hi_open;
    return e;
}

// The hits at the exact roots, each t and point rounded to Target: t from `enclosed[i]` (the
// filter's enclosure of root i, where it has one) where its bound proves the rounding, else
// exactly.
template <class Target>
void add_hits(const SurdRoot<BigFloat>* roots, const std::optional<BoundedDD>* enclosed, int count,
              const BigFloat& D, const Line& l, Query query, Result& r) {
    for (int i = 0; i < count; ++i) {
        const SurdRoot<BigFloat>& rt = roots[i];
        BigFloat S(rt.S);
        Hit& h = r.hits[r.count++];
        h.kind = rt.kind;
        h.part = rt.part;
        RootBounds shared;
        ExactRounder<Target> exact_t(rt.N, S, D, rt.Den, shared);
        std::optional<BoundedDD> t = enclosed[i];
        std::optional<double> rounded = t ? round_proven<Target>(*t, 1.0) : std::nullopt;
        if (rounded) {
            h.t = *rounded;
        } else {
            h.t = exact_t.run();
            t = exact_t.enclosed();
        }
        h.p = {};
        if (!query.points) continue;
        // L0 + t v from t's enclosure, as the double-double rung forms it, where its bound
        // proves the rounding (t needs about 53 + k bits for a line 2^k sizes away); else
        // exactly, L0 + t v = (L0 Den + v N + v S sqrt(D)) / Den.
        for (int k = 0; k < 3; ++k) {
            std::optional<double> pk;
            if (t) pk = round_proven<Target>(BoundedDD(l.L0[k]) + BoundedDD(l.v[k]) * *t, 1.0);
            if (!pk) {
                BigFloat L0(l.L0[k]), v(l.v[k]);
                pk = ExactRounder<Target>(L0 * rt.Den + v * rt.N, v * S, D, rt.Den, shared).run();
            }
            (k == 0 ? h.p.x : k == 1 ? h.p.y : h.p.z) = *pk;
        }
    }
}

} // namespace

template <class Target>
Result exact_rung(const LineQuadratic<BigFloat>& q, const BigFloat& D, const Line& l, Query query,
                  bool filter_first) {
    Result r;
    // D exact: the double-double rung's D, formed from rounded coefficients, loses the bits that
    // cancel in B^2 - A C0 (near a tangency, an apex, or from far away); enclosed from its exact
    // value, the filter's roots carry some 100 bits.
    if (filter_first) {
        // The classification in double-double, from every value's enclosure; its roots then
        // rounded from their exact forms (a point at a zero coordinate, or a tie, needs them).
        BoundedDD D_enclosed = enclosure(D);
        LineQuadratic<BoundedDD> e = enclosed(q);
        Classification<BoundedDD> c = exact_form::classify(
            e, exact_form::parameter_range<BoundedDD>(l.range), query.need, &D_enclosed);
        if (c.outcome == Outcome::none) return r;
        if (c.outcome == Outcome::hits) {
            SurdRoot<BigFloat> roots[max_hits];
            std::optional<BoundedDD> t[max_hits];
            BoundedDD sqrt_D = sign(c.D) == 0 ? BoundedDD() : sqrt(c.D);
            for (int i = 0; i < c.count; ++i) {
                roots[i] = exact_form::exact_root(q, c.roots[i]);
                t[i] = root_value(c.roots[i], sqrt_D, e);
            }
            add_hits<Target>(roots, t, c.count, D, l, query, r);
            return r;
        }
    }
    Classification<BigFloat> c =
        exact_form::classify(q, exact_form::parameter_range<BigFloat>(l.range), query.need, &D);
    if (c.outcome == Outcome::none) return r; // exact: never undecided
    if (c.outcome == Outcome::on_surface) {
        BigFloat zero;
        r.on_surface = true;
        r.surface_part = c.surface_part;
        auto end = [&](const exact_form::Fraction<BigFloat>& f) {
            return round_exact<Target>(f.num, BigFloat(f.S), f.S == 0 ? zero : c.D, f.den);
        };
        r.s0 = c.s0.bounded ? end(c.s0) : -INFINITY;
        r.s1 = c.s1.bounded ? end(c.s1) : INFINITY;
        return r;
    }
    const std::optional<BoundedDD> none[max_hits];
    add_hits<Target>(c.roots, none, c.count, c.D, l, query, r);
    return r;
}

template Result exact_rung<Binary64>(const LineQuadratic<BigFloat>&, const BigFloat&, const Line&,
                                     Query, bool);
template Result exact_rung<Binary32>(const LineQuadratic<BigFloat>&, const BigFloat&, const Line&,
                                     Query, bool);

} // namespace linequad::detail
