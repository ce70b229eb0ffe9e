// Scenes: every answer equals the brute-force loop over all shapes with the same solver (the
// boxes and the hierarchy only skip work), the boxes hold every hit, ties are named, and bad
// input is refused by name.
#include "linequad/exact.hpp"
#include "linequad/families.hpp"
#include "linequad/scene.hpp"
#include "linequad/solvers.hpp"

#include <catch2/catch.hpp>
#include <mpfr.h>

#include <cmath>
#include <cstring>
#include <random>
#include <thread>

using namespace linequad;

namespace {

// The shape carried by d (its frame vectors unchanged).
Shape translated(const Shape& s, Vec3 d) {
    return std::visit(
        [&](auto x) -> Shape {
            using S = decltype(x);
            if constexpr (std::is_same_v<S, Cylinder> || std::is_same_v<S, Capsule>) {
                x.C = x.C + d, x.H = x.H + d;
            } else if constexpr (std::is_same_v<S, EllipticCylinder>) {
                x.C = x.C + d;
            } else if constexpr (std::is_same_v<S, EllipticCone>) {
                x.C = x.C + d, x.H = x.H + d;
            } else if constexpr (std::is_same_v<S, Frustum>) {
                x.C0 = x.C0 + d, x.C1 = x.C1 + d;
            } else if constexpr (std::is_same_v<S, Plane>) {
                x.d = x.d + dot(x.n, d); // rounded: some plane near the carried one
            } else if constexpr (std::is_same_v<S, Quadric>) {
                // f(y - d), expanded (rounded: some quadric near the carried one).
                const auto& q = x.q;
                Quadric m = x;
                m.q[6] = q[6] - (2 * q[0] * d.x + q[3] * d.y + q[5] * d.z);
                m.q[7] = q[7] - (2 * q[1] * d.y + q[3] * d.x + q[4] * d.z);
                m.q[8] = q[8] - (2 * q[2] * d.z + q[4] * d.y + q[5] * d.x);
                m.q[9] = q[9] + q[0] * d.x * d.x + q[1] * d.y * d.y + q[2] * d.z * d.z +
                         q[3] * d.x * d.y + q[4] * d.y * d.z + q[5] * d.z * d.x -
                         (q[6] * d.x + q[7] * d.y + q[8] * d.z);
                x = m;
            } else {
                static_assert(std::is_same_v<S, Sphere> || std::is_same_v<S, Ellipsoid>,
                              "a new shape: translate its points");
                x.C = x.C + d;
            }
            return x;
        },
        s);
}

struct World {
    std::vector<Shape> shapes;
    std::vector<Line> lines;
};

// n shapes of every kind and family (closed, two-nappe and unbounded ones among them) scattered
// over a cube of side `spread`, and lines: each family case's own line carried with its shape
// (they hit it, often near tangency or a rim), and rays across the cube.
World world(int n, double spread, std::uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(-spread / 2, spread / 2), dir(-1, 1);
    World w;
    for (int i = 0; w.shapes.size() < std::size_t(n); ++i) {
        Family f = Family(i % family_count);
        int shape = (i / family_count) % 4;
        if (!family_applies(f, shape) || f == Family::scale) continue;
        Case c = make_case(f, shape, Range(i % 3), seed, std::uint64_t(i));
        Vec3 d{u(rng), u(rng), u(rng)};
        Shape carried = translated(c.shape, d);
        Line l = c.line;
        l.L0 = l.L0 + d;
        // A frame thinner than the move's rounding collapses (degenerate_frame): left out.
        if (!validate(carried, l).ok()) continue;
        w.shapes.push_back(carried);
        w.lines.push_back(l);
        Line across{{u(rng), u(rng), u(rng)}, {dir(rng), dir(rng), dir(rng)}, Range(i % 3)};
        w.lines.push_back(across);
    }
    return w;
}

bool same_hit(const SceneHit& a, const SceneHit& b) {
    return a.shape == b.shape && a.tied == b.tied && a.hit.kind == b.hit.kind &&
           a.hit.part == b.hit.part && std::memcmp(&a.hit.t, &b.hit.t, sizeof(double)) == 0 &&
           std::memcmp(&a.hit.p, &b.hit.p, sizeof(Vec3)) == 0;
}

// Every hit of every shape, as the scene would list them, by solving each shape in turn.
SceneAnswer brute_force(const std::vector<Shape>& shapes, SceneSolver solver, const Line& line,
                        Query q) {
    SceneAnswer all;
    for (std::uint32_t s = 0; s < shapes.size(); ++s) {
        Result r = solver == SceneSolver::correct ? correct::intersect(shapes[s], line, q)
                                                  : stable::intersect(shapes[s], line, q);
        if (!r.ok()) {
            all.error = r.error(), all.error_shape = s, all.hits.clear();
            return all;
        }
        for (int k = 0; k < r.count; ++k)
            all.hits.push_back({r.hits[k], s, std::uint8_t(k), false});
        if (r.on_surface) {
            Hit h{};
            h.t = r.s0, h.kind = HitKind::tangent, h.part = r.surface_part;
            if (q.points && std::isfinite(r.s0))
                h.p = {std::fma(r.s0, line.v.x, line.L0.x), std::fma(r.s0, line.v.y, line.L0.y),
                       std::fma(r.s0, line.v.z, line.L0.z)};
            all.hits.push_back({h, s, 255, false});
        }
    }
    std::sort(all.hits.begin(), all.hits.end(), [](const SceneHit& a, const SceneHit& b) {
        return a.hit.t < b.hit.t ||
               (a.hit.t == b.hit.t && std::pair(a.shape, a.index) < std::pair(b.shape, b.index));
    });
    for (std::size_t k = 1; k < all.hits.size(); ++k)
        if (all.hits[k].hit.t == all.hits[k - 1].hit.t &&
            all.hits[k].shape != all.hits[k - 1].shape)
            all.hits[k].tied = all.hits[k - 1].tied = true;
    return all;
}

void check_against_brute_force(SceneSolver solver,
                               SceneTraversal traversal = SceneTraversal::hierarchy) {
    // Shapes of median size 7 (a few unbounded) over a cube of side 400.
    World w = world(240, 400, 7);
    Scene scene(w.shapes, solver, traversal);
    REQUIRE(scene.traversal() == traversal);
    INFO("shape " << scene.error_shape() << ": " << message(scene.error()));
    REQUIRE(scene.error().ok());
    SceneAnswer a;
    std::size_t solved = 0, hits = 0, comparisons = 0;
    for (const Line& line : w.lines) {
        SceneAnswer all = brute_force(w.shapes, solver, line, {Need::all, true});
        scene.intersect(line, {Need::all, true}, a);
        REQUIRE(a.error.code == all.error.code);
        REQUIRE(a.error_shape == all.error_shape);
        REQUIRE(a.hits.size() == all.hits.size());
        // Bit for bit; but a correct scene orders hits at the same double exactly (tested
        // below), where the brute force lists them in shape order.
        if (solver == SceneSolver::correct) comparisons += a.exact_comparisons;
        for (std::size_t k = 0; k < a.hits.size(); ++k)
            REQUIRE((same_hit(a.hits[k], all.hits[k]) ||
                     (solver == SceneSolver::correct && all.hits[k].tied &&
                      a.hits[k].hit.t == all.hits[k].hit.t)));
        solved += a.shapes_solved;
        hits += a.hits.size();

        // nearest: the first hits of `all` that share its t (ties named among them only). A
        // shape that all's solver refuses may lie beyond the nearest hit, unsolved.
        scene.intersect(line, {Need::nearest, true}, a);
        if (!all.ok()) {
            REQUIRE((a.error.code == all.error.code ||
                     (all.error.code == ErrorCode::out_of_range && a.ok())));
            continue;
        }
        REQUIRE(a.ok());
        std::vector<SceneHit> first;
        for (const SceneHit& h : all.hits)
            if (h.hit.t == all.hits.front().hit.t) first.push_back(h);
        for (SceneHit& h : first)
            h.tied = first.size() > 1 && std::any_of(first.begin(), first.end(),
                                                     [&](auto& o) { return o.shape != h.shape; });
        if (solver == SceneSolver::stable || first.size() <= 1) {
            REQUIRE(a.hits.size() == first.size());
            for (std::size_t k = 0; k < a.hits.size(); ++k)
                REQUIRE(same_hit(a.hits[k], first[k]));
        } else { // the exactly nearest of those that round alike
            REQUIRE(!a.hits.empty());
            REQUIRE(a.hits.size() <= first.size());
            REQUIRE(a.hits[0].hit.t == first[0].hit.t);
        }

        // any: a hit exactly when there is one, on a shape the line does hit.
        scene.intersect(line, {Need::any, false}, a);
        REQUIRE(a.ok());
        REQUIRE(a.hits.size() == (all.hits.empty() ? 0u : 1u));
        if (!a.hits.empty())
            REQUIRE(std::any_of(all.hits.begin(), all.hits.end(),
                                [&](const SceneHit& h) { return h.shape == a.hits[0].shape; }));
    }
    INFO("shapes solved per line " << double(solved) / double(w.lines.size()));
    INFO("exact comparisons " << comparisons);
    CHECK(hits > w.lines.size() / 2); // the family lines hit their shapes
    // The shapes are scattered: culling leaves a small part of the 240 to solve per line.
    CHECK(solved < w.lines.size() * 240 / 4);
}

} // namespace

