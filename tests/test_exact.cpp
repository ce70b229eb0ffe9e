// The exact oracle: cross-checks of its number types and derivations, exact identities, and
// its rounding against a 4096-bit MPFR evaluation.
#include "support.hpp"

#include "linequad/exact.hpp"

#include <gmp.h>
#include <gmpxx.h>
#include <mpfr.h>

#include <cstring>
#include <random>
#include <string>

using namespace linequad;
using namespace linequad::test;

namespace {

struct Random : RandomReals {
    Random() : RandomReals(20261121) {}
    Range range() { return Range(rng() % 3); }
    Shape shape() {
        switch (rng() % 3) {
        case 0:
            return Cylinder{vec(4), vec(4), real(0.5, 3), rng() % 4 != 0};
        case 1:
            return EllipticCylinder{vec(4), vec(3), vec(3), vec(3), rng() % 4 != 0};
        default:
            return EllipticCone{vec(4), vec(4), vec(3), vec(3), rng() % 4 != 0};
        }
    }
    Line line() { return {vec(6), vec(2), range()}; }
};

bool same(const Result& a, const Result& b) {
    return format_result("0", "", a) == format_result("0", "", b);
}

Shape scaled(const Shape& s, double k) {
    if (auto* c = std::get_if<Cylinder>(&s))
        return Cylinder{k * c->C, k * c->H, k * c->r, c->finite};
    if (auto* e = std::get_if<EllipticCylinder>(&s))
        return EllipticCylinder{k * e->C, k * e->a, k * e->b, k * e->c, e->finite};
    const auto& n = std::get<EllipticCone>(s);
    return EllipticCone{k * n.C, k * n.H, k * n.a, k * n.b, n.finite};
}

} // namespace

TEST_CASE("exact: Mpzf and Gmpq kernels agree bit for bit", "[exact]") {
    Random r;
    int hits = 0;
    for (int i = 0; i < 3000; ++i) {
        Shape s = r.shape();
        Line l = r.line();
        Result a = exact::intersect(s, l), b = exact::intersect_gmpq(s, l);
        INFO(describe(a) << "\n" << describe(b));
        REQUIRE(same(a, b));
        hits += a.count;
    }
    CHECK(hits > 300); // the random cases do hit
}

TEST_CASE("exact: the interval filter decides as the exact path does", "[exact]") {
    // The oracle (Mpzf) takes its interval filter's misses as they are and rebuilds the roots
    // of the hits it decides from each root's form; Gmpq never filters. Every form: lines 2^-k
    // of the radius beside a closed cylinder's side and past its rims (k = 0: grazing; up to 60:
    // past what intervals decide), across its discs, in a disc's plane grazing the rim, and a
    // cone's lines parallel to a generator (A = 0) and through the apex of two nappes.
    auto agree = [](const Shape& s, const Line& l) {
        Result a = exact::intersect(s, l), b = exact::intersect_gmpq(s, l);
        CHECK(same(a, b));
        return a.count;
    };
    int hits = 0;
    std::uint64_t decided0 = exact::rounding_stats().interval_decided;
    for (int k = 0; k <= 60; ++k) {
        double d = k == 0 ? 0 : std::ldexp(1.0, -k);
        for (double side : {-1.0, 1.0}) {
            for (bool caps : {false, true}) {
                INFO("k " << k << " side " << side << " caps " << caps);
                Cylinder c{{0, 0, 0}, {0, 0, 2}, 1, true, caps};
                hits += agree(c, {{-3, 1 + side * d, 1}, {1, 0, 0}, Range::line});
                hits += agree(c, {{-3, 0, 2 + side * d}, {1, 0, 0}, Range::ray});
                hits += agree(c, {{-3, 1 + side * d, 3}, {3, 0, -1}, Range::segment});
                hits += agree(c, {{0.5, side * d, 5}, {0, 0, -1}, Range::line});   // the discs
                hits += agree(c, {{-3, 1 + side * d, 2}, {1, 0, 0}, Range::line}); // disc plane
                EllipticCone cone{{0, 0, 0}, {0, 0, 2}, {1, 0, 0}, {0, 1, 0}, true, caps, 2};
                // Parallel to the generator through (1, 0, 0) and (0, 0, 2), moved 2^-k.
                hits += agree(cone, {{0.5 + side * d, 0, 0}, {-1, 0, 2}, Range::line});
                hits += agree(cone, {{side * d, 0, 2}, {1, 0.5, 1}, Range::line}); // the apex
            }
        }
    }
    CHECK(hits > 500);
    // And the filter is at work here (it is off only where upward rounding is not honoured, as
    // under valgrind): most of these lines are far enough from their forms' edges.
    CHECK(exact::rounding_stats().interval_decided - decided0 > 1000);
}

