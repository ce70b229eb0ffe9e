// Closed shapes (caps), two-nappe cones and parts: hand-built cases with dyadic inputs and known
// answers, and the discs against an independent plane intersection in exact rationals.
#include "support.hpp"

#include "forms/closure.hpp"

#include "linequad/exact.hpp"

#include <CGAL/Gmpq.h>

#include <cstring>
#include <iterator>
#include <limits>
#include <random>

using namespace linequad;
using test::check_hits;
using test::run;
using test::Want;

namespace {

// The unit-radius cylinder around the z axis from z = 0 to z = 2, closed.
const Cylinder drum{{0, 0, 0}, {0, 0, 2}, 1, true, true};

} // namespace

TEST_CASE("closed cylinder: hits name their part and cross where the line enters or leaves") {
    // Along the axis through both disc centres: base at t = 1, top at t = 3.
    check_hits(drum, {{0.5, 0, -1}, {0, 0, 1}},
               {{1, HitKind::cross, Part::base}, {3, HitKind::cross, Part::top}});
    // The same line without caps: inside the lateral surface, it meets nothing.
    Cylinder open = drum;
    open.caps = false;
    for (const char* solver : test::every_solver)
        CHECK(!run(solver, open, {{0.5, 0, -1}, {0, 0, 1}}).any_hit());
    // From rim to rim, (1, 0, 0) to (-1, 0, 2): each rim belongs to its disc.
    check_hits(drum, {{1, 0, 0}, {-2, 0, 2}},
               {{0, HitKind::cross, Part::base}, {1, HitKind::cross, Part::top}});
    // Through the base disc and out through the side: (1/2, 0, 0) to (1, 0, 1/2).
    check_hits(drum, {{0.25, 0, -0.25}, {0.25, 0, 0.25}},
               {{1, HitKind::cross, Part::base}, {3, HitKind::cross, Part::lateral}});
    // Tangent to the lateral surface inside the extent: it touches without entering.
    check_hits(drum, {{-2, 1, 1}, {1, 0, 0}}, {{2, HitKind::tangent, Part::lateral}});
    // Grazing the base rim at (0, 1, 0) in the disc's plane: one point, tangent, the disc's.
    check_hits(drum, {{-2, 1, 0}, {1, 0, 0}}, {{2, HitKind::tangent, Part::base}});
    // Grazing the top rim from outside, out of its plane: touches the solid at the rim only.
    check_hits(drum, {{-1, 1, 1}, {1, 0, 1}}, {{1, HitKind::tangent, Part::top}});
}

TEST_CASE("closed cylinder: rays from inside, on the surface and outside") {
    // From the centre: the one exit, through the side.
    Line inside{{0, 0, 1}, {1, 0, 0}, Range::ray};
    check_hits(drum, inside, {{1, HitKind::cross, Part::lateral}});
    // From a point of the base disc, upwards: t = 0 on the base, then the top.
    Line on_base{{0.5, 0, 0}, {0, 0, 1}, Range::ray};
    check_hits(drum, on_base, {{0, HitKind::cross, Part::base}, {2, HitKind::cross, Part::top}});
    // From just below the base (2^-40), upwards. (2 + 2^-40 is not a float, and stable32
    // refuses a coordinate 2^-40 of the scene: its zeros could be underflow.)
    Line below{{0.5, 0, -0x1p-40}, {0, 0, 1}, Range::ray};
    check_hits(drum, below,
               {{0x1p-40, HitKind::cross, Part::base}, {2 + 0x1p-40, HitKind::cross, Part::top}},
               test::double_solvers);
    // The segment from the centre to the axis' top: the top disc at its end.
    check_hits(drum, {{0, 0, 1}, {0, 0, 1}, Range::segment}, {{1, HitKind::cross, Part::top}});
}

