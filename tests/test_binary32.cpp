// binary32 end to end: float cases, the correct ladder rounding to float (correct32), the oracle
// rounding to float, and the audit grading in float ulps. References: 4096-bit MPFR rounded by
// mpfr_get_flt, and the oracle.
#include "mpfr_reference.hpp"
#include "support.hpp"

#include "correct/ladder.hpp"
#include "correct/rungs.hpp"
#include "numeric/big_float.hpp"
#include "numeric/format.hpp"
#include "shapes/all.hpp"

#include "linequad/audit.hpp"
#include "linequad/case_io.hpp"
#include "linequad/exact.hpp"
#include "linequad/families.hpp"
#include "linequad/invariants.hpp"

#include <mpfr.h>

#include <cmath>
#include <random>

using namespace linequad;
using namespace linequad::test;
using detail::Binary32;
using detail::Binary64;

namespace {

Result correct32_solve(const Shape& s, const Line& l, Query q = {}) {
    return std::visit([&](const auto& shape) { return correct32::intersect(shape, l, q); }, s);
}

// A closed cylinder along h = (1, 2^-12, 0) from the origin, and a line along x from just
// behind the base: it leaves through the top disc at t = (h.h - L0.h) / (v.h) =
// 1 + 2^-24 + 2^-70 exactly, just above the midpoint between the floats 1 and 1 + 2^-23. The
// nearest double is that midpoint, which rounds to the even float 1: rounding twice gives 1, the
// correctly rounded float is 1 + 2^-23.
Case double_rounding_trap() {
    Case c;
    c.shape = Cylinder{{0, 0, 0}, {1, 0x1p-12, 0}, 1, true, true};
    c.line = Line{{-0x1p-70, 0, 0}, {1, 0, 0}, Range::line};
    c.precision = Precision::binary32;
    return c;
}

} // namespace

TEST_CASE("round_proven to float answers only when every value within the bound rounds to it") {
    // hi + lo +- e times 2^k near float midpoints (exactly at them, just beside them by less than
    // a double's ulp: where rounding to double first would decide the tie), power-of-two floats
    // (whose cell is narrower below), scales down to the float's smallest normals. Where
    // round_proven answers v, both ends of the interval must round to v as floats (then every
    // value between does); 4096-bit MPFR is exact here.
    std::mt19937_64 rng(7);
    auto rounds_to = [&](double hi, double lo, double e, int k, double v) {
        return same_bits(mpfr_rounded(hi, lo, e, k, Precision::binary32), v);
    };
    long answered = 0, traps = 0;
    for (int i = 0; i < 200000; ++i) {
        // A float f, and the midpoint to its neighbour above (a double: 25 bits).
        float f =
            std::ldexp(std::uniform_real_distribution<float>(1, 2)(rng), int(rng() % 60) - 30);
        if (rng() % 8 == 0) f = std::ldexp(1.0f, std::ilogb(f));
        if (rng() % 2) f = -f;
        double half = Binary32::half_ulp(f), hi;
        switch (rng() % 4) {
        case 0:
            hi = f;
            break;
        case 1:
            hi = f + std::copysign(half, f);
            break; // the midpoint away from zero
        case 2:
            hi = f - std::copysign(half, f) / (Binary32::bits(std::fabs(f)) & 0x7fffff ? 1 : 2);
            break; // the midpoint towards zero (half as far below a power of two)
        default:
            hi = f + std::uniform_real_distribution<double>(-1, 1)(rng) * half;
        }
        double ulp = 2 * Binary64::half_ulp(hi);
        // lo within a double's ulp: the value is on either side of hi, which a double rounding
        // would take as the tie.
        double lo = rng() % 3 == 0 ? 0 : std::ldexp(ulp, -int(rng() % 20)) * (rng() % 2 ? 1 : -1);
        double e = rng() % 4 == 0 ? 0 : std::ldexp(half, -int(rng() % 40));
        int k = int(rng() % 161) - 80;
        if (std::fabs(hi) * std::ldexp(1.0, k) < 0x1p-120) k = 0;
        std::optional<double> v = detail::round_proven<Binary32>({hi, lo, e}, std::ldexp(1.0, k));
        if (!v) continue;
        ++answered;
        INFO("hi " << hi << " lo " << lo << " e " << e << " k " << k);
        REQUIRE(Binary32::holds(*v));
        REQUIRE(rounds_to(hi, lo, -e, k, *v));
        REQUIRE(rounds_to(hi, lo, e, k, *v));
        traps += lo != 0 && hi != float(hi);
    }
    CHECK(answered > 50000);
    CHECK(traps > 1000); // a midpoint and a tiny lo: the cases where double rounding would fail
}