TEST_CASE("scene: every answer is the brute-force one (stable)", "[scene]") {
    check_against_brute_force(SceneSolver::stable);
}

TEST_CASE("scene: every answer is the brute-force one (correct)", "[scene]") {
    check_against_brute_force(SceneSolver::correct);
}

TEST_CASE("scene: Embree's traversal gives every answer the hierarchy gives", "[scene]") {
    if (!scene_traversal_available(SceneTraversal::embree)) {
        WARN("built without Embree: its traversal is not tested");
        return;
    }
    check_against_brute_force(SceneSolver::stable, SceneTraversal::embree);
    check_against_brute_force(SceneSolver::correct, SceneTraversal::embree);
}

TEST_CASE("scene: Embree's float frame holds shapes of any size anywhere", "[scene]") {
    // Embree drops boxes beyond 2^60 of the origin and cannot tell float ulps apart: the boxes
    // are moved and scaled into [-2, 2] around their centre. A cylinder 2^82 out (the fuzzer's
    // case: dropped before the scaling) and one 2^-300 small, each alone and both together.
    Cylinder far{{0x1.db69ce4f5b0fcp+81, 0x1.443b4baa3a2fp+80, 0x1.09355d7431ac4p+80},
                 {0x1.5e2d2a0be3676p+82, 0x1.1930f7b7c8932p+80, 0x1.09f170b7466d9p+82},
                 0x1.4ed21614047dep+81,
                 true,
                 false};
    Line far_ray{{0x1.979bd8ae69019p+83, 0x1.3f8c9d744ed9ep+81, 0x1.17623b0c94947p+80},
                 {-0x1.768d29a5f4c6ep+82, 0x1.6bc3591ca97c8p+79, 0x1.975624c642148p+79},
                 Range::ray};
    Cylinder tiny{{0, 0, -0x1p-300}, {0, 0, 0x1p-300}, 0x1p-301, true, true};
    Line tiny_ray{{-1, 0x1p-303, 0}, {1, 0, 0}, Range::ray};
    for (auto shapes :
         {std::vector<Shape>{far}, std::vector<Shape>{tiny}, std::vector<Shape>{far, tiny}}) {
        Scene scene(shapes, SceneSolver::correct, SceneTraversal::embree);
        for (const Line& l : {far_ray, tiny_ray}) {
            SceneAnswer got, want;
            scene.intersect(l, {Need::all, true}, got);
            exact::intersect(shapes, l, {Need::all, true}, want);
            REQUIRE(got.hits.size() == want.hits.size());
            for (std::size_t k = 0; k < got.hits.size(); ++k)
                CHECK(same_hit(got.hits[k], want.hits[k]));
        }
    }
    // The stable scene as its own hierarchy answers (it refuses the tiny cylinder: out_of_range).
    Scene both({far, tiny}, SceneSolver::stable, SceneTraversal::embree),
        own({far, tiny}, SceneSolver::stable, SceneTraversal::hierarchy);
    for (const Line& l : {far_ray, tiny_ray}) {
        SceneAnswer a, b;
        both.intersect(l, {Need::all, true}, a);
        own.intersect(l, {Need::all, true}, b);
        CHECK(a.error.code == b.error.code);
        REQUIRE(a.hits.size() == b.hits.size());
        for (std::size_t k = 0; k < a.hits.size(); ++k)
            CHECK(same_hit(a.hits[k], b.hits[k]));
    }
}