TEST_CASE("exact: the rounding filter's answers equal the unfiltered path's on every family",
          "[exact]") {
    // The oracle (Mpzf) rounds each value from double-word enclosures of its parts where their
    // error bound proves the rounding; Gmpq rounds every value by MPFR. Every family's cases in
    // both precisions, every query that rounds (t with points, the nearest t, a hit test's t),
    // every way taken.
    for (Precision p : {Precision::binary64, Precision::binary32}) {
        std::uint64_t by_intervals = 0, by_filter = 0, by_mpfr = 0;
        std::size_t compared = 0;
        for_each_family_case(21, 20, p, [&](const Case& c) {
            for (Query q : {Query{}, Query{Need::nearest, false}, Query{Need::any, false}}) {
                const exact::RoundingStats& stats = exact::rounding_stats();
                std::uint64_t intervals0 = stats.by_intervals, filter0 = stats.by_filter,
                              mpfr0 = stats.values;
                Result a = exact::intersect(c.shape, c.line, q, p);
                by_intervals += stats.by_intervals - intervals0;
                by_filter += stats.by_filter - filter0, by_mpfr += stats.values - mpfr0;
                Result b = exact::intersect_gmpq(c.shape, c.line, q, p);
                INFO(format_case(c) << "\n" << describe(a) << "\n" << describe(b));
                REQUIRE(same(a, b));
                ++compared;
            }
        });
        // Every way: almost every value by the filter (a float, most often from the intervals
        // alone); by MPFR those beyond its range (the scale family), zeros, ties and the ends of
        // an interval on the surface.
        INFO((p == Precision::binary32 ? "binary32" : "binary64")
             << ": " << by_intervals << " from the intervals, " << by_filter
             << " by the double-word filter, " << by_mpfr << " by MPFR");
        if (p == Precision::binary32) {
            CHECK(by_intervals > 5000);
            CHECK(by_filter > 1000);
        } else {
            CHECK(by_intervals == 0); // a double's cells are narrower than the intervals
            CHECK(by_filter > 10000);
        }
        CHECK(by_mpfr > 100);
        CHECK(compared > 5000);
    }
}

TEST_CASE("exact: a float tie that the intervals hold exactly rounds to even", "[exact]") {
    // A binary32 line along a capped cylinder's axis from z0 = -(1 + k 2^-23): it leaves by the
    // top disc at t = 2 - z0 = 3 + k 2^-23, a double and (k odd) a float midpoint, and every
    // interval on the way is exact, so the filter's enclosure of t is that one point. k = 1 lies
    // between 3 (even) and 3 + 2^-22; k = 3 between 3 + 2^-22 and 3 + 2^-21 (even).
    Cylinder c{{0, 0, 0}, {0, 0, 2}, 1, true, true};
    for (int k : {1, 3}) {
        double z0 = -(1 + k * 0x1p-23), even = k == 1 ? 3.0 : 3 + 0x1p-21;
        Line l{{0.5, 0, z0}, {0, 0, 1}, Range::line};
        std::uint64_t intervals0 = exact::rounding_stats().by_intervals;
        Result a = exact::intersect(c, l, Query{}, Precision::binary32);
        INFO("k " << k << "\n" << describe(a));
        CHECK(exact::rounding_stats().by_intervals - intervals0 == 8); // two hits, 4 values each
        REQUIRE(a.count == 2);
        CHECK(a.hits[1].t == even);
        CHECK(a.hits[1].p.z == 2.0);
        CHECK(same(a, exact::intersect_gmpq(c, l, Query{}, Precision::binary32)));
    }
}

