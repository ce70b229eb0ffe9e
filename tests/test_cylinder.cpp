// The right circular cylinder (seed 001) with every solver, on cases whose answers are exact.
#include "support.hpp"

using namespace linequad;
using namespace linequad::test;

namespace {
// Radius 5 around the z axis from z = 0 to z = 10: (3, 4, z) lies on it.
const Cylinder upright{{0, 0, 0}, {0, 0, 10}, 5};
} // namespace

TEST_CASE("cylinder: a line through two surface points crosses at t = 0 and t = 1", "[cylinder]") {
    check_through_two_points(upright, {3, 4, 2}, {-4, -3, 7},
                             {"seed", "stable", "exact", "seed32", "stable32", "correct32"});
    CHECK(run("stable", upright, through({3, 4, 2}, {-4, -3, 7})).hits[0].kind == HitKind::cross);
}

TEST_CASE("cylinder: tilted axis with integer frame / radius 25", "[cylinder]") {
    // Axis (3, 4, 0); e1 = (0, 0, 1), e2 = (-4, 3, 0) / 5 are orthonormal to it. The points
    // C + 20 e1 + 15 e2 + s h are at distance 25 from the axis, with exact coordinates.
    Cylinder tilted{{1, 1, 1}, {1 + 30, 1 + 40, 1}, 25};
    Vec3 p{1 - 12 + 3, 1 + 9 + 4, 1 + 20};   // s = 1/10
    Vec3 q{1 + 12 + 15, 1 - 9 + 20, 1 - 20}; // e1 -> -20, e2 -> -15, s = 1/2
    check_through_two_points(
        tilted, p, q, {"seed", "stable", "certified", "exact", "seed32", "stable32", "correct32"});
}

TEST_CASE("cylinder: power-of-two scales leave t unchanged", "[cylinder]") {
    for (int k : {-300, -40, 0, 40, 300}) {
        double s = std::ldexp(1.0, k);
        Cylinder c{{0, 0, 0}, {0, 0, 10 * s}, 5 * s};
        Line l = through({3 * s, 4 * s, 2 * s}, {-4 * s, -3 * s, 7 * s});
        for (const char* solver : {"stable", "exact"}) {
            INFO(solver << " k=" << k);
            Result r = run(solver, c, l);
            INFO(describe(r));
            REQUIRE(r.count == 2);
            check_t(solver, r.hits[0].t, 0);
            check_t(solver, r.hits[1].t, 1);
            // Scaling by 2^k is exact, so the error relative to the scene is as at k = 0.
            check_p(solver, std::ldexp(1.0, -k) * r.hits[1].p, Vec3{-4, -3, 7});
        }
    }
}

TEST_CASE("cylinder: tangent line is one tangent hit", "[cylinder]") {
    Line l{{5, -3, 4}, {0, 1, 0}}; // touches (5, 0, 4)
    for (const char* s : every_solver) {
        Result r = run(s, upright, l);
        INFO(s << " " << describe(r));
        REQUIRE(r.count == 1);
        CHECK(r.hits[0].kind == HitKind::tangent);
        check_t(s, r.hits[0].t, 3);
        check_p(s, r.hits[0].p, Vec3{5, 0, 4});
    }
}

TEST_CASE("cylinder: lines parallel to the axis", "[cylinder]") {
    for (const char* s : every_solver) {
        INFO(s);
        CHECK_FALSE(run(s, upright, {{1, 1, -3}, {0, 0, 2}}).any_hit()); // inside
        CHECK_FALSE(run(s, upright, {{9, 1, -3}, {0, 0, 2}}).any_hit()); // outside
        Result on = run(s, upright, {{3, 4, -3}, {0, 0, 2}});            // on the surface
        INFO(describe(on));
        REQUIRE(on.on_surface);
        CHECK(on.count == 0);
        check_t(s, on.s0, 1.5); // z = -3 + 2t in [0, 10]
        check_t(s, on.s1, 6.5);
        Cylinder infinite = upright;
        infinite.finite = false;
        Result all = run(s, infinite, {{3, 4, -3}, {0, 0, -2}});
        REQUIRE(all.on_surface);
        check_t(s, all.s0, -INFINITY);
        check_t(s, all.s1, INFINITY);
        Result ray = run(s, infinite, {{3, 4, -3}, {0, 0, -2}, Range::ray});
        REQUIRE(ray.on_surface);
        check_t(s, ray.s0, 0);
        check_t(s, ray.s1, INFINITY);
    }
}

TEST_CASE("cylinder: hits exactly at the extent's ends count / just beyond do not", "[cylinder]") {
    Line bottom = through({3, 4, 0}, {-3, -4, 10}); // t = 0 at z = 0, t = 1 at z = 10
    for (const char* s : every_solver) {
        Result r = run(s, upright, bottom);
        INFO(s << " " << describe(r));
        CHECK(r.count == 2);
    }
    double above = std::nextafter(10.0, 11.0), below = std::nextafter(0.0, -1.0);
    Line beyond = through({3, 4, below}, {-3, -4, above});
    Result r = run("exact", upright, beyond);
    INFO(describe(r));
    CHECK(r.count == 0);
    Cylinder infinite = upright;
    infinite.finite = false;
    CHECK(run("exact", infinite, beyond).count == 2);
}

TEST_CASE("cylinder: ranges", "[cylinder]") {
    Vec3 p{3, 4, 2}, q{-4, -3, 7};
    for (const char* s : every_solver) {
        INFO(s);
        // Roots at t = 0 and 1: both in every range.
        CHECK(run(s, upright, through(p, q, Range::ray)).count == 2);
        CHECK(run(s, upright, through(p, q, Range::segment)).count == 2);
        // From the midpoint of p and q: roots at t = -1/2 and t = 1/2.
        Line l{{-0.5, 0.5, 4.5}, q - p};
        Result line = run(s, upright, l);
        INFO(describe(line));
        REQUIRE(line.count == 2);
        check_t(s, line.hits[0].t, -0.5);
        check_t(s, line.hits[1].t, 0.5);
        l.range = Range::ray;
        Result ray = run(s, upright, l);
        REQUIRE(ray.count == 1);
        check_t(s, ray.hits[0].t, 0.5);
        l.range = Range::segment;
        CHECK(run(s, upright, l).count == 1);
        l.v = 4 * l.v; // roots at -1/8 and 1/8
        CHECK(run(s, upright, l).count == 1);
        l.v = 0.25 * l.v;
        l.L0 = p - (q - p); // roots at t = 1 and t = 2: the segment keeps t = 1 only
        Result seg = run(s, upright, l);
        REQUIRE(seg.count == 1);
        check_t(s, seg.hits[0].t, 1);
    }
}

TEST_CASE("cylinder: the caller's needs", "[cylinder]") {
    Line l = through({3, 4, 2}, {-4, -3, 7});
    for (const char* s : every_solver) {
        INFO(s);
        Result any = run(s, upright, l, {Need::any, false});
        CHECK(any.count == 1);
        Result nearest = run(s, upright, l, {Need::nearest, true});
        REQUIRE(nearest.count == 1);
        check_t(s, nearest.hits[0].t, 0);
        Result no_points = run(s, upright, l, {Need::all, false});
        REQUIRE(no_points.count == 2);
        CHECK(no_points.hits[1].p == Vec3{}); // not computed
    }
}
