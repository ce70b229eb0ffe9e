// The range is an interval t0 <= t <= t1, either end possibly infinite: hand-built exact cases,
// a renderer's tMax against rescaling v, clipping of a line on the surface, bad ranges, and the
// correct solver against the oracle on random intervals over every family.
#include "support.hpp"

#include "linequad/exact.hpp"
#include "linequad/families.hpp"

#include <limits>

using namespace linequad;
using namespace linequad::test;

namespace {
const double inf = std::numeric_limits<double>::infinity();
// Radius 5 around the z axis from z = 0 to z = 10; the line y = 4, z = 2 along x crosses it at
// x = -3 and 3: t = 7 and 13 from x = -10.
const Cylinder upright{{0, 0, 0}, {0, 0, 10}, 5};
Line across(Interval range) {
    return {{-10, 4, 2}, {1, 0, 0}, range};
}
} // namespace

TEST_CASE("range: hits are kept exactly when t0 <= t <= t1, the ends included", "[range]") {
    struct Expect {
        Interval range;
        std::vector<double> t;
    } expect[] = {
        {{0, 10}, {7}},   {{7, 13}, {7, 13}},     {{7.5, 12.5}, {}},
        {{-inf, 7}, {7}}, {{13, inf}, {13}},      {{7, 7}, {7}},
        {{8, 8}, {}},     {{-inf, inf}, {7, 13}}, {{13.000000000000002, inf}, {}},
    };
    for (const Expect& e : expect)
        for (const char* s : every_solver) {
            Result r = run(s, upright, across(e.range));
            INFO(s << " [" << e.range.t0 << ", " << e.range.t1 << "] " << describe(r));
            REQUIRE(r.count == int(e.t.size()));
            for (std::size_t i = 0; i < e.t.size(); ++i)
                check_t(s, r.hits[i].t, e.t[i]);
        }
}

TEST_CASE("range: a tMax gives what rescaling v would, without rescaling", "[range]") {
    // The ray from (-10, 4, 2) along (1, 0, 0) with tMax = 8, against the segment of v = 8 (1,
    // 0, 0): t differs by the factor 8 exactly, for the correctly rounded solvers bit for bit.
    for (const char* s : {"correct", "exact"}) {
        Result ranged = run(s, upright, {{-10, 4, 2}, {1, 0, 0.125}, Interval(0, 8)});
        Result segment = run(s, upright, {{-10, 4, 2}, {8, 0, 1}, Range::segment});
        INFO(s << "\n" << describe(ranged) << "\n" << describe(segment));
        REQUIRE(ranged.count == 1);
        REQUIRE(segment.count == 1);
        CHECK(ranged.hits[0].t == 8 * segment.hits[0].t);
        CHECK(ranged.hits[0].p == segment.hits[0].p);
    }
}

TEST_CASE("range: a line on the surface is clipped to the interval", "[range]") {
    // Along the axis on the surface: z = t - 2, so 0 <= z <= 10 for 2 <= t <= 12.
    Line on{{5, 0, -2}, {0, 0, 1}};
    struct Expect {
        Interval range;
        double s0, s1;
    } expect[] = {{{-inf, inf}, 2, 12}, {{3, 20}, 3, 12}, {{-inf, 5}, 2, 5}, {{12, 12}, 12, 12}};
    for (const Expect& e : expect)
        for (const char* s : every_solver) {
            // One point at the extent's end: only the exact solvers can tell (the others round
            // the end to either side of 12).
            if (e.range.t0 == e.range.t1 && !exact_solver(s)) continue;
            on.range = e.range;
            Result r = run(s, upright, on);
            INFO(s << " " << describe(r));
            REQUIRE(r.on_surface);
            check_t(s, r.s0, e.s0); // exact for the oracle and correct; rounded otherwise
            check_t(s, r.s1, e.s1);
        }
    // Past the extent: nothing.
    on.range = Interval(12.5, inf);
    for (const char* s : every_solver) {
        Result r = run(s, upright, on);
        CHECK_FALSE(r.on_surface);
        CHECK(r.count == 0);
    }
}

