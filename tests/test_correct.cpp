// The correct solver and the two number types of its ladder: BigFloat (exact) and BoundedDD
// (double-double with a proven bound). References: GMP rationals and 4096-bit MPFR.
#include "rational.hpp"
#include "support.hpp"

#include "correct/correct.hpp"
#include "correct/rungs.hpp"
#include "forms/exact_form.hpp"
#include "forms/frame.hpp"
#include "numeric/big_float.hpp"
#include "numeric/bounded_dd.hpp"
#include "numeric/exact_in_double.hpp"
#include "numeric/format.hpp"
#include "solve/solve.hpp"

#include "linequad/exact.hpp"
#include "linequad/families.hpp"

#include <gmp.h>
#include <mpfr.h>

#include <array>
#include <cstring>
#include <string>

using namespace linequad;
using namespace linequad::test;
using linequad::detail::Binary64;

namespace {

// Doubles over the whole range: random mantissas, exponents from -1074 to 1023 (subnormals
// included), either sign.
double wide_double(std::mt19937_64& rng) {
    double m = std::uniform_real_distribution<double>(1, 2)(rng);
    int e = int(rng() % 2098) - 1074;
    double x = std::ldexp(m, e); // rounds to a subnormal below 2^-1022: still a double
    return rng() % 2 ? -x : x;
}

Result correct_solve(const Shape& s, const Line& l, Query q = {}) {
    return std::visit([&](const auto& shape) { return correct::intersect(shape, l, q); }, s);
}

} // namespace

TEST_CASE("BigFloat sums and products are exact over the whole double range") {
    std::mt19937_64 rng(11);
    int led = 0; // values whose leading double-double was checked
    for (int i = 0; i < 3000; ++i) {
        double a = wide_double(rng), b = wide_double(rng), c = wide_double(rng),
               d = wide_double(rng);
        // a b + c - d, exactly, both ways; then their signs and difference must agree.
        BigFloat x = BigFloat(a) * BigFloat(b) + BigFloat(c) - BigFloat(d);
        Q qa(a), qb(b), qc(c), qd(d), r;
        mpq_mul(r.q, qa.q, qb.q);
        mpq_add(r.q, r.q, qc.q);
        mpq_sub(r.q, r.q, qd.q);
        INFO(hex(a) << " " << hex(b) << " " << hex(c) << " " << hex(d));
        REQUIRE(sign(x) == mpq_sgn(r.q));
        // Subtracting the same value built another way leaves exactly zero.
        BigFloat y = BigFloat(c) - BigFloat(d) + BigFloat(b) * BigFloat(a);
        REQUIRE(sign(x - y) == 0);
        // The approximation: within 2^-52 of the value (compared in MPFR at 4096 bits).
        BigFloat::Approx ap = x.approx();
        if (sign(x) == 0) {
            CHECK(ap.m == 0);
            continue;
        }
        mpfr_t exact, approx;
        mpfr_inits2(4096, exact, approx, (mpfr_ptr) nullptr);
        mpfr_set_q(exact, r.q, MPFR_RNDN);
        mpfr_set_d(approx, ap.m, MPFR_RNDN);
        mpfr_mul_2si(approx, approx, ap.e, MPFR_RNDN);
        mpfr_sub(approx, approx, exact, MPFR_RNDN);
        mpfr_div(approx, approx, exact, MPFR_RNDN);
        CHECK(std::fabs(mpfr_get_d(approx, MPFR_RNDN)) <= 0x1p-52);
        CHECK(std::fabs(ap.m) >= 1);
        CHECK(std::fabs(ap.m) < 2);
        mpfr_clears(exact, approx, (mpfr_ptr) nullptr);
        // The leading double-double: |x - hi - lo| <= err, and err <= 2^-104 |x| in range.
        BigFloat::Leading lead = x.leading();
        if (std::isinf(lead.err)) continue;
        Q hi(lead.hi), lo(lead.lo), err(lead.err), bound(std::ldexp(1.0, -104)), gap, at_most;
        mpq_sub(gap.q, r.q, hi.q);
        mpq_sub(gap.q, gap.q, lo.q);
        mpq_abs(gap.q, gap.q);
        REQUIRE(mpq_cmp(gap.q, err.q) <= 0);
        mpq_abs(at_most.q, r.q);
        mpq_mul(at_most.q, at_most.q, bound.q);
        CHECK(mpq_cmp(err.q, at_most.q) <= 0);
        ++led;
    }
    CHECK(led > 1000);
}

TEST_CASE("BigFloat differences that cancel whole low limbs are exact") {
    // x = a 2^k + c and y = b 2^k + c share their low part c: x - y = (a - b) 2^k exactly,
    // whose low limbs cancel to zero (the borrow, or a negated result's carry, crosses them).
    std::mt19937_64 rng(3);
    for (int i = 0; i < 2000; ++i) {
        double a = wide_double(rng), b = wide_double(rng), c = wide_double(rng);
        long k = long(rng() % 400);
        BigFloat x = BigFloat(a) * BigFloat::pow2(k) + BigFloat(c);
        BigFloat y = BigFloat(b) * BigFloat::pow2(k) + BigFloat(c);
        BigFloat want = (BigFloat(a) - BigFloat(b)) * BigFloat::pow2(k);
        INFO(hex(a) << " " << hex(b) << " " << hex(c) << " 2^" << k);
        REQUIRE(sign(x - y - want) == 0);
        REQUIRE(sign(y - x + want) == 0);
        REQUIRE(sign(x - y) == sign(want));
        // From zero: 0 - x is -x.
        REQUIRE(sign(BigFloat() - x) == -sign(x));
        REQUIRE(sign(BigFloat() - x + x) == 0);
    }
    // 3 2^64 + 5 - (4 2^64 + 5) = -2^64: every low bit cancels.
    BigFloat five(5.0), p64 = BigFloat::pow2(64);
    BigFloat x = BigFloat(3.0) * p64 + five, y = BigFloat(4.0) * p64 + five;
    CHECK(sign(x - y) < 0);
    CHECK(sign(x - y + p64) == 0);
    CHECK(sign(y - x - p64) == 0);
}

namespace {

// x as an exact rational, read back through leading() alone: its hi + lo taken off until nothing
// is left, each step removing at least 104 bits. For values whose bits lie above about 2^-750: a
// step's rounded lo can leave a remainder some 127 bits below x's lowest bit, and leading() needs
// its top above 2^-773.
Q exact_value(BigFloat x) {
    Q sum;
    for (int step = 0; sign(x) != 0; ++step) {
        REQUIRE(step < 200);
        BigFloat::Leading l = x.leading();
        REQUIRE(std::isfinite(l.err));
        sum = sum + Q(l.hi) + Q(l.lo);
        x = x - BigFloat(l.hi) - BigFloat(l.lo);
    }
    return sum;
}

} // namespace

TEST_CASE("BigFloat sums and products of several limbs equal GMP's exactly") {
    // Values of one to many limbs: sums of products of doubles whose exponents lie 0 to 160 bits
    // apart, so that sums meet operands from zero to several limbs apart (and the one-limb sums
    // and products the exact forms mostly make, d < 63 or not), of either sign, cancelling or not.
    std::mt19937_64 rng(29);
    auto near_double = [&](int spread) {
        double m = std::uniform_real_distribution<double>(1, 2)(rng);
        double x = std::ldexp(m, int(rng() % unsigned(spread + 1)) - spread / 2);
        return rng() % 2 ? -x : x;
    };
    for (int i = 0; i < 4000; ++i) {
        int spread = std::array<int, 4>{0, 62, 130, 160}[rng() % 4];
        BigFloat x, y;
        Q qx, qy;
        for (int k = 0, n = 1 + int(rng() % 4); k < n; ++k) {
            double a = near_double(spread), b = near_double(spread), c = near_double(spread);
            x = x + BigFloat(a) * BigFloat(b);
            qx = qx + Q(a) * Q(b);
            y = y - BigFloat(c);
            qy = qy - Q(c);
        }
        if (rng() % 4 == 0) y = y + x, qy = qy + qx; // cancels x's leading limbs in x - y
        INFO("case " << i);
        REQUIRE(mpq_equal(exact_value(x + y).q, (qx + qy).q));
        REQUIRE(mpq_equal(exact_value(x - y).q, (qx - qy).q));
        REQUIRE(mpq_equal(exact_value(x * y).q, (qx * qy).q));
        REQUIRE(mpq_equal(exact_value(y * x * x).q, (qy * qx * qx).q));
        REQUIRE(sign(x - x) == 0);
    }
}

