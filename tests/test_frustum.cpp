// The frustum: hand-built cases with dyadic inputs and known answers; r0 = r1 against the
// cylinder and r1 = 0 against the circular cone, exactly; lines through two surface points; its
// validation.
#include "support.hpp"

#include "linequad/exact.hpp"

#include <random>

using namespace linequad;
using test::check_hits;
using test::run;
using test::Want;

namespace {

// Radius 2 at z = 0 narrowing to 1 at z = 4 around the z axis: the radius at z is 2 - z / 4.
const Frustum lamp{{0, 0, 0}, 2, {0, 0, 4}, 1};
// The same narrowing to an apex at z = 4: radius 2 - z / 2.
const Frustum spike{{0, 0, 0}, 2, {0, 0, 4}, 0};

Frustum closed(Frustum f) {
    f.caps = true;
    return f;
}
Frustum infinite(Frustum f) {
    f.finite = false;
    return f;
}

// The shapes and lines of a random test: small integers and dyadics.
struct Dyadics {
    std::mt19937_64 rng;
    explicit Dyadics(unsigned seed) : rng(seed) {}
    int integer(int lo, int hi) { return lo + int(rng() % std::uint64_t(hi - lo + 1)); }
    Vec3 ivec(int s) {
        return {double(integer(-s, s)), double(integer(-s, s)), double(integer(-s, s))};
    }
    double quarter(int lo, int hi) { return 0.25 * integer(4 * lo, 4 * hi); }
    bool coin() { return rng() & 1; }
};

// An integer quaternion's rotation times N = |q|^2: an integer matrix whose columns are
// orthogonal and of length N.
struct RoundFrame {
    Vec3 a, b, c;
    double N;
};
RoundFrame round_frame(Dyadics& d) {
    double w, x, y, z;
    do
        w = d.integer(-2, 2), x = d.integer(-2, 2), y = d.integer(-2, 2), z = d.integer(-2, 2);
    while (w == 0 && x == 0 && y == 0 && z == 0);
    RoundFrame f;
    f.N = w * w + x * x + y * y + z * z;
    f.a = {w * w + x * x - y * y - z * z, 2 * (x * y + w * z), 2 * (x * z - w * y)};
    f.b = {2 * (x * y - w * z), w * w - x * x + y * y - z * z, 2 * (y * z + w * x)};
    f.c = {2 * (x * z + w * y), 2 * (y * z - w * x), w * w - x * x - y * y + z * z};
    return f;
}

// The frustum's exact answers (the oracle's and correct's) are the other shape's, bit for bit.
void same_answers(const Frustum& frustum, const Shape& other, Line l, Range range) {
    l.range = range;
    if (l.v == Vec3{}) return;
    Result want = exact::intersect(other, l);
    Case c;
    c.shape = other, c.line = l;
    INFO(format_case(c) << "\n" << shape_name(other) << " " << test::describe(want));
    test::check_same_answer(exact::intersect(frustum, l), want);
    test::check_same_answer(correct::intersect(frustum, l), want);
}

} // namespace

