// The elliptic cylinder (seed 000) with every solver, on cases whose answers are exact.
#include "support.hpp"

using namespace linequad;
using namespace linequad::test;

namespace {
// Orthogonal axes of lengths 5 and 10 (a rotation with a scale), height 7.
const Vec3 C{1, 2, 3}, a{3, 4, 0}, b{-8, 6, 0}, c{0, 0, 7};
const EllipticCylinder ellipse{C, a, b, c};
Vec3 at(double x, double y, double z, Vec3 cc = c) {
    return C + x * a + y * b + z * cc;
}
} // namespace

TEST_CASE("elliptic cylinder: line through two surface points", "[elliptic_cylinder]") {
    Vec3 p = at(1, 0, 0.5), q = at(0, -1, 0.25);
    check_through_two_points(ellipse, p, q,
                             {"seed", "stable", "exact", "seed32", "stable32", "correct32"});
}

TEST_CASE("elliptic cylinder: a point off the axes / (3/5 / 4/5)", "[elliptic_cylinder]") {
    // 3/5 a + 4/5 b = (9/5 - 32/5, 12/5 + 24/5, 0) = (-23/5, 36/5, 0): not dyadic. Scale the
    // frame by 5 instead: a' = 5a, b' = 5b, then 3/5 a' + 4/5 b' = 3a + 4b exactly.
    EllipticCylinder big{C, 5 * a, 5 * b, c};
    Vec3 p = C + 3 * a + 4 * b + 0.5 * c, q = C - 5 * a + 0.75 * c;
    check_through_two_points(
        big, p, q, {"seed", "stable", "certified", "exact", "seed32", "stable32", "correct32"});
}

TEST_CASE("elliptic cylinder: oblique (sheared) frame", "[elliptic_cylinder]") {
    Vec3 sheared{1, 2, 4};
    EllipticCylinder oblique{C, a, b, sheared};
    Vec3 p = at(-1, 0, 0.75, sheared), q = at(0, 1, 0.125, sheared);
    for (const char* s : every_solver) {
        Result r = run(s, oblique, through(p, q));
        INFO(s << " " << describe(r));
        REQUIRE(r.count == 2);
        check_t(s, r.hits[0].t, 0);
        check_t(s, r.hits[1].t, 1);
    }
}

TEST_CASE("elliptic cylinder: tangent line", "[elliptic_cylinder]") {
    Vec3 p = at(1, 0, 0.5); // the tangent there runs along b
    for (const char* s : every_solver) {
        Result r = run(s, ellipse, {p - b, b});
        INFO(s << " " << describe(r));
        REQUIRE(r.count == 1);
        CHECK(r.hits[0].kind == HitKind::tangent);
        check_t(s, r.hits[0].t, 1);
        check_p(s, r.hits[0].p, p);
    }
}

TEST_CASE("elliptic cylinder: lines parallel to the axis", "[elliptic_cylinder]") {
    for (const char* s : every_solver) {
        INFO(s);
        CHECK_FALSE(run(s, ellipse, {at(0.5, 0, 0), c}).any_hit());
        CHECK_FALSE(run(s, ellipse, {at(2, 0, 0), c}).any_hit());
        Result on = run(s, ellipse, {at(1, 0, -1), c});
        INFO(describe(on));
        REQUIRE(on.on_surface);
        check_t(s, on.s0, 1);
        check_t(s, on.s1, 2);
    }
}

TEST_CASE("elliptic cylinder: extent ends and not-finite shapes", "[elliptic_cylinder]") {
    Line ends = through(at(1, 0, 0), at(-1, 0, 1));
    for (const char* s : every_solver) {
        Result r = run(s, ellipse, ends);
        INFO(s << " " << describe(r));
        CHECK(r.count == 2);
    }
    Line outside = through(at(1, 0, -0.5), at(-1, 0, 1.5));
    EllipticCylinder infinite = ellipse;
    infinite.finite = false;
    for (const char* s : every_solver) {
        INFO(s);
        CHECK(run(s, ellipse, outside).count == 0);
        CHECK(run(s, infinite, outside).count == 2);
    }
}