TEST_CASE("BigFloat values of one or two limbs less than 64 bits apart add and multiply exactly") {
    // The fast paths: operands of one or two limbs (doubles, products of two) whose exponents lie
    // 0 to 63 bits apart, so that a sum carries into a third limb, cancels to zero or to a value
    // with 64 or more trailing zero bits (equal exponents), and a product fills four limbs.
    std::mt19937_64 rng(31);
    auto mantissa = [&] { return std::uniform_real_distribution<double>(1, 2)(rng); };
    int cancelled = 0, carried = 0;
    for (int i = 0; i < 20000; ++i) {
        int e = int(rng() % 64), f = int(rng() % 64);
        double a = mantissa(), b = std::ldexp(mantissa(), e), c = mantissa(),
               d = std::ldexp(mantissa(), f);
        if (rng() % 2) a = -a;
        if (rng() % 2) c = -c;
        BigFloat x = BigFloat(a) * BigFloat(b), y = BigFloat(c) * BigFloat(d);
        Q qx = Q(a) * Q(b), qy = Q(c) * Q(d);
        if (rng() % 8 == 0) y = -x, qy = Q() - qx; // x + y = 0 exactly
        if (rng() % 8 == 0) { // y = -x + a power of two well below: 64 or more zeros cancel
            BigFloat low = BigFloat::pow2(-int(rng() % 40) - 110);
            y = low - x;
            qy = exact_value(low) - qx;
        }
        INFO(hex(a) << " " << hex(b) << " " << hex(c) << " " << hex(d));
        Q sum = qx + qy;
        REQUIRE(mpq_equal(exact_value(x + y).q, sum.q));
        REQUIRE(mpq_equal(exact_value(x - y).q, (qx - qy).q));
        REQUIRE(mpq_equal(exact_value(y - x).q, (qy - qx).q));
        REQUIRE(mpq_equal(exact_value(x * y).q, (qx * qy).q));
        REQUIRE(mpq_equal(exact_value(BigFloat(a) + BigFloat(c)).q, (Q(a) + Q(c)).q));
        cancelled += mpq_sgn(sum.q) == 0;
        // The sum's significant bits, numerator's highest to lowest set bit: beyond two limbs.
        mpz_srcptr n = mpq_numref(sum.q);
        carried += mpq_sgn(sum.q) != 0 && mpz_sizeinbase(n, 2) - mpz_scan1(n, 0) > 128;
    }
    CHECK(cancelled > 1000);
    CHECK(carried > 1000);
}

namespace {

// A vector whose components are far apart: one exponent near `base`, the others up to 1100
// binades below it (into subnormals or to zero), so that two-fold products underflow while
// the third factor is huge.
Vec3 spread_vector(std::mt19937_64& rng, int base) {
    Vec3 u;
    for (int k = 0; k < 3; ++k) {
        double m = std::uniform_real_distribution<double>(1, 2)(rng);
        int drop = rng() % 3 == 0 ? 0 : int(rng() % 1100);
        double x = rng() % 5 == 0 ? 0 : std::ldexp(rng() % 2 ? -m : m, base - drop);
        (k == 0 ? u.x : k == 1 ? u.y : u.z) = x;
    }
    return u;
}

// sgn(a . (b x (H - C - R))) in GMP rationals.
int det_sign_gmp(Vec3 a, Vec3 b, Vec3 C, Vec3 H, Vec3 R = {}) {
    Q c[3], t, u, det;
    for (int k = 0; k < 3; ++k) {
        Q h(H[k]), g(C[k]), r(R[k]);
        mpq_sub(c[k].q, h.q, g.q);
        mpq_sub(c[k].q, c[k].q, r.q);
    }
    for (int i = 0; i < 3; ++i) {
        int j = (i + 1) % 3, k = (i + 2) % 3;
        Q ai(a[i]), bj(b[j]), bk(b[k]);
        mpq_mul(t.q, bj.q, c[k].q);
        mpq_mul(u.q, bk.q, c[j].q);
        mpq_sub(t.q, t.q, u.q);
        mpq_mul(t.q, ai.q, t.q);
        mpq_add(det.q, det.q, t.q);
    }
    return mpq_sgn(det.q);
}

} // namespace

TEST_CASE("frame orientation is exact when products underflow inside a huge determinant") {
    // The fuzzer's case: b.y (H.x - C.x) = 2^-1452 underflows to zero in doubles, and a.z =
    // 2^954 makes it the determinant's largest term (2^-498). The double filter once believed
    // the rest and called this frame left-handed.
    Vec3 C{-0x1.2923192929292p-726, -0x1.2929292929292p-726, -0x1.2929292929292p-726};
    Vec3 H{-0x1.5929292929292p-731, -0x1.2923192929292p-726, -0x1.2929292929292p-726};
    Vec3 a{-0x1.2929292929292p-726, -0x1.592928e929292p-731, 0x1.2929292929292p+954};
    Vec3 b{0x0.dbc8525646922p-1022, -0x1.2922c5d22616p-726, 0x1.27b9292929292p+659};
    REQUIRE(det_sign_gmp(a, b, C, H) == 1);
    CHECK(cone_det_sign_exact(a, b, C, H) == 1);

    std::mt19937_64 rng(23);
    for (int i = 0; i < 20000; ++i) {
        int base_a = int(rng() % 1800) - 900, base_b = int(rng() % 1800) - 900,
            base_c = int(rng() % 1800) - 900;
        Vec3 a = spread_vector(rng, base_a), b = spread_vector(rng, base_b);
        Vec3 c = spread_vector(rng, base_c), C = spread_vector(rng, base_c);
        // H near C half the time, so that H - C cancels to a few bits as in the fuzzer's case.
        Vec3 H = rng() % 2 ? C + ldexp(spread_vector(rng, base_c), -int(rng() % 60)) : c;
        INFO(hex(a.x) << " " << hex(a.y) << " " << hex(a.z) << " / " << hex(b.x) << " " << hex(b.y)
                      << " " << hex(b.z));
        INFO("c " << hex(c.x) << " " << hex(c.y) << " " << hex(c.z));
        INFO("C " << hex(C.x) << " " << hex(C.y) << " " << hex(C.z) << " H " << hex(H.x) << " "
                  << hex(H.y) << " " << hex(H.z));
        REQUIRE(det3_sign_exact(a, b, c) == det_sign_gmp(a, b, Vec3{}, c));
        REQUIRE(cone_det_sign_exact(a, b, C, H) == det_sign_gmp(a, b, C, H));
    }
}

TEST_CASE("a point's side of a plane through a sum of points is exact (det[a b P - Q - R])") {
    // What the correct solver's constant_z asks of an elliptic shape: L0 against a disc's plane
    // through C + c, with L0 a few ulps from it (P - Q - R cancels to a few bits), or exactly on
    // it (sign 0); and over spread exponents, where products underflow.
    std::mt19937_64 rng(29);
    int zeros = 0;
    for (int i = 0; i < 20000; ++i) {
        int base = int(rng() % 1800) - 900;
        Vec3 a = spread_vector(rng, int(rng() % 1800) - 900);
        Vec3 b = spread_vector(rng, int(rng() % 1800) - 900);
        Vec3 Q = spread_vector(rng, base), R = spread_vector(rng, base);
        Vec3 P = spread_vector(rng, base);
        switch (rng() % 3) {
        case 0: // on the plane, when Q + R and its moves along a and b are exact
            P = Q + R + (rng() % 2 ? 0.5 * a : Vec3{});
            break;
        case 1: // a few ulps off it
            P = Q + R + ldexp(spread_vector(rng, base), -50 - int(rng() % 10));
            break;
        default:
            break;
        }
        int exact = det_sign_gmp(a, b, Q, P, R);
        zeros += exact == 0 && a != Vec3{} && b != Vec3{};
        INFO(hex(a.x) << " " << hex(a.y) << " " << hex(a.z) << " / " << hex(b.x) << " " << hex(b.y)
                      << " " << hex(b.z));
        INFO("P " << hex(P.x) << " " << hex(P.y) << " " << hex(P.z) << " Q " << hex(Q.x) << " "
                  << hex(Q.y) << " " << hex(Q.z) << " R " << hex(R.x) << " " << hex(R.y) << " "
                  << hex(R.z));
        REQUIRE(det3_sign_exact(a, b, P, Q, R) == exact);
    }
    CHECK(zeros > 1000); // points exactly on their plane (a and b not zero) were tested
}

TEST_CASE("signs computed in double where nothing rounds are exact, and declined otherwise") {
    // det[a b P - Q - R] and (a - a') . (b - b') in double (numeric/exact_in_double.hpp): on small
    // integers and halves (a frame of small integers: every product and sum a double) they must
    // answer, and exactly, zeros included; on wide doubles, near the subnormals or near overflow
    // they may decline, but never answer wrongly.
    std::mt19937_64 rng(37);
    auto small = [&] {
        return Vec3{0.5 * double(int(rng() % 33) - 16), double(int(rng() % 17) - 8),
                    double(int(rng() % 9) - 4)};
    };
    int answered = 0, zeros = 0, declined = 0;
    for (int i = 0; i < 20000; ++i) {
        int kind = int(rng() % 4);
        auto draw = [&] {
            if (kind == 0) return small();
            int base = kind == 1 ? int(rng() % 100) - 50 : kind == 2 ? -1000 : 990;
            return spread_vector(rng, base);
        };
        Vec3 a = draw(), b = draw(), q = draw(), r = draw(), p = draw();
        if (rng() % 2) p = q + r + (rng() % 2 ? a : b); // on the plane (exactly, for small ones)
        int exact = det_sign_gmp(a, b, q, p, r);
        std::optional<int> d = det3_sign_in_double(a, b, p, q, r);
        INFO("kind " << kind << " case " << i);
        if (kind == 0) REQUIRE(d);
        if (d) {
            REQUIRE(*d == exact);
            ++answered, zeros += exact == 0;
        } else {
            ++declined;
        }
        Q dot_exact;
        for (int k = 0; k < 3; ++k)
            dot_exact = dot_exact + (Q(a[k]) - Q(b[k])) * (Q(p[k]) - Q(r[k]));
        std::optional<int> s = dot_sign_in_double(a, b, p, r);
        if (kind == 0) REQUIRE(s);
        if (s) REQUIRE(*s == mpq_sgn(dot_exact.q));
    }
    CHECK(zeros > 1000);
    CHECK(declined > 1000);
}