TEST_CASE("scene: one scene answers from many threads at once as from one", "[scene]") {
    // A renderer shares one scene between its threads: every query is const, Embree's included.
    World w = world(240, 400, 5);
    Scene scene(w.shapes, SceneSolver::correct);
    std::vector<SceneAnswer> alone(w.lines.size());
    for (std::size_t i = 0; i < w.lines.size(); ++i)
        scene.intersect(w.lines[i], {Need::nearest, true}, alone[i]);
    std::vector<std::vector<SceneAnswer>> by(4, std::vector<SceneAnswer>(w.lines.size()));
    std::vector<std::thread> threads;
    for (std::size_t k = 0; k < by.size(); ++k)
        threads.emplace_back([&, k] {
            for (std::size_t n = 0; n < w.lines.size(); ++n) {
                std::size_t i = k % 2 ? w.lines.size() - 1 - n : n; // forwards and backwards
                scene.intersect(w.lines[i], {Need::nearest, true}, by[k][i]);
            }
        });
    for (std::thread& t : threads)
        t.join();
    for (std::size_t k = 0; k < by.size(); ++k)
        for (std::size_t i = 0; i < w.lines.size(); ++i) {
            REQUIRE(by[k][i].hits.size() == alone[i].hits.size());
            for (std::size_t h = 0; h < alone[i].hits.size(); ++h)
                CHECK(same_hit(by[k][i].hits[h], alone[i].hits[h]));
        }
}

