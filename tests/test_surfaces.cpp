// Lines against planes and general quadrics: hits at points known to lie on the surface, every
// degenerate quadric answered as its polynomial, `coincident` as the docs define it, the same
// surface written 2^k q answered alike, and bad input named; every solver that claims exactness
// (correct, correct32 on floats, the oracle) equal bit for bit.
#include "linequad/case_io.hpp"
#include "linequad/exact.hpp"
#include "linequad/families.hpp"
#include "linequad/solvers.hpp"

#include <catch2/catch.hpp>

#include "support.hpp"

#include <cmath>
#include <cstring>
#include <string>

using namespace linequad;
using namespace linequad::test;

namespace {

Quadric gq(double A, double B, double C, double D, double E, double F, double G, double H, double J,
           double K, bool coincident = false) {
    return {{A, B, C, D, E, F, G, H, J, K}, coincident};
}

// correct's answer, required equal to the oracle's bit for bit; returned.
Result exact_both(const Shape& s, const Line& l) {
    Case posed;
    posed.shape = s, posed.line = l;
    INFO(format_case(posed));
    Result c = correct::intersect(s, l), e = exact::intersect(s, l);
    REQUIRE(c.error_code == e.error_code);
    REQUIRE(c.count == e.count);
    REQUIRE(c.on_surface == e.on_surface);
    for (int i = 0; i < c.count; ++i) {
        CHECK(same_bits(c.hits[i].t, e.hits[i].t));
        CHECK(c.hits[i].kind == e.hits[i].kind);
        for (int k = 0; k < 3; ++k)
            CHECK(same_bits(c.hits[i].p[k], e.hits[i].p[k]));
    }
    return e;
}

} // namespace

TEST_CASE("surfaces: hits where the surface equation says, every kind and degeneracy",
          "[surfaces]") {
    // The plane x + 2y + 2z = 9 along x from the origin: t = 9, the point (9, 0, 0).
    Result r = exact_both(Plane{{1, 2, 2}, 9}, Line{{0, 0, 0}, {1, 0, 0}});
    REQUIRE(r.count == 1);
    CHECK(r.hits[0].t == 9);
    CHECK(r.hits[0].kind == HitKind::cross);
    // In the plane: on the surface; parallel beside it: no hit.
    CHECK(exact_both(Plane{{0, 0, 1}, 2}, Line{{5, 1, 2}, {1, 3, 0}}).on_surface);
    CHECK(exact_both(Plane{{0, 0, 1}, 2}, Line{{5, 1, 3}, {1, 3, 0}}).count == 0);

    // The unit sphere x^2 + y^2 + z^2 - 1 through its centre: t = -1, 1.
    r = exact_both(gq(1, 1, 1, 0, 0, 0, 0, 0, 0, -1), Line{{0, 0, 0}, {0, 0, 2}});
    REQUIRE(r.count == 2);
    CHECK(r.hits[0].t == -0.5);
    CHECK(r.hits[1].t == 0.5);
    // The cone x^2 + y^2 - z^2 through its apex across the axis: a double root there (tangent);
    // along a generator through the apex: on the surface.
    r = exact_both(gq(1, 1, -1, 0, 0, 0, 0, 0, 0, 0), Line{{-1, 0, 0}, {1, 0, 0}});
    REQUIRE(r.count == 1);
    CHECK(r.hits[0].kind == HitKind::tangent);
    CHECK(r.hits[0].t == 1);
    CHECK(exact_both(gq(1, 1, -1, 0, 0, 0, 0, 0, 0, 0), Line{{3, 4, 5}, {3, 4, 5}}).on_surface);
    // The paraboloid z = x^2 + y^2 along its axis: A = 0, one root, at the vertex.
    r = exact_both(gq(1, 1, 0, 0, 0, 0, 0, 0, -1, 0), Line{{0, 0, 4}, {0, 0, -1}});
    REQUIRE(r.count == 1);
    CHECK(r.hits[0].t == 4);
    // The hyperbolic paraboloid z = xy contains the line x = 2, z = 2y (a ruling).
    CHECK(exact_both(gq(0, 0, 0, 1, 0, 0, 0, 0, -1, 0), Line{{2, 0, 0}, {0, 1, 2}}).on_surface);
    // A plane pair x^2 - y^2 = 0 crossed by y = 1: at x = -1 and 1.
    r = exact_both(gq(1, -1, 0, 0, 0, 0, 0, 0, 0, 0), Line{{0, 1, 0}, {1, 0, 0}});
    REQUIRE(r.count == 2);
    CHECK(r.hits[0].t == -1);
    CHECK(r.hits[1].t == 1);
    // The line x^2 + y^2 = 0 (the z axis) crossed: a tangent hit; the point x^2+y^2+z^2 = 0 the
    // same; the empty x^2 + y^2 + z^2 + 1 = 0 no hit.
    r = exact_both(gq(1, 1, 0, 0, 0, 0, 0, 0, 0, 0), Line{{-2, 0, 7}, {1, 0, 0}});
    REQUIRE(r.count == 1);
    CHECK(r.hits[0].kind == HitKind::tangent);
    CHECK(r.hits[0].p == Vec3{0, 0, 7});
    r = exact_both(gq(1, 1, 1, 0, 0, 0, 0, 0, 0, 0), Line{{-2, 0, 0}, {1, 0, 0}});
    REQUIRE(r.count == 1);
    CHECK(r.hits[0].kind == HitKind::tangent);
    CHECK(exact_both(gq(1, 1, 1, 0, 0, 0, 0, 0, 0, 1), Line{{-2, 0, 0}, {1, 0, 0}}).count == 0);
    // f constant along the line: a cylinder's axis direction off the cylinder, no hit.
    CHECK(exact_both(gq(1, 1, 0, 0, 0, 0, 0, 0, 0, -1), Line{{3, 0, 0}, {0, 0, 1}}).count == 0);
}

