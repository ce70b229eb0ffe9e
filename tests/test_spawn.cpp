// Spawned rays: the origin spawn_ray proves off the surface is checked against geometry the
// oracle (robust/, CGAL) decides on its own: a ray continuing along its line meets exactly the
// crossings that line has beyond the hit, a ray reflected outward off a convex solid meets it no
// more, and the crossing it left lies behind it. Started at the hit point itself, the same rays
// find the crossing they left again (the tests count that too: they would fail without the offset).
#include "linequad/exact.hpp"
#include "linequad/families.hpp"
#include "linequad/scene.hpp"
#include "linequad/solvers.hpp"
#include "linequad/spawn.hpp"
#include "linequad/spawn_audit.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <limits>

using namespace linequad;

namespace {

// Whether a parent line's hits are well apart: every one a simple crossing, and consecutive ones
// further apart than 2^-20 of their size, so that an offset of a few ulps cannot carry a spawned
// ray across the next one (the test's geometry is then not in question, only the origin).
bool well_separated(const Result& r) {
    if (r.on_surface || r.count == 0) return false;
    for (int i = 0; i < r.count; ++i)
        if (r.hits[i].kind != HitKind::cross) return false;
    for (int i = 1; i < r.count; ++i) {
        Vec3 a = r.hits[i - 1].p, b = r.hits[i].p;
        double size = std::fmax(1, std::fmax(max_abs(a), max_abs(b)));
        if (max_abs(b - a) <= 0x1p-20 * size) return false;
    }
    return true;
}

// The whole quadric the shape is part of: no extent, no caps.
Shape unbounded(Shape s) {
    std::visit(
        [](auto& x) {
            if constexpr (has_extent_options<std::decay_t<decltype(x)>>) x.finite = x.caps = false;
        },
        s);
    return s;
}

double distance(Vec3 a, Vec3 b) {
    return norm(b - a);
}

} // namespace

TEST_CASE("a spawned ray continuing along its line meets exactly the crossings beyond the hit",
          "[spawn]") {
    int checked = 0, naive_self_hits = 0, refused = 0;
    // On the whole quadric: a finite extent could end between a crossing of the line and the
    // same crossing of the spawned line, which the offset moves by a little (caps: below). Not
    // the axis_parallel family: its lines tilted 2^-52 off the axis cross 2^55 out, where an ulp
    // is wider than the shape and the moved line is another line altogether.
    for (Family f : {Family::generic, Family::scale, Family::near_tangent, Family::two_nappes}) {
        for (int shape = 0; shape < 4; ++shape) {
            if (!family_applies(f, shape)) continue;
            for (std::uint64_t i = 0; i < 150; ++i) {
                Case c = make_case(f, shape, Range::line, 11, i);
                c.shape = unbounded(c.shape);
                Line line{c.line.L0, c.line.v, Range::line};
                Result parent = correct::intersect(c.shape, line, {Need::all, true});
                if (!parent.ok() || !well_separated(parent)) continue;
                for (int k = 0; k < parent.count; ++k) {
                    const Hit& h = parent.hits[k];
                    SpawnedRay s = spawn_ray(c.shape, h, line.v);
                    INFO(c.id << " hit " << k);
                    INFO(message(s.error));
                    // Within an ulp of p the side the direction leaves to may change: near a
                    // cone's apex (two_nappes; the scale family's small cones at 2^49, whose
                    // ulp is as wide as the shape). spawn_ray then proves nothing and says so.
                    if ((f == Family::scale || f == Family::two_nappes) &&
                        s.error.code == ErrorCode::along_surface) {
                        ++refused;
                        continue;
                    }
                    REQUIRE(s.ok());
                    Result ahead = exact::intersect(c.shape, s.line, {Need::all, true});
                    REQUIRE(ahead.ok());
                    REQUIRE(!ahead.on_surface);
                    REQUIRE(ahead.count == parent.count - 1 - k);
                    // The first crossing ahead is the line's next one, not the one it left.
                    if (ahead.count > 0)
                        CHECK(distance(ahead.hits[0].p, parent.hits[k + 1].p) <
                              distance(ahead.hits[0].p, h.p));
                    // The one it left is behind the origin.
                    Line back = s.line;
                    back.range = Interval(-std::numeric_limits<double>::infinity(), 0);
                    Result behind = exact::intersect(c.shape, back, {Need::all, true});
                    REQUIRE(behind.count == k + 1);
                    for (int j = 0; j < parent.count; ++j)
                        if (j != k)
                            CHECK(distance(behind.hits[k].p, h.p) <
                                  distance(behind.hits[k].p, parent.hits[j].p));
                    Line naive{h.p, line.v, Range::ray};
                    if (exact::intersect(c.shape, naive, {Need::all, false}).count > ahead.count)
                        ++naive_self_hits;
                    ++checked;
                }
            }
        }
    }
    CHECK(checked > 1000);
    CHECK(refused <= checked / 50);
    // Started at the correctly rounded hit point, the ray finds the crossing it left often.
    CHECK(naive_self_hits > checked / 10);
}