TEST_CASE("BoundedDD bounds hold: |hi + lo - exact| <= e for every operation") {
    // Operands near unit size, as the solver's prescaling makes them, with the low words and
    // error bounds that chains of operations produce; the exact results in 4096-bit MPFR.
    std::mt19937_64 rng(12);
    auto operand = [&](bool exact) {
        double hi =
            std::ldexp(std::uniform_real_distribution<double>(1, 2)(rng), int(rng() % 40) - 20) *
            (rng() % 2 ? 1 : -1);
        double lo = exact ? 0 : hi * 0x1p-54 * std::uniform_real_distribution<double>(-1, 1)(rng);
        TwoTerm n = two_sum(hi, lo);
        double e =
            exact ? 0
                  : std::fabs(n.hi) * 0x1p-100 * std::uniform_real_distribution<double>(0, 1)(rng);
        return BoundedDD(n.hi, n.lo, e);
    };
    mpfr_t x, y, z, w;
    mpfr_inits2(4096, x, y, z, w, (mpfr_ptr) nullptr);
    auto load = [](mpfr_t m, const BoundedDD& a) {
        mpfr_set_d(m, a.hi, MPFR_RNDN);
        mpfr_add_d(m, m, a.lo, MPFR_RNDN); // exact at 4096 bits
    };
    for (int i = 0; i < 20000; ++i) {
        BoundedDD a = operand(i % 3 == 0), b = operand(i % 5 == 0);
        for (int op = 0; op < 5; ++op) {
            BoundedDD r;
            load(x, a);
            load(y, b);
            switch (op) {
            case 0:
                r = a + b, mpfr_add(z, x, y, MPFR_RNDN);
                break;
            case 1:
                r = a - b, mpfr_sub(z, x, y, MPFR_RNDN);
                break;
            case 2:
                r = a * b, mpfr_mul(z, x, y, MPFR_RNDN);
                break;
            case 3:
                r = a / b, mpfr_div(z, x, y, MPFR_RNDN);
                break;
            default: {
                BoundedDD pos = a.hi < 0 ? -a : a;
                r = sqrt(pos);
                load(x, pos);
                mpfr_sqrt(z, x, MPFR_RNDN);
            }
            }
            // The centres' exact result must lie within the bound (the propagated terms only
            // make it larger): |hi + lo - z| <= e.
            load(w, r);
            mpfr_sub(w, w, z, MPFR_RNDN);
            mpfr_abs(w, w, MPFR_RNDN);
            double err = mpfr_get_d(w, MPFR_RNDU);
            INFO("op " << op << " a " << hex(a.hi) << "+" << hex(a.lo) << " b " << hex(b.hi) << "+"
                       << hex(b.lo));
            REQUIRE(err <= r.e);
        }
    }
    mpfr_clears(x, y, z, w, (mpfr_ptr) nullptr);
}

TEST_CASE("BoundedDD decides a sign only when it is certain, and keeps exact zeros exact") {
    BoundedDD a(0.1), b(3.0);
    BoundedDD p = a * b; // a product of two doubles is exact
    CHECK(p.e == 0);
    CHECK(sign(a - a) == 0); // so is a sum of two: an exact zero is decided
    // A sum of double-doubles is not tracked as exact: its zero is left to the exact rung.
    CHECK(sign(p - p) == exact_form::undecided);
    BoundedDD q = p * BoundedDD(1.0 / 3.0); // inexact: carries a bound
    CHECK(q.e > 0);
    CHECK(sign(q - q) == exact_form::undecided); // zero within the bound: not decided
    CHECK(sign(q) == 1);
    BoundedDD huge(0x1p+1000);
    CHECK(sign(huge * huge * huge - huge) == exact_form::undecided); // overflow decides nothing
}

TEST_CASE("correct rounds ties to even, as the oracle does") {
    // Along the x axis through a cylinder of radius r around the z axis: t = -x0 -+ r exactly.
    auto line_across = [](double x0, double r) {
        return std::pair<Shape, Line>{Cylinder{{0, 0, -1}, {0, 0, 1}, r, true},
                                      Line{{x0, 0, 0}, {1, 0, 0}, Range::line}};
    };
    SECTION("1 +- 2^-53: a midpoint rounds to the even 1, the other root is a double") {
        auto [s, l] = line_across(-1, 0x1p-53);
        Result r = correct_solve(s, l);
        REQUIRE(r.count == 2);
        CHECK(r.hits[0].t == 1 - 0x1p-53);
        CHECK(r.hits[1].t == 1.0); // 1 + 2^-53 is halfway to 1 + 2^-52
        CHECK(r.hits[0].p.x == -0x1p-53);
        CHECK(r.hits[1].p.x == 0x1p-53);
        check_same_answer(r, exact::intersect(s, l));
    }
    SECTION("-1 +- 2^-54: both roots round to -1") {
        auto [s, l] = line_across(1, 0x1p-54);
        Result r = correct_solve(s, l);
        REQUIRE(r.count == 2);
        CHECK(r.hits[0].t == -1.0);
        CHECK(r.hits[1].t == -1.0); // -1 + 2^-54 is halfway to -(1 - 2^-53): even is -1
        check_same_answer(r, exact::intersect(s, l));
    }
}

TEST_CASE("correct rounds beyond double's range to infinity, and into subnormals, as the oracle") {
    SECTION("a root beyond DBL_MAX") {
        Cylinder s{{0, 0, -1}, {0, 0, 1}, 1, true};
        Line l{{-0x1p+1000, 0, 0}, {0x1p-100, 0, 0}, Range::line};
        Result r = correct_solve(s, l);
        REQUIRE(r.ok());
        REQUIRE(r.count == 2);
        CHECK(std::isinf(r.hits[0].t));
        CHECK(r.rung == Rung::exact); // the double-double rung cannot scale there
        check_same_answer(r, exact::intersect(s, l));
    }
    SECTION("roots in the subnormal range") {
        Cylinder s{{0, 0, -1}, {0, 0, 1}, 0x1p-1060, true};
        Line l{{0x1.8p-1060, 0, 0}, {3, 0, 0}, Range::line}; // t = (-x0 -+ r) / 3
        Result r = correct_solve(s, l);
        REQUIRE(r.count == 2);
        CHECK(r.hits[0].t < 0);
        CHECK(std::fabs(r.hits[1].t) < 0x1p-1022);
        check_same_answer(r, exact::intersect(s, l));
    }
}

TEST_CASE("correct answers exactly where exact zeros decide: on the surface, at the apex") {
    SECTION("a line on the cylinder, clipped by the extent and the segment") {
        Cylinder s{{0, 0, 0}, {0, 0, 4}, 1, true};
        Line l{{1, 0, -1}, {0, 0, 2}, Range::segment};
        Result r = correct_solve(s, l);
        REQUIRE(r.on_surface);
        CHECK(r.s0 == 0.5);
        CHECK(r.s1 == 1.0);
        CHECK(r.rung == Rung::exact);
        check_same_answer(r, exact::intersect(s, l));
    }
    SECTION("a line through the cone's apex") {
        EllipticCone s{{0, 0, 0}, {0, 0, 1}, {1, 0, 0}, {0, 1, 0}, true};
        Line l{{-0.25, 0, 2}, {0.25, 0, -1}, Range::line}; // through the apex at t = 1
        Result r = correct_solve(s, l);
        check_same_answer(r, exact::intersect(s, l));
        REQUIRE(r.count >= 1);
        CHECK(r.hits[0].t == 1.0);
        CHECK(r.hits[0].kind == HitKind::tangent);
    }
}

TEST_CASE("correct equals the oracle bit for bit on every family, range and query") {
    // Every query but the hit test, whose t is not rounded: checked against the oracle's roots
    // and its own bound.
    const Query queries[] = {{Need::all, true}, {Need::nearest, false}, {Need::any, true}};
    std::uint64_t by_rung[4] = {};
    for_each_family_case(31, 60, Precision::binary64, [&](const Case& c) {
        for (Query q : queries) {
            Result got = correct_solve(c.shape, c.line, q);
            INFO(format_case(c));
            if (q.need == Need::any)
                check_hit_test(got, exact::intersect(c.shape, c.line));
            else
                check_same_answer(got, exact::intersect(c.shape, c.line, q));
            if (got.ok()) {
                ++by_rung[std::size_t(got.rung)];
                CHECK(got.certainty == Certainty::certain);
            }
        }
    });
    // Every rung is exercised, and only they answer.
    CHECK(by_rung[std::size_t(Rung::none)] == 0);
    CHECK(by_rung[std::size_t(Rung::newton)] > 0);
    CHECK(by_rung[std::size_t(Rung::double_double)] > 0);
    CHECK(by_rung[std::size_t(Rung::exact)] > 0);
}