TEST_CASE("closed cylinder: a line in a disc's plane meets it in the chord, or grazes its rim") {
    // y = 3/5 in the base plane: the chord x in [-4/5, 4/5], t in [6/5, 14/5] (not dyadic:
    // rounded; the correct solver and the oracle to nearest).
    Line chord{{-2, 0.6, 0}, {1, 0, 0}};
    Result want = exact::intersect(drum, chord);
    REQUIRE(want.on_surface);
    CHECK(want.surface_part == Part::base);
    CHECK(want.s0 == 1.2); // 2 - 0.8, the nearest doubles as strtod gives them
    CHECK(want.s1 == 2.8);
    for (const char* solver : test::double_solvers) { // 0.6 is not a float
        Result r = run(solver, drum, chord);
        INFO(solver << ": " << test::describe(r));
        REQUIRE(r.on_surface);
        CHECK(r.surface_part == Part::base);
        CHECK(std::fabs(r.s0 - 1.2) <= 4 * 0x1p-52);
        CHECK(std::fabs(r.s1 - 2.8) <= 8 * 0x1p-52);
    }
    Result c = run("correct", drum, chord);
    CHECK(c.s0 == want.s0);
    CHECK(c.s1 == want.s1);
    // A ray starting inside the chord: the interval from t = 0.
    Result ray = exact::intersect(drum, {{0, 0.6, 0}, {1, 0, 0}, Range::ray});
    REQUIRE(ray.on_surface);
    CHECK(ray.s0 == 0);
    CHECK(ray.s1 == 0.8);
    // Beside the disc, in its plane: nothing.
    for (const char* solver : test::every_solver)
        CHECK(!run(solver, drum, {{-2, 1.5, 2}, {1, 0, 0}}).any_hit());
    // Along a generator: the interval as without caps, now from rim to rim.
    Result gen = exact::intersect(drum, {{1, 0, -1}, {0, 0, 1}});
    REQUIRE(gen.on_surface);
    CHECK(gen.surface_part == Part::lateral);
    CHECK(gen.s0 == 1);
    CHECK(gen.s1 == 3);
}

TEST_CASE("closed elliptic cylinder: discs at z = 0 and z = 1 whatever the frame's handedness") {
    // c points down: the base disc (z = 0) is at C, the top (z = 1) three units below.
    EllipticCylinder s{{0, 0, 0}, {2, 0, 0}, {0, 1, 0}, {0, 0, -3}, true, true};
    check_hits(s, {{1, 0, 1}, {0, 0, -1}},
               {{1, HitKind::cross, Part::base}, {4, HitKind::cross, Part::top}});
    // x = 2 (the ellipse's vertex) along the axis: on the surface from rim to rim.
    Result gen = exact::intersect(s, {{2, 0, 1}, {0, 0, -1}});
    REQUIRE(gen.on_surface);
    CHECK(gen.s0 == 1);
    CHECK(gen.s1 == 4);
}

TEST_CASE("two-nappe cones: four hits closed, the apex between the solids tangent") {
    // Apex at (0, 0, 1), base z = 0 and top z = 2 (local z = -1 and 1), radius 1 at each.
    EllipticCone both{{0, 0, 0}, {0, 0, 1}, {1, 0, 0}, {0, 1, 0}, true, true, 2};
    // Parallel to the axis at x = 1/4: base, lateral at z = 3/4 and 5/4, top.
    check_hits(both, {{0.25, 0, -1}, {0, 0, 1}},
               {{1, HitKind::cross, Part::base},
                {1.75, HitKind::cross, Part::lateral},
                {2.25, HitKind::cross, Part::lateral},
                {3, HitKind::cross, Part::top}});
    // Along the axis: through the apex from one solid into the other without reaching the
    // outside: tangent there.
    check_hits(both, {{0, 0, -1}, {0, 0, 1}},
               {{1, HitKind::cross, Part::base},
                {2, HitKind::tangent, Part::lateral},
                {3, HitKind::cross, Part::top}});
    // Touching the apex from outside (across the axis): tangent.
    check_hits(both, {{-1, 0, 1}, {1, 0, 0}}, {{1, HitKind::tangent, Part::lateral}});
    // One nappe, closed: entering through the apex is a crossing.
    EllipticCone one = both;
    one.nappes = 1;
    check_hits(one, {{0, 0, -1}, {0, 0, 1}},
               {{1, HitKind::cross, Part::base}, {2, HitKind::cross, Part::lateral}});
    // Two nappes, open and finite: the lateral roots on both, kinds as double roots have them.
    EllipticCone open = both;
    open.caps = false;
    check_hits(open, {{0.25, 0, -1}, {0, 0, 1}},
               {{1.75, HitKind::cross, Part::lateral}, {2.25, HitKind::cross, Part::lateral}});
    check_hits(open, {{0, 0, -1}, {0, 0, 1}}, {{2, HitKind::tangent, Part::lateral}});
    // One nappe (the default) keeps only z <= 0 of it.
    open.nappes = 1;
    check_hits(open, {{0.25, 0, -1}, {0, 0, 1}}, {{1.75, HitKind::cross, Part::lateral}});
    // Two infinite nappes: the mirror nappe's root is kept far beyond z = 1.
    EllipticCone infinite{{0, 0, 0}, {0, 0, 1}, {1, 0, 0}, {0, 1, 0}, false, false, 2};
    check_hits(infinite, {{0.25, 0, -1}, {0, 0, 1}},
               {{1.75, HitKind::cross, Part::lateral}, {2.25, HitKind::cross, Part::lateral}});
    check_hits(infinite, {{-8, 0, 9}, {1, 0, 0}},
               {{0, HitKind::cross, Part::lateral}, {16, HitKind::cross, Part::lateral}});
}