TEST_CASE("frustum: hand-built lines cross, touch and lie on it where the geometry says") {
    // Across at z = 2 (radius 3/2) from x = -5.
    check_hits(lamp, {{-5, 0, 2}, {1, 0, 0}},
               {{3.5, HitKind::cross, Part::lateral}, {6.5, HitKind::cross, Part::lateral}});
    // Tangent to the circle of radius 3/2 at z = 2.
    check_hits(lamp, {{1.5, -3, 2}, {0, 1, 0}}, {{3, HitKind::tangent, Part::lateral}});
    // Along the axis: through both discs when closed, nothing of the lateral surface.
    check_hits(lamp, {{0, 0, -1}, {0, 0, 1}}, {});
    check_hits(closed(lamp), {{0, 0, -1}, {0, 0, 1}},
               {{1, HitKind::cross, Part::base}, {5, HitKind::cross, Part::top}});
    // A ray from inside the closed frustum leaves it once.
    check_hits(closed(lamp), {{0, 0, 2}, {1, 0, 0}, Range::ray},
               {{1.5, HitKind::cross, Part::lateral}});
    // Parallel to the generator through (2, 0, 0) and (1, 0, 4), from (1, 0, 0): x = 1 - t meets
    // the radius 2 - t only at t = 3/2 (z = 6), beyond the top, on the nappe that goes on to the
    // apex at z = 8.
    check_hits(lamp, {{1, 0, 0}, {-1, 0, 4}}, {});
    check_hits(infinite(lamp), {{1, 0, 0}, {-1, 0, 4}}, {{1.5, HitKind::cross, Part::lateral}});
    // Through the apex across the axis: it touches the solid from outside.
    check_hits(spike, {{-1, 0, 4}, {1, 0, 0}}, {{1, HitKind::tangent, Part::lateral}});
    check_hits(closed(spike), {{-1, 0, 4}, {1, 0, 0}}, {{1, HitKind::tangent, Part::lateral}});
    // Along the axis into the closed cone: in through the base, out through the apex. The apex
    // has no disc (its radius is 0), so closed means the base alone.
    check_hits(closed(spike), {{0, 0, -1}, {0, 0, 1}},
               {{1, HitKind::cross, Part::base}, {5, HitKind::cross, Part::lateral}});
}

TEST_CASE("frustum: a line along a generator lies on it, over the extent or the whole nappe") {
    // (2, 0, 0) + t (-1, 0, 4): radius 2 - z / 4 = 2 - t = |x|, on the surface for 0 <= t <= 1
    // (finite) and t <= 2 (the nappe, up to the apex at z = 8).
    Line generator{{2, 0, 0}, {-1, 0, 4}};
    for (const char* solver : test::every_solver) {
        Result r = run(solver, lamp, generator);
        INFO(solver << ": " << test::describe(r));
        REQUIRE(r.on_surface);
        CHECK(r.s0 == 0);
        CHECK(r.s1 == 1);
        Result n = run(solver, infinite(lamp), generator);
        INFO(solver << ": " << test::describe(n));
        REQUIRE(n.on_surface);
        CHECK(n.s0 == -INFINITY);
        CHECK(n.s1 == 2);
    }
    // A frustum with equal radii that is not finite is the whole cylinder: a line on it lies on
    // it everywhere (its radius coordinate does not change along the line).
    Frustum tube{{0, 0, 0}, 1.5, {0, 1, 0}, 1.5, false};
    for (const char* solver : test::every_solver) {
        Result r = run(solver, tube, {{1.5, -3, 0}, {0, 1, 0}, Range::segment});
        INFO(solver << ": " << test::describe(r));
        REQUIRE(r.on_surface);
        CHECK(r.s0 == 0);
        CHECK(r.s1 == 1);
    }
}

TEST_CASE("frustum: lines through two of its points meet it exactly there") {
    // Axis-aligned frusta with dyadic radii; two points at dyadic heights and quarter turns on
    // different generators.
    Dyadics d(3);
    int checked = 0;
    for (int i = 0; i < 200; ++i) {
        Vec3 C0 = d.ivec(4);
        double length = d.integer(1, 8), r0 = d.quarter(0, 3), r1 = d.quarter(0, 3);
        if (r0 == 0 && r1 == 0) continue;
        Frustum f{C0, r0, C0 + Vec3{0, 0, length}, r1};
        auto point = [&](double z, int turn) {
            double rho = r0 + (r1 - r0) * z;
            static const double cs[4] = {1, 0, -1, 0};
            return C0 + Vec3{rho * cs[turn], rho * cs[(turn + 3) % 4], z * length};
        };
        int turn = d.integer(0, 3), other = (turn + d.integer(1, 3)) % 4;
        Vec3 p = point(0.125 * d.integer(1, 7), turn), q = point(0.125 * d.integer(1, 7), other);
        if (p == q) continue; // both at the apex
        INFO("frustum r0 " << r0 << " r1 " << r1 << " length " << length);
        test::check_through_two_points(
            f, p, q, {"stable", "certified", "correct", "exact", "stable32", "correct32"});
        ++checked;
    }
    CHECK(checked > 150);
}