TEST_CASE("scene: a traversal that is not built in leaves the hierarchy in use", "[scene]") {
    Scene scene({Cylinder{{0, 0, 0}, {0, 0, 1}, 1, true, false}}, SceneSolver::correct,
                SceneTraversal::embree);
    CHECK(scene.traversal() == (scene_traversal_available(SceneTraversal::embree)
                                    ? SceneTraversal::embree
                                    : SceneTraversal::hierarchy));
}

TEST_CASE("scene: the exact oracle gives every correct scene answer bit for bit", "[scene]") {
    // The oracle solves every shape (no culling) in CGAL::Mpzf and orders all hits by comparing
    // their surds; the correct scene culls, rounds, and compares exactly only hits that round
    // alike, in big floats. Two implementations of one definition: they must agree exactly.
    World w = world(240, 400, 11);
    Scene scene(w.shapes, SceneSolver::correct);
    REQUIRE(scene.error().ok());
    SceneAnswer got, want;
    std::size_t hits = 0;
    for (std::size_t i = 0; i < w.lines.size(); ++i) {
        INFO("line " << i);
        for (Query q : {Query{Need::all, true}, Query{Need::nearest, true}}) {
            exact::intersect(w.shapes, w.lines[i], q, want);
            scene.intersect(w.lines[i], q, got);
            REQUIRE(want.ok());
            REQUIRE(got.error.code == want.error.code);
            REQUIRE(got.hits.size() == want.hits.size());
            for (std::size_t k = 0; k < got.hits.size(); ++k)
                REQUIRE(same_hit(got.hits[k], want.hits[k]));
            hits += got.hits.size();
        }
        exact::intersect(w.shapes, w.lines[i], {Need::any, false}, want);
        scene.intersect(w.lines[i], {Need::any, false}, got);
        REQUIRE(got.hits.size() == want.hits.size());
    }
    CHECK(hits > w.lines.size());
}

