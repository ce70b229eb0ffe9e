// Bad input gets an error naming the problem, from every solver, never a hit.
#include "support.hpp"

#include <limits>

using namespace linequad;
using namespace linequad::test;

namespace {
const double qnan = std::numeric_limits<double>::quiet_NaN();
const double inf = std::numeric_limits<double>::infinity();

void expect_error(const Shape& s, const Line& l, ErrorCode code, const std::string& field) {
    for (const char* solver : every_solver) {
        Result r = run(solver, s, l);
        INFO(solver << " " << describe(r));
        CHECK(r.error_code == code);
        CHECK(r.error_field == field);
        CHECK(r.count == 0);
        CHECK_FALSE(r.on_surface);
        CHECK_FALSE(message(r.error()).empty());
    }
}
const Line good{{-10, 1, 2}, {1, 0, 0}};
} // namespace

TEST_CASE("bad input: NaN and infinite coordinates name the field", "[validation]") {
    Cylinder cyl{{0, 0, 0}, {0, 0, 10}, 5};
    expect_error(cyl, {{qnan, 0, 0}, {1, 0, 0}}, ErrorCode::not_a_number, "L0");
    expect_error(cyl, {{0, 0, 0}, {1, inf, 0}}, ErrorCode::infinite, "v");
    expect_error(Cylinder{{0, 0, -inf}, {0, 0, 10}, 5}, good, ErrorCode::infinite, "C");
    expect_error(Cylinder{{0, 0, 0}, {0, 0, 10}, qnan}, good, ErrorCode::not_a_number, "r");
    expect_error(Cylinder{{0, 0, 0}, {0, 0, 10}, inf}, good, ErrorCode::infinite, "r");
    expect_error(EllipticCylinder{{0, 0, 0}, {1, 0, 0}, {0, qnan, 0}, {0, 0, 1}}, good,
                 ErrorCode::not_a_number, "b");
    expect_error(EllipticCone{{0, 0, 0}, {0, 0, 1}, {1, 0, 0}, {0, 1, 0}},
                 {{0, 0, 0}, {-inf, 0, 0}}, ErrorCode::infinite, "v");
}

TEST_CASE("bad input: zero direction / radius / axis", "[validation]") {
    Cylinder cyl{{0, 0, 0}, {0, 0, 10}, 5};
    expect_error(cyl, {{1, 2, 3}, {0, -0.0, 0}}, ErrorCode::zero_direction, "v");
    expect_error(Cylinder{{0, 0, 0}, {0, 0, 10}, 0}, good, ErrorCode::bad_radius, "r");
    expect_error(Cylinder{{0, 0, 0}, {0, 0, 10}, -1}, good, ErrorCode::bad_radius, "r");
    expect_error(Cylinder{{1, 2, 3}, {1, 2, 3}, 1}, good, ErrorCode::degenerate_axis, "H-C");
    expect_error(EllipticCone{{1, 2, 3}, {1, 2, 3}, {1, 0, 0}, {0, 1, 0}}, good,
                 ErrorCode::degenerate_axis, "H-C");
}

TEST_CASE("bad input: singular frames are detected exactly", "[validation]") {
    expect_error(EllipticCylinder{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}}, good,
                 ErrorCode::singular_frame, "a,b,c");
    expect_error(EllipticCylinder{{0, 0, 0}, {0, 0, 0}, {0, 1, 0}, {0, 0, 1}}, good,
                 ErrorCode::singular_frame, "a,b,c");
    // c = H - C in the plane of a and b.
    expect_error(EllipticCone{{0, 0, 0}, {3, 5, 0}, {1, 0, 0}, {0, 1, 0}}, good,
                 ErrorCode::singular_frame, "a,b,H-C");
    // Dependent only in exact arithmetic: the third vector is 0.1 a + 0.3 b with every
    // product exact, but det is a cancellation of rounded terms in floating point.
    Vec3 a{0.1, 0.7, 0.3}, b{0.3, 0.1, 0.7};
    Vec3 c{0.1 * 0.5 + 0.3 * 0.25, 0.7 * 0.5 + 0.1 * 0.25, 0.3 * 0.5 + 0.7 * 0.25};
    EllipticCylinder maybe{{0, 0, 0}, a, b, c};
    Result exact = run("exact", maybe, good);
    // Whatever the exact oracle decides, every solver decides the same: validation is shared.
    for (const char* s : {"seed", "stable"})
        CHECK(run(s, maybe, good).error_code == exact.error_code);
    // A frame singular to the last bit: c = a + b with exact sums.
    EllipticCylinder flat{{0, 0, 0}, {0.5, 0.25, 1}, {0.125, 3, -2}, {0.625, 3.25, -1}};
    for (const char* s : every_solver)
        CHECK(run(s, flat, good).error_code == ErrorCode::singular_frame);
    // Nearly singular is not singular: det = 2^-100. (stable32 cannot hold c beside a and b:
    // products of four such sizes underflow float, and it says so.)
    EllipticCylinder thin{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 0x1p-100}};
    for (const char* s : every_solver) {
        INFO(s);
        ErrorCode want = std::string(s) == "stable32" ? ErrorCode::out_of_range : ErrorCode::none;
        CHECK(run(s, thin, good).error_code == want);
    }
}

TEST_CASE("bad input: messages say what is wrong", "[validation]") {
    CHECK(message({ErrorCode::zero_direction, "v"}) == "the direction v is the zero vector");
    CHECK(message({ErrorCode::not_a_number, "L0"}) == "L0 has a NaN coordinate");
}

TEST_CASE("extreme magnitudes: an error or the right answer / never a wrong hit", "[validation]") {
    // A radius 2^-700 cylinder seen from 2^300 away: beyond double's reach for the stable
    // solver (which says so); the exact oracle still answers.
    double tiny = 0x1p-700, far = 0x1p300;
    Cylinder c{{0, 0, 0}, {0, 0, tiny}, tiny};
    Line l{{-far, 0, tiny / 2}, {1, 0, 0}};
    Result exact = run("exact", c, l);
    REQUIRE(exact.count == 2);
    Result stable = run("stable", c, l);
    INFO(describe(stable));
    CHECK((stable.error_code == ErrorCode::out_of_range || stable.count == 2));
}