TEST_CASE("options a shape cannot take are refused by name") {
    Cylinder infinite = drum;
    infinite.finite = false;
    EllipticCone three{{0, 0, 0}, {0, 0, 1}, {1, 0, 0}, {0, 1, 0}, true, false, 3};
    for (const char* solver : test::every_solver) {
        Result r = run(solver, infinite, {{0, 0, 0}, {1, 0, 0}});
        CHECK(r.error_code == ErrorCode::bad_option);
        CHECK(std::string(r.error_field) == "caps");
        Result n = run(solver, three, {{0, 0, 0}, {1, 0, 0}});
        CHECK(n.error_code == ErrorCode::bad_option);
        CHECK(std::string(n.error_field) == "nappes");
    }
}

TEST_CASE("disc hits agree with an independent plane intersection in exact rationals") {
    // Integer frames; a dyadic point of a disc (inside it, or on its rim) and a dyadic t give
    // the line. The plane through the disc is intersected directly: t = (Q - L0).n / (v.n) with
    // n = a x b the disc's normal and Q its centre, and the point's distance from the centre
    // measured in the frame. The oracle's disc hit must be that t, on that disc.
    std::mt19937_64 rng(13);
    auto integer = [&](int lo, int hi) { return lo + int(rng() % std::uint64_t(hi - lo + 1)); };
    auto ivec = [&](int s) {
        return Vec3{double(integer(-s, s)), double(integer(-s, s)), double(integer(-s, s))};
    };
    using Q = CGAL::Gmpq;
    int checked = 0;
    for (int i = 0; i < 300; ++i) {
        Vec3 O = ivec(5), a = ivec(3), b = ivec(3), c = ivec(3);
        if (dot(a, cross(b, c)) == 0) continue;
        int kind = i % 4;
        bool top = integer(0, 1) == 1;
        Shape shape;
        Vec3 centre;
        if (kind == 0) { // a cylinder needs a round frame: an axis-aligned one
            a = {2, 0, 0}, b = {0, 2, 0}, c = {0, 0, double(integer(1, 4))};
            shape = Cylinder{O, O + c, 2, true, true};
            centre = top ? O + c : O;
        } else if (kind == 1) {
            shape = EllipticCylinder{O, a, b, c, true, true};
            centre = top ? O + c : O;
        } else if (kind == 2) { // the cone's base z = -1 at C = O - c, its top z = 1 at O + c
            shape = EllipticCone{O - c, O, a, b, true, true, 2};
            centre = top ? O + c : O - c;
        } else { // a frustum whose discs (radii 2 and 3) hold every point x a + y b below
            a = {2, 0, 0}, b = {0, 2, 0}, c = {0, 0, double(integer(1, 4))};
            bool wider_top = integer(0, 1) == 1;
            shape = Frustum{O, wider_top ? 2.0 : 3.0, O + c, wider_top ? 3.0 : 2.0, true, true};
            centre = top ? O + c : O;
        }
        double x = integer(-4, 4) * 0.25, y = integer(-4, 4) * 0.25;
        if (x * x + y * y > 1) x = 0.5, y = 0.5;
        Vec3 P = centre + x * a + y * b, v = ivec(4);
        if (dot(v, cross(a, b)) == 0) continue;
        double t = integer(-8, 8) * 0.125;
        Line l{P - t * v, v};
        // Independent: the plane's intersection, in rationals.
        Vec3 n = cross(a, b);
        auto q = [](double d) { return Q(d); };
        Q num = (q(centre.x) - q(l.L0.x)) * q(n.x) + (q(centre.y) - q(l.L0.y)) * q(n.y) +
                (q(centre.z) - q(l.L0.z)) * q(n.z);
        Q den = q(v.x) * q(n.x) + q(v.y) * q(n.y) + q(v.z) * q(n.z);
        Q t_plane = num / den;
        REQUIRE(t_plane == Q(t));
        Result r = exact::intersect(shape, l);
        INFO(test::describe(r));
        REQUIRE(r.ok());
        bool found = false;
        for (int h = 0; h < r.count; ++h)
            if (r.hits[h].part == (top ? Part::top : Part::base)) {
                CHECK(Q(r.hits[h].t) == t_plane);
                found = true;
            }
        // A point of the disc is always a hit of the closed shape unless the line lies in the
        // disc's plane (it does not: v.n != 0).
        CHECK(found);
        Result c2 = correct::intersect(shape, l);
        test::check_same_answer(c2, r);
        ++checked;
    }
    CHECK(checked > 150);
}