TEST_CASE("range: bad ranges are named", "[range][validation]") {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    struct Bad {
        Interval range;
        ErrorCode code;
        const char* field;
    } bad[] = {{{nan, 1}, ErrorCode::not_a_number, "t0"},
               {{0, nan}, ErrorCode::not_a_number, "t1"},
               {{2, 1}, ErrorCode::empty_range, "t0,t1"},
               {{inf, inf}, ErrorCode::empty_range, "t0,t1"},
               {{-inf, -inf}, ErrorCode::empty_range, "t0,t1"}};
    for (const Bad& b : bad)
        for (const char* s : every_solver) {
            Result r = run(s, upright, across(b.range));
            INFO(s << " " << describe(r));
            CHECK(r.error_code == b.code);
            CHECK(std::string(r.error_field) == b.field);
            CHECK(r.count == 0);
        }
}

TEST_CASE("range: the case format reads and writes t0 and t1", "[range][case_io]") {
    Case c;
    std::string why;
    REQUIRE(parse_case(R"({"id":1,"shape":"cylinder","C":[0,0,0],"H":[0,0,10],"r":5,)"
                       R"("L0":[-10,4,2],"v":[1,0,0],"t0":"0x1p-3","t1":"inf"})",
                       &c, &why));
    CHECK(c.line.range == Interval(0.125, inf));
    Case back;
    REQUIRE(parse_case(format_case(c), &back, &why));
    CHECK(back.line.range == c.line.range);
    CHECK(format_case(c).find("\"t1\"") == std::string::npos); // an infinite end is left out
    // A shorthand stays a shorthand.
    c.line.range = Range::ray;
    CHECK(format_case(c).find("\"range\":\"ray\"") != std::string::npos);
    // Not both.
    CHECK_FALSE(parse_case(R"({"id":1,"shape":"cylinder","C":[0,0,0],"H":[0,0,10],"r":5,)"
                           R"("L0":[-10,4,2],"v":[1,0,0],"range":"ray","t1":2})",
                           &c, &why));
    CHECK_THAT(why, Catch::Contains("t1"));
}

TEST_CASE("range: correct equals the oracle on random intervals, every family", "[range]") {
    // Ends at the roots themselves (exactly), near them, and anywhere: every rung decides them.
    std::mt19937_64 rng(77);
    long compared = 0;
    for (int f = 0; f < family_count; ++f)
        for (int shape = 0; shape < shape_kinds; ++shape) {
            if (!family_applies(Family(f), shape)) continue;
            for (std::uint64_t i = 0; i < 40; ++i) {
                Case c = make_case(Family(f), shape, Range::line, 53, i);
                Result all = exact::intersect(c.shape, c.line);
                double near = all.count > 0 ? all.hits[rng() % all.count].t : 1.0;
                auto end = [&] {
                    switch (rng() % 4) {
                    case 0:
                        return near;
                    case 1:
                        return std::nextafter(near, rng() % 2 ? inf : -inf);
                    case 2:
                        return std::uniform_real_distribution<double>(-4, 4)(rng);
                    default:
                        return rng() % 2 ? inf : -inf;
                    }
                };
                double a = end(), b = end();
                if (a > b) std::swap(a, b);
                if (a == inf || b == -inf) continue;
                c.line.range = Interval(a, b);
                for (Query q : {Query{}, Query{Need::nearest, false}}) {
                    Result want = exact::intersect(c.shape, c.line, q);
                    Result got = correct::intersect(c.shape, c.line, q);
                    INFO(format_case(c));
                    check_same_answer(got, want);
                    for (const char* s : {"seed", "stable", "certified"}) {
                        Result r = run(s, c.shape, c.line, q);
                        for (int h = 0; h < r.count; ++h)
                            CHECK(c.line.range.contains(r.hits[h].t));
                    }
                    ++compared;
                }
            }
        }
    CHECK(compared > 1500);
}
