// The sense of a point against a plane or a general quadric: fast/'s filtered sign equals the
// oracle's exact one (robust/, CGAL::Mpzf) everywhere, on points known to lie on the surface
// (exact constructions), just off them, far out, tiny, and where double rounding gives the wrong
// sign; the direction rule on tangents, axes, apexes and rulings; and bad input named.
#include "linequad/exact.hpp"
#include "linequad/surfaces.hpp"

#include <catch2/catch.hpp>

#include "numeric/fp_environment.hpp"
#include "support.hpp"

#include <cfenv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <vector>

using namespace linequad;

namespace {

// f = A x^2 + B y^2 + C z^2 + D xy + E yz + F zx + G x + H y + J z + K.
Quadric gq(double A, double B, double C, double D, double E, double F, double G, double H, double J,
           double K) {
    return {{A, B, C, D, E, F, G, H, J, K}};
}
Quadric sphere(double r2) {
    return gq(1, 1, 1, 0, 0, 0, 0, 0, 0, -r2);
}

// Both layers' answers, required equal; the fast one returned.
template <class S>
Sense both(const S& s, Vec3 p) {
    SenseResult fast = sense(s, p), oracle = exact::sense(s, p);
    REQUIRE(fast.ok());
    REQUIRE(oracle.ok());
    CHECK(fast.sense == oracle.sense);
    return fast.sense;
}
template <class S>
Sense both(const S& s, Vec3 p, Vec3 u) {
    SenseResult fast = sense(s, p, u), oracle = exact::sense(s, p, u);
    REQUIRE(fast.ok());
    REQUIRE(oracle.ok());
    CHECK(fast.sense == oracle.sense);
    return fast.sense;
}

double up(double x) {
    return std::nextafter(x, std::numeric_limits<double>::infinity());
}

// A double of random sign, mantissa and exponent in [-e, e].
double any(std::mt19937_64& g, int e) {
    std::uniform_real_distribution<double> m(1, 2);
    std::uniform_int_distribution<int> k(-e, e), s(0, 1);
    return std::ldexp(s(g) ? m(g) : -m(g), k(g));
}

} // namespace

TEST_CASE("sense: points on a surface by construction are on it, their neighbours off it",
          "[sense]") {
    // (3, 4, 0) 2^k on the sphere of radius 5 2^k, at every scale its r^2 holds exactly.
    for (int k : {0, 10, 40, 400, 509, -500, -537}) {
        INFO("k = " << k);
        double s = std::ldexp(1.0, k);
        Quadric q = sphere(std::ldexp(25.0, 2 * k));
        CHECK(both(q, {3 * s, 4 * s, 0}) == Sense::on);
        CHECK(both(q, {up(3 * s), 4 * s, 0}) == Sense::positive);
        CHECK(both(q, {std::nextafter(3 * s, 0.0), 4 * s, 0}) == Sense::negative);
    }
    // Products that overflow double: 2^600 x - 2^600 y at x = y = 2^600.
    double big = std::ldexp(1.0, 600);
    Plane steep{{big, -big, 0}, 0};
    CHECK(both(steep, {big, big, 5}) == Sense::on);
    CHECK(both(steep, {up(big), big, 5}) == Sense::positive);
    // Products that underflow to 0 in double: 2^-1000 (x^2 - y^2) at x = y (1 + 2^-52) is
    // about 2^-1171 > 0, though every term of it reads 0 in double.
    double tiny = std::ldexp(3.0, -60);
    Quadric shallow = gq(0x1p-1000, -0x1p-1000, 0, 0, 0, 0, 0, 0, 0, 0);
    CHECK(both(shallow, {tiny, tiny, 0}) == Sense::on);
    CHECK(both(shallow, {up(tiny), tiny, 0}) == Sense::positive);
    // 2^k q is the same surface: the same sense at every scale its coefficients hold.
    Quadric cone = gq(1, 4, -9, 0, 0, 0, 0, 0, 0, 0);
    for (Vec3 p : {Vec3{3, 0, 1}, Vec3{0, 1.5, 1}, Vec3{up(3.0), 0, 1}, Vec3{3, 0, up(1.0)}}) {
        Sense at = both(cone, p);
        for (int k : {-1000, -60, 1, 60, 1000}) {
            Quadric scaled = cone;
            for (double& c : scaled.q)
                c = std::ldexp(c, k);
            CHECK(both(scaled, p) == at);
        }
    }
    // A plane with a point on it, and the next doubles around it.
    Plane plane{{1, 2, 3}, 24};
    CHECK(both(plane, {5, -7, 11}) == Sense::on);
    CHECK(both(plane, {up(5.0), -7, 11}) == Sense::positive);
    CHECK(both(plane, {5, -7, std::nextafter(11.0, 0.0)}) == Sense::negative);
}