TEST_CASE("scene: each box holds every hit of its shape", "[scene]") {
    World w = world(400, 10, 11);
    Scene scene(w.shapes, SceneSolver::correct);
    int checked = 0;
    for (std::size_t i = 0; i < w.shapes.size(); ++i) {
        Box b = scene.bounds(std::uint32_t(i));
        Result r = correct::intersect(w.shapes[i], w.lines[2 * i], {Need::all, true});
        for (int k = 0; k < r.count; ++k) {
            const Vec3& p = r.hits[k].p;
            INFO("shape " << i << " hit " << k);
            CHECK((p.x >= b.lo.x && p.y >= b.lo.y && p.z >= b.lo.z));
            CHECK((p.x <= b.hi.x && p.y <= b.hi.y && p.z <= b.hi.z));
            ++checked;
        }
    }
    CHECK(checked > 300);
}

TEST_CASE("scene: hits at the same t on two shapes are named as tied", "[scene]") {
    Cylinder c{{0, 0, 0}, {0, 0, 2}, 1, true, false};
    Cylinder other{{5, 5, 0}, {5, 5, 2}, 1, true, false};
    Scene scene({c, other, c}, SceneSolver::correct);
    SceneAnswer a;
    Line ray{{-3, 0, 1}, {1, 0, 0}, Range::ray};
    scene.intersect(ray, {Need::nearest, true}, a);
    REQUIRE(a.hits.size() == 2);
    CHECK(a.hits[0].shape == 0);
    CHECK(a.hits[1].shape == 2);
    CHECK((a.hits[0].tied && a.hits[1].tied));
    CHECK(a.hits[0].hit.t == 2);
    scene.intersect(ray, {Need::all, true}, a);
    REQUIRE(a.hits.size() == 4);
    CHECK(a.hits[3].hit.t == 4);
    CHECK((a.hits[2].tied && a.hits[3].tied));
}

TEST_CASE("scene: a line along a surface, and shapes without bounds", "[scene]") {
    Cylinder finite{{0, 0, 0}, {0, 0, 2}, 1, true, false};
    Cylinder infinite{{100, 0, 0}, {100, 0, 1}, 1, false, false};
    Scene scene({finite, infinite}, SceneSolver::correct);
    SceneAnswer a;
    // Along the finite cylinder's surface from below: on it for t in [1, 3].
    scene.intersect({{1, 0, -1}, {0, 0, 1}, Range::ray}, {Need::nearest, true}, a);
    REQUIRE(a.hits.size() == 1);
    CHECK(a.hits[0].hit.t == 1);
    CHECK(a.hits[0].hit.kind == HitKind::tangent);
    CHECK(a.hits[0].hit.p.z == 0);
    // The infinite cylinder far along its axis is still hit.
    scene.intersect({{90, 0, 1e12}, {1, 0, 0}, Range::ray}, {Need::all, false}, a);
    REQUIRE(a.hits.size() == 2);
    CHECK(a.hits[0].shape == 1);
}

TEST_CASE("scene: bad lines and bad shapes are refused by name", "[scene]") {
    Cylinder good{{0, 0, 0}, {0, 0, 1}, 1, true, false};
    Cylinder bad = good;
    bad.r = 0;
    SceneAnswer a;
    Scene scene({good}, SceneSolver::stable);
    // Far from every box: refused all the same.
    scene.intersect({{NAN, 100, 100}, {1, 0, 0}}, {Need::any, false}, a);
    CHECK(a.error.code == ErrorCode::not_a_number);
    CHECK(std::string(a.error.field) == "L0");
    CHECK(a.error_shape == no_shape);
    scene.intersect({{100, 100, 100}, {0, 0, 0}}, {Need::all, true}, a);
    CHECK(a.error.code == ErrorCode::zero_direction);
    scene.intersect({{100, 100, 100}, {1, 0, 0}, Interval(2, 1)}, {Need::nearest, true}, a);
    CHECK(a.error.code == ErrorCode::empty_range);

    Scene broken({good, good, bad}, SceneSolver::correct);
    CHECK(broken.error().code == ErrorCode::bad_radius);
    CHECK(broken.error_shape() == 2);
    broken.intersect({{-3, 0, 0.5}, {1, 0, 0}}, {Need::all, true}, a);
    CHECK(a.error.code == ErrorCode::bad_radius);
    CHECK(a.error_shape == 2);
    CHECK(a.hits.empty());

    Scene empty({}, SceneSolver::correct);
    empty.intersect({{0, 0, 0}, {1, 0, 0}}, {Need::all, true}, a);
    CHECK((a.ok() && a.hits.empty()));
}