TEST_CASE("correct's hit test: proven on its quick rung almost always, never beyond the oracle") {
    // Every family, shape and range, and ranges ending a few ulps from a root: each answer must
    // be the oracle's (a hit within its bound of an oracle root, or none); on generic cases the
    // quick rung (Rung::newton, t not rounded) must give nearly all of them.
    std::mt19937_64 rng(5);
    long generic = 0, generic_quick = 0, checked = 0;
    for (int f = 0; f < family_count; ++f)
        for (int shape = 0; shape < shape_kinds; ++shape) {
            if (!family_applies(Family(f), shape)) continue;
            for (Range range : {Range::line, Range::ray, Range::segment})
                for (std::uint64_t i = 0; i < 80; ++i) {
                    Case c = make_case(Family(f), shape, range, 71, i);
                    Result all = exact::intersect(c.shape, c.line);
                    if (i % 4 == 3 && all.count > 0) { // a range ending within ulps of a root
                        double t = all.hits[rng() % all.count].t;
                        for (int k = int(rng() % 5) - 2; k != 0; k += k > 0 ? -1 : 1)
                            t = std::nextafter(t, k > 0 ? INFINITY : -INFINITY);
                        c.line.range = rng() % 2 ? Interval(t, INFINITY) : Interval(-INFINITY, t);
                        all = exact::intersect(c.shape, c.line);
                    }
                    Result got = correct_solve(c.shape, c.line, {Need::any, false});
                    INFO(format_case(c));
                    check_hit_test(got, all);
                    ++checked;
                    // The frustum, the plane and the quadric have no quick rung (no Newton
                    // form): the ladder answers.
                    bool quick_rung = !std::holds_alternative<Frustum>(c.shape) &&
                                      !std::holds_alternative<Plane>(c.shape) &&
                                      !std::holds_alternative<Quadric>(c.shape);
                    if (Family(f) == Family::generic && c.line.range == Interval(range) &&
                        quick_rung) {
                        ++generic;
                        // A hit from the quick rung carries its enclosure, wider than the
                        // half ulp a rounded t would; a miss is proven by either Newton rung.
                        generic_quick += got.rung == Rung::newton &&
                                         (got.count == 0 ||
                                          got.hits[0].bound > Binary64::half_ulp(got.hits[0].t));
                    }
                }
        }
    INFO(generic_quick << " of " << generic << " generic hit tests on the quick rung");
    CHECK(generic_quick * 10 >= generic * 9);
    CHECK(checked > 4000);
}

TEST_CASE("correct answers convex closed shapes on the Newton rung: discs, sides, misses") {
    // Lines through both discs, through a disc and the side (a cone's steep line: the rays of
    // A < 0), through the side alone, and past an end: each answered on the Newton rung (a disc's
    // t rounded from its rational value), as the oracle answers, for every query.
    Vec3 C{0, 0, 0}, H{0, 0, 4};
    struct Closed {
        Shape shape;
        Line line;
        Part first, second; // the parts of the hits (Part::lateral twice; none when missed)
        int hits;
    };
    // Lines whose hits are not at round t: a point L0 + t v at t = 1 can be a tie between two
    // doubles, whose rounding no enclosure proves (the next rungs answer it).
    Line discs{{0.1, 0.2, -1.3}, {0.05, 0.03, 1.1}, Range::line};
    Line side{{-5, 0.1, 2}, {1, 0, 0.1}, Range::line};
    Line past_top{{-5, 0.1, 6}, {1, 0, 0.1}, Range::line};
    Line base_then_side{{0.2, 0, -1.3}, {0.5, 0.01, 1.1}, Range::line};
    Cylinder cylinder{C, H, 1, true, true};
    EllipticCylinder elliptic{C, {1, 0, 0}, {0, 1, 0}, {0, 0, 4}, true, true};
    EllipticCone cone{C, H, {2, 0, 0}, {0, 2, 0}, true, true};
    Frustum frustum{C, 2, H, 1, true, true};
    const Closed cases[] = {
        {cylinder, discs, Part::base, Part::top, 2},
        {cylinder, side, Part::lateral, Part::lateral, 2},
        {cylinder, past_top, Part::lateral, Part::lateral, 0},
        {cylinder, base_then_side, Part::base, Part::lateral, 2},
        {elliptic, discs, Part::base, Part::top, 2},
        {elliptic, base_then_side, Part::base, Part::lateral, 2},
        {elliptic, past_top, Part::lateral, Part::lateral, 0},
        {frustum, discs, Part::base, Part::top, 2},
        {frustum, side, Part::lateral, Part::lateral, 2},
        {frustum, past_top, Part::lateral, Part::lateral, 0},
        // A steep line (A < 0) into the base and out of the side; a shallow one through the side.
        {cone, Line{{0.1, 0, -1.3}, {0.1, 0.01, 1}, Range::line}, Part::base, Part::lateral, 2},
        {cone, Line{{-5, 0, 1}, {1, 0, 0}, Range::line}, Part::lateral, Part::lateral, 2},
    };
    for (const Closed& c : cases) {
        for (Query q :
             {Query{Need::all, true}, Query{Need::nearest, true}, Query{Need::all, false}}) {
            Result got = correct_solve(c.shape, c.line, q);
            INFO(shape_name(c.shape) << " L0 " << c.line.L0.x << " " << c.line.L0.y << " "
                                     << c.line.L0.z << " need " << int(q.need));
            check_same_answer(got, exact::intersect(c.shape, c.line, q));
            CHECK(got.rung == Rung::newton);
            int want = q.need == Need::all ? c.hits : std::min(c.hits, 1);
            REQUIRE(got.count == want);
            if (want > 0) CHECK(got.hits[0].part == c.first);
            if (want > 1) CHECK(got.hits[1].part == c.second);
        }
        // The hit test, on its quick rung: a hit where there are hits, none past the end.
        Result any = correct_solve(c.shape, c.line, {Need::any, false});
        check_hit_test(any, exact::intersect(c.shape, c.line));
        CHECK(any.rung == Rung::newton);
    }
}

TEST_CASE("correct decides roots at and beside an extent's end on the Newton rung") {
    // The rim point (3, 4, 4) of a radius-5 cylinder from z = 0 to 4: a line through it exactly
    // (at t = 1/2; its other root inside the extent), one that grazes it from above the top, and
    // the first moved four ulps up, beside the rim (its points still doubles, not ties). The
    // rung's enclosures cannot tell a root at an end from one an ulp away. At the rim the Newton
    // rung answers from the exact sign of the quadratic where the line crosses the end's plane (a
    // rim belongs to its disc; on an open shape a root at an end is a hit); beside it, the root
    // is placed against that end's plane crossing in double-double on the Newton rung (a closed
    // shape's disc, an open shape's end alike). Each as the oracle answers it.
    Vec3 C{0, 0, 0}, H{0, 0, 4};
    Line through{{4, 3.75, 4.5}, {-2, 0.5, -1}, Range::line};
    Line grazing{{4, 3.75, 3.5}, {-2, 0.5, 1}, Range::line};
    Line beside{{4, 3.75, 4.5 + 0x1p-48}, {-2, 0.5, -1}, Range::line};
    struct AtEnd {
        Line line;
        bool caps;
        int hits;
        Part first;
        HitKind kind;
        Rung rung;
    };
    const AtEnd cases[] = {
        {through, false, 2, Part::lateral, HitKind::cross, Rung::newton},
        {through, true, 2, Part::top, HitKind::cross, Rung::newton},
        {grazing, false, 1, Part::lateral, HitKind::cross, Rung::newton},
        {grazing, true, 1, Part::top, HitKind::tangent, Rung::newton},
        {beside, false, 1, Part::lateral, HitKind::cross, Rung::newton},
        {beside, true, 2, Part::top, HitKind::cross, Rung::newton},
    };
    for (const AtEnd& c : cases) {
        Cylinder cylinder{C, H, 5, true, c.caps};
        EllipticCylinder elliptic{C, {5, 0, 0}, {0, 5, 0}, {0, 0, 4}, true, c.caps};
        for (Shape shape : {Shape(cylinder), Shape(elliptic)}) {
            for (Query q : {Query{Need::all, true}, Query{Need::nearest, true}}) {
                INFO(shape_name(shape)
                     << " caps " << c.caps << " L0.z " << c.line.L0.z << " need " << int(q.need));
                Result got = correct_solve(shape, c.line, q);
                check_same_answer(got, exact::intersect(shape, c.line, q));
                CHECK(got.rung == c.rung);
                REQUIRE(got.count == (q.need == Need::all ? c.hits : 1));
                CHECK(got.hits[0].part == c.first);
                CHECK(got.hits[0].kind == c.kind);
            }
        }
    }
}