TEST_CASE("frustum with r0 = r1 answers as the cylinder, exactly") {
    Dyadics d(5);
    for (int i = 0; i < 400; ++i) {
        Vec3 C = d.ivec(4), H = C + d.ivec(3);
        if (H == C) continue;
        double r = d.quarter(1, 3);
        bool finite = d.integer(0, 3) != 0, caps = finite && d.coin();
        Cylinder cyl{C, H, r, finite, caps};
        Frustum fr{C, r, H, r, finite, caps};
        // Lines through the shape's middle, along its axis, in a disc's plane, or anywhere.
        Line l;
        switch (i % 4) {
        case 0:
            l = {d.ivec(6), 0.5 * (C + H) + 0.25 * d.ivec(2) - d.ivec(6)};
            break;
        case 1:
            l = {C + 0.25 * d.ivec(4) - (H - C), H - C};
            break;
        case 2:
            l = {C + 0.25 * d.ivec(4), cross(H - C, d.ivec(2))};
            break;
        default:
            l = {d.ivec(6), d.ivec(3)};
        }
        same_answers(fr, cyl, l, Range(i % 3));
    }
}

TEST_CASE("frustum with r1 = 0 answers as the elliptic cone with a circular frame, exactly") {
    // The cone {C, H, a, b} with a, b orthogonal to c = H - C and of length R is the frustum
    // from the base disc of radius R at C to the apex H.
    Dyadics d(7);
    for (int i = 0; i < 400; ++i) {
        RoundFrame f = round_frame(d);
        double rad = d.integer(1, 3), len = d.integer(1, 3) * (d.coin() ? 1 : -1);
        Vec3 a = rad * f.a, b = rad * f.b, c = len * f.c, C = d.ivec(6), H = C + c;
        bool finite = d.integer(0, 3) != 0, caps = finite && d.coin();
        EllipticCone cone{C, H, a, b, finite, caps};
        Frustum fr{C, rad * f.N, H, 0, finite, caps};
        Line l;
        switch (i % 4) {
        case 0:
            l = {d.ivec(8), C + 0.5 * c + 0.25 * d.ivec(2) - d.ivec(8)};
            break;
        case 1:
            l = {H - d.ivec(3), d.ivec(3)};
            break; // through the apex
        case 2:
            l = {C + a, d.ivec(3)};
            break; // through a point of the rim
        default:
            l = {d.ivec(8), d.ivec(3)};
        }
        same_answers(fr, cone, l, Range(i % 3));
    }
}

TEST_CASE("frustum: what is wrong with one is named") {
    Line l{{0, 0, 0}, {1, 0, 0}};
    struct Bad {
        Frustum f;
        ErrorCode code;
        const char* field;
    };
    const double nan = std::nan("");
    const Bad bad[] = {
        {{{0, 0, 0}, -1, {0, 0, 1}, 1}, ErrorCode::bad_radius, "r0"},
        {{{0, 0, 0}, 1, {0, 0, 1}, -0.5}, ErrorCode::bad_radius, "r1"},
        {{{0, 0, 0}, 0, {0, 0, 1}, 0}, ErrorCode::bad_radius, "r0,r1"},
        {{{1, 2, 3}, 1, {1, 2, 3}, 2}, ErrorCode::degenerate_axis, "C1-C0"},
        {{{0, 0, 0}, 1, {0, 0, 1}, nan}, ErrorCode::not_a_number, "r1"},
        {{{0, 0, 0}, 1, {0, INFINITY, 1}, 1}, ErrorCode::infinite, "C1"},
        {{{0, 0, 0}, 1, {0, 0, 1}, 1, false, true}, ErrorCode::bad_option, "caps"},
    };
    for (const Bad& b : bad)
        for (const char* solver : test::every_solver) {
            Result r = run(solver, b.f, l);
            INFO(solver << ": " << test::describe(r));
            CHECK(r.error_code == b.code);
            CHECK(std::string(r.error_field) == b.field);
            CHECK(r.count == 0);
        }
}