TEST_CASE("scene: directions at the ends of double's range lose no hit", "[scene]") {
    // 1 / v overflows for a subnormal v and is subnormal for a huge one: the slab test divides.
    std::vector<Shape> shapes;
    for (int i = 0; i < 64; ++i)
        shapes.push_back(Cylinder{{double(i), 0, 0}, {double(i), 0, 1}, 0.25, true, false});
    for (SceneSolver solver : {SceneSolver::stable, SceneSolver::correct}) {
        Scene scene(shapes, solver);
        SceneAnswer a;
        for (double scale : {0x1p-1060, 0x1p-600, 1.0, 0x1p600, 0x1p1020}) {
            // Along x through every cylinder, the other components at the other end of the range.
            Line l{{-1, 0, 0.5}, {scale, scale * 0x1p-30, 0}, Range::ray};
            SceneAnswer all = brute_force(shapes, solver, l, {Need::all, true});
            scene.intersect(l, {Need::all, true}, a);
            INFO("scale " << scale);
            REQUIRE(a.error.code == all.error.code);
            REQUIRE(a.hits.size() == all.hits.size());
            // Far out, many hits round to one t; a correct scene orders those exactly.
            for (std::size_t k = 0; k < a.hits.size(); ++k)
                CHECK((same_hit(a.hits[k], all.hits[k]) ||
                       (solver == SceneSolver::correct && all.hits[k].tied &&
                        a.hits[k].hit.t == all.hits[k].hit.t)));
        }
    }
}

TEST_CASE("scene: hits that round to the same double are put in their exact order", "[scene]") {
    // B is A moved by 2^-55 along the ray: its hits at 2 + 2^-55 and 4 + 2^-55 round to A's 2
    // and 4 (ulps of 2^-51 and 2^-50), yet come after them. A2 is A again: tied with A.
    Cylinder A{{0, 0, 0}, {0, 0, 2}, 1, true, false};
    Cylinder B{{0x1p-55, 0, 0}, {0x1p-55, 0, 2}, 1, true, false};
    Scene scene({B, A, A}, SceneSolver::correct);
    SceneAnswer a;
    Line ray{{-3, 0, 1}, {1, 0, 0}, Range::ray};
    scene.intersect(ray, {Need::nearest, true}, a);
    REQUIRE(a.hits.size() == 2); // A and its copy, not B
    CHECK((a.hits[0].shape == 1 && a.hits[1].shape == 2));
    CHECK((a.hits[0].tied && a.hits[1].tied));
    CHECK(a.hits[0].hit.t == 2);
    CHECK(a.exact_comparisons > 0);
    scene.intersect(ray, {Need::all, true}, a);
    REQUIRE(a.hits.size() == 6);
    std::uint32_t order[6] = {1, 2, 0, 1, 2, 0};
    bool tied[6] = {true, true, false, true, true, false};
    for (int k = 0; k < 6; ++k) {
        INFO("hit " << k);
        CHECK(a.hits[k].shape == order[k]);
        CHECK(a.hits[k].tied == tied[k]);
        CHECK(a.hits[k].hit.t == (k < 3 ? 2 : 4));
    }
    SceneAnswer o; // the oracle agrees
    exact::intersect({B, A, A}, ray, {Need::all, true}, o);
    REQUIRE(o.hits.size() == 6);
    for (int k = 0; k < 6; ++k)
        CHECK(same_hit(o.hits[k], a.hits[k]));
    // The stable scene only sees equal doubles: B first, by shape order, all tied.
    Scene approximate({B, A, A}, SceneSolver::stable);
    approximate.intersect(ray, {Need::nearest, true}, a);
    REQUIRE(a.hits.size() == 3);
    CHECK((a.hits[0].shape == 0 && a.hits[0].tied));
}