TEST_CASE("correct answers lines parallel to a cylinder's axis on the Newton rung") {
    // A cylinder along z from C to H, its ends and the lines' starts not dyadic: the rung's
    // bounds cannot tell A from 0, nor the double-double rung B; exact products show that each
    // line is parallel to the axis (g constant along it), and the double-double bound gives C0's
    // sign. Inside the quadric (C0 < 0) a closed cylinder meets the line at its two discs, in
    // the order dZ's sign gives, and an open one nowhere; outside, no shape meets it. Each as the
    // oracle answers it.
    Vec3 C{0.1, 0.2, 0.3}, H{0.1, 0.2, 4.3};
    struct Parallel {
        Line line;
        bool caps;
        int hits;
        Part first;
    };
    const Line inside_up{{1.1, 2.3, -1.7}, {0, 0, 1.5}, Range::line};
    const Line inside_down{{-2.9, 0.7, 9.1}, {0, 0, -0.3}, Range::line};
    const Line outside{{5.3, 2.3, -1.7}, {0, 0, 1.5}, Range::line};
    const Parallel cases[] = {
        {inside_up, true, 2, Part::base},     {inside_down, true, 2, Part::top},
        {inside_up, false, 0, Part::lateral}, {inside_down, false, 0, Part::lateral},
        {outside, true, 0, Part::lateral},    {outside, false, 0, Part::lateral},
    };
    for (const Parallel& c : cases) {
        Cylinder cylinder{C, H, 5, true, c.caps};
        for (Query q :
             {Query{Need::all, true}, Query{Need::nearest, true}, Query{Need::any, false}}) {
            INFO("caps " << c.caps << " L0 " << c.line.L0.x << " need " << int(q.need));
            Result got = correct_solve(cylinder, c.line, q);
            check_same_answer(got, exact::intersect(cylinder, c.line, q));
            CHECK(got.rung == Rung::newton);
            REQUIRE(got.count == (q.need == Need::all ? c.hits : std::min(c.hits, 1)));
            if (got.count > 0) CHECK(got.hits[0].part == c.first);
            for (int i = 0; i < got.count; ++i)
                CHECK(got.hits[i].kind == HitKind::cross);
        }
    }
}

TEST_CASE("correct answers a line in a disc's plane on the Newton rung") {
    // A case of the rim family: the line lies in the base disc's plane, (L0 - C).h = v.h = 0
    // exactly, h = H - C, and crosses the disc. The answer is the chord between the lateral
    // roots, on the disc's surface, cut to the range; the Newton rung encloses the roots and the
    // exact products show the plane. Each as the oracle answers it.
    Cylinder drum{{-6, 4, 1}, {-22, -12, 9}, 36, true, true};
    Line line{{-30, 47.5, 40}, {24, -39, -30}, Range::line};
    Result whole = exact::intersect(drum, line);
    REQUIRE(whole.on_surface);
    REQUIRE(whole.surface_part == Part::base);
    double mid = 0.5 * (whole.s0 + whole.s1), inf = std::numeric_limits<double>::infinity();
    // The whole chord; from its middle on (cut there); a piece inside it (the range's ends); and
    // from past its end (nothing). The exact products answer at once, before the double-double
    // rung is tried.
    const Interval pieces[] = {Range::line, {mid, inf}, {mid, mid + 0.25}, {2 * whole.s1, inf}};
    for (const Interval& piece : pieces) {
        Line l{line.L0, line.v, piece};
        for (Query q : {Query{Need::all, true}, Query{Need::any, false}}) {
            INFO("range " << l.range.t0 << " to " << l.range.t1 << " need " << int(q.need));
            Result got = correct_solve(drum, l, q);
            check_same_answer(got, exact::intersect(drum, l, q));
            CHECK(got.rung == Rung::newton);
        }
    }
}

TEST_CASE("correct answers a line beside a disc's plane on the Newton rung") {
    // The line of the test above moved a few ulps off the base's plane, still parallel to it
    // (v.h = 0 exactly): Z is constant along it, a few ulps inside the extent (the chord between
    // the lateral roots, inside the solid) or outside it (nothing). The rung's bounds cannot
    // tell which; the exact products (L0 - C).h and (L0 - H).h can. Each as the oracle answers.
    Cylinder drum{{-6, 4, 1}, {-22, -12, 9}, 36, true, true};
    for (int ulps = -4; ulps <= 4; ++ulps) {
        if (ulps == 0) continue;
        double z = 40;
        for (int k = 0; k < std::abs(ulps); ++k)
            z = std::nextafter(z, ulps > 0 ? 100.0 : 0.0);
        Line line{{-30, 47.5, z}, {24, -39, -30}, Range::line};
        for (Query q : {Query{Need::all, true}, Query{Need::any, false}}) {
            INFO("ulps " << ulps << " need " << int(q.need));
            Result got = correct_solve(drum, line, q), want = exact::intersect(drum, line, q);
            check_same_answer(got, want);
            CHECK(got.rung == Rung::newton);
            CHECK(want.count == (ulps > 0 ? (q.need == Need::all ? 2 : 1) : 0));
        }
    }
}

TEST_CASE("correct answers lines in and beside any closed shape's disc plane on the Newton rung") {
    // The same for the shapes whose Z is a determinant (an elliptic cylinder's and an elliptic
    // cone's, det[a b P - O]) or a frustum's dot product: a line along a and b (or across h) in
    // a disc's plane exactly, and moved 1 to 3 ulps across it along x. dZ = 0 and Z0's level come
    // from exact signs of determinants (det3_sign_exact) and products, before any other rung.
    // Each as the oracle answers it.
    Vec3 C{1, 2, 3}, a{3, 0, 1}, b{0, 2, 0}, c{1, 1, 4};
    EllipticCylinder cylinder{C, a, b, c, true, true};
    EllipticCone cone{C, C + c, a, b, true, true};
    Frustum frustum{{1, 2, 3}, 3, {3, 2, 4}, 1.5, true, true};
    struct InPlane {
        Shape shape;
        Line line;
    };
    const InPlane cases[] = {
        // The base disc's plane through C: L0 - C = a/4 + b/2, v = a - b.
        {cylinder, {{1.75, 3, 3.25}, {3, -2, 1}, Range::line}},
        // The top's through C + c = (2, 3, 7).
        {cylinder, {{2.75, 4, 7.25}, {3, -2, 1}, Range::line}},
        {cone, {{1.75, 3, 3.25}, {3, -2, 1}, Range::line}},
        // The frustum's base through C0 across h = (2, 0, 1): v = (1, 5, -2), L0 = C0 + (0, 1/2,
        // 0).
        {frustum, {{1, 2.5, 3}, {1, 5, -2}, Range::line}},
    };
    for (const InPlane& c : cases)
        for (int ulps = -3; ulps <= 3; ++ulps) {
            Line line = c.line;
            for (int k = 0; k < std::abs(ulps); ++k)
                line.L0.x = std::nextafter(line.L0.x, ulps > 0 ? 100.0 : -100.0);
            for (Query q : {Query{Need::all, true}, Query{Need::any, false}}) {
                INFO(shape_name(c.shape) << " L0 " << hex(line.L0.x) << " need " << int(q.need));
                Result got = correct_solve(c.shape, line, q), all = exact::intersect(c.shape, line);
                if (q.need == Need::any)
                    check_hit_test(got, all);
                else
                    check_same_answer(got, all);
                CHECK(got.rung == Rung::newton);
                if (ulps == 0) CHECK(all.on_surface);
            }
        }
}

TEST_CASE(
    "correct proves most roots of lines from 2^10 to 2^19 shape sizes away on the Newton rung") {
    // The far_origin family's lines from that far: the double estimate of a root loses k bits
    // to cancellation, so one Newton step from it leaves an enclosure too wide to round t: of
    // these 1,600 lines the rung proved 817 with one step, and proves 1,436 with the further
    // steps from the refined root. What they cannot narrow (near-tangent lines) goes on to the
    // next rungs. Every answer as the oracle's.
    int lines = 0, on_newton = 0;
    for (int shape = 0; shape < 4; ++shape)
        for (std::uint64_t i = 0; lines < 400 * (shape + 1) && i < 20000; ++i) {
            Case c = make_case(Family::far_origin, shape, Range::line, 3, i);
            if (c.k < 10 || c.k > 19) continue;
            Result got = correct_solve(c.shape, c.line, {Need::all, true});
            INFO(c.id);
            check_same_answer(got, exact::intersect(c.shape, c.line, {Need::all, true}));
            ++lines, on_newton += got.rung == Rung::newton;
        }
    CHECK(lines == 1600);
    CHECK(on_newton >= lines * 8 / 10);
}

namespace {
// The exact rung alone, as the ladder calls it on a line none of the rungs before could answer:
// from the exact form of the line as given, with its double-double filter first or not.
Result exact_rung_alone(const Shape& shape, const Line& l, Query q, bool filter_first) {
    return std::visit(
        [&](const auto& s) {
            using S = std::decay_t<decltype(s)>;
            if constexpr (!(std::is_same_v<S, Cylinder> || std::is_same_v<S, EllipticCylinder> ||
                            std::is_same_v<S, EllipticCone> || std::is_same_v<S, Frustum>)) {
                FAIL("no single exact form for this shape");
                return Result();
            } else {
                detail::AsGiven<S> src{s};
                detail::Validity valid = detail::check(src, l);
                REQUIRE(valid.error.ok());
                exact_form::LineQuadratic<BigFloat> eq =
                    detail::ShapeTraits<S>::template exact_quadratic<BigFloat>(s, l,
                                                                               valid.orientation);
                BigFloat D = eq.B * eq.B - eq.A * eq.C0;
                return detail::exact_rung<Binary64>(eq, D, l, q, filter_first);
            }
        },
        shape);
}
} // namespace