TEST_CASE("surfaces: coincident takes g's constant term as 0, as the caller states", "[surfaces]") {
    // From (1, 0, 0) on the unit sphere along x: hits at t = 0 and t = -2, with or without the
    // flag (the point is on the surface).
    for (bool coincident : {false, true}) {
        Result r =
            exact_both(gq(1, 1, 1, 0, 0, 0, 0, 0, 0, -1, coincident), Line{{1, 0, 0}, {1, 0, 0}});
        REQUIRE(r.count == 2);
        CHECK(r.hits[0].t == -2);
        CHECK(r.hits[1].t == 0);
    }
    // From (1.5, 0, 0), off it: with the flag, g(t) = t^2 + 3t: t = -3 and 0, and the "hit" at
    // t = 0 is the point L0 itself, as a transport code that says so means it.
    Result r = exact_both(gq(1, 1, 1, 0, 0, 0, 0, 0, 0, -1, true), Line{{1.5, 0, 0}, {1, 0, 0}});
    REQUIRE(r.count == 2);
    CHECK(r.hits[0].t == -3);
    CHECK(r.hits[1].t == 0);
    // A plane: the one hit is t = 0; along the plane, on the surface.
    r = exact_both(Plane{{0, 0, 1}, 2, true}, Line{{0, 0, 2.5}, {1, 0, 1}});
    REQUIRE(r.count == 1);
    CHECK(r.hits[0].t == 0);
    CHECK(exact_both(Plane{{0, 0, 1}, 2, true}, Line{{0, 0, 2.5}, {1, 0, 0}}).on_surface);
    // Every solver honours it (the seed as the transport codes write it too).
    for (const char* name : {"seed", "stable", "certified", "correct"}) {
        INFO(name);
        Result s = run(name, gq(1, 1, 1, 0, 0, 0, 0, 0, 0, -1, true), Line{{1.5, 0, 0}, {1, 0, 0}});
        REQUIRE(s.count == 2);
        CHECK(s.hits[1].t == 0);
    }
}

TEST_CASE("surfaces: the same surface written 2^k q answers alike, bit for bit", "[surfaces]") {
    // Every family's cases of both shapes, their coefficients times 2^k (k = -300 .. 300): the
    // oracle's and correct's answers do not move.
    int compared = 0;
    for (int f = 0; f < family_count; ++f)
        for (int shape : {shape_named("plane"), shape_named("quadric")}) {
            if (!family_applies(Family(f), shape)) continue;
            for (std::uint64_t i = 0; i < 40; ++i) {
                Case c = make_case(Family(f), shape, Range::line, 3, i);
                Shape scaled = c.shape;
                int k = int(i * 37 % 601) - 300;
                if (auto* q = std::get_if<Quadric>(&scaled))
                    for (double& x : q->q)
                        x = std::ldexp(x, k);
                if (auto* p = std::get_if<Plane>(&scaled))
                    p->n = std::ldexp(1.0, k) * p->n, p->d = std::ldexp(p->d, k);
                INFO(format_case(c) << "\ntimes 2^" << k);
                Result a = exact_both(c.shape, c.line), b = exact_both(scaled, c.line);
                REQUIRE(a.count == b.count);
                CHECK(a.on_surface == b.on_surface);
                for (int h = 0; h < a.count; ++h)
                    CHECK(same_bits(a.hits[h].t, b.hits[h].t));
                ++compared;
            }
        }
    CHECK(compared > 500);
}