TEST_CASE("exact: the rounding filter proves only what MPFR rounds, and defers near a tie",
          "[exact][rounding]") {
    using P = Precision;
    // Y is a double here, as in the oracle's own values.
    auto both = [](const std::string& X, double Y, const std::string& D, const std::string& Den,
                   P p) {
        std::string y = mpz_class(Y).get_str();
        double quick = exact::round_surd_by_filter(X.c_str(), Y, D.c_str(), Den.c_str(), p);
        double sure = exact::round_surd(X.c_str(), y.c_str(), D.c_str(), Den.c_str(), p);
        INFO(X << " + " << y << " sqrt(" << D << ") / " << Den
               << (p == P::binary32 ? " (float)" : " (double)"));
        if (!std::isnan(quick)) REQUIRE(std::memcmp(&quick, &sure, sizeof quick) == 0);
        return !std::isnan(quick);
    };
    auto pow2 = [](int k) {
        mpz_class z;
        mpz_ui_pow_ui(z.get_mpz_t(), 2, unsigned(k));
        return z;
    };
    // Random values of every form and sign: all but a few decided.
    std::mt19937_64 rng(5);
    int decided = 0, tried = 0;
    for (int i = 0; i < 4000; ++i) {
        auto part = [&](bool positive) {
            mpz_class n = mpz_class(std::to_string(rng() >> (rng() % 64))) *
                          mpz_class(std::to_string(rng() >> (rng() % 64)));
            return (!positive && rng() % 2) ? mpz_class(-n) : n;
        };
        mpz_class X = part(false), D = part(true), Den = part(false);
        // An integer double: up to 53 bits, scaled by up to 2^70.
        double Y = i % 5 == 0
                       ? 0
                       : std::ldexp(double(rng() >> 11) * (rng() % 2 ? 1 : -1), int(rng() % 71));
        if (Den == 0 || (X == 0 && (Y == 0 || D == 0))) continue;
        for (P p : {P::binary64, P::binary32}) {
            decided += both(X.get_str(), Y, D.get_str(), Den.get_str(), p);
            ++tried;
        }
    }
    CHECK(decided * 100 >= tried * 99);
    // Near a tie: m / 2^b with m = 2^b + 1 is the midpoint after 1 in a b-bit format (53 or
    // 24). Values 2^-(b+j) from it (relatively): (m 2^j +- 1) / 2^(b+j), and the square root
    // sqrt(M^2 +- m^2 2^(b+j+1)) / 2^(2b+j) with M = m 2^(b+j), that is m / 2^b times
    // sqrt(1 +- 2^-(b+j-1)). The filter must never disagree, must decide while the distance is
    // far above its bound (relative: 2^-94 for the value, under 2^-90 with the double's final
    // step, under 2^-74 with the float's), and must defer at the tie itself.
    for (P p : {P::binary64, P::binary32}) {
        int b = p == P::binary64 ? 53 : 24;
        mpz_class m = pow2(b) + 1;
        for (int j = 0; j <= 80; ++j) {
            for (int side : {-1, 1}) {
                mpz_class X = m * pow2(j) + side, Den = pow2(b + j);
                bool d1 = both(X.get_str(), 0, "0", Den.get_str(), p);
                mpz_class M = m * pow2(b + j), D = M * M + side * m * m * pow2(b + j + 1);
                bool d2 = both("0", 1, D.get_str(), pow2(2 * b + j).get_str(), p);
                // The same rational, signs on both parts; and twice it as 3X - sqrt(X^2) and
                // -X + sqrt(9 X^2), one term more than twice the other.
                bool d3 = both(mpz_class(-X).get_str(), 0, "0", mpz_class(-Den).get_str(), p);
                mpz_class X2 = X * X;
                bool d4 = both(mpz_class(3 * X).get_str(), -1, X2.get_str(), Den.get_str(), p);
                bool d5 =
                    both(mpz_class(-X).get_str(), 1, mpz_class(9 * X2).get_str(), Den.get_str(), p);
                INFO("b " << b << ", j " << j << ", side " << side);
                if (b + j <= (p == P::binary64 ? 88 : 72)) CHECK((d1 && d2 && d3 && d4 && d5));
            }
        }
        CHECK_FALSE(both(m.get_str(), 0, "0", pow2(b).get_str(), p)); // exactly the tie
        CHECK(both("3", 0, "0", "1", p));                             // exactly a double
        CHECK(both("0", 2, "4", "1", p));                             // sqrt(4) 2 = 4
        CHECK(both("-7", 3, "5", "2", p)); // the conjugate form: (-7 + 3 sqrt(5)) / 2
    }
    // Zero, and parts beyond its range: left to MPFR.
    CHECK_FALSE(both("0", 0, "0", "5", P::binary64));
    CHECK_FALSE(both("3", -1, "9", "1", P::binary64)); // 3 - sqrt(9) = 0
    CHECK_FALSE(both(pow2(1000).get_str(), 0, "0", "1", P::binary64));
}