TEST_CASE("correct's exact rung rounds the points of lines from 2^20 to 2^60 sizes away exactly") {
    // The exact rung forms a point from t's double-double enclosure where its bound proves the
    // rounding (t carries about 100 bits, and a point 2^k sizes from the line's origin needs
    // 53 + k), and exactly from the surd otherwise: lines from that far need both. The ladder
    // answers most of these on the Newton rung (its estimates taken again at the vertex, each
    // root's enclosure about x0 phi(y): 1,022 of 1,200; fewer than 700 before), so the exact
    // rung is run alone too, with its filter and without. Every point as the oracle's.
    int lines = 0, on_newton = 0;
    for (int shape = 0; shape < 4; ++shape)
        for (std::uint64_t i = 0; lines < 300 * (shape + 1) && i < 40000; ++i) {
            Case c = make_case(Family::far_origin, shape, Range::line, 5, i);
            if (c.k < 20) continue;
            for (Query q : {Query{Need::all, true}, Query{Need::nearest, true}}) {
                Result want = exact::intersect(c.shape, c.line, q);
                Result got = correct_solve(c.shape, c.line, q);
                INFO(c.id << " k " << c.k);
                check_same_answer(got, want);
                for (bool filter_first : {true, false})
                    check_same_answer(exact_rung_alone(c.shape, c.line, q, filter_first), want);
                on_newton += q.need == Need::all && got.rung == Rung::newton;
            }
            ++lines;
        }
    CHECK(lines == 1200);
    CHECK(on_newton >= lines * 8 / 10);
}

namespace {
// Over `count` lines of a family (shapes first_shape to last_shape, each as many): each answer
// as the oracle's, for every hit and the nearest; how many the Newton rung answered.
int on_newton_rung(Family family, int first_shape, int last_shape, std::uint64_t seed, int count) {
    int lines = 0, on_newton = 0, shapes = last_shape - first_shape + 1;
    for (int shape = first_shape; shape <= last_shape; ++shape)
        for (std::uint64_t i = 0; lines < count / shapes * (shape - first_shape + 1); ++i) {
            Case c = make_case(family, shape, i % 2 ? Range::ray : Range::line, seed, i);
            for (Query q : {Query{Need::all, true}, Query{Need::nearest, true}}) {
                Result got = correct_solve(c.shape, c.line, q);
                INFO(c.id << " k " << c.k);
                check_same_answer(got, exact::intersect(c.shape, c.line, q));
                on_newton += q.need == Need::all && got.rung == Rung::newton;
            }
            ++lines;
        }
    return on_newton;
}
} // namespace

TEST_CASE("correct proves roots a few ulps from the line's origin on the Newton rung") {
    // The inside_start family: lines starting inside a closed shape, on its surface or 2^-k
    // outside it. A root a few ulps from t = 0, or a disc's crossing there, is tiny beside the
    // rung's bounds (absolute, about 2^-100 of the scene): its t cannot be rounded from them.
    // The exact form's local quadratic at the root, whose value is enclosed relatively, and the
    // disc's crossing from the exact form, prove it on the rung: 1,390 of 1,400 lines over the
    // seven shapes (1,124 without them, 1,340 before a root at the line's origin was tried
    // whatever the range). Every answer as the oracle's.
    CHECK(on_newton_rung(Family::inside_start, 0, 6, 21, 1400) >= 1380);
}

TEST_CASE("correct places roots at and beside open ends and seams on the Newton rung") {
    // extent_edge: open shapes' lines through a rim point (a third of them), or moved 2^-40 to
    // 2^-53 along the axis beside it; seam: a capsule's lines through a seam point or a few ulps
    // from it. The rung's Z, in double, leaves such a root's side of the end open; the end's
    // plane in double-double (ExtentEnds::end_planes) places it, and a coordinate at or beside
    // zero (the rim point of an axis-aligned frame) comes from the exact form. 1,200 and 1,130
    // of 1,200 lines on the Newton rung (936 and 744 before them; the ties placed since then
    // took extent_edge from 1,166 to all). Every answer as the oracle's.
    CHECK(on_newton_rung(Family::extent_edge, 0, 3, 23, 1200) >= 1195);
    CHECK(on_newton_rung(Family::seam, 6, 6, 23, 1200) >= 1080);
}

TEST_CASE("correct rounds a lateral hit beside a coordinate plane on the Newton rung") {
    // The rim family: lines through a rim point, or one moved a few ulps. Where the frame is
    // axis-aligned, a moved hit's coordinate lies a few ulps from 0, where L0_k + t v_k cancels
    // and t's bound (about 2^-100 of the scene) cannot round it. That coordinate is a root of its
    // own quadratic, from the exact form's coefficients (ExtentEnds::coordinate_roots), enclosed
    // relative to itself: 1,565 of 1,600 lines on the Newton rung (1,464 without it, and
    // without the tangency at an end and the tie that came after it). Every answer as the
    // oracle's.
    CHECK(on_newton_rung(Family::rim, 0, 3, 25, 1600) >= 1555);
}

TEST_CASE("correct answers lines parallel to a cone's generator on the Newton rung") {
    // The two_nappes family (a two-nappe cone, open or closed) has lines parallel to a
    // generator: A = 0, which the rung's bounds cannot tell from 0. Where B != 0 too, g is linear
    // and crosses the quadric once, at -C0 / 2B (ExtentEnds::linear_root); a closed cone meets
    // the ray beyond it, inside one nappe, up to a disc. 1,064 of 1,200 lines on the rung (950
    // without it). Every answer as the oracle's.
    CHECK(on_newton_rung(Family::two_nappes, 2, 2, 26, 1200) >= 1050);
}

TEST_CASE("correct answers a tangency at a rim or a cone's apex on the Newton rung") {
    // rim: lines touching a shape at a rim point (or one moved a few ulps); apex: lines through
    // or beside a cone's apex, some touching it. The tangency (D = 0 exactly) lies at an end or
    // within ulps of it, which its enclosure cannot tell; its side of that end is the sign of a
    // few exact products (ExtentEnds::vertex_against). At it, the end's point: kept where the
    // extent is closed, as the disc's where there is one. 1,179 and 1,047 of 1,200 lines on the
    // rung (1,126 and 1,008 without it and the tie that came after it). Every answer as the
    // oracle's.
    CHECK(on_newton_rung(Family::rim, 0, 3, 27, 1200) >= 1170);
    CHECK(on_newton_rung(Family::apex, 2, 3, 27, 1200) >= 1040);
}

TEST_CASE("correct rounds a t or a coordinate at or beside a tie on the Newton rung") {
    // rim and extent_edge: lines through a rim point of small integers, or one moved a few ulps:
    // a hit's t or coordinate can lie exactly on, or within its enclosure of, the midpoint of two
    // doubles, which no enclosure rounds. Its sign against that midpoint is exact from the exact
    // form (g and g' there for t; a root of the coordinate's quadratic, or an end's crossing, for
    // a coordinate): beyond it, the double past it; on it, the even one. 1,174 and all 1,200 lines
    // on the Newton rung (1,145 and 1,180 without either). Every answer as the oracle's.
    CHECK(on_newton_rung(Family::rim, 0, 3, 28, 1200) >= 1170);
    CHECK(on_newton_rung(Family::extent_edge, 0, 3, 28, 1200) == 1200);
}

TEST_CASE("correct proves a root at the line's origin on the Newton rung whatever the range") {
    // inside_start on the ellipsoid: lines starting on its surface (t = 0 a root), most of them
    // lines with no range end there. t = 0 has no rounding cell an enclosure can prove; the
    // local quadratic formed exactly at the origin shows the root there exactly. 1,197 of 1,200
    // lines on the rung (1,095 where only a range's end was tried). Every answer as the oracle's.
    CHECK(on_newton_rung(Family::inside_start, 5, 5, 29, 1200) >= 1190);
}

TEST_CASE("correct finds a steep line's nappe beside the apex on the Newton rung") {
    // cap_axis on the closed cone and frustum: lines along the axis, some moved 2^-k beside it,
    // so through or beside the apex. A line steeper than the generators (A < 0) has a root on
    // each nappe; beside the apex neither root's Z (the frustum's R) has a proven sign, but the
    // roots are apart and Z is linear in t, so the one with the smaller Z (larger R) is on the
    // solid's nappe. 1,144 of 1,200 lines on the rung (1,096 without it). Every answer as the
    // oracle's.
    CHECK(on_newton_rung(Family::cap_axis, 2, 3, 30, 1200) >= 1135);
}