TEST_CASE("a ray reflected outward off a convex solid meets it no more", "[spawn]") {
    int checked = 0, naive_self_hits = 0;
    for (int shape : {0, 1}) { // the cylinders, unbounded: convex solids
        for (std::uint64_t i = 0; i < 400; ++i) {
            Case c = make_case(Family::generic, shape, Range::line, 12, i);
            c.shape = unbounded(c.shape);
            Result parent = correct::intersect(c.shape, c.line, {Need::nearest, true});
            if (!parent.ok() || parent.count == 0 || parent.hits[0].kind != HitKind::cross)
                continue;
            const Hit& h = parent.hits[0];
            // Reflection off the tangent plane: an approximate normal is enough, since the
            // reflected ray's side is decided exactly by spawn_ray (refused if it is not out).
            Vec3 n = normal(c.shape, h);
            REQUIRE(dot(n, c.line.v) < 0); // the nearest crossing enters the solid
            Vec3 d = c.line.v - (2 * dot(c.line.v, n)) * n;
            SpawnedRay s = spawn_ray(c.shape, h, d);
            INFO(c.id);
            if (s.error.code == ErrorCode::along_surface) continue; // grazing: no side
            REQUIRE(s.ok());
            CHECK(s.side == 1);
            CHECK(exact::intersect(c.shape, s.line, {Need::all, false}).count == 0);
            if (exact::intersect(c.shape, Line{h.p, d, Range::ray}, {Need::all, false}).count > 0)
                ++naive_self_hits;
            ++checked;
        }
    }
    CHECK(checked > 300);
    CHECK(naive_self_hits > checked / 10);
}

TEST_CASE("a spawned ray leaves a disc: through the solid to the other or off it", "[spawn]") {
    int checked = 0;
    for (int shape = 0; shape < 4; ++shape) {
        for (std::uint64_t i = 0; i < 200; ++i) {
            Case c = make_case(Family::cap_axis, shape, Range::line, 13, i);
            Result parent = correct::intersect(c.shape, c.line, {Need::all, true});
            // Lines near the axis, through both discs of a closed solid (a one-nappe cone's
            // apex instead of its top) well apart.
            if (!parent.ok() || !well_separated(parent) || parent.count != 2) continue;
            const Hit& in = parent.hits[0];
            if (in.part == Part::lateral) continue;
            INFO(c.id);
            SpawnedRay through = spawn_ray(c.shape, in, c.line.v);
            REQUIRE(through.ok());
            CHECK(through.side == -1);
            Result ahead = exact::intersect(c.shape, through.line, {Need::all, true});
            REQUIRE(ahead.count == 1);
            CHECK(ahead.hits[0].part == parent.hits[1].part);
            SpawnedRay off = spawn_ray(c.shape, in, -1.0 * c.line.v); // back out of the disc
            REQUIRE(off.ok());
            CHECK(off.side == 1);
            CHECK(exact::intersect(c.shape, off.line, {Need::all, false}).count == 0);
            ++checked;
        }
    }
    CHECK(checked > 100);
}

TEST_CASE("spawning at a cone's apex moves along the direction", "[spawn]") {
    EllipticCone cone{{0, 0, -1}, {0, 0, 0}, {1, 0, 0}, {0, 1, 0}, false, false, 1};
    Hit apex{0, {0, 0, 0}, 0, HitKind::tangent, Part::lateral, true};
    Vec3 down{0.25, 0, -1}; // into the nappe (z <= 0, |x| < |z|)
    SpawnedRay s = spawn_ray(cone, apex, down);
    REQUIRE(s.ok());
    CHECK(exact::intersect(cone, s.line, {Need::all, false}).count == 0);
    // From the apex itself the ray touches it at t = 0.
    CHECK(exact::intersect(cone, Line{apex.p, down, Range::ray}, {Need::all, false}).count == 1);
}