TEST_CASE("scene: irrational roots of two shapes within an ulp are ordered exactly", "[scene]") {
    // A: radius 1; B: radius 1 + 2^-40 moved along x by the double nearest to the difference of
    // their entry distances, so that t_A = 3 - sqrt(3/4) and t_B = 3 + x - sqrt(rB^2 - 1/4) differ
    // by x's rounding alone. MPFR (400 bits) says which comes first.
    double rB = 1 + 0x1p-40;
    mpfr_t sa, sb, diff, x;
    mpfr_inits2(400, sa, sb, diff, x, (mpfr_ptr)0);
    mpfr_set_d(sa, 0.75, MPFR_RNDN);
    mpfr_sqrt(sa, sa, MPFR_RNDN);
    mpfr_set_d(sb, rB, MPFR_RNDN);
    mpfr_sqr(sb, sb, MPFR_RNDN);
    mpfr_sub_d(sb, sb, 0.25, MPFR_RNDN);
    mpfr_sqrt(sb, sb, MPFR_RNDN);
    mpfr_sub(diff, sb, sa, MPFR_RNDN);
    double shift = mpfr_get_d(diff, MPFR_RNDN);
    mpfr_set_d(x, shift, MPFR_RNDN);
    int b_after_a = mpfr_cmp(x, diff); // t_B - t_A = shift - diff
    mpfr_clears(sa, sb, diff, x, (mpfr_ptr)0);
    REQUIRE(b_after_a != 0);

    Cylinder A{{0, 0, 0}, {0, 0, 2}, 1, true, false};
    Cylinder B{{shift, 0, 0}, {shift, 0, 2}, rB, true, false};
    Line ray{{-3, 0.5, 1}, {1, 0, 0}, Range::ray};
    Result ra = correct::intersect(A, ray, {Need::nearest, false});
    Result rb = correct::intersect(B, ray, {Need::nearest, false});
    REQUIRE((ra.count == 1 && rb.count == 1));
    REQUIRE(ra.hits[0].t == rb.hits[0].t); // the case needs them to round alike
    for (bool a_first_in_scene : {true, false}) {
        Scene scene(a_first_in_scene ? std::vector<Shape>{A, B} : std::vector<Shape>{B, A},
                    SceneSolver::correct);
        std::uint32_t a_index = a_first_in_scene ? 0 : 1, b_index = 1 - a_index;
        SceneAnswer ans;
        scene.intersect(ray, {Need::nearest, false}, ans);
        REQUIRE(ans.hits.size() == 1);
        CHECK(ans.hits[0].shape == (b_after_a > 0 ? a_index : b_index));
        CHECK_FALSE(ans.hits[0].tied);
        scene.intersect(ray, {Need::all, false}, ans);
        REQUIRE(ans.hits.size() == 4);
        CHECK(ans.hits[0].shape == (b_after_a > 0 ? a_index : b_index));
        CHECK(ans.hits[1].shape == (b_after_a > 0 ? b_index : a_index));
        CHECK_FALSE((ans.hits[0].tied || ans.hits[1].tied));
        SceneAnswer o;
        exact::intersect(a_first_in_scene ? std::vector<Shape>{A, B} : std::vector<Shape>{B, A},
                         ray, {Need::all, false}, o);
        REQUIRE(o.hits.size() == 4);
        for (int k = 0; k < 4; ++k)
            CHECK(same_hit(o.hits[k], ans.hits[k]));
    }
}