namespace {
// Each of 12 cases of every family, shape and range (seed `seed`), valid ones only, as visit(s,
// line, orientation) for each shape, or for each of a capsule's three patches.
template <class Visit>
void for_each_patch_case(std::uint64_t seed, Visit visit) {
    for (int f = 0; f < family_count; ++f)
        for (int shape = 0; shape < shape_kinds; ++shape) {
            if (!family_applies(Family(f), shape)) continue;
            for (Range range : {Range::line, Range::ray, Range::segment})
                for (std::uint64_t i = 0; i < 12; ++i) {
                    Case c = make_case(Family(f), shape, range, seed, i);
                    INFO(format_case(c));
                    std::visit(
                        [&](const auto& s) {
                            using S = std::decay_t<decltype(s)>;
                            detail::Validity valid = detail::check(detail::AsGiven<S>{s}, c.line);
                            if (!valid.error.ok()) return;
                            if constexpr (std::is_same_v<S, Capsule>) {
                                auto [side, base, top] = detail::ShapeTraits<Capsule>::patches(s);
                                visit(side, c.line, 0);
                                visit(base, c.line, 0);
                                visit(top, c.line, 0);
                            } else {
                                visit(s, c.line, valid.orientation);
                            }
                        },
                        c.shape);
                }
        }
}
} // namespace

namespace {
// Shape S's Z alone (exact_axial, where it has one) against its exact quadratic's Z: equal values
// (exact, so compared exactly) and the same bounded ends.
template <class S>
void check_axial(const S& s, const Line& l, int orientation, long& compared) {
    if constexpr (detail::has_exact_axial<S>) {
        using Traits = detail::ShapeTraits<S>;
        exact_form::LineAxial<BigFloat> z =
            Traits::template exact_axial<BigFloat>(s, l, orientation);
        exact_form::LineQuadratic<BigFloat> q =
            Traits::template exact_quadratic<BigFloat>(s, l, orientation);
        CHECK(sign(z.Z0 - q.Z0) == 0);
        CHECK(sign(z.dZ - q.dZ) == 0);
        CHECK(sign(z.lo - q.lo) == 0);
        CHECK(sign(z.hi - q.hi) == 0);
        CHECK(z.lo_bounded == q.lo_bounded);
        CHECK(z.hi_bounded == q.hi_bounded);
        ++compared;
    }
}
} // namespace

TEST_CASE("each shape's Z alone (exact_axial) is its exact quadratic's Z exactly") {
    // The Newton rung asks for Z alone at an end's crossing (exact_axial: a few dot products);
    // the exact rung for the whole quadratic. Both must be one form: every family, shape (the
    // capsule's three patches) and range, either orientation of an elliptic frame.
    long compared = 0;
    for_each_patch_case(72, [&](const auto& s, const Line& l, int orientation) {
        check_axial(s, l, orientation, compared);
    });
    CHECK(compared > 2000);
}

namespace {
// Shape S's exact form in double (ExactDouble) against its exact form in BigFloat: where every
// coefficient is exact, each equal exactly; where one is not, it is declined (counted).
template <class S>
void check_in_double(const S& s, const Line& l, int orientation, long& exact, long& rounded) {
    using Traits = detail::ShapeTraits<S>;
    exact_form::LineQuadratic<ExactDouble> d =
        Traits::template exact_quadratic<ExactDouble>(s, l, orientation);
    exact_form::LineQuadratic<BigFloat> q =
        Traits::template exact_quadratic<BigFloat>(s, l, orientation);
    const std::pair<const ExactDouble*, const BigFloat*> pairs[] = {
        {&d.A, &q.A},   {&d.B, &q.B},   {&d.C0, &q.C0}, {&d.Z0, &q.Z0},
        {&d.dZ, &q.dZ}, {&d.lo, &q.lo}, {&d.hi, &q.hi}};
    for (auto [x, y] : pairs) {
        if (!x->exact) {
            ++rounded;
            continue;
        }
        CHECK(sign(BigFloat(x->v) - *y) == 0);
        exact += x->v != 0; // a zero (an ellipsoid's Z0, a base at 0) is exact for any input
    }
    // Which ends belong to other parts, asked of the type (ExactForm::end_open), is the form's.
    CHECK((q.lo_open && q.hi_open) == detail::ends_open<S>);
    CHECK((q.lo_open || q.hi_open) == detail::ends_open<S>);
}
} // namespace

TEST_CASE("each shape's exact form in double, where nothing rounds, is its exact form") {
    // The exact form in double (ExactDouble: every sum's and product's error zero) stands for the
    // BigFloat one where the inputs are small dyadic numbers (a frame of small integers: a line
    // through a rim, along an axis, in a disc's plane). Every family, shape (the capsule's three
    // patches) and range: each coefficient that says it is exact must equal BigFloat's, and
    // most generic coefficients must say they are not.
    long exact = 0, rounded = 0;
    for_each_patch_case(73, [&](const auto& s, const Line& l, int orientation) {
        check_in_double(s, l, orientation, exact, rounded);
    });
    CHECK(exact > 2000);   // 2,347 nonzero coefficients exact in double
    CHECK(rounded > 3000); // 15,244 that round
}

namespace {
// Shape S's sign of D from its form of lower degree (discriminant_sign), and a cylinder's
// tangency against its ends (tangency_against_end), against the exact quadratic's.
template <class S>
void check_lower_degree(const S& s, const Line& l, int orientation, long& compared, long& zeros) {
    using Traits = detail::ShapeTraits<S>;
    if constexpr (detail::has_discriminant_sign<S>) {
        exact_form::LineQuadratic<BigFloat> q =
            Traits::template exact_quadratic<BigFloat>(s, l, orientation);
        int D = sign(q.B * q.B - q.A * q.C0);
        CHECK(Traits::template discriminant_sign<BigFloat>(s, l, orientation) == D);
        ++compared, zeros += D == 0;
        if constexpr (detail::has_tangency_against_end<S>)
            if (sign(q.A) > 0 && q.lo_bounded)
                for (bool top : {false, true}) {
                    BigFloat end = top ? q.hi : q.lo;
                    CHECK(Traits::template tangency_against_end<BigFloat>(s, l, top) ==
                          sign((q.Z0 - end) * q.A - q.dZ * q.B));
                }
    }
}
} // namespace

TEST_CASE("each shape's sign of D from Lagrange's identity is its exact quadratic's") {
    // Where the Newton rung must show a tangency exactly (D = 0), the cylinder, the elliptic
    // cylinder, the cone, the sphere, the ellipsoid and the capsule's patches take D's sign from
    // a form of degree 6 (triple products of the inputs) instead of B^2 - A C0 of degree 8 or 12.
    // Every family (near_tangent and cap_plane make exact tangencies), shape and range.
    long compared = 0, zeros = 0;
    for_each_patch_case(74, [&](const auto& s, const Line& l, int orientation) {
        check_lower_degree(s, l, orientation, compared, zeros);
    });
    CHECK(compared > 2000); // 2,844
    CHECK(zeros > 50);      // 102 exact tangencies
}

namespace {
// The roots of q's quadratic in double (points near them to test at: not correctly rounded), or
// its vertex where it has none; not finite where A = 0.
std::pair<double, double> roots_near(const exact_form::LineQuadratic<BigFloat>& q) {
    double A = enclosure(q.A).hi, B = enclosure(q.B).hi, C0 = enclosure(q.C0).hi;
    double root_D = std::sqrt(std::max(0.0, B * B - A * C0));
    return {(-B - root_D) / A, (-B + root_D) / A};
}
// Whether x's enclosure holds the exact value y: |hi + lo - y| <= e, in BigFloat.
bool holds(const BoundedDD& x, const BigFloat& y) {
    BigFloat off = BigFloat(x.hi) + BigFloat(x.lo) - y;
    return sign(BigFloat(x.e) - off) >= 0 && sign(BigFloat(x.e) + off) >= 0;
}
// A sphere-like patch's local quadratic (local_at) against its exact quadratic's at t = 0 and at
// the double nearest each root: each value held by its enclosure, and G exactly 0 only where it is.
template <class S>
void check_local_at(const S& s, const Line& l, long& compared, long& exact_zeros) {
    if constexpr (detail::has_local_at<S>) {
        using Traits = detail::ShapeTraits<S>;
        exact_form::LineQuadratic<BigFloat> q = Traits::template exact_quadratic<BigFloat>(s, l, 0);
        auto [t0, t1] = roots_near(q);
        for (double t : {0.0, t0, t1, 0x1p-40}) {
            std::optional<exact_form::LocalQuadratic> L = Traits::local_at(s, l, t);
            if (!L) continue;
            BigFloat at(t), half_slope = q.B + q.A * at, G = q.C0 + at * (half_slope + q.B);
            CHECK(holds(L->A, q.A));
            CHECK(holds(L->half_slope, half_slope));
            CHECK(holds(L->G, G));
            CHECK((L->G.hi == 0 && L->G.e == 0) == (t == 0 && sign(G) == 0));
            ++compared, exact_zeros += sign(G) == 0;
        }
    }
}
} // namespace

TEST_CASE("a sphere's local quadratic from C0 exact holds the exact form's values") {
    // Where the rung's absolute bounds leave a root a few ulps from the line's origin open (a line
    // starting on or just off a sphere or a capsule's end), G = C0 + t (2B + A t) with C0 exact
    // in an expansion encloses G relative to itself, at a tenth of the BigFloat form's cost.
    long compared = 0, exact_zeros = 0;
    for_each_patch_case(75, [&](const auto& s, const Line& l, int) {
        check_local_at(s, l, compared, exact_zeros);
    });
    INFO(compared << " local quadratics, " << exact_zeros << " exact zeros");
    CHECK(compared > 1000);  // 2,286
    CHECK(exact_zeros >= 4); // 8 lines starting on the sphere (G = 0 exactly at t = 0)
}