TEST_CASE("sense: the sign double rounding gets wrong is found exactly", "[sense]") {
    // D x y - 2^-200 with D = 2^-1000, x = 2^-100, y = 2^1000: exactly 2^-100 - 2^-200 > 0. In
    // double, D x underflows to 0 before y multiplies it back up, and the sum is -2^-200.
    Quadric lifted = gq(0, 0, 0, 0x1p-1000, 0, 0, 0, 0, 0, -0x1p-200);
    Vec3 at{0x1p-100, 0x1p1000, 0};
    REQUIRE(lifted.q[3] * at.x * at.y + lifted.q[9] < 0);
    CHECK(both(lifted, at) == Sense::positive);

    // f = (x - y)^2 - 2^-110 at x = 1 + 2^-52, y = 1: exactly 2^-104 - 2^-110 > 0. In double,
    // x^2 loses its 2^-104 and the sum is -2^-110: the textbook evaluation says inside.
    Quadric q = gq(1, 1, 0, -2, 0, 0, 0, 0, 0, -0x1p-110);
    double x = 1 + 0x1p-52, y = 1;
    double naive = x * x + y * y - 2 * x * y - 0x1p-110;
    REQUIRE(naive < 0);
    CHECK(both(q, {x, y, 0}) == Sense::positive);
}

TEST_CASE("sense: a point on the surface takes the side its direction points into", "[sense]") {
    Quadric unit = sphere(1);
    CHECK(both(unit, {1, 0, 0}, {1, 0, 0}) == Sense::positive);   // out through the surface
    CHECK(both(unit, {1, 0, 0}, {-1, 0, 0}) == Sense::negative);  // in
    CHECK(both(unit, {1, 0, 0}, {0, 1, 0}) == Sense::positive);   // tangent: curves away
    CHECK(both(unit, {0.5, 0, 0}, {1, 0, 0}) == Sense::negative); // off the surface: f decides
    // A cylinder written as a quadric: a line along its axis stays on it.
    Quadric cylinder = gq(1, 1, 0, 0, 0, 0, 0, 0, 0, -1);
    CHECK(both(cylinder, {1, 0, 0}, {0, 0, 1}) == Sense::on);
    CHECK(both(cylinder, {1, 0, 0}, {0, 1, 1}) == Sense::positive);
    // A cone's apex: out along x, along a generator on it, inside along the axis.
    Quadric cone = gq(1, 1, -1, 0, 0, 0, 0, 0, 0, 0);
    CHECK(both(cone, {0, 0, 0}, {1, 0, 0}) == Sense::positive);
    CHECK(both(cone, {0, 0, 0}, {1, 0, 1}) == Sense::on);
    CHECK(both(cone, {0, 0, 0}, {0, 0, 1}) == Sense::negative);
    // A hyperboloid of one sheet's throat: the ruling (1, t, t) lies on it.
    Quadric hyperboloid = gq(1, 1, -1, 0, 0, 0, 0, 0, 0, -1);
    CHECK(both(hyperboloid, {1, 0, 0}, {0, 1, 1}) == Sense::on);
    CHECK(both(hyperboloid, {1, 0, 0}, {0, 1, 0}) == Sense::positive);
    // Cross terms: f = xy (a pair of planes) at the origin, along a diagonal and along an axis.
    Quadric planes = gq(0, 0, 0, 1, 0, 0, 0, 0, 0, 0);
    CHECK(both(planes, {0, 0, 0}, {1, 1, 0}) == Sense::positive);
    CHECK(both(planes, {0, 0, 0}, {1, -1, 0}) == Sense::negative);
    CHECK(both(planes, {0, 0, 0}, {1, 0, 0}) == Sense::on);
    // A plane: along it, through it.
    Plane plane{{0, 0, 2}, 2};
    CHECK(both(plane, {7, -3, 1}, {1, 1, 0}) == Sense::on);
    CHECK(both(plane, {7, -3, 1}, {1, 1, -1e-300}) == Sense::negative);
    CHECK(both(plane, {7, -3, 1}, {0, 0, 1}) == Sense::positive);
}