TEST_CASE("scene: lines along discs of different radii are ordered exactly", "[scene]") {
    // Three closed coaxial cylinders an ulp apart in radius; a ray in their base plane runs along
    // each base disc from t = 32 - sqrt(r^2 - 1/4): the largest first. Those starts differ by
    // about 2^-52 and round alike (ulps of 2^-48 near 31.1), so only their exact values order
    // them; the scene once left such starts (not roots) tied in shape order. The audit's nested
    // family found it.
    double r0 = 1, r1 = std::nextafter(r0, 2.0), r2 = std::nextafter(r1, 2.0);
    std::vector<Shape> shapes = {Cylinder{{0, 0, 0}, {0, 0, 1}, r0, true, true},
                                 Cylinder{{0, 0, 0}, {0, 0, 1}, r1, true, true},
                                 Cylinder{{0, 0, 0}, {0, 0, 1}, r2, true, true}};
    Line ray{{-32, 0.5, 0}, {1, 0, 0}, Range::ray};
    Scene scene(shapes, SceneSolver::correct);
    SceneAnswer a, o;
    scene.intersect(ray, {Need::all, true}, a);
    REQUIRE(a.hits.size() == 3);
    REQUIRE(a.hits[0].hit.t == a.hits[2].hit.t); // they round alike: the case needs it
    CHECK(a.exact_comparisons > 0);
    for (int k = 0; k < 3; ++k) {
        INFO("hit " << k);
        CHECK(a.hits[k].shape == std::uint32_t(2 - k));
        CHECK_FALSE(a.hits[k].tied);
        CHECK(a.hits[k].hit.part == Part::base);
    }
    exact::intersect(shapes, ray, {Need::all, true}, o);
    REQUIRE(o.hits.size() == 3);
    for (int k = 0; k < 3; ++k)
        CHECK(same_hit(o.hits[k], a.hits[k]));
    scene.intersect(ray, {Need::nearest, true}, a);
    REQUIRE(a.hits.size() == 1);
    CHECK(a.hits[0].shape == 2);
}

TEST_CASE("scene: shapes of every size make a deep hierarchy and lose no hit", "[scene]") {
    // Cylinders of radius 0.9 r around x = r, for r = 2^-200 ... 2^199: binned by their centres,
    // nearly all fall in the first bin at every level, so the area heuristic peels them a few at
    // a time (past the 64 levels of area splits, where medians take over; that bounds the
    // traversal's stack).
    std::vector<Shape> shapes;
    for (int k = 0; k < 400; ++k) {
        double r = std::ldexp(1.0, k - 200);
        shapes.push_back(Cylinder{{r, 0, -r}, {r, 0, r}, 0.9 * r, true, true});
    }
    // Through Embree too (where it is built in): boxes from 2^-200 to 2^199, scaled into its
    // float frame, the smallest far below float's resolution there.
    for (auto [solver, traversal] : {std::pair{SceneSolver::stable, SceneTraversal::hierarchy},
                                     std::pair{SceneSolver::correct, SceneTraversal::hierarchy},
                                     std::pair{SceneSolver::stable, SceneTraversal::automatic},
                                     std::pair{SceneSolver::correct, SceneTraversal::automatic}}) {
        Scene scene(shapes, solver, traversal);
        CHECK(scene.traversal() == (traversal == SceneTraversal::automatic &&
                                            scene_traversal_available(SceneTraversal::embree)
                                        ? SceneTraversal::embree
                                        : SceneTraversal::hierarchy));
        CHECK(scene.depth() > 64); // past the area heuristic's levels
        SceneAnswer a;
        for (Line l : {Line{{-0x1p210, 0, 0}, {1, 0, 0}, Range::ray},
                       Line{{0x1p-190, 0x1p-192, 0}, {0.3, -0.2, 1}, Range::line},
                       Line{{0x1p100, 0x1p99, 0x1p98}, {-1, -0.5, -0.25}, Range::ray}}) {
            SceneAnswer all = brute_force(shapes, solver, l, {Need::all, true});
            scene.intersect(l, {Need::all, true}, a);
            REQUIRE(a.error.code == all.error.code);
            REQUIRE(a.hits.size() == all.hits.size());
            for (std::size_t k = 0; k < a.hits.size(); ++k)
                CHECK(a.hits[k].hit.t == all.hits[k].hit.t);
            // A shape stable refuses (2^-200 beside a line 2^100 away) that lies beyond the
            // nearest hit is never solved: nearest answers where all must refuse.
            scene.intersect(l, {Need::nearest, true}, a);
            if (!all.ok()) {
                CHECK(all.error.code == ErrorCode::out_of_range);
                CHECK((a.error.code == ErrorCode::out_of_range || a.ok()));
                continue;
            }
            REQUIRE(a.hits.empty() == all.hits.empty());
            if (!all.hits.empty()) CHECK(a.hits[0].hit.t == all.hits[0].hit.t);
        }
    }
}