namespace {
// Shape S's exact form in bounded double-double of the line through its point at t (line_through:
// ExactForm's cheaper local quadratic for a line from far away) against the exact form's values
// there: A, B + A t, g(t), Z0 + t dZ and dZ each held by their enclosures.
template <class S>
void check_through(const S& s, const Line& l, int orientation, long& compared) {
    using Traits = detail::ShapeTraits<S>;
    exact_form::LineQuadratic<BigFloat> q =
        Traits::template exact_quadratic<BigFloat>(s, l, orientation);
    auto [t0, t1] = roots_near(q);
    for (double t : {t0, t1, -0.75, 1e3}) {
        std::optional<exact_form::LineThrough<BoundedDD>> through = detail::line_through(l, t);
        if (!std::isfinite(t) || !through) continue;
        exact_form::LineQuadratic<BoundedDD> m =
            Traits::template exact_quadratic<BoundedDD>(s, *through, orientation);
        BigFloat at(t), half_slope = q.B + q.A * at;
        CHECK(holds(m.A, q.A));
        CHECK(holds(m.B, half_slope));
        CHECK(holds(m.C0, q.C0 + at * (half_slope + q.B)));
        CHECK(holds(m.Z0, q.Z0 + at * q.dZ));
        CHECK(holds(m.dZ, q.dZ));
        ++compared;
    }
}
} // namespace

TEST_CASE("each shape's exact form through a point of the line holds its values there") {
    // A line from far away: the exact form in double-double of the line through its point near the
    // shape keeps the digits the line's own form cancels, so that a root there is proven without
    // the BigFloat quadratic. Every family, shape and range, at both roots and two other points.
    long compared = 0;
    for_each_patch_case(76, [&](const auto& s, const Line& l, int orientation) {
        check_through(s, l, orientation, compared);
    });
    INFO(compared << " forms compared");
    CHECK(compared > 5000); // 13,118
}

TEST_CASE("correct proves the roots of thin shapes on the Newton rung") {
    // The thin family: an ellipsoid's axis 2^-k of the others. Two roots within a few ulps of
    // each other leave no double near enough to one of them for the proof at a double; the
    // local quadratic expanded again about its own root proves them (root_beside): 1,193 of
    // 1,200 lines (998 without it). Every answer as the oracle's.
    CHECK(on_newton_rung(Family::thin, 5, 5, 22, 1200) >= 1150);
}

TEST_CASE("correct answers tangent lines on the Newton rung") {
    // x = 5 = r from the axis x = 0, y = 0.2, along y (and up z): tangent to the cylinder where
    // y = 0.2. Its ends and the lines' starts are not dyadic, so neither the rung's bounds nor
    // the double-double rung's show the double root; the exact form does, and t = -B/A is then
    // rational and rounded on the rung. Inside the extent: one tangent hit (a closed cylinder's
    // too); beyond it: none. Each as the oracle answers it.
    Vec3 C{0, 0.2, 0.3}, H{0, 0.2, 4.3};
    struct Tangent {
        Line line;
        int hits;
    };
    const Tangent cases[] = {
        {{{5, 1.7, 2.9}, {0, 1.5, 0.25}, Range::line}, 1}, // touches at z = 2.65, inside
        {{{5, 1.7, 9.1}, {0, 1.5, 0.25}, Range::line}, 0}, // at z = 8.85, above the top
        {{{5, 1.7, 2.9}, {0, 1.5, 0.25}, Range::ray}, 0},  // touches at t < 0
    };
    for (const Tangent& c : cases)
        for (bool caps : {false, true}) {
            Cylinder cylinder{C, H, 5, true, caps};
            for (Query q : {Query{Need::all, true}, Query{Need::any, false}}) {
                INFO("L0.z " << c.line.L0.z << " ray " << c.line.range.has_t0() << " caps " << caps
                             << " need " << int(q.need));
                Result got = correct_solve(cylinder, c.line, q);
                check_same_answer(got, exact::intersect(cylinder, c.line, q));
                CHECK(got.rung == Rung::newton);
                REQUIRE(got.count == c.hits);
                if (got.count == 1) {
                    CHECK(got.hits[0].kind == HitKind::tangent);
                    CHECK(got.hits[0].part == Part::lateral);
                }
            }
        }
}

TEST_CASE("correct answers a tangent to a closed two-nappe cone on the Newton rung") {
    // The cone x^2 + y^2 = z^2 about the apex (0, 0.2, 0), -1 <= z <= 1, both nappes closed, and
    // lines along y in its tangent planes x = z and x = -z: g = (y - 0.2)^2 along each, a double
    // root where it touches a generator. 0.45 is not dyadic: only the exact form shows D = 0,
    // and t = -B/A is then rounded on the rung. Inside either nappe's extent: one tangent hit;
    // beyond the top: none; behind a ray's start: none. Each as the oracle answers it.
    EllipticCone cone{{0, 0.2, -1}, {0, 0.2, 0}, {1, 0, 0}, {0, 1, 0}, true, true, 2};
    struct Tangent {
        Line line;
        int hits;
    };
    const Tangent cases[] = {
        {{{0.45, 1.7, 0.45}, {0, 1.5, 0}, Range::line}, 1},   // the upper nappe, z = 0.45
        {{{0.45, 1.7, -0.45}, {0, 1.5, 0}, Range::line}, 1},  // the lower one, z = -0.45
        {{{-0.45, 1.7, 0.45}, {0, -1.5, 0}, Range::line}, 1}, // x = -z, upper
        {{{1.45, 1.7, 1.45}, {0, 1.5, 0}, Range::line}, 0},   // z = 1.45, beyond the top
        {{{0.45, 1.7, 0.45}, {0, 1.5, 0}, Range::ray}, 0},    // touches at t = -1
    };
    for (const Tangent& c : cases)
        for (Query q : {Query{Need::all, true}, Query{Need::nearest, true}}) {
            INFO("L0 " << c.line.L0.x << " " << c.line.L0.z << " ray " << c.line.range.has_t0());
            Result got = correct_solve(cone, c.line, q);
            check_same_answer(got, exact::intersect(cone, c.line, q));
            CHECK(got.rung == Rung::newton);
            REQUIRE(got.count == c.hits);
            if (got.count == 1) CHECK(got.hits[0].kind == HitKind::tangent);
        }
}

TEST_CASE("correct answers lines through a closed two-nappe cone's two solids on the Newton rung") {
    // Random closed two-nappe cones (apex H, base C at z = -1, the top disc at z = 1) and lines
    // through a point inside each nappe's solid: steeper than the generators, one ray in each
    // nappe, so up to four hits, each solid's two crossing; and lines through two points of one
    // solid (A > 0: one piece in one nappe). Each answer the oracle's, and nearly all from the
    // Newton rung, which before declined every hit on two solids.
    std::mt19937_64 rng(61);
    std::uniform_real_distribution<double> unit(-1, 1), len(0.5, 3);
    auto vec = [&](double scale) { return scale * Vec3{unit(rng), unit(rng), unit(rng)}; };
    int lines = 0, newton = 0, four = 0;
    for (int i = 0; i < 400; ++i) {
        Vec3 H = vec(4), a = vec(len(rng)), b = vec(len(rng)), c = vec(len(rng));
        EllipticCone cone{H - c, H, a, b, true, true, 2};
        // A point of the solid z0 < z < z0 + 1 (z0 = -1 or 0), strictly inside its surface.
        auto inside = [&](double z0) {
            double z = z0 + 0.05 + 0.9 * std::uniform_real_distribution<double>(0, 1)(rng);
            double rho = 0.9 * std::fabs(z) * std::uniform_real_distribution<double>(0, 1)(rng);
            double phi = std::uniform_real_distribution<double>(0, 2 * M_PI)(rng);
            return H + rho * std::cos(phi) * a + rho * std::sin(phi) * b + z * c;
        };
        bool both = i % 4 != 0;
        Vec3 P = inside(-1), Q = inside(both ? 0 : -1);
        const Range ranges[] = {Range::line, Range::ray, Range::segment};
        Line l{P - 1.5 * (Q - P), Q - P, ranges[i % 3]};
        for (Query q :
             {Query{Need::all, true}, Query{Need::nearest, true}, Query{Need::any, false}}) {
            INFO("cone " << i << " need " << int(q.need));
            Result got = correct_solve(cone, l, q), want = exact::intersect(cone, l, q);
            if (q.need == Need::any) // a hit test's hit is any one it proves
                REQUIRE((got.count > 0) == (want.count > 0));
            else
                check_same_answer(got, want);
            ++lines;
            newton += got.rung == Rung::newton;
            four += got.count == 4;
        }
    }
    INFO(newton << " of " << lines << " on the Newton rung, " << four << " with four hits");
    CHECK(newton >= lines * 9 / 10);
    CHECK(four > 50);
}