TEST_CASE("surfaces: bad input is named", "[surfaces]") {
    Line l{{0, 0, 0}, {1, 0, 0}};
    for (const char* name : {"seed", "stable", "certified", "correct"}) {
        INFO(name);
        Result r = run(name, Plane{{0, 0, 0}, 1}, l);
        CHECK(r.error_code == ErrorCode::zero_coefficients);
        CHECK(std::string(r.error_field) == "n");
        r = run(name, Quadric{}, l);
        CHECK(r.error_code == ErrorCode::zero_coefficients);
        CHECK(std::string(r.error_field) == "q");
        r = run(name, gq(1, NAN, 1, 0, 0, 0, 0, 0, 0, -1), l);
        CHECK(r.error_code == ErrorCode::not_a_number);
        CHECK(std::string(r.error_field) == "q");
        r = run(name, Plane{{0, 0, 1}, INFINITY}, l);
        CHECK(r.error_code == ErrorCode::infinite);
        CHECK(std::string(r.error_field) == "d");
    }
    // The case format: q needs ten numbers; coincident a boolean; both written back.
    Case c;
    std::string why;
    CHECK_FALSE(
        parse_case(R"({"shape":"quadric","q":[1,2,3],"L0":[0,0,0],"v":[1,0,0]})", &c, &why));
    CHECK(why == "field \"q\": expected an array of 10 numbers (A B C D E F G H J K)");
    CHECK_FALSE(
        parse_case(R"({"shape":"plane","n":[0,0,1],"d":1,"coincident":1,"L0":[0,0,0],"v":[1,0,0]})",
                   &c, &why));
    CHECK(why == "field \"coincident\": expected true or false");
    CHECK_FALSE(parse_case(
        R"({"shape":"sphere","C":[0,0,0],"r":1,"coincident":true,"L0":[0,0,0],"v":[1,0,0]})", &c,
        &why));
    REQUIRE(parse_case(
        R"({"shape":"plane","n":[0,0,1],"d":1,"coincident":true,"L0":[0,0,0],"v":[1,0,0]})", &c,
        &why));
    CHECK(std::get<Plane>(c.shape).coincident);
    Case back;
    REQUIRE(parse_case(format_case(c), &back, &why));
    CHECK(std::get<Plane>(back.shape).coincident);
}

TEST_CASE("stable: a quadric seen from 2^30 away keeps A's low part in D", "[surfaces]") {
    // Found by the tracking audit (linequad cells examples/models/spheres.json --audit): the
    // sphere of radius 4, a ray from 2^30 away through it. B^2 and A C0 are some 2^62 A while D
    // is some 16 A^2: A rounded to a double erred by 2^9 A in A C0, and stable saw no crossing.
    Quadric sphere{{1, 1, 1, 0, 0, 0, 0, 0, 0, -16}};
    Line ray{{0x1.c0619c853cc6bp+30, -0x1.ec5529748952bp+29, -0x1.65e599478373cp+26},
             {-0x1.8dbb396520ac3p+0, 0x1.b4b7c78fbbfe3p-1, 0x1.3d77dbe8023efp-4},
             Range::ray};
    Result want = exact::intersect(sphere, ray, {});
    REQUIRE(want.count == 2);
    Result got = stable::intersect(sphere, ray, {});
    REQUIRE(got.count == 2);
    for (int h = 0; h < 2; ++h) {
        CHECK(got.hits[h].kind == HitKind::cross);
        // t is some 2^30: stable's roots are within a few ulps of it.
        CHECK(std::fabs(got.hits[h].t - want.hits[h].t) <= 8 * 0x1p-52 * 0x1p30);
    }
}