namespace {

// close_convex's candidates against close()'s, one R at a time: roots, disc tests and extents
// drawn from values that sit on an end, beside it, far off, or are not numbers at all.
template <class R>
void check_convex_closure_against_close(std::mt19937_64& rng) {
    using detail::CandidateT;
    const R pool[] = {0,
                      2,
                      1,
                      -1,
                      R(0.5),
                      std::nextafter(R(0), R(1)),
                      std::nextafter(R(2), R(3)),
                      std::nextafter(R(2), R(1)),
                      R(1e30),
                      -R(1e30),
                      std::numeric_limits<R>::infinity(),
                      std::numeric_limits<R>::quiet_NaN()};
    auto any = [&] { return pool[rng() % std::size(pool)]; };
    auto small = [&] { return R(int(rng() % 9) - 4) / 2; };
    for (int trial = 0; trial < 20000; ++trial) {
        auto pick = [&] { return rng() % 4 == 0 ? any() : small(); };
        detail::RootsT<R> r;
        r.kind = static_cast<typename detail::RootsT<R>::Kind>(rng() % 4);
        r.t[0] = pick(), r.t[1] = pick();
        detail::AxialQuadratic<R> q{pick(), pick(), pick(), pick(), pick(), pick(), R(0.5)};
        detail::Extent e{0, 2, {bool(rng() & 1), bool(rng() & 2), false}};
        if (!e.caps.lo && !e.caps.hi) e.caps.hi = true;
        auto z_of = [&](const detail::RootsT<R>& roots, int i) { return q.z0 + roots.t[i] * q.dz; };
        CandidateT<R> lean[max_hits];
        int n = detail::close_convex(r, z_of, q, e, lean);
        detail::BoundaryPoint<R> lateral[2];
        for (int i = 0; i < r.count(); ++i)
            lateral[i] = {r.t[i] * q.t_scale, z_of(r, i), Part::lateral, r.hit_kind(), true};
        detail::ClosedPoints<R> general = detail::close(lateral, r.count(), q, e);
        INFO("trial " << trial);
        REQUIRE(n == general.n);
        for (int i = 0; i < n; ++i) {
            const detail::BoundaryPoint<R>& p = general.p[i];
            // bit for bit: a NaN is the same NaN, and -0 is not +0
            CHECK(std::memcmp(&lean[i].t, &p.t, sizeof(R)) == 0);
            CHECK(std::memcmp(&lean[i].z, &p.z, sizeof(R)) == 0);
            CHECK(lean[i].kind == p.kind);
            CHECK(lean[i].part == p.part);
        }
    }
}

} // namespace

TEST_CASE("seed's and stable's convex closure equals the general one, NaN and rims included") {
    std::mt19937_64 rng(41);
    check_convex_closure_against_close<double>(rng);
    check_convex_closure_against_close<float>(rng);
}