TEST_CASE("exact: a circular cylinder is an elliptic cylinder with axes of length r", "[exact]") {
    Random r;
    // Axis 2 (3, 4, 0); a, b orthogonal to it with length 5, exactly.
    Vec3 C{1, -2, 0.5}, h{6, 8, 0}, a{0, 0, 5}, b{-4, 3, 0};
    Cylinder circular{C, C + h, 5};
    EllipticCylinder elliptic{C, a, b, h};
    int hits = 0;
    for (int i = 0; i < 2000; ++i) {
        Line l{C + r.vec(12), r.vec(2), r.range()};
        if (i % 7 == 0) l.v = h;                 // parallel to the axis as well
        if (i % 11 == 0) l.L0 = C + a + 0.5 * h; // through a surface point
        Result x = exact::intersect(circular, l), y = exact::intersect(elliptic, l);
        INFO(describe(x) << "\n" << describe(y));
        REQUIRE(same(x, y));
        hits += x.count;
    }
    CHECK(hits > 300);
}

TEST_CASE("exact: reversing v negates t / doubling v halves t / scaling by 2^k scales points",
          "[exact]") {
    Random r;
    for (int i = 0; i < 1500; ++i) {
        Shape s = r.shape();
        Line l = r.line();
        l.range = Range::line;
        Result base = exact::intersect(s, l);
        if (!base.ok()) continue;

        Line reversed{l.L0, -1.0 * l.v};
        Result rev = exact::intersect(s, reversed);
        REQUIRE(rev.count == base.count);
        for (int j = 0; j < base.count; ++j) {
            CHECK(rev.hits[base.count - 1 - j].t == -base.hits[j].t);
            CHECK(rev.hits[base.count - 1 - j].p == base.hits[j].p);
        }

        Result twice = exact::intersect(s, {l.L0, 2.0 * l.v});
        REQUIRE(twice.count == base.count);
        for (int j = 0; j < base.count; ++j)
            CHECK(twice.hits[j].t == base.hits[j].t / 2);

        for (int k : {-60, 37}) {
            double f = std::ldexp(1.0, k);
            Result sc = exact::intersect(scaled(s, f), {f * l.L0, f * l.v});
            REQUIRE(sc.count == base.count);
            for (int j = 0; j < base.count; ++j) {
                CHECK(sc.hits[j].t == base.hits[j].t);
                CHECK(sc.hits[j].p == f * base.hits[j].p);
            }
        }
    }
}

namespace {
// (X + Y sqrt(D)) / Den at 4096 bits, then to the nearest double. Double rounding could only
// bite if the 4096-bit value were exactly a midpoint between doubles: reported as NaN.
double reference(const mpq_t X, const mpq_t Y, const mpq_t D, const mpq_t Den) {
    mpfr_t x, y, d, den;
    mpfr_inits2(4096, x, y, d, den, (mpfr_ptr)0);
    mpfr_set_q(d, D, MPFR_RNDN);
    mpfr_sqrt(d, d, MPFR_RNDN);
    mpfr_set_q(y, Y, MPFR_RNDN);
    mpfr_mul(y, y, d, MPFR_RNDN);
    mpfr_set_q(x, X, MPFR_RNDN);
    mpfr_add(x, x, y, MPFR_RNDN);
    mpfr_set_q(den, Den, MPFR_RNDN);
    mpfr_div(x, x, den, MPFR_RNDN);
    double out = mpfr_get_d(x, MPFR_RNDN);
    // Midpoint check: the value equals (out + neighbour) / 2 exactly?
    double next = std::nextafter(out, mpfr_cmp_d(x, out) > 0 ? INFINITY : -INFINITY);
    mpfr_set_d(y, out, MPFR_RNDN);
    mpfr_add_d(y, y, next, MPFR_RNDN);
    mpfr_div_2ui(y, y, 1, MPFR_RNDN);
    bool tie = mpfr_equal_p(x, y);
    mpfr_clears(x, y, d, den, (mpfr_ptr)0);
    return tie ? NAN : out;
}

std::string str(const mpq_t q) {
    char* s = mpq_get_str(nullptr, 10, q);
    std::string out(s);
    void (*freefunc)(void*, size_t);
    mp_get_memory_functions(nullptr, nullptr, &freefunc);
    freefunc(s, std::strlen(s) + 1);
    return out;
}
} // namespace