TEST_CASE("the exact rounding to float: ties to even, double rounding, subnormals, overflow") {
    using linequad::BigFloat;
    auto to_float = [](const BigFloat& x) {
        return detail::round_exact<Binary32>(x, BigFloat(), BigFloat(), BigFloat(1.0));
    };
    auto to_double = [](const BigFloat& x) {
        return detail::round_exact<Binary64>(x, BigFloat(), BigFloat(), BigFloat(1.0));
    };
    BigFloat one(1.0), tie = one + BigFloat::pow2(-24);
    CHECK(to_float(tie) == 1.0);                                       // a tie: the even float
    CHECK(to_float(tie + BigFloat::pow2(-80)) == 1 + 0x1p-23);         // just above it
    CHECK(double(float(to_double(tie + BigFloat::pow2(-80)))) == 1.0); // twice: wrong
    CHECK(to_float(tie - BigFloat::pow2(-80)) == 1.0);
    CHECK(to_float(BigFloat(0x1.8p-149)) == 0x1p-148); // a subnormal tie: even
    CHECK(to_float(BigFloat::pow2(-150) + BigFloat::pow2(-200)) == 0x1p-149);
    CHECK(same_bits(to_float(-BigFloat::pow2(-151)), -0.0)); // below half the smallest: -0
    double fmax = Binary32::max;
    CHECK(to_float(BigFloat(fmax) + BigFloat::pow2(103) - BigFloat::pow2(60)) == fmax);
    CHECK(std::isinf(to_float(BigFloat(fmax) + BigFloat::pow2(103)))); // the tie beyond: inf
    CHECK(to_float(-(BigFloat(fmax) + BigFloat::pow2(104))) == -INFINITY);
    // The oracle's MPFR rounding agrees.
    CHECK(exact::round_surd("1208925819614629174706177", "0", "0", "1208925819614629174706176",
                            Precision::binary32) == 1.0); // 1 + 2^-80 rounds to 1
    CHECK(exact::round_surd("1208925819614629174706176", "0", "0", "1", Precision::binary32) ==
          0x1p+80);
}

TEST_CASE("correct32 rounds once, where rounding the double answer again would be wrong") {
    Case c = double_rounding_trap();
    Result want = exact::intersect(c.shape, c.line, {}, Precision::binary32);
    Result dbl = exact::intersect(c.shape, c.line);
    REQUIRE(want.count == 2);
    CHECK(want.hits[1].t == 1 + 0x1p-23);
    CHECK(want.hits[1].part == Part::top);
    CHECK(dbl.hits[1].t == 1 + 0x1p-24);        // the nearest double: the midpoint
    CHECK(double(float(dbl.hits[1].t)) == 1.0); // rounded again: the wrong float
    Result got = correct32_solve(c.shape, c.line);
    check_same_answer(got, want);
    CHECK(got.hits[1].bound == 0x1p-24); // half a float ulp
}

TEST_CASE("correct32 rounds a line grazing a disc's rim in its plane from the lateral root") {
    // A closed two-nappe cone along x (apex (-3, -5, -1), top disc in the plane x = 1) and a line
    // in that plane along -z, touching the top disc's rim at one point (a tangent hit, part
    // top). The exact rung's filter classifies it in double-double; the root it stands for is
    // the lateral one, (-B) / A, not a disc crossing (there dZ = 0). Found by the audit
    // (cap_plane, axis frames, seed 105), where the float's rounding fell to the exact root.
    EllipticCone cone{{-7, -5, -1}, {-3, -5, -1}, {0, 1, 0}, {0, 0, 1}, true, true, 2};
    Line l{{1, -6, 0x1.da5fdep-1}, {0, 0, -1}, Range::line};
    for (Query q : {Query{Need::all, true}, Query{Need::nearest, true}}) {
        Result want = exact::intersect(cone, l, q, Precision::binary32);
        REQUIRE(want.count == 1);
        CHECK(want.hits[0].kind == HitKind::tangent);
        CHECK(want.hits[0].part == Part::top);
        check_same_answer(correct32_solve(cone, l, q), want);
        check_same_answer(correct::intersect(cone, l, q), exact::intersect(cone, l, q));
    }
}