TEST_CASE("spawn_ray refuses what it cannot prove and says why", "[spawn]") {
    Cylinder cyl{{0, 0, 0}, {0, 0, 2}, 1, true, false};
    Hit h{0, {1, 0, 1}, 0, HitKind::cross, Part::lateral, true};
    double nan = std::numeric_limits<double>::quiet_NaN();
    double inf = std::numeric_limits<double>::infinity();
    auto code = [&](const Shape& s, const Hit& hit, Vec3 d) {
        SpawnedRay r = spawn_ray(s, hit, d);
        if (!r.ok()) CHECK((r.line.v.x == 0 && r.line.v.y == 0 && r.line.v.z == 0));
        return std::string(code_name(r.error.code)) + " " + r.error.field;
    };
    CHECK(code(cyl, h, {1, 0, 0}) == "none ");
    CHECK(code(cyl, h, {0, 0, 1}) == "along_surface direction"); // along the axis
    CHECK(code(cyl, h, {0, 1, 0}) == "along_surface direction"); // tangent
    CHECK(code(cyl, h, {0, 0, 0}) == "zero_direction direction");
    CHECK(code(cyl, h, {nan, 0, 0}) == "not_a_number direction");
    CHECK(code(cyl, h, {inf, 0, 0}) == "infinite direction");
    Hit bad = h;
    bad.p.y = nan;
    CHECK(code(cyl, bad, {1, 0, 0}) == "not_a_number p");
    bad.p.y = -inf;
    CHECK(code(cyl, bad, {1, 0, 0}) == "infinite p");
    Hit top = h;
    top.part = Part::top, top.p = {0.5, 0, 2};
    CHECK(code(cyl, top, {0, 0, 1}) == "bad_option part"); // no caps: no top disc
    Cylinder closed = cyl;
    closed.caps = true;
    CHECK(code(closed, top, {0, 0, 1}) == "none ");
    CHECK(code(closed, top, {1, 0, 0}) == "along_surface direction"); // in the disc's plane
    Cylinder flat = cyl;
    flat.r = -1;
    CHECK(code(flat, h, {1, 0, 0}) == "bad_radius r");
    // A point at the end of double: every step off it overflows.
    Hit huge = h;
    huge.p = {std::numeric_limits<double>::max(), 0, 1};
    CHECK(code(cyl, huge, {1, 0, 0}) == "out_of_range p");
}

TEST_CASE("a scene spawns from its shapes' hits", "[spawn][scene]") {
    std::vector<Shape> shapes{Cylinder{{0, 0, 0}, {0, 0, 2}, 1, true, true},
                              Cylinder{{5, 0, 0}, {5, 0, 2}, 1, true, true}};
    Scene scene(shapes);
    SceneAnswer a;
    Line ray{{-3, 0.25, 1}, {1, 0, 0}, Range::ray};
    scene.intersect(ray, {Need::all, true}, a);
    REQUIRE(a.hits.size() == 4);
    for (const SceneHit& h : a.hits) {
        SpawnedRay s = scene.spawn_ray(h, ray.v);
        REQUIRE(s.ok());
        SpawnedRay direct = spawn_ray(shapes[h.shape], h.hit, ray.v);
        CHECK(s.line.L0 == direct.line.L0);
        SceneAnswer next;
        scene.intersect(s.line, {Need::all, true}, next);
        CHECK(next.hits.size() == std::size_t(3 - (&h - a.hits.data())));
    }
    SceneHit stray = a.hits[0];
    stray.shape = 7;
    SpawnedRay s = scene.spawn_ray(stray, ray.v);
    CHECK(s.error.code == ErrorCode::bad_option);
    CHECK(std::string(s.error.field) == "shape");
}

TEST_CASE("the spawn audit grades the proven offset against the usual epsilon", "[spawn]") {
    audit::SpawnAuditOptions o;
    o.cases = 40;
    std::vector<audit::SpawnRow> rows = audit::run_spawn_audit(o);
    auto method = [](const audit::SpawnRow& r, audit::SpawnMethod m) { return r.methods[int(m)]; };
    std::uint64_t at_hit_self = 0, spawned = 0;
    for (const audit::SpawnRow& r : rows) {
        INFO(r.family << " " << r.kind);
        audit::SpawnTally c = method(r, audit::SpawnMethod::correct_spawned);
        at_hit_self += method(r, audit::SpawnMethod::correct_at_hit).self_hits;
        spawned += c.spawns;
        // Where hit points are well inside double's grid for their shape, the proof holds: no
        // spawned ray starts on the side it left. (The scale, axis_parallel and cap_axis
        // families place hits where an ulp is as wide as the shape, and two_nappes within
        // rounding of the apex: there the rounded hit point may lie on the other side.)
        if (r.family == "generic" || r.family == "near_tangent" || r.family == "rim" ||
            r.family == "inside_start" || r.family == "extent_edge")
            CHECK(c.self_hits == 0);
        CHECK(c.misparent == 0); // correct's parents are the oracle's
    }
    CHECK(spawned > 1000);
    CHECK(at_hit_self > spawned / 10); // without the offset, correctly rounded points self-hit
    std::string md = audit::spawn_report_markdown(rows, o, "linequad spawn --cases 40");
    CHECK(md.find("| generic | through | correct, spawn_ray |") != std::string::npos);
    CHECK(md.find("## Every family") != std::string::npos);
}