TEST_CASE("exact: rounding matches a 4096-bit evaluation on random values", "[exact][rounding]") {
    std::mt19937_64 rng(7);
    mpq_t X, Y, D, Den;
    mpq_inits(X, Y, D, Den, (mpq_ptr)0);
    int compared = 0;
    for (int i = 0; i < 3000; ++i) {
        // Integers of 0 to ~120 bits; X / Den is then any rational, and sqrt(D) irrational
        // unless D is a perfect square.
        auto set = [&](mpq_t q, bool positive) {
            mpz_t n;
            mpz_init(n);
            mpz_set_ui(n, rng() >> (rng() % 64));
            mpz_mul_ui(n, n, rng() >> (rng() % 64));
            if (!positive && rng() % 2) mpz_neg(n, n);
            mpq_set_z(q, n);
            mpz_clear(n);
        };
        set(X, false), set(Y, false), set(D, true), set(Den, false);
        if (mpq_sgn(Den) == 0) continue;
        if (i % 5 == 0) mpq_set_ui(Y, 0, 1); // rationals too
        double ref = reference(X, Y, D, Den);
        if (std::isnan(ref)) continue;
        double got =
            exact::round_surd(str(X).c_str(), str(Y).c_str(), str(D).c_str(), str(Den).c_str());
        INFO(str(X) << " + " << str(Y) << " sqrt(" << str(D) << ") / " << str(Den));
        // Bit for bit, except that an exact zero is +0 by design (it has no sign to keep).
        if (ref == 0)
            REQUIRE((got == 0 && !std::signbit(got)));
        else
            REQUIRE(std::memcmp(&got, &ref, sizeof got) == 0);
        ++compared;
    }
    CHECK(compared > 2500);
    mpq_clears(X, Y, D, Den, (mpq_ptr)0);
}

TEST_CASE("exact: rounding near ties / subnormals and overflow", "[exact][rounding]") {
    // 1 + 2^-53 is the midpoint between 1 and its successor: ties to even gives 1.
    CHECK(exact::round_surd("9007199254740993", "0", "0", "9007199254740992") == 1.0);
    // 1 + 3 * 2^-53 is the midpoint between 1 + 2^-52 and 1 + 2^-51: even is 1 + 2^-51.
    CHECK(exact::round_surd("9007199254740995", "0", "0", "9007199254740992") == 1 + 0x1p-51);
    // sqrt(D) just above and below a midpoint: D = (2^53 + 1)^2 +- 1, scaled by 2^-53.
    const char* m2 = "81129638414606699710187514626049"; // (2^53 + 1)^2
    CHECK(exact::round_surd("0", "1", "81129638414606699710187514626050", "9007199254740992") ==
          1 + 0x1p-52);
    CHECK(exact::round_surd("0", "1", "81129638414606699710187514626048", "9007199254740992") ==
          1.0);
    CHECK(exact::round_surd("0", "1", m2, "9007199254740992") == 1.0); // exactly the tie
    // Half the smallest subnormal (a tie with 0: even is 0), and 3/2 of it (a tie: even is 2).
    mpz_t p;
    mpz_init(p);
    mpz_ui_pow_ui(p, 2, 1075);
    char* big = mpz_get_str(nullptr, 10, p);
    CHECK(exact::round_surd("1", "0", "0", big) == 0.0);       // 2^-1075: tie, to even (0)
    CHECK(exact::round_surd("3", "0", "0", big) == 0x1p-1073); // 3 * 2^-1075 -> 2^-1073
    CHECK(exact::round_surd("0", "1", "1", big) == 0.0);       // sqrt(1) / 2^1075
    CHECK(exact::round_surd("0", "1", "2", big) == 0x1p-1074); // sqrt(2) / 2^1075: up
    mpz_ui_pow_ui(p, 2, 1024);
    char* huge = mpz_get_str(nullptr, 10, p);
    CHECK(exact::round_surd(huge, "0", "0", "1") == INFINITY);
    CHECK(exact::round_surd(huge, "0", "0", "-1") == -INFINITY);
    void (*freefunc)(void*, size_t);
    mp_get_memory_functions(nullptr, nullptr, &freefunc);
    freefunc(big, std::strlen(big) + 1);
    freefunc(huge, std::strlen(huge) + 1);
    mpz_clear(p);
}

TEST_CASE("exact: rounding needs few precision steps on the oracle's own cases",
          "[exact][rounding]") {
    Random r;
    exact::rounding_stats() = {};
    for (int i = 0; i < 2000; ++i)
        exact::intersect(r.shape(), r.line());
    const auto& st = exact::rounding_stats();
    // Almost every value by the filter, none of the rest beyond MPFR's first precision (64 bits)
    // but a few.
    CHECK(st.by_filter > 1000);
    CHECK(st.by_filter * 100 >= (st.by_filter + st.values) * 99);
    CHECK(st.by_steps[0] * 100 >= st.values * 99);
}