TEST_CASE("correct32 equals the oracle's float answer bit for bit on every family") {
    const Query queries[] = {{Need::all, true}, {Need::nearest, false}, {Need::any, true}};
    std::uint64_t by_rung[4] = {};
    for_each_family_case(41, 40, Precision::binary32, [&](const Case& c) {
        INFO(format_case(c));
        for (Query q : queries) {
            Result got = correct32_solve(c.shape, c.line, q);
            if (q.need == Need::any) {
                check_hit_test(got, exact::intersect(c.shape, c.line));
                for (int h = 0; h < got.count; ++h)
                    CHECK(Binary32::holds(got.hits[h].t));
            } else {
                check_same_answer(got, exact::intersect(c.shape, c.line, q, Precision::binary32));
            }
            if (got.ok()) ++by_rung[std::size_t(got.rung)];
        }
    });
    CHECK(by_rung[std::size_t(Rung::newton)] > 0);
    CHECK(by_rung[std::size_t(Rung::double_double)] > 0);
    CHECK(by_rung[std::size_t(Rung::exact)] > 0);
}

TEST_CASE("float solvers and the float oracle refuse inputs that are not floats, by name") {
    Cylinder s{{0, 0, 0}, {0, 0, 1}, 1, true};
    Line l{{-2, 0, 0.5}, {1, 0, 0}, Range::line};
    REQUIRE(correct32::intersect(s, l).ok());
    struct Bad {
        Cylinder s;
        Line l;
        const char* field;
    } bad[] = {
        {s, {{-2, 0, 0.5 + 0x1p-40}, {1, 0, 0}, Range::line}, "L0"}, // the last component
        {s, {{-2, 0, 0.5}, {1, 0, 0x1p-200}, Range::line}, "v"},     // below float's range
        {s, {{-2, 0, 0.5}, {1, 0, 0}, Interval(0, 0.1)}, "t1"},
        {{{0, 0, 0}, {0, 0, 1e300}, 1, true}, l, "H"}, // beyond float's range
        {{{0, 0, 0}, {0, 0, 1}, 0.1, true}, l, "r"},
    };
    for (const Bad& b : bad) {
        INFO(b.field);
        for (const char* solver : {"seed32", "stable32", "correct32"}) {
            INFO(solver);
            Result r = run(solver, b.s, b.l);
            CHECK(r.error_code == ErrorCode::not_binary32);
            CHECK(std::string(r.error_field) == b.field);
        }
        Result o = exact::intersect(b.s, b.l, {}, Precision::binary32);
        CHECK(o.error_code == ErrorCode::not_binary32);
        CHECK(std::string(o.error_field) == b.field);
        CHECK(exact::intersect(b.s, b.l).ok()); // in double they are fine
    }
    // A NaN is named as NaN first, as every solver does.
    Line nan_line{{-2, 0, NAN}, {1, 0, 0}, Range::line};
    for (const char* solver : {"seed32", "stable32", "correct32"})
        CHECK(run(solver, s, nan_line).error_code == ErrorCode::not_a_number);
}

TEST_CASE("binary32 cases: the parser refuses a number that is not a float, naming it") {
    Case c;
    std::string why;
    std::string good = R"({"id":1,"shape":"cylinder","C":[0,0,0],"H":[0,0,1],"r":1,)"
                       R"("L0":[-2,0,"0x1.8p-1"],"v":[1,0,0],"precision":"binary32"})";
    REQUIRE(parse_case(good, &c, &why));
    CHECK(c.precision == Precision::binary32);
    Case again;
    REQUIRE(parse_case(format_case(c), &again, &why));
    CHECK(again.precision == Precision::binary32);
    std::string bad = R"({"id":1,"shape":"cylinder","C":[0,0,0],"H":[0,0,1],"r":"0.1",)"
                      R"("L0":[-2,0,0],"v":[1,0,0],"precision":"binary32"})";
    CHECK_FALSE(parse_case(bad, &c, &why));
    CHECK(why.find("\"r\"") != std::string::npos);
    CHECK(why.find("binary32") != std::string::npos);
    std::string unknown = R"({"id":1,"shape":"cylinder","C":[0,0,0],"H":[0,0,1],"r":1,)"
                          R"("L0":[-2,0,0],"v":[1,0,0],"precision":"binary16"})";
    CHECK_FALSE(parse_case(unknown, &c, &why));
    CHECK(why.find("precision") != std::string::npos);
}