TEST_CASE("sense: fast equals the oracle on random surfaces, points and directions", "[sense]") {
    std::mt19937_64 g(20261202);
    for (int i = 0; i < 20000; ++i) {
        // Exponents up to 700 (products overflow double) for a fifth, small ones (cancellation
        // near the surface) for the rest.
        int e = i % 5 == 0 ? 700 : 4;
        Quadric q;
        for (double& c : q.q)
            c = i % 3 == 0 && g() % 3 == 0 ? 0.0 : any(g, e); // some terms absent
        Plane plane{{any(g, e), any(g, e), any(g, e)}, any(g, e)};
        Vec3 p{any(g, e), any(g, e), any(g, e)}, u{any(g, e), any(g, e), any(g, e)};
        if (i % 7 == 0) {
            // On the plane exactly: d = n . p where that sum is exact in double.
            plane = {{1, -2, 0.5}, 0};
            p = {std::ldexp(3.0, e), std::ldexp(1.0, e), 4};
            plane.d = p.x - 2 * p.y + 0.5 * p.z;
        }
        INFO("case " << i);
        both(q, p);
        both(q, p, u);
        both(plane, p);
        both(plane, p, u);
    }
}

TEST_CASE("sense: bad input is named, by both layers alike", "[sense]") {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const double inf = std::numeric_limits<double>::infinity();
    auto refused = [](SenseResult fast, SenseResult oracle, ErrorCode code, const char* field) {
        CHECK(fast.error.code == code);
        CHECK(std::string(fast.error.field) == field);
        CHECK(oracle.error.code == code);
        CHECK(std::string(oracle.error.field) == field);
    };
    Quadric bad = sphere(1);
    bad.q[4] = nan;
    refused(sense(bad, {0, 0, 0}), exact::sense(bad, {0, 0, 0}), ErrorCode::not_a_number, "q");
    Quadric zero{};
    refused(sense(zero, {0, 0, 0}), exact::sense(zero, {0, 0, 0}), ErrorCode::zero_coefficients,
            "q");
    Plane flat{{0, 0, 0}, 1};
    refused(sense(flat, {0, 0, 0}), exact::sense(flat, {0, 0, 0}), ErrorCode::zero_coefficients,
            "n");
    Plane far{{1, 0, 0}, inf};
    refused(sense(far, {0, 0, 0}), exact::sense(far, {0, 0, 0}), ErrorCode::infinite, "d");
    Plane plane{{1, 0, 0}, 0};
    refused(sense(plane, {0, inf, 0}), exact::sense(plane, {0, inf, 0}), ErrorCode::infinite, "p");
    refused(sense(plane, {0, 0, 0}, {0, 0, 0}), exact::sense(plane, {0, 0, 0}, {0, 0, 0}),
            ErrorCode::zero_direction, "u");
    refused(sense(sphere(1), {1, 0, 0}, {nan, 0, 0}),
            exact::sense(sphere(1), {1, 0, 0}, {nan, 0, 0}), ErrorCode::not_a_number, "u");
    // A direction is checked even where the point alone decides.
    refused(sense(sphere(1), {5, 0, 0}, {0, 0, 0}), exact::sense(sphere(1), {5, 0, 0}, {0, 0, 0}),
            ErrorCode::zero_direction, "u");
}