TEST_CASE("seed32 and stable32 answer in floats, and stable32 classifies generic cases exactly") {
    std::uint64_t answered[2] = {}, generic = 0;
    for_each_family_case(17, 30, Precision::binary32, [&](const Case& c) {
        INFO(format_case(c));
        Result oracle = exact::intersect(c.shape, c.line, {}, Precision::binary32);
        const char* names[2] = {"seed32", "stable32"};
        for (int k = 0; k < 2; ++k) {
            Result r = run(names[k], c.shape, c.line);
            INFO(names[k] << " " << describe(r));
            // What they refuse is beyond float's range (out_of_range), never a silent NaN.
            CHECK((r.ok() || r.error_code == ErrorCode::out_of_range));
            CHECK(answered_in_floats(r));
            // far_origin's rays from 2^13 shape sizes and more put stable32's discriminant, a
            // product of up to ten sizes, beyond float's range: it refuses them (out_of_range,
            // checked above) where the textbook form answers anything.
            if (c.family != "far_origin") answered[k] += r.ok();
            if (k == 1 && c.family == "generic") {
                // Generic cases are well separated from tangency: the classification is the
                // oracle's. Their condition numbers reach about 10^3 (stable's largest error
                // over the audit's generic cases is about 1,300 ulps in double, 500 in float);
                // 2^-10 relative, 2^14 float ulps, bounds that with room, and a wrong formula
                // is off by O(1).
                REQUIRE(r.count == oracle.count);
                for (int i = 0; i < r.count; ++i) {
                    CHECK(r.hits[i].kind == oracle.hits[i].kind);
                    CHECK(std::fabs(r.hits[i].t - oracle.hits[i].t) <=
                          0x1p-10 * std::fmax(1.0, std::fabs(oracle.hits[i].t)));
                }
                ++generic;
            }
        }
    });
    CHECK(generic > 300);
    CHECK(answered[0] > 0);
    CHECK(answered[1] > answered[0]); // stable32 refuses less than the textbook form
}

TEST_CASE("stable32 takes no underflowed discriminant for a tangency") {
    // A frustum of unit size 2^23 from the origin (the scale family): prescaled, its
    // discriminant h.h (|G|^2 - K^2), a product of ten of its sizes, underflows float to an exact
    // zero. The line crosses it twice; stable32 once called that a tangency. It now refuses.
    Case c;
    std::string why;
    REQUIRE(parse_case(
        R"({"id":"underflowed","shape":"frustum","C0":["-0x1.abbf22p+21","-0x1.7c2416p+21",)"
        R"("0x1.6489cap+23"],"r0":"0x1.23038p-1","C1":["-0x1.abbf0ap+21","-0x1.7c23f8p+21",)"
        R"("0x1.6489dp+23"],"r1":"0x1.4763fp-1","L0":["-0x1.abbf3ap+21","-0x1.7c23dep+21",)"
        R"("0x1.6489dp+23"],"v":["0x1.0e7222p+2","-0x1.4c6982p+2","-0x1.ef9a3cp+0"],)"
        R"("range":"line","finite":true,"precision":"binary32"})",
        &c, &why));
    Result oracle = exact::intersect(c.shape, c.line, {}, Precision::binary32);
    REQUIRE(oracle.count == 2);
    Result r = run("stable32", c.shape, c.line);
    INFO(describe(r));
    CHECK(r.error_code == ErrorCode::out_of_range);
}

TEST_CASE("every family generates float cases: every input a float, offsets in float's reach") {
    for_each_family_case(5, 24, Precision::binary32, [&](const Case& c) {
        INFO(format_case(c));
        CHECK(c.precision == Precision::binary32);
        CHECK(c.k <= (c.family == "scale" ? 120 : 24));
        CHECK(std::visit([&](const auto& s) { return detail::binary32_error(s, c.line); }, c.shape)
                  .ok());
        Case parsed;
        std::string why;
        CHECK(parse_case(format_case(c), &parsed, &why));
    });
}

TEST_CASE("the audit poses float solvers binary32 cases and grades them in float ulps") {
    audit::Options o;
    o.cases_per_group = 20;
    o.seed = 3;
    o.families = {Family::generic, Family::near_tangent};
    o.solvers = {"correct", "correct32"};
    audit::Report r = audit::run(o);
    audit::Row d = r.total("correct"), f = r.total("correct32");
    CHECK(d.cases == f.cases);
    CHECK(d.binary32_cases == 0);
    CHECK(f.binary32_cases == f.cases);
    CHECK(f.cases_mismatched == 0);
    CHECK(f.t_max == 0);
    CHECK(audit::broken_claims(r).empty());
    std::string md = audit::markdown(r);
    CHECK(md.find("| correct32 | float |") != std::string::npos);
    CHECK(md.find("## Float beside double") != std::string::npos);
    // In float ulps: 1 and the next float are 1 apart, 1 and the next double (not a float) too.
    CHECK(audit::ulps_between(1.0, 1 + 0x1p-23, Precision::binary32) == 1);
    CHECK(audit::ulps_between(1.0, 1 + 0x1p-52, Precision::binary32) == 1);
    CHECK(audit::ulps_between(1.0, 1 + 0x1p-52) == 1);
    CHECK(audit::ulps_between(-0x1p-149, 0x1p-149, Precision::binary32) == 2);
}