TEST_CASE("sense: the CLI answers as the library and the oracle do, and names bad lines",
          "[sense][cli]") {
    namespace fs = std::filesystem;
    fs::path dir = test::scratch("sense_cli");
    std::ofstream(dir / "q.jsonl")
        << "{\"id\":1,\"shape\":\"plane\",\"n\":[1,2,3],\"d\":24,\"p\":[5,-7,11]}\n"
           "{\"id\":2,\"shape\":\"quadric\",\"q\":[1,1,1,0,0,0,0,0,0,-1],\"p\":[1,0,0],"
           "\"u\":[0,1,0]}\n"
           "{\"id\":3,\"shape\":\"quadric\",\"q\":[\"0x1p-1000\",\"-0x1p-1000\",0,0,0,0,0,0,0,0],"
           "\"p\":[\"0x1.8000000000001p-59\",\"0x1.8p-59\",0]}\n"
           "{\"id\":4,\"shape\":\"quadric\",\"q\":[0,0,0,0,0,0,0,0,0,0],\"p\":[1,0,0]}\n"
           "{\"id\":5,\"shape\":\"plane\",\"n\":[1,0,0],\"d\":0,\"p\":[0,0,0],\"w\":1}\n";
    test::Ran fast = test::program("sense q.jsonl", dir);
    test::Ran oracle = test::program("sense --oracle q.jsonl", dir);
    CHECK(fast.status == 1); // a malformed line
    CHECK(fast.out == oracle.out);
    CHECK(fast.out == "{\"id\":1,\"sense\":\"on\",\"sign\":0}\n"
                      "{\"id\":2,\"sense\":\"positive\",\"sign\":1}\n"
                      "{\"id\":3,\"sense\":\"positive\",\"sign\":1}\n"
                      "{\"id\":4,\"solver\":\"sense\",\"error\":\"q has every coefficient 0 (it "
                      "is no surface)\",\"code\":\"zero_coefficients\"}\n"
                      "{\"id\":5,\"solver\":\"sense\",\"error\":\"line 5: field \\\"w\\\": not a "
                      "field of a plane sense query\",\"code\":\"malformed\"}\n");
}

TEST_CASE("sense: the caller's rounding mode and flush-to-zero do not move an answer", "[sense]") {
    // Subnormal inputs and products that underflow: what flush-to-zero and denormals-are-zero
    // would read as 0, and an upward rounding mode would widen the filter's error past its bound.
    double tiny = std::ldexp(3.0, -60), sub = 0x1p-1074;
    Quadric shallow = gq(0x1p-1000, -0x1p-1000, 0, 0, 0, 0, 0, 0, 0, 0);
    Plane plane{{1, 0, 0}, 0};
    auto answers = [&] {
        return std::vector<Sense>{sense(shallow, {up(tiny), tiny, 0}).sense,
                                  sense(plane, {sub, 0, 0}).sense,
                                  sense(plane, {0, 0, 0}, {sub, 1, 0}).sense,
                                  exact::sense(shallow, {up(tiny), tiny, 0}).sense,
                                  exact::sense(plane, {sub, 0, 0}).sense};
    };
    std::vector<Sense> standard = answers();
    CHECK(standard == std::vector<Sense>(5, Sense::positive));
    numeric::FpState caller = numeric::fp_state();
    std::fesetround(FE_UPWARD);
    __builtin_ia32_ldmxcsr(__builtin_ia32_stmxcsr() | 0x8040); // FTZ and DAZ
    numeric::FpState hostile = numeric::fp_state();
    std::vector<Sense> under = answers();
    numeric::FpState after = numeric::fp_state();
    numeric::set_fp_state(caller);
    CHECK(after == hostile); // the caller's own environment is given back
    CHECK(under == standard);
}
